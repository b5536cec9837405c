"""Multi-objective drivers: the epsilon-constraint sweep (paper eq. 10) and the
two-step process (paper 5.5), both over artificial electric power (W, minimised)
and total reflected light power (lm, maximised)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from lightinv_core.design.model import Design, Goal
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.optimize.multilevel import multilevel
from lightinv_core.optimize.pareto import non_dominated
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.vns import Progress, StopRule
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches

ProgressFn = Callable[[Progress], None]

POWER, LIGHT = "min_electric_power", "max_light_power"
OBJECTIVES = (POWER, LIGHT)


def _light_goal(design: Design) -> Goal:
    return next((g for g in design.goals if g.kind == LIGHT), Goal(LIGHT))


def front_of(solutions: list[Solution], method: str) -> ParetoFront:
    """The non-dominated feasible solutions (power minimised, light maximised), each
    objective point once."""
    feasible = [s for s in solutions if s.feasible]
    if feasible:
        F = np.array([[s.objectives[POWER], -s.objectives[LIGHT]] for s in feasible])
        keep = non_dominated(F)
        # Two epsilon runs can end on the same layout (a bound below the previous
        # optimum): a front lists each point once, the first run that found it.
        _, first = np.unique(F, axis=0, return_index=True)
        keep &= np.isin(np.arange(len(F)), first)
        order = np.argsort(F[:, 0], kind="stable")
        front = tuple(feasible[i] for i in order if keep[i])
    else:
        front = ()
    return ParetoFront(OBJECTIVES, front, method, tuple(solutions))


def _solve(
    design: Design,
    scene,
    patches,
    op,
    seed: int,
    stop: StopRule,
    divisors,
    epsilon=(),
    x0=None,
    cancel=None,
    vns_progress: ProgressFn | None = None,
    run: tuple[int, int] = (0, 1),
):
    problem = DesignProblem(design, scene, patches, op, epsilon=epsilon)
    tagged = _tagged(vns_progress, *run)
    res, _ = multilevel(
        problem, divisors, seed=seed, stop=stop, x0=x0, cancel=cancel, progress=tagged
    )
    sol = problem.solution(
        res.x,
        {
            "seed": seed,
            "evaluations": res.evaluations,
            "seconds": res.seconds,
            "status": res.status,
        },
    )
    return problem, res, sol


def _tagged(progress: ProgressFn | None, run: int, runs: int) -> ProgressFn | None:
    """``progress`` with each snapshot marked as run ``run`` of ``runs``."""
    if progress is None:
        return None
    return lambda p: progress(replace(p, run=run, runs=runs))


def light_power_range(
    design: Design,
    scene: Scene,
    patches: Patches,
    op: RadiosityOperator,
    seed: int = 0,
    stop: StopRule | None = None,
    divisors=(1,),
    cancel: Callable[[], bool] | None = None,
    vns_progress: ProgressFn | None = None,
    runs: int = 2,
) -> tuple[float, float]:
    """(light power of the least-power feasible layout, largest feasible light power), lm:
    the interval the epsilon sweep covers when none is given. Its two VNS runs report as
    runs 0 and 1 of ``runs``."""
    stop = stop or StopRule(max_evals=5000)
    light = _light_goal(design)
    common = (scene, patches, op, seed, stop, divisors)
    _, _, hi = _solve(
        replace(design, goals=(light, Goal(POWER))),
        *common,
        cancel=cancel,
        vns_progress=vns_progress,
        run=(0, runs),
    )
    _, _, lo = _solve(
        replace(design, goals=(Goal(POWER), light)),
        *common,
        cancel=cancel,
        vns_progress=vns_progress,
        run=(1, runs),
    )
    return lo.objectives[LIGHT], hi.objectives[LIGHT]


def epsilon_constraint(
    design: Design,
    scene: Scene,
    patches: Patches,
    op: RadiosityOperator,
    epsilons: list[float] | None = None,
    count: int = 12,
    seed: int = 0,
    stop: StopRule | None = None,
    divisors=(1,),
    progress: Callable[[int, int, Solution], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    vns_progress: ProgressFn | None = None,
) -> ParetoFront:
    """Minimise electric power subject to light power >= epsilon for each epsilon (lm),
    warm-starting each run from the previous best; returns the non-dominated front.

    ``progress(q, total, solution)`` follows the sweep; ``vns_progress`` gets every VNS
    snapshot, tagged with its run (the two range runs first when ``epsilons`` is None).
    """
    stop = stop or StopRule(max_evals=20000)
    first = 0
    if epsilons is None:
        lo, hi = light_power_range(
            design,
            scene,
            patches,
            op,
            seed,
            stop=stop,
            divisors=divisors,
            cancel=cancel,
            vns_progress=vns_progress,
            runs=count + 2,
        )
        epsilons = list(np.linspace(lo, hi, count))
        first = 2
    mop = replace(design, goals=(Goal(POWER), _light_goal(design)))
    solutions, x = [], None
    for q, eps in enumerate(epsilons):
        if cancel is not None and cancel():
            break
        _, res, sol = _solve(
            mop,
            scene,
            patches,
            op,
            seed + q,
            stop,
            divisors,
            epsilon=((LIGHT, float(eps)),),
            x0=x,
            cancel=cancel,
            vns_progress=vns_progress,
            run=(first + q, first + len(epsilons)),
        )
        sol.info["epsilon"] = float(eps)
        solutions.append(sol)
        x = res.x
        if progress is not None:
            progress(q + 1, len(epsilons), sol)
    return front_of(solutions, "epsilon-constraint")


def two_step(
    design: Design,
    scene: Scene,
    patches: Patches,
    op: RadiosityOperator,
    runs: int = 10,
    seed: int = 0,
    stop: StopRule | None = None,
    divisors=(1,),
    progress: Callable[[int, int, Solution], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    vns_progress: ProgressFn | None = None,
) -> ParetoFront:
    """Step 1: skylights alone, most natural light, under their geometric rules only.
    Step 2: skylights fixed, luminaires minimise electric power under every rule and
    intention. Repeated with ``runs`` seeds; returns the non-dominated front."""
    stop = stop or StopRule(max_evals=20000)
    sky = tuple(s for s in design.sources if s.kind == "skylight")
    lum = tuple(s for s in design.sources if s.kind == "luminaire")
    sky_names = {s.name for s in sky}
    step1 = Design(
        sky,
        (Goal(LIGHT, ("skylight",)),),
        tuple(r for r in design.rules if set(r.sources) <= sky_names),
        daylight=design.daylight,
        penalty_power=design.penalty_power,
    )
    solutions = []
    for r in range(runs):
        if cancel is not None and cancel():
            break
        common = (scene, patches, op, seed + r, stop, divisors)
        hooks = {"cancel": cancel, "vns_progress": vns_progress}
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
        _, _, sol = _solve(step2, *common, **hooks, run=(2 * r + 1, 2 * runs))
        sol.info["step1_light_power"] = first.objectives[LIGHT]
        solutions.append(sol)
        if progress is not None:
            progress(r + 1, runs, sol)
    return front_of(solutions, "two-step")
