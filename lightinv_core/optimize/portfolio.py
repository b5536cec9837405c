"""``auto``: the default method, a portfolio a user can leave on.

By the problem's shape (decided from bench/optimizers.py, table in docs/design.md):

- a design with both power goals gets a front of them: NSGA-II, which on experiment 5
  reaches the sweeps' hypervolume with a sixth of their evaluations;
- any other design gets one best layout from two searches run interleaved, batch by
  batch, on one budget: CMA-ES with IPOP restarts (the fastest to a target on the
  paper's experiments and the demos) and VNS restarted from diverse layouts (the
  explorer: on deceptive matches every CMA-ES restart ends on one local optimum). The
  next batch goes to the search that has used the least of its share (``COST``:
  evaluations plus a fixed cost per batch, so the share is about CPU time yet the same
  seed gives the same run on any machine). A search whose best has not improved by
  ``GAIN`` (relative) for ``patience`` of its own evaluations is stagnating: CMA-ES's
  share falls to ``STAGNANT_SHARE`` (its restarts keep ending in one basin) until it
  improves again. VNS restarts when a whole sweep of its neighbourhoods finds nothing
  better (a local optimum of every one), from the random valid layout farthest from
  where its earlier runs ended. The answer is the best of both (search.better).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.optimize.cmaes import CMAESRun
from lightinv_core.optimize.fronts import OBJECTIVES
from lightinv_core.optimize.method import MethodSpec, RunContext
from lightinv_core.optimize.nsga2 import NSGA2
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import Budget, SearchResult, better, judged, random_layouts
from lightinv_core.optimize.termination import StopRule
from lightinv_core.optimize.vns import VNSRun

FRONT_GOALS = frozenset(OBJECTIVES)
COST = {"cmaes": 50, "vns": 8}
"""Fixed cost of one batch, in evaluations: ``cma``'s ask and tell and the batch's own
overhead. Measured (CPU, one BLAS thread) with VNS's batch of 32 as 32 + 8: a CMA-ES
generation of 10-11 costs as much as 56 evaluations on the office demo and 69 on the
patio."""
GAIN = 1e-3
"""A search improves when its best f + P falls by this share (or becomes feasible)."""
STAGNANT_SHARE = 0.25
"""CMA-ES's share while it stagnates (its restarts keep ending in one basin)."""
RESTART_SEED = 104_729
"""Added to the run's seed for the VNS restarts' layouts. Each search draws from the
run's seed as it would alone, so until VNS first restarts each is step for step the
method run alone: ``auto`` reaches a target wherever either does within its share."""
DIVERSE_DRAWS = 64
"""Random valid layouts drawn for a VNS restart; the farthest from earlier ends wins."""


def wants_front(design: Design) -> bool:
    """Whether ``auto`` finds a front for ``design``: it has both power goals. A design
    with another pair gets one best layout of its first goal (the Run panel's goal is
    the user's choice); its front comes from ``nsga2`` or ``epsilon``, chosen by name."""
    return {str(g.kind) for g in design.goals} >= FRONT_GOALS


def patience(nvar: int) -> int:
    """Evaluations without a ``GAIN`` after which a search stagnates."""
    return max(500, 50 * nvar)


def real_gain(value: float, penalty: float, value0: float, penalty0: float) -> bool:
    """Whether (value, penalty) improves on (value0, penalty0) by more than ``GAIN``:
    it becomes feasible, or its f + P falls by that share in the same class."""
    if (penalty == 0.0) != (penalty0 == 0.0):
        return penalty == 0.0
    if not np.isfinite(value0):
        return bool(np.isfinite(value))
    return value < value0 - GAIN * abs(value0)


class _Arm:
    """One search of the portfolio: its cost so far and its last real improvement."""

    def __init__(self, name: str, run):
        self.name, self.run = name, run
        self.cost = 0.0
        self.mark = (np.inf, np.inf)  # (value, penalty) at the last real gain
        self.mark_evals = 0
        self.ends: list[np.ndarray] = []  # VNS: where each run ended (unit cube)

    @property
    def evals(self) -> int:
        return self.run.budget.evals

    def step(self) -> None:
        m = self.run.step()
        self.cost += m + COST[self.name]
        value, pen = self.run.budget.best[:2]
        if real_gain(value, pen, *self.mark):
            self.mark, self.mark_evals = (value, pen), self.evals

    def stagnating(self, nvar: int) -> bool:
        return self.evals - self.mark_evals >= patience(nvar)


def _restart_vns(problem: DesignProblem, arm: _Arm, rng: np.random.Generator) -> None:
    """Restart the VNS arm from the random valid layout farthest (unit cube) from the
    ends of its earlier runs."""
    lo, hi = problem.vars.lo, problem.vars.hi
    span = np.where(hi > lo, hi - lo, 1.0)
    arm.ends.append((arm.run.x - lo) / span)
    X = random_layouts(problem, rng, DIVERSE_DRAWS)
    Z = (X - lo) / span
    gap = np.min(np.linalg.norm(Z[:, None] - np.asarray(arm.ends)[None], axis=2), axis=1)
    arm.run.restart(X[int(np.argmax(gap))])
    arm.mark, arm.mark_evals = (np.inf, np.inf), arm.evals


def _stalled(arms: list[_Arm], stall: int | None) -> str | None:
    """ "stall" when no search has improved its best in ``stall`` of its evaluations."""
    if stall is None:
        return None
    done = all(a.evals - a.run.budget.last_gain >= stall for a in arms)
    return "stall" if done else None


def interleaved(
    problem: DesignProblem, context: RunContext, trials: int = 32
) -> tuple[SearchResult, dict[str, int]]:
    """CMA-ES and VNS interleaved on one budget (module docstring), with the context's
    seed, stop rule and hooks; returns the best over both and each search's
    evaluations. Progress and history follow the best so far over both."""
    quiet = RunContext(stop=StopRule(max_evals=None), seed=context.seed)
    arms = [
        _Arm("cmaes", CMAESRun(problem, quiet)),
        _Arm("vns", VNSRun(problem, quiet, trials=trials)),
    ]
    rng = np.random.default_rng(context.seed + RESTART_SEED)
    nvar = problem.vars.n
    # The stall rule is each search's own: auto stalls when both do (interleaved, the
    # run's evaluations grow twice as fast as either search's).
    stall = context.stop.stall
    total = Budget(problem, replace(context.stop, stall=None), context.cancel)
    best_x = arms[0].run.best_x
    iterations = 0

    def absorb() -> None:
        nonlocal best_x
        total.evals = sum(a.evals for a in arms)
        for a in arms:
            b = a.run.budget.best
            if better(b[0], b[1], *total.best[:2]):
                total.best = b
                total.history.append((total.evals, *b))
                total.gain()
                best_x = a.run.best_x

    absorb()
    while (why := total.why() or _stalled(arms, stall)) is None:
        share = {"cmaes": STAGNANT_SHARE if arms[0].stagnating(nvar) else 1.0, "vns": 1.0}
        arm = min(arms, key=lambda a: a.cost / share[a.name])
        if arm.name == "vns" and (arm.run.stuck or arm.stagnating(2 * nvar)):
            _restart_vns(problem, arm, rng)
        arm.step()
        iterations += 1
        absorb()
        if context.progress is not None:
            context.progress(total.snapshot(iterations, 1, best_x))
    res = total.result(best_x, iterations, why)
    return res, {a.name: a.evals for a in arms}


@dataclass(frozen=True)
class AutoSettings:
    """``trials``: VNS's, in the single-layout search; ``population``: NSGA-II's, for a
    front."""

    trials: int = 32
    population: int = 100


def run_auto(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """NSGA-II, or CMA-ES and VNS interleaved, by the design's goals (module
    docstring)."""
    s = context.options(AutoSettings)
    if wants_front(problem.design):
        return NSGA2.run(problem, context.but(settings=s))
    res, _ = interleaved(problem, context, s.trials)
    return judged(problem, res, AUTO.name, context.seed)


AUTO = MethodSpec(
    "auto",
    "Auto (CMA-ES + VNS, or NSGA-II for a front)",
    run_auto,
    AutoSettings,
    wants_front,
    count_setting=("Population", "population"),  # of its front (NSGA-II)
    progress_label="front hypervolume",  # shown only when it finds a front
)
"""The default: NSGA-II for a front of the design's two goals, else CMA-ES and VNS
interleaved."""
