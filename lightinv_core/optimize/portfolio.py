"""``auto``: the default method, a portfolio a user can leave on.

By the problem's shape (decided from bench/optimizers.py, table in docs/design.md):

- a design with both power goals gets a front of them: NSGA-II,
  which on experiment 5 reaches the sweeps' hypervolume with a sixth of their
  evaluations;
- any other design gets one best layout: CMA-ES with IPOP restarts on every patch for
  up to ``CMA_SHARE`` of the evaluation and time budgets, then VNS from a random layout
  with what is left; the better of the two is the answer. CMA-ES is the fastest to a
  target on the paper's experiments and the demos, and the first phase is exactly a
  CMA-ES run with the same seed, so wherever CMA-ES alone reaches a target within its
  share, ``auto`` reaches it at the same evaluation. VNS covers deceptive problems
  where every CMA-ES restart ends on the same local optimum (a three-luminaire match:
  bench/optimizers.py). VNS from CMA-ES's best instead was tried: it never improved a
  CMA-ES answer on the benchmark problems and could not leave such an optimum.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from lightinv_core.design.model import Design
from lightinv_core.optimize.cmaes import cmaes
from lightinv_core.optimize.fronts import OBJECTIVES
from lightinv_core.optimize.method import MethodSpec, RunContext
from lightinv_core.optimize.nsga2 import NSGA2
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.progress import Progress
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import SearchResult, better, judged
from lightinv_core.optimize.vns import vns

CMA_SHARE = 0.5
"""Part of the evaluation and time budgets CMA-ES may use before VNS takes over."""
FRONT_GOALS = frozenset(OBJECTIVES)


def wants_front(design: Design) -> bool:
    """Whether ``auto`` finds a front for ``design``: it has both power goals. A design
    with another pair gets one best layout of its first goal (the Run panel's goal is
    the user's choice); its front comes from ``nsga2`` or ``epsilon``, chosen by name."""
    return {str(g.kind) for g in design.goals} >= FRONT_GOALS


def cma_then_vns(
    problem: DesignProblem, context: RunContext, trials: int = 32
) -> tuple[SearchResult, int]:
    """CMA-ES for ``CMA_SHARE`` of the budgets, then VNS from a random layout with the
    rest (a second, different search: where CMA-ES's restarts keep ending on one local
    optimum, VNS's small moves from elsewhere find the answer). Returns the best over
    both phases and the evaluations CMA-ES used. Progress and history are one
    continuous curve of the best so far (VNS's evaluations and seconds counted on from
    CMA-ES's). The context's ``x0`` is not read: both phases start at random layouts."""
    seed, stop, progress = context.seed, context.stop, context.progress
    first = replace(
        stop,
        max_evals=None if stop.max_evals is None else max(1, int(stop.max_evals * CMA_SHARE)),
        time_limit=None if stop.time_limit is None else stop.time_limit * CMA_SHARE,
    )
    a = cmaes(problem, context.but(x0=None, stop=first))
    if a.status in ("cancelled", "target"):
        return a, a.evaluations
    rest = replace(
        stop,
        max_evals=None if stop.max_evals is None else stop.max_evals - a.evaluations,
        time_limit=None if stop.time_limit is None else stop.time_limit - a.seconds,
    )
    if (rest.max_evals is not None and rest.max_evals <= 0) or (
        rest.time_limit is not None and rest.time_limit <= 0
    ):
        return a, a.evaluations

    a_x = tuple(float(c) for c in a.x)

    def shifted(p: Progress) -> None:
        p = replace(p, evaluations=p.evaluations + a.evaluations, elapsed=p.elapsed + a.seconds)
        if not better(p.best_value, p.best_penalty, a.value, a.penalty):
            p = replace(p, best_value=a.value, best_penalty=a.penalty, best_goal=a.goal, best_x=a_x)
        progress(p)

    later = context.but(
        x0=None, seed=seed + 104_729, stop=rest, progress=None if progress is None else shifted
    )
    b = vns(problem, later, trials=trials)
    best = b if better(b.value, b.penalty, a.value, a.penalty) else a
    history = a.history + [
        (e + a.evaluations, v, pen, g)
        for e, v, pen, g in b.history
        if better(v, pen, a.value, a.penalty)
    ]
    total = SearchResult(
        best.x,
        best.value,
        best.penalty,
        best.goal,
        a.evaluations + b.evaluations,
        a.iterations + b.iterations,
        a.seconds + b.seconds,
        b.status,
        history,
    )
    return total, a.evaluations


@dataclass(frozen=True)
class AutoSettings:
    """``trials``: VNS's, in the single-layout search; ``population``: NSGA-II's, for a
    front."""

    trials: int = 32
    population: int = 100


def run_auto(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """NSGA-II or CMA-ES then VNS, by the design's goals (module docstring)."""
    s = context.options(AutoSettings)
    if wants_front(problem.design):
        return NSGA2.run(problem, context.but(settings=s))
    res, cma_evals = cma_then_vns(problem, context, s.trials)
    return judged(problem, res, AUTO.name, context.seed, extra={"cmaes_evaluations": cma_evals})


AUTO = MethodSpec(
    "auto",
    "Auto (CMA-ES + VNS, or NSGA-II for a front)",
    run_auto,
    AutoSettings,
    wants_front,
    count_setting=("Population", "population"),  # of its front (NSGA-II)
    progress_label="front hypervolume",  # shown only when it finds a front
)
"""The default: NSGA-II for a front of the design's two goals, else CMA-ES then VNS."""
