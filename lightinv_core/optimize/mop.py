"""Multi-objective drivers: the epsilon-constraint sweep (paper eq. 10) and the
two-step process (paper 5.5), over artificial electric power (W, minimised) and total
reflected light power (lm, maximised); the sweep also over a design's climate pair,
annual energy (kWh, minimised) against glazing area (m², minimised)."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from lightinv_core.design.model import Design, Goal
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.kinds import MAXIMISED_GOALS, GoalKind, SourceKind
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.method import MethodSpec, RunContext, always_front
from lightinv_core.optimize.multilevel import DEFAULT_DIVISORS, multilevel
from lightinv_core.optimize.pareto import non_dominated
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.progress import CancelFn, ProgressFn
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import judged
from lightinv_core.optimize.termination import StopRule

POWER, LIGHT = GoalKind.MIN_ELECTRIC_POWER, GoalKind.MAX_LIGHT_POWER
OBJECTIVES = (POWER, LIGHT)
CLIMATE = (GoalKind.MIN_ANNUAL_ENERGY, GoalKind.MIN_GLAZING_AREA)
"""The climate front: least annual energy for each bound on the glazing area."""


def design_goal(design: Design, kind: str) -> Goal:
    """The design's goal of ``kind`` (with its settings), or a plain one."""
    return next((g for g in design.goals if g.kind == kind), Goal(kind))


def front_pair(design: Design) -> tuple[GoalKind, GoalKind]:
    """The two objectives a sweep trades: (minimised, bounded). Power against light
    power, unless the design's goals are the climate pair and not both power goals."""
    kinds = {GoalKind(g.kind) for g in design.goals}
    if set(CLIMATE) <= kinds and not set(OBJECTIVES) <= kinds:
        return CLIMATE
    return OBJECTIVES


def _minimised(s: Solution, kind: str) -> float:
    value = s.objectives[kind]
    return -value if kind in MAXIMISED_GOALS else value


def front_of(solutions: list[Solution], method: str, pair=OBJECTIVES) -> ParetoFront:
    """The non-dominated feasible solutions of the two objectives ``pair`` (power
    minimised and light maximised by default), each objective point once."""
    feasible = [s for s in solutions if s.feasible]
    if feasible:
        F = np.array([[_minimised(s, k) for k in pair] for s in feasible])
        keep = non_dominated(F)
        # Two epsilon runs can end on the same layout (a bound below the previous
        # optimum): a front lists each point once, the first run that found it.
        _, first = np.unique(F, axis=0, return_index=True)
        keep &= np.isin(np.arange(len(F)), first)
        order = np.argsort(F[:, 0], kind="stable")
        front = tuple(feasible[i] for i in order if keep[i])
    else:
        front = ()
    return ParetoFront(tuple(map(str, pair)), front, method, tuple(solutions))


def _solve(
    design: Design,
    light: LightModel,
    seed: int,
    stop: StopRule,
    divisors,
    epsilon=(),
    x0=None,
    cancel=None,
    vns_progress: ProgressFn | None = None,
    run: tuple[int, int] = (0, 1),
    method: str = "",
    info: dict | None = None,
):
    """One (multilevel) VNS sub-run of a sweep and its solution judged on every patch."""
    problem = DesignProblem(design, light, epsilon=epsilon)
    tagged = _tagged(vns_progress, *run)
    res, _ = multilevel(
        problem, divisors, seed=seed, stop=stop, x0=x0, cancel=cancel, progress=tagged
    )
    sol = judged(problem, res, method, seed, **(info or {})).best
    # A sweep's points carry no convergence history (each is one of many runs).
    return problem, res, replace(sol, info=sol.info.but(history=()))


def _tagged(progress: ProgressFn | None, run: int, runs: int) -> ProgressFn | None:
    """``progress`` with each snapshot marked as run ``run`` of ``runs``."""
    if progress is None:
        return None
    return lambda p: progress(replace(p, run=run, runs=runs))


def bounded_range(
    design: Design,
    light: LightModel,
    pair=OBJECTIVES,
    seed: int = 0,
    stop: StopRule | None = None,
    divisors=(1,),
    cancel: CancelFn | None = None,
    vns_progress: ProgressFn | None = None,
    runs: int = 2,
) -> tuple[float, float, np.ndarray]:
    """(low, high) of the bounded objective ``pair[1]`` over the front: its value at the
    best feasible layout of ``pair[0]`` and its own best feasible value; and the layout
    at the low end. Two VNS runs, reported as runs 0 and 1 of ``runs``."""
    stop = stop or StopRule(max_evals=5000)
    first, second = design_goal(design, pair[0]), design_goal(design, pair[1])
    common = (light, seed, stop, divisors)
    hooks = {"cancel": cancel, "vns_progress": vns_progress, "method": "epsilon"}
    _, r_own, own = _solve(replace(design, goals=(second, first)), *common, run=(0, runs), **hooks)
    _, r_other, other = _solve(
        replace(design, goals=(first, second)), *common, run=(1, runs), **hooks
    )
    a, b = own.objectives[pair[1]], other.objectives[pair[1]]
    return min(a, b), max(a, b), (r_own.x if a <= b else r_other.x)


def epsilon_constraint(
    design: Design,
    light: LightModel,
    epsilons: list[float] | None = None,
    count: int = 12,
    seed: int = 0,
    stop: StopRule | None = None,
    divisors=(1,),
    progress: Callable[[int, int, Solution], None] | None = None,
    cancel: CancelFn | None = None,
    vns_progress: ProgressFn | None = None,
) -> ParetoFront:
    """Minimise electric power subject to light power >= epsilon for each epsilon (lm) —
    or, for the climate pair (``front_pair``), annual energy subject to glazing area <=
    epsilon (m²) — warm-starting each run from the previous best; returns the
    non-dominated front.

    ``progress(q, total, solution)`` follows the sweep; ``vns_progress`` gets every VNS
    snapshot, tagged with its run (the two range runs first when ``epsilons`` is None).
    """
    stop = stop or StopRule(max_evals=20000)
    pair = front_pair(design)
    first, x = 0, None
    if epsilons is None:
        lo, hi, x_lo = bounded_range(
            design,
            light,
            pair,
            seed,
            stop=stop,
            divisors=divisors,
            cancel=cancel,
            vns_progress=vns_progress,
            runs=count + 2,
        )
        epsilons = list(np.linspace(lo, hi, count))
        first = 2
        if pair[1] not in MAXIMISED_GOALS:
            # The least value of a minimised bound leaves a band only the tolerance
            # wide (glazing area at its rule's minimum): start where it was reached.
            x = x_lo
    mop = replace(design, goals=(design_goal(design, pair[0]), design_goal(design, pair[1])))
    solutions = []
    for q, eps in enumerate(epsilons):
        if cancel is not None and cancel():
            break
        _, res, sol = _solve(
            mop,
            light,
            seed + q,
            stop,
            divisors,
            epsilon=((pair[1], float(eps)),),
            x0=x,
            cancel=cancel,
            vns_progress=vns_progress,
            run=(first + q, first + len(epsilons)),
            method="epsilon",
            info={"epsilon": float(eps)},
        )
        solutions.append(sol)
        x = res.x
        if progress is not None:
            progress(q + 1, len(epsilons), sol)
    return front_of(solutions, "epsilon-constraint", pair)


def two_step(
    design: Design,
    light: LightModel,
    runs: int = 10,
    seed: int = 0,
    stop: StopRule | None = None,
    divisors=(1,),
    progress: Callable[[int, int, Solution], None] | None = None,
    cancel: CancelFn | None = None,
    vns_progress: ProgressFn | None = None,
) -> ParetoFront:
    """Step 1: skylights alone, most natural light, under their geometric rules only.
    Step 2: skylights fixed, luminaires minimise electric power under every rule and
    intention. Repeated with ``runs`` seeds; returns the non-dominated front."""
    stop = stop or StopRule(max_evals=20000)
    sky = tuple(s for s in design.sources if s.kind == SourceKind.SKYLIGHT)
    lum = tuple(s for s in design.sources if s.kind == SourceKind.LUMINAIRE)
    sky_names = {s.name for s in sky}
    step1 = Design(
        sky,
        (Goal(LIGHT, (SourceKind.SKYLIGHT,)),),
        tuple(r for r in design.rules if set(r.sources) <= sky_names),
        daylight=design.daylight,
        penalty_power=design.penalty_power,
    )
    solutions = []
    for r in range(runs):
        if cancel is not None and cancel():
            break
        common = (light, seed + r, stop, divisors)
        hooks = {"cancel": cancel, "vns_progress": vns_progress, "method": "two_step"}
        _, _, first = _solve(step1, *common, **hooks, run=(2 * r, 2 * runs))
        fixed = tuple(replace(s, free=()) for s in first.sources)
        step2 = Design(
            (*fixed, *lum),
            (Goal(POWER), Goal(LIGHT)),
            tuple(r for r in design.rules if not set(r.sources) <= sky_names),
            design.intentions,
            daylight=design.daylight,
            penalty_power=design.penalty_power,
        )
        _, _, sol = _solve(
            step2,
            *common,
            **hooks,
            run=(2 * r + 1, 2 * runs),
            info={"step1_light_power": first.objectives[LIGHT]},
        )
        solutions.append(sol)
        if progress is not None:
            progress(r + 1, runs, sol)
    return front_of(solutions, "two-step")


def _front_result(front: ParetoFront, cancelled: bool, seconds: float) -> OptimizationResult:
    """A sweep's outcome: its front, the first point as ``best``, evaluations summed."""
    evals = sum(int(s.info.evaluations or 0) for s in front.candidates)
    best = front.solutions[0] if front.solutions else None
    status = "cancelled" if cancelled else ("feasible" if best is not None else "infeasible")
    return OptimizationResult(status, best, front, evals, seconds)


def _swept(context: RunContext, sweep: Callable[..., ParetoFront]) -> OptimizationResult:
    """A sweep run with the context's seed, stop rule and hooks: each point as it is
    found goes to ``on_solution``, every VNS snapshot to ``progress``."""
    t0 = time.perf_counter()
    c = context
    found = None if c.on_solution is None else (lambda _q, _n, sol: c.on_solution(sol))
    front = sweep(
        seed=c.seed, stop=c.stop, progress=found, cancel=c.cancel, vns_progress=c.progress
    )
    cancelled = c.cancel is not None and c.cancel()
    return _front_result(front, cancelled, time.perf_counter() - t0)


@dataclass(frozen=True)
class EpsilonSettings:
    """``epsilons``: the bounds to sweep (None: ``epsilon_count`` automatic ones);
    ``divisors``: each run's multilevel levels."""

    epsilons: tuple[float, ...] | None = None
    epsilon_count: int = 12
    divisors: tuple[int, ...] = DEFAULT_DIVISORS


def run_epsilon(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """The epsilon-constraint sweep over ``epsilons`` or ``epsilon_count`` bounds."""
    s = context.options(EpsilonSettings)
    eps = list(s.epsilons) if s.epsilons else None
    d, light, levels = problem.design, problem.light, tuple(s.divisors)
    return _swept(
        context,
        lambda **kw: epsilon_constraint(d, light, eps, s.epsilon_count, divisors=levels, **kw),
    )


@dataclass(frozen=True)
class TwoStepSettings:
    """``runs``: repetitions of the two steps with seeds seed, seed + 1, ...;
    ``divisors``: each run's multilevel levels."""

    runs: int = 10
    divisors: tuple[int, ...] = DEFAULT_DIVISORS


def run_two_step(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """``runs`` runs of the two steps."""
    s = context.options(TwoStepSettings)
    d, light, levels = problem.design, problem.light, tuple(s.divisors)
    return _swept(context, lambda **kw: two_step(d, light, s.runs, divisors=levels, **kw))


_SWEEP = {"finds_front": always_front, "progress_label": "objective of each sub-run"}
EPSILON = MethodSpec(
    "epsilon",
    "Epsilon-constraint front",
    run_epsilon,
    EpsilonSettings,
    count_setting=("Front points", "epsilon_count"),
    **_SWEEP,
)
"""Epsilon-constraint sweep (paper eq. 10): least power for each light-power bound."""
TWO_STEP = MethodSpec(
    "two_step",
    "Two-step front",
    run_two_step,
    TwoStepSettings,
    count_setting=("Two-step runs", "runs"),
    **_SWEEP,
)
"""Two-step process (paper 5.5): skylights first, then luminaires, ``runs`` seeds."""
