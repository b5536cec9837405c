"""Running a project's optimisation end to end: scene -> operator -> problem -> method.

Used by ``lightinv-cli solve`` and the GUI's run panel; everything long takes
``progress`` and ``cancel`` callbacks and a cancelled run keeps its best solution.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace

from lightinv_core.design.model import DesignError
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.optimize.mop import epsilon_constraint, two_step
from lightinv_core.optimize.multilevel import multilevel
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.vns import Progress, StopRule, vns
from lightinv_core.project import Project
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches, mesh_patches


@dataclass
class Prepared:
    """A project's scene, patches and operator, ready to optimise."""

    scene: Scene
    patches: Patches
    operator: RadiosityOperator
    from_cache: bool
    seconds: float


@dataclass
class RunResult:
    """The outcome of ``solve``: the best solution (single objective) or the front."""

    status: str
    best: Solution | None
    pareto: ParetoFront | None
    evaluations: int
    seconds: float
    precompute_seconds: float
    history: list


def prepare(
    project: Project,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    warn: Callable[[str], None] | None = None,
) -> Prepared:
    """Load the scene and build (or load from the cache) its radiosity operator."""
    t0 = time.perf_counter()
    base = project.path.parent if project.path is not None else None
    scene = project.scene.load(base)
    patches = mesh_patches(scene)
    s = project.operator
    got = get_operator(
        patches,
        rank=s.rank,
        tol=s.tol,
        rays=s.rays,
        seed=s.seed,
        progress=progress,
        cancel=cancel,
        warn=warn,
    )
    return Prepared(scene, patches, got.operator, got.from_cache, time.perf_counter() - t0)


def stop_rule(
    project: Project, max_evals: int | None = None, time_limit: float | None = None
) -> StopRule:
    """The project's stopping rule, with command-line overrides."""
    o = project.optimizer
    return StopRule(
        max_evals=max_evals if max_evals is not None else o.max_evals,
        time_limit=time_limit if time_limit is not None else o.time_limit,
        target=o.target,
        stall=o.stall,
    )


def solve(
    project: Project,
    prepared: Prepared,
    seed: int | None = None,
    max_evals: int | None = None,
    time_limit: float | None = None,
    progress: Callable[[Progress], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    on_solution: Callable[[Solution], None] | None = None,
) -> RunResult:
    """Run the project's optimizer (vns, multilevel, epsilon or two_step).

    ``progress`` gets every VNS snapshot (for epsilon and two-step, each tagged with its
    sub-run); ``on_solution`` gets each point of a multi-objective sweep as it is found
    (the GUI draws the front live and autosaves it). A cancelled run returns status
    "cancelled" with the best solution (or the front) found so far.
    """
    o = project.optimizer
    seed = o.seed if seed is None else seed
    stop = stop_rule(project, max_evals, time_limit)
    args = (project.design, prepared.scene, prepared.patches, prepared.operator)
    t0 = time.perf_counter()
    if o.method in ("epsilon", "two_step"):
        found = None if on_solution is None else (lambda _q, _n, sol: on_solution(sol))
        shared = {
            "seed": seed,
            "stop": stop,
            "divisors": tuple(o.divisors),
            "progress": found,
            "cancel": cancel,
            "vns_progress": progress,
        }
        if o.method == "epsilon":
            epsilons = list(o.epsilons) if o.epsilons else None
            front = epsilon_constraint(*args, epsilons=epsilons, count=o.epsilon_count, **shared)
        else:
            front = two_step(*args, runs=o.runs, **shared)
        cancelled = cancel is not None and cancel()
        evals = sum(int(s.info.get("evaluations", 0)) for s in front.candidates)
        status = "cancelled" if cancelled else ("feasible" if front.solutions else "infeasible")
        return RunResult(
            status,
            front.solutions[0] if front.solutions else None,
            front,
            evals,
            time.perf_counter() - t0,
            prepared.seconds,
            [],
        )
    problem = DesignProblem(*args)
    if o.method == "multilevel":
        level_stop = StopRule(max_evals=o.level_max_evals, target=o.level_target, stall=o.stall)
        res, _ = multilevel(
            problem,
            tuple(o.divisors),
            seed=seed,
            stop=stop,
            level_stop=level_stop,
            trials=o.trials,
            progress=progress,
            cancel=cancel,
        )
    else:
        res = vns(problem, seed=seed, stop=stop, trials=o.trials, progress=progress, cancel=cancel)
    seconds = time.perf_counter() - t0
    # The convergence history travels with the solution (project file, report):
    # rows of (evaluations, best f + P, best P, best primary goal).
    history = [[int(e), float(v), float(p), float(g)] for e, v, p, g in res.history]
    best = problem.solution(
        res.x,
        {
            "seed": seed,
            "evaluations": res.evaluations,
            "seconds": seconds,
            "status": res.status,
            "history": history,
        },
    )
    if res.status == "cancelled":
        status = "cancelled"
    else:
        status = "feasible" if best.feasible else "infeasible"
    return RunResult(status, best, None, res.evaluations, seconds, prepared.seconds, res.history)


SINGLE_METHODS = ("vns", "multilevel")


def solve_seeds(
    project: Project,
    prepared: Prepared,
    seeds: list[int],
    max_evals: int | None = None,
    time_limit: float | None = None,
    progress: Callable[[Progress], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    on_result: Callable[[RunResult], None] | None = None,
) -> list[RunResult]:
    """The same single-objective problem run once per seed (paper experiment 4: how much
    the answers vary). ``progress`` snapshots are tagged with the run index; a cancel
    ends the current run (its best kept) and skips the rest."""
    if project.optimizer.method not in SINGLE_METHODS:
        raise DesignError(
            f"runs with several seeds take a single-objective method {SINGLE_METHODS}; "
            f"{project.optimizer.method!r} already sweeps several runs"
        )
    if not seeds:
        raise DesignError("give at least one seed")
    results: list[RunResult] = []
    for i, seed in enumerate(seeds):
        if results and cancel is not None and cancel():
            break
        tagged = None
        if progress is not None:
            tagged = (lambda j: lambda p: progress(replace(p, run=j, runs=len(seeds))))(i)
        res = solve(project, prepared, seed, max_evals, time_limit, tagged, cancel)
        results.append(res)
        if on_result is not None:
            on_result(res)
    return results
