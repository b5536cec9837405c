"""Multi-objective drivers: the epsilon-constraint sweep (paper eq. 10) over the
design's two goals (``fronts.front_pair``: artificial electric power (W, minimised)
against total reflected light power (lm, maximised) in the paper, annual energy (kWh)
against glazing area (m²) on the climate demo, any other pair), and the two-step process
(paper 5.5) over electric power and light power.

Every sub-run's evaluations count towards the sweep's: the range runs and the
two-step's first steps too, each level of a multilevel run (a ``_Tally``). Run as a
method (``run_epsilon``, ``run_two_step``), the stop rule's ``max_evals`` and
``time_limit`` are the sweep's totals: each sub-run gets an even share of what is left
(``_Tally.rule``), so what one leaves unused goes to the next."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from lightinv_core.design.model import Design, Goal
from lightinv_core.design.solution import ParetoFront
from lightinv_core.errors import DesignError
from lightinv_core.goals import goal_spec
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.fronts import (
    CLIMATE,
    LIGHT,
    OBJECTIVES,
    POWER,
    design_goal,
    design_pair,
    front_of,
    front_pair,
    front_refusal,
)
from lightinv_core.optimize.method import (
    MethodSpec,
    RunContext,
    always_front,
    context_of,
    settings_as,
)
from lightinv_core.optimize.multilevel import DEFAULT_DIVISORS, multilevel
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.progress import ProgressFn
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import judged
from lightinv_core.optimize.termination import StopRule
from lightinv_core.sources.types import daylit, electric, source_types

__all__ = [
    "CLIMATE",
    "EPSILON",
    "LIGHT",
    "OBJECTIVES",
    "POWER",
    "TWO_STEP",
    "bounded_range",
    "design_goal",
    "epsilon_constraint",
    "front_of",
    "front_pair",
    "two_step",
]


class _Tally:
    """The light evaluations of a sweep's sub-runs so far (every level of each), and,
    given ``total``, the budgets the sweep shares out: ``plan(runs)`` says how many
    sub-runs will come, ``rule(stop)`` is the next one's stop rule."""

    def __init__(self, total: StopRule | None = None) -> None:
        self.evaluations = 0
        self.total, self.left_runs = total, 1
        self.t0 = time.perf_counter()

    def plan(self, runs: int) -> None:
        """``runs`` sub-runs are still to come."""
        self.left_runs = max(1, runs)

    def rule(self, stop: StopRule) -> StopRule:
        """The next sub-run's stop rule: ``stop`` with an even share of the evaluations
        and seconds left of ``total`` (none given: ``stop`` as it is)."""
        t = self.total
        if t is None:
            return stop
        n = max(1, self.left_runs)
        self.left_runs = n - 1
        if t.max_evals is not None:
            stop = replace(stop, max_evals=max(1, (t.max_evals - self.evaluations) // n))
        if t.time_limit is not None:
            left = t.time_limit - (time.perf_counter() - self.t0)
            stop = replace(stop, time_limit=max(0.0, left / n))
        return stop


def _solve(
    design: Design,
    light: LightModel,
    context: RunContext,
    divisors,
    run: tuple[int, int] = (0, 1),
    method: str = "",
    epsilon=(),
    info: dict | None = None,
    tally: _Tally | None = None,
):
    """One (multilevel) VNS sub-run of a sweep, with the context's seed, stop rule, start
    and hooks (its snapshots tagged as ``run``), and its solution judged on every patch;
    its evaluations (every level's) are added to ``tally``."""
    problem = DesignProblem(design, light, epsilon=epsilon)
    stop = context.stop if tally is None else tally.rule(context.stop)
    sub = context.but(progress=_tagged(context.progress, *run), stop=stop)
    res, _ = multilevel(problem, sub, divisors)
    if tally is not None:
        tally.evaluations += res.evaluations
    sol = judged(problem, res, method, context.seed, **(info or {})).best
    # A sweep's points carry no convergence history (each is one of many runs).
    return res, replace(sol, info=sol.info.but(history=()))


def _tagged(progress: ProgressFn | None, run: int, runs: int) -> ProgressFn | None:
    """``progress`` with each snapshot marked as run ``run`` of ``runs``."""
    if progress is None:
        return None
    return lambda p: progress(replace(p, run=run, runs=runs))


def bounded_range(
    design: Design,
    light: LightModel,
    pair=OBJECTIVES,
    divisors=(1,),
    runs: int = 2,
    context: RunContext | None = None,
    tally: _Tally | None = None,
    **given: Any,
) -> tuple[float, float, np.ndarray]:
    """(low, high) of the bounded objective ``pair[1]`` over the front: its value at the
    best feasible layout of ``pair[0]`` and its own best feasible value; and the layout
    at the low end. Two VNS runs with the context's seed, stop rule (default 5,000
    evaluations) and hooks, reported as runs 0 and 1 of ``runs``."""
    c = context_of(context or RunContext(stop=StopRule(max_evals=5000)), given)
    first, second = design_goal(design, pair[0]), design_goal(design, pair[1])
    own_goals, other_goals = (second, first), (first, second)
    own_design, other_design = replace(design, goals=own_goals), replace(design, goals=other_goals)
    r_own, own = _solve(own_design, light, c, divisors, (0, runs), "epsilon", tally=tally)
    r_other, other = _solve(other_design, light, c, divisors, (1, runs), "epsilon", tally=tally)
    a, b = own.objectives[pair[1]], other.objectives[pair[1]]
    return min(a, b), max(a, b), (r_own.x if a <= b else r_other.x)


def epsilon_constraint(
    design: Design,
    light: LightModel,
    epsilons: list[float] | None = None,
    count: int = 12,
    divisors=(1,),
    context: RunContext | None = None,
    tally: _Tally | None = None,
    **given: Any,
) -> ParetoFront:
    """Minimise the design's first front goal subject to a bound epsilon on its second
    (``front_pair``): electric power subject to light power >= epsilon (lm) in the
    paper, annual energy subject to glazing area <= epsilon (m²) for the climate pair —
    warm-starting each run from the previous best; returns the non-dominated front.
    Every sub-run's evaluations are added to ``tally``.

    The context (or its fields ``given`` as keywords) gives the seed (run q uses seed +
    q), each run's stop rule, ``cancel``, ``on_solution`` (each point as it is found)
    and ``progress`` (every VNS snapshot, tagged with its run: the two range runs first
    when ``epsilons`` is None).
    """
    c = context_of(context, given)
    pair = front_pair(design)
    first, x = 0, None
    if tally is not None:
        tally.plan(count + 2 if epsilons is None else len(epsilons))
    if epsilons is None:
        lo, hi, x_lo = bounded_range(design, light, pair, divisors, count + 2, c, tally)
        epsilons = list(np.linspace(lo, hi, count))
        first = 2
        if not goal_spec(pair[1]).maximise:
            # The least value of a minimised bound leaves a band only the tolerance
            # wide (glazing area at its rule's minimum): start where it was reached.
            x = x_lo
    mop = replace(design, goals=(design_goal(design, pair[0]), design_goal(design, pair[1])))
    solutions = []
    for q, eps in enumerate(epsilons):
        if c.cancel is not None and c.cancel():
            break
        res, sol = _solve(
            mop,
            light,
            c.but(seed=c.seed + q, x0=x),
            divisors,
            (first + q, first + len(epsilons)),
            "epsilon",
            epsilon=((pair[1], float(eps)),),
            info={"epsilon": float(eps)},
            tally=tally,
        )
        solutions.append(sol)
        x = res.x
        if c.on_solution is not None:
            c.on_solution(sol)
    return front_of(solutions, "epsilon-constraint", pair)


def two_step(
    design: Design,
    light: LightModel,
    runs: int = 10,
    divisors=(1,),
    context: RunContext | None = None,
    tally: _Tally | None = None,
    **given: Any,
) -> ParetoFront:
    """Step 1: daylit sources alone, most natural light, under their geometric rules
    only. Step 2: those fixed, the electric sources minimise electric power under every
    rule and intention. Repeated with ``runs`` seeds (seed, seed + 1, ...: the context's,
    or its fields ``given`` as keywords, with its stop rule and hooks; each point goes
    to ``on_solution``); returns the non-dominated front. Both steps' evaluations are
    added to ``tally``."""
    c = context_of(context, given)
    if tally is not None:
        tally.plan(2 * runs)
    sky, lum = daylit(design.sources), electric(design.sources)
    sky_names = {s.name for s in sky}
    daylit_kinds = tuple(t.kind for t in source_types() if t.daylit)
    step1 = Design(
        sky,
        (Goal(LIGHT, daylit_kinds),),
        tuple(r for r in design.rules if set(r.sources) <= sky_names),
        daylight=design.daylight,
        penalty_power=design.penalty_power,
    )
    solutions = []
    for r in range(runs):
        if c.cancel is not None and c.cancel():
            break
        seeded = c.but(seed=c.seed + r, x0=None)
        step = (2 * r, 2 * runs)
        _, first = _solve(step1, light, seeded, divisors, step, "two_step", tally=tally)
        fixed = tuple(replace(s, free=()) for s in first.sources)
        step2 = Design(
            (*fixed, *lum),
            (Goal(POWER), Goal(LIGHT)),
            tuple(r for r in design.rules if not set(r.sources) <= sky_names),
            design.intentions,
            daylight=design.daylight,
            penalty_power=design.penalty_power,
        )
        _, sol = _solve(
            step2,
            light,
            seeded,
            divisors,
            (2 * r + 1, 2 * runs),
            "two_step",
            info={"step1_light_power": first.objectives[LIGHT]},
            tally=tally,
        )
        solutions.append(sol)
        if c.on_solution is not None:
            c.on_solution(sol)
    return front_of(solutions, "two-step")


def _front_result(
    front: ParetoFront, cancelled: bool, seconds: float, evaluations: int
) -> OptimizationResult:
    """A sweep's outcome: its front, the first point as ``best``, and the evaluations of
    every sub-run."""
    best = front.solutions[0] if front.solutions else None
    status = "cancelled" if cancelled else ("feasible" if best is not None else "infeasible")
    return OptimizationResult(status, best, front, evaluations, seconds)


def _swept(
    context: RunContext, sweep: Callable[[RunContext, _Tally], ParetoFront]
) -> OptimizationResult:
    """A sweep run with the context's seed, stop rule and hooks: each point as it is
    found goes to ``on_solution``, every VNS snapshot to ``progress``."""
    t0 = time.perf_counter()
    tally = _Tally(context.stop)  # the stop rule's budgets are the sweep's totals
    front = sweep(context.but(x0=None), tally)
    cancelled = context.cancel is not None and context.cancel()
    return _front_result(front, cancelled, time.perf_counter() - t0, tally.evaluations)


def epsilon_run_goal(design: Design, settings: Any, run: int) -> str:
    """The goal sub-run ``run`` of an epsilon sweep minimises: with automatic bounds, the
    first range run the bounded goal, every other run the swept one."""
    pair = front_pair(design)
    automatic = not settings_as(EpsilonSettings, settings).epsilons
    return str(pair[1] if automatic and run == 0 else pair[0])


def two_step_run_goal(design: Design, settings: Any, run: int) -> str:
    """The goal sub-run ``run`` of the two-step process optimises: the skylights' light
    power (lm) in a first step (even runs), electric power (W) in a second."""
    return str(POWER if run % 2 else LIGHT)


def _refuse(why: str | None) -> None:
    if why is not None:
        raise DesignError(why)


def epsilon_refusal(design: Design) -> str | None:
    """Why the epsilon-constraint sweep cannot run on ``design`` (``front_refusal``)."""
    return front_refusal(design, "The epsilon-constraint sweep")


def two_step_refusal(design: Design) -> str | None:
    """Why the two-step process cannot run on ``design``: it trades electric power
    against light power, skylights first, then luminaires."""
    what = "The two-step process"
    if design_pair(design) != tuple(map(str, OBJECTIVES)):
        return (
            f"{what} trades electric power against reflected light power, and they are "
            "not the design's goals: choose both (Design > Goals), or another method"
        )
    if not daylit(design.sources) or not electric(design.sources):
        return f"{what} places skylights first, then luminaires: the design needs both"
    return None


@dataclass(frozen=True)
class EpsilonSettings:
    """``epsilons``: the bounds to sweep (None: ``epsilon_count`` automatic ones);
    ``divisors``: each run's multilevel levels."""

    epsilons: tuple[float, ...] | None = None
    epsilon_count: int = 12
    divisors: tuple[int, ...] = DEFAULT_DIVISORS


def run_epsilon(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """The epsilon-constraint sweep over ``epsilons`` or ``epsilon_count`` bounds."""
    _refuse(epsilon_refusal(problem.design))
    s = context.options(EpsilonSettings)
    eps = list(s.epsilons) if s.epsilons else None
    d, light, levels = problem.design, problem.light, tuple(s.divisors)
    return _swept(
        context, lambda c, t: epsilon_constraint(d, light, eps, s.epsilon_count, levels, c, t)
    )


@dataclass(frozen=True)
class TwoStepSettings:
    """``runs``: repetitions of the two steps with seeds seed, seed + 1, ...;
    ``divisors``: each run's multilevel levels."""

    runs: int = 10
    divisors: tuple[int, ...] = DEFAULT_DIVISORS


def run_two_step(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """``runs`` runs of the two steps."""
    _refuse(two_step_refusal(problem.design))
    s = context.options(TwoStepSettings)
    d, light, levels = problem.design, problem.light, tuple(s.divisors)
    return _swept(context, lambda c, t: two_step(d, light, s.runs, levels, c, t))


_SWEEP = {"finds_front": always_front, "progress_label": "objective of each sub-run"}
EPSILON = MethodSpec(
    "epsilon",
    "Epsilon-constraint front",
    run_epsilon,
    EpsilonSettings,
    count_setting=("Front points", "epsilon_count"),
    refusal=epsilon_refusal,
    run_goal=epsilon_run_goal,
    **_SWEEP,
)
"""Epsilon-constraint sweep (paper eq. 10): the least of the design's first front goal
for each bound on the second (least power for each light-power bound)."""
TWO_STEP = MethodSpec(
    "two_step",
    "Two-step front",
    run_two_step,
    TwoStepSettings,
    count_setting=("Two-step runs", "runs"),
    refusal=two_step_refusal,
    run_goal=two_step_run_goal,
    **_SWEEP,
)
"""Two-step process (paper 5.5): skylights first, then luminaires, ``runs`` seeds."""
