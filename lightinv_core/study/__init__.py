"""Studies of a scene or a project, end to end.

- a project's optimisation: scene -> operator -> problem -> method (``prepare``,
  ``solve``, ``solve_seeds``, here), used by ``lightinv-cli solve`` and the GUI's run
  panel; everything long takes ``progress`` and ``cancel`` callbacks and a cancelled
  run keeps its best solution;
- a forward simulation: ``simulate(SimulationSpec) -> SimulationResult``
  (``study.simulation``: static light, the design sky, the weather year and dimming;
  ``study.annual``: the year on a work plane), used by ``lightinv-cli simulate``;
- the light of one solution of a project: ``solution_light(prepared, design,
  solution)`` (``study.solution_light``), used by the report and ``lightinv-cli solve``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import cached_property

from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.errors import DesignError
from lightinv_core.light.model import LightModel
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.optimize.method import RunContext, SolutionFn
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.progress import CancelFn, ProgressFn
from lightinv_core.optimize.registry import finds_front, get_method
from lightinv_core.optimize.result import HistoryRow
from lightinv_core.optimize.termination import StopRule
from lightinv_core.project import Project
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches, mesh_patches
from lightinv_core.study.annual import GridYear
from lightinv_core.study.simulation import SimulationResult, SimulationSpec, simulate
from lightinv_core.study.solution_light import SolutionLight, solution_light

__all__ = [
    "DesignProblem",
    "GridYear",
    "Prepared",
    "RunResult",
    "SimulationResult",
    "SimulationSpec",
    "SolutionLight",
    "prepare",
    "simulate",
    "solution_light",
    "solve",
    "solve_seeds",
    "stop_rule",
]


@dataclass
class Prepared:
    """A project's scene, patches and operator, ready to optimise."""

    scene: Scene
    patches: Patches
    operator: RadiosityOperator
    from_cache: bool
    seconds: float

    @cached_property
    def light(self) -> LightModel:
        """The light model of the scene (every light the project shows comes from it)."""
        return LightModel(self.scene, self.patches, self.operator)


@dataclass
class RunResult:
    """The outcome of ``solve``: the best solution (single objective) or the front."""

    status: str
    best: Solution | None
    pareto: ParetoFront | None
    evaluations: int
    seconds: float
    precompute_seconds: float
    history: list[HistoryRow]


def prepare(
    project: Project,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    warn: Callable[[str], None] | None = None,
    scheduler: str | None = None,
) -> Prepared:
    """Load the scene and build (or load from the cache) its radiosity operator; a build
    runs on the Dask cluster at ``scheduler`` (``tcp://host:port``) when one is given."""
    t0 = time.perf_counter()
    base = project.path.parent if project.path is not None else None
    scene = project.scene.load(base)
    patches = mesh_patches(scene)
    got = get_operator(
        patches,
        project.operator,
        progress=progress,
        cancel=cancel,
        warn=warn,
        scheduler=scheduler,
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
    progress: ProgressFn | None = None,
    cancel: CancelFn | None = None,
    on_solution: SolutionFn | None = None,
    precompute: Callable[[float], None] | None = None,
) -> RunResult:
    """Run the project's optimisation method (found in the registry by name).

    ``progress`` gets every snapshot (for a sweep, each tagged with its sub-run);
    ``on_solution`` gets each point of a multi-objective sweep as it is found (the GUI
    draws the front live and autosaves it). A cancelled run returns status "cancelled"
    with the best solution (or the front) found so far. ``precompute(fraction)`` reports
    the luminaire arrays' responses, computed before the run.
    """
    o = project.optimizer
    seed = o.seed if seed is None else seed
    method = get_method(o.method)
    problem = DesignProblem(project.design, prepared.light, progress=precompute, cancel=cancel)
    context = RunContext(
        settings=method.settings_from(o),
        stop=stop_rule(project, max_evals, time_limit),
        seed=seed,
        progress=progress,
        cancel=cancel,
        on_solution=on_solution,
    )
    r = method.run(problem, context)
    return RunResult(
        r.status, r.best, r.front, r.evaluations, r.seconds, prepared.seconds, list(r.history)
    )


def solve_seeds(
    project: Project,
    prepared: Prepared,
    seeds: list[int],
    max_evals: int | None = None,
    time_limit: float | None = None,
    progress: ProgressFn | None = None,
    cancel: CancelFn | None = None,
    on_result: Callable[[RunResult], None] | None = None,
    precompute: Callable[[float], None] | None = None,
) -> list[RunResult]:
    """The same single-objective problem run once per seed (paper experiment 4: how much
    the answers vary). ``progress`` snapshots are tagged with the run index; a cancel
    ends the current run (its best kept) and skips the rest."""
    if finds_front(project.optimizer.method, project.design):
        raise DesignError(
            f"runs with several seeds take one best layout; {project.optimizer.method!r} "
            "finds a front for this design (it already makes several runs or points)"
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
        res = solve(
            project, prepared, seed, max_evals, time_limit, tagged, cancel, precompute=precompute
        )
        results.append(res)
        if on_result is not None:
            on_result(res)
    return results
