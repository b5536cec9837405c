"""``auto``: the default method, a portfolio a user can leave on.

By the problem's shape (decided from bench/optimizers.py, table in the README):

- a design with both power goals gets a front of them: NSGA-II, which on experiment 5
  reaches the sweeps' hypervolume with a sixth of their evaluations;
- any other design gets one best layout from two searches run interleaved, batch by
  batch, on one budget: CMA-ES with IPOP restarts (the fastest to a target on the
  paper's patio experiments) and VNS restarted from random layouts (the fastest in
  CPU time at the office's scale, and the explorer: on deceptive matches every CMA-ES
  restart ends on one local optimum).

The rule (a bandit over the two searches, by recent gain per unit of work):

- each search's work is counted, not timed: the CPU seconds its batches would take by
  ``work_model`` (its own Python per batch, a CMA-ES run's set-up, and the light its
  candidates lit: the GEMMs' multiply-adds and the operator entries copied, tallied as
  they are made). Counted, so the same project and seed give the same run on any
  machine and under any load (docs/project-file.md promises it). The model before,
  evaluations plus a fixed cost per batch scaled by the patches, missed the CPU by up
  to 2.5x either way: on experiment 4 (a lux field on the patio) a VNS candidate costs
  as much as a CMA-ES one and VNS got about five sixths of the CPU where the shares
  were equal (``auto`` 2.6x CMA-ES's expected running time); on experiment 1 (the
  match's Gram product) a VNS candidate costs a fifth of one and CMA-ES was
  undercounted;
- its **rate** is the relative fall of its best f + P (``relative_gain``; becoming
  feasible counts ``FEASIBLE_GAIN``) over the most recent ``WINDOW`` of its own work,
  divided by that work;
- its **weight** is its rate over the best rate, at least ``FLOOR`` (so a search that
  is behind keeps a sixth of the work and can overtake); both weigh 1 until each has
  done ``PROBE`` evaluations (a cheap first phase that measures both);
- **a search trailing the leader** (the one holding the best) by more than ``LEAD`` =
  5% of its f + P weighs ``FLOOR`` and the leader 1, while the leader is not
  stagnating, whatever their rates: one far behind gains fast from a poor start (on
  experiment 4 VNS's best, far below CMA-ES's, rose by large shares and took the work
  from the CMA-ES run about to reach the target);
- **head starts by the scale**: each search first works alone for a number of its own
  evaluations, split by s = min(1, SMALL / patches)^2: VNS first for s ``HEAD[0]``
  (two sweeps at most), CMA-ES not even made (its start-up, a random layout evaluated
  and ``cma``'s set-up, not paid), then CMA-ES for (1 - s) ``HEAD[1]``. On the
  office-scale problems (s = 1) VNS has it all: there ``cma``'s own Python makes a
  CMA-ES candidate many times a VNS candidate's CPU, and VNS's first two sweeps reach
  the target in most seeds of the bench's matches (medians 1,000-2,000 evaluations).
  On the patio (s = 0.05) VNS does three batches and CMA-ES about 950 evaluations: it
  needs far fewer evaluations there (the bench: medians of 235-1,271 against VNS's
  486-24,007), and a shorter head start (320) left experiment 1's CMA-ES behind a VNS
  that led but did not reach the target. The head starts are not counted in the shares
  that follow;
- the next batch goes to the search with the least work per weight, each batch's work
  divided by the weight it was chosen under (stride scheduling): a change of weights
  moves the shares from then on. Before, the least total work over the current
  weight chose, so a search floored for long then weighted 1 took every batch until
  its total caught up (a debt repaid, whatever the rates said then);
- a search whose best has not improved by ``GAIN`` for ``patience`` of its own
  evaluations is stagnating and weighs ``FLOOR`` (CMA-ES's restarts ending in one
  basin; a VNS run in a local optimum), whatever its rate (its small gains there lead
  nowhere more often than not: measured, weighting them by their rate cost a run on
  the three-luminaire match its success);
- when both stagnate and the one holding the best still gains a little (its rate is
  above 0), it weighs 1 and the other ``FLOOR`` if its best f + P trails by more than
  ``LEAD`` (else both weigh 1): the leader's small gains improve the answer, the
  other's must first close the gap. A leader that gains nothing is not favoured: on
  experiment 1 a CMA-ES run stuck early at e = 0.36, far behind VNS, then found the
  target, which that rule had delayed from 0.6 to 1.35 CPU s;
- VNS restarts when a whole sweep of its neighbourhoods finds nothing better, or when
  it has not gained in ``patience(2 nvar)`` of its evaluations, from a random valid
  layout (its own generator, ``RESTART_SEED``). The layout farthest from where its
  earlier runs ended (of 64 drawn) was the rule before: measured on the three built
  matches, 20 seeds each, it reached the target in 17 of 20 on ``three-luminaires``
  (ERT 9,367 evaluations) where a plain random layout reaches it in 20 of 20 (4,769):
  the farthest layouts are extreme ones (luminaires in corners, very long or small),
  poor starts.

The answer is the best of both (search.better). Each search's own moves are those of
the seed (it draws from its own generator, as it would alone).
"""

from __future__ import annotations

import bisect
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
from lightinv_core.optimize.work_model import LightTally, batch_seconds

FRONT_GOALS = frozenset(OBJECTIVES)
GAIN = 1e-3
"""A search improves when its best f + P falls by this share (or becomes feasible)."""
FLOOR = 0.2
"""Least weight of a search (behind, or stagnating): it keeps a sixth of the work."""
LEAD = 0.05
"""A search whose best f + P trails the leader's by more than this share weighs ``FLOOR``
while the leader improves, or still gains a little when both stagnate (module
docstring)."""
WINDOW = 0.25
"""A search's rate is measured over this share of its own work (the recent quarter)."""
SMALL = 5424
"""Patches up to which a candidate's light is cheap beside the searches' own Python (the
office demo's count): there VNS does the whole head start (``head_start``)."""
HEAD = (2048, 1000)
"""Evaluations done alone first: VNS's where a candidate's light is cheap (64 batches of
32 candidates), CMA-ES's where it is dear (about 120 generations of 8 on the patio);
split by the scale (module docstring)."""
PROBE = 64
"""Evaluations each search does before the rates move the shares (the first phase: a
few CMA-ES generations, two VNS batches)."""
FEASIBLE_GAIN = 1.0
"""The relative gain of becoming feasible (as large as any fall of f + P)."""
RESTART_SEED = 104_729
"""Added to the run's seed for the VNS restarts' layouts. Each search draws from the
run's seed as it would alone, so until VNS first restarts each is step for step the
method run alone: ``auto`` reaches a target wherever either does within its share."""


def wants_front(design: Design) -> bool:
    """Whether ``auto`` finds a front for ``design``: it has both power goals. A design
    with another pair gets one best layout of its first goal (the Run panel's goal is
    the user's choice); its front comes from ``nsga2`` or ``epsilon``, chosen by name."""
    return {str(g.kind) for g in design.goals} >= FRONT_GOALS


def head_start(patches: int) -> tuple[float, float]:
    """Evaluations (VNS, CMA-ES) each does alone first, in that order (module
    docstring): s HEAD[0] and (1 - s) HEAD[1], s = min(1, SMALL / patches)^2."""
    s = min(1.0, SMALL / max(patches, 1)) ** 2
    return HEAD[0] * s, HEAD[1] * (1.0 - s)


def patience(nvar: int) -> int:
    """Evaluations without a ``GAIN`` after which a search stagnates."""
    return max(500, 50 * nvar)


def real_gain(value: float, penalty: float, value0: float, penalty0: float) -> bool:
    """Whether (value, penalty) improves on (value0, penalty0) by more than ``GAIN``:
    it becomes feasible, or its f + P falls by that share in the same class."""
    return relative_gain(value, penalty, value0, penalty0) > GAIN


def relative_gain(value: float, penalty: float, value0: float, penalty0: float) -> float:
    """How much (value, penalty) improves on (value0, penalty0), at most 1: becoming
    feasible counts ``FEASIBLE_GAIN``, else the fall of f + P over abs(value0)."""
    if (penalty == 0.0) != (penalty0 == 0.0):
        return FEASIBLE_GAIN if penalty == 0.0 else 0.0
    if not np.isfinite(value0):
        return FEASIBLE_GAIN if np.isfinite(value) else 0.0
    fall = (value0 - value) / max(abs(value0), 1e-12)
    return float(min(max(fall, 0.0), 1.0))


class _Arm:
    """One search of the portfolio: its work (modelled CPU seconds), its best after
    each of its steps and its last real improvement."""

    def __init__(self, name: str, run, tally: LightTally):
        self.name, self.tally = name, tally
        self.work = 0.0  # its modelled CPU seconds (``work_model.batch_seconds``)
        self.last = batch_seconds(name, 0.0, new_run=name == "cmaes")  # its last batch's
        self.turn = 0.0  # its work, each batch's divided by its weight then (the shares)
        self.mark = (np.inf, np.inf)  # (value, penalty) at the last real gain
        self.mark_evals = 0
        # ``run`` is the search, or a function making it at its first step (CMA-ES:
        # not begun, not paid for, while VNS has its head start).
        self.run, self.make = (None, run) if callable(run) else (run, None)
        self.trace: list[tuple[float, float, float]] = []
        self.times: list[float] = []  # the trace's work column, for the rate's bisection
        if self.run is not None:
            self._record()

    @property
    def evals(self) -> int:
        return 0 if self.run is None else self.run.budget.evals

    def _record(self) -> None:
        value, pen = self.run.budget.best[:2]
        self.trace.append((self.work, value, pen))
        self.times.append(self.work)
        if real_gain(value, pen, *self.mark):
            self.mark, self.mark_evals = (value, pen), self.evals

    def step(self, before=None) -> None:
        """One batch of the search (``before()`` first: a VNS restart's draws); the
        search is made first if it has not begun (its start evaluated with the batch)."""
        light0 = self.tally.seconds()
        if self.run is None:
            self.run = self.make()  # its start is evaluated and counted with this batch
            self._record()
        if before is not None:
            before()
        es = getattr(self.run, "es", None)  # CMA-ES's current run
        self.run.step()
        new_run = es is not getattr(self.run, "es", None)
        # A VNS restart's start and CMA-ES's first point are evaluated in this batch.
        self.last = batch_seconds(self.name, self.tally.seconds() - light0, new_run)
        self.work += self.last
        self._record()

    def stagnating(self, nvar: int) -> bool:
        return self.evals - self.mark_evals >= patience(nvar)

    def rate(self) -> float:
        """Relative gain per unit of work over the most recent ``WINDOW`` of its work."""
        span = WINDOW * self.work
        if span <= 0.0:
            return 0.0
        i = max(bisect.bisect_right(self.times, self.work - span) - 1, 0)
        _, v0, p0 = self.trace[i]
        _, v1, p1 = self.trace[-1]
        return relative_gain(v1, p1, v0, p0) / span


def _leader(arms: list[_Arm]) -> int:
    """The index of the search holding the best (value, penalty)."""
    lead = 0
    for i, a in enumerate(arms):
        if better(*a.run.budget.best[:2], *arms[lead].run.budget.best[:2]):
            lead = i
    return lead


def weights(arms: list[_Arm], nvar: int) -> list[float]:
    """Each search's weight (module docstring): 1 each while probing; ``FLOOR`` for one
    trailing a leader that still improves by more than ``LEAD`` (the leader 1); else
    its rate over the best rate, at least ``FLOOR``, and ``FLOOR`` while it stagnates."""
    if any(a.evals < PROBE for a in arms):
        return [1.0 for _ in arms]
    if all(a.stagnating(nvar) for a in arms):
        return _by_lead(arms)
    lead = _leader(arms)
    if not arms[lead].stagnating(nvar):
        best = arms[lead].run.budget.best[:2]
        trail = [relative_gain(*best, *a.run.budget.best[:2]) > LEAD for a in arms]
        if any(trail):
            return [FLOOR if t else 1.0 for t in trail]
    rates = [a.rate() for a in arms]
    top = max(rates)
    w = [max(FLOOR, r / top) if top > 0.0 else 1.0 for r in rates]
    return [FLOOR if a.stagnating(nvar) else x for a, x in zip(arms, w, strict=True)]


def _by_lead(arms: list[_Arm]) -> list[float]:
    """Weights when every search stagnates: while the one holding the best still gains
    (its rate is above 0), 1 for it and for any within ``LEAD`` of it, ``FLOOR`` for one
    trailing it by more; else ``FLOOR`` each, the same shares (module docstring)."""
    lead = _leader(arms)
    if arms[lead].rate() <= 0.0:  # the leader is stuck too: neither is favoured
        return [FLOOR for _ in arms]
    best = arms[lead].run.budget.best[:2]
    return [FLOOR if relative_gain(*best, *a.run.budget.best[:2]) > LEAD else 1.0 for a in arms]


def _restart_vns(problem: DesignProblem, arm: _Arm, rng: np.random.Generator) -> None:
    """Restart the VNS arm from a random valid layout (module docstring)."""
    arm.run.restart(random_layouts(problem, rng, 1)[0])
    arm.mark, arm.mark_evals = (np.inf, np.inf), arm.evals


def _stalled(arms: list[_Arm], stall: int | None) -> str | None:
    """ "stall" when no search has improved its best in ``stall`` of its evaluations."""
    if stall is None:
        return None
    done = all(a.run is not None and a.evals - a.run.budget.last_gain >= stall for a in arms)
    return "stall" if done else None


def interleaved(
    problem: DesignProblem, context: RunContext, trials: int = 32, log: list | None = None
) -> tuple[SearchResult, dict[str, int]]:
    """CMA-ES and VNS interleaved on one budget (module docstring), with the context's
    seed, stop rule and hooks; returns the best over both and each search's
    evaluations. Progress and history follow the best so far over both. ``log``, when
    given, gets one row per batch: (search stepped, each search's work so far,
    the weights that chose it, each search's evaluations so far)."""
    quiet = RunContext(stop=StopRule(max_evals=None), seed=context.seed)
    n = problem.patches.n
    tally = problem.lighting.tally
    arms = [
        _Arm("cmaes", lambda: CMAESRun(problem, quiet), tally),
        _Arm("vns", VNSRun(problem, quiet, trials=trials), tally),
    ]
    rng = np.random.default_rng(context.seed + RESTART_SEED)
    nvar = problem.vars.n
    # The stall rule is each search's own: auto stalls when both do (interleaved, the
    # run's evaluations grow twice as fast as either search's).
    stall = context.stop.stall
    total = Budget(problem, replace(context.stop, stall=None), context.cancel)
    best_x = arms[1].run.best_x
    iterations = 0

    def absorb() -> None:
        nonlocal best_x
        total.evals = sum(a.evals for a in arms)
        for a in arms:
            if a.run is None:
                continue
            b = a.run.budget.best
            if better(b[0], b[1], *total.best[:2]):
                total.best = b
                total.history.append((total.evals, *b))
                total.gain()
                best_x = a.run.best_x

    absorb()
    head = head_start(n)
    while (why := total.why() or _stalled(arms, stall)) is None:
        w = weights(arms, nvar)
        # The head starts (VNS's, CMA-ES not begun; then CMA-ES's), then the least
        # work per weight, each
        # batch's work divided by the weight it was chosen under (stride scheduling:
        # a change of weights moves the shares from then on, with no debt to repay);
        # on a tie (the first batch) the cheaper batch.
        vns_first = arms[1].evals < head[0] and arms[0].run is None
        heading = vns_first or arms[0].evals < head[1]
        if heading:
            k = 1 if vns_first else 0
        else:
            k = min(range(2), key=lambda i: (arms[i].turn, arms[i].last))
        arm = arms[k]
        work0 = arm.work
        before = None
        if arm.name == "vns" and (arm.run.stuck or arm.stagnating(2 * nvar)):
            before = lambda arm=arm: _restart_vns(problem, arm, rng)  # noqa: E731
        arm.step(before)
        if not heading:  # the head start is not counted in the shares
            arm.turn += (arm.work - work0) / w[k]
        if log is not None:
            log.append(
                (arm.name, tuple(a.work for a in arms), tuple(w), tuple(a.evals for a in arms))
            )
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
