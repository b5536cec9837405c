"""The results of a project as the user browses them: labels, the list, pinning.

Pure functions over a ``Project``: the project's ``solutions`` hold each run's best
(pinned ones first, kept across runs) and ``pareto`` the last sweep's front; a result is
identified by its variable vector ``x``.
"""

from __future__ import annotations

from dataclasses import replace

from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.project import Project


def result_label(s: Solution) -> str:
    """A short name for a result: which run found it."""
    info = s.info
    if info.epsilon is not None:
        return f"epsilon {info.epsilon:,.0f} lm"
    if info.method == "nsga2" and "min_electric_power" in s.objectives:
        return f"NSGA-II {s.objectives['min_electric_power']:,.1f} W"
    if info.step1_light_power is not None:
        return f"two-step seed {'?' if info.seed is None else info.seed}"
    if info.seed is not None:
        return f"seed {info.seed}"
    return "result"


def pinned_results(project: Project) -> list[Solution]:
    """The pinned results, in stored order."""
    return [s for s in project.solutions if s.info.pinned]


def front_candidates(project: Project) -> tuple[Solution, ...]:
    """The last sweep's candidates (every point it found), or its front if it kept none."""
    front = project.pareto
    return () if front is None else (front.candidates or front.solutions)


def on_front(project: Project, solution: Solution) -> bool:
    """Whether ``solution`` is on the project's Pareto front."""
    front = project.pareto
    return front is not None and any(s.x == solution.x for s in front.solutions)


def with_results(
    project: Project, solutions: tuple[Solution, ...], pareto: ParetoFront | None
) -> Project:
    """``project`` holding a new run's results: the pinned results of earlier runs are
    kept ahead of ``solutions``; ``pareto`` replaces the front."""
    pinned = tuple(pinned_results(project))
    return replace(project, solutions=pinned + tuple(solutions), pareto=pareto)


def browse(project: Project) -> list[tuple[str, Solution]]:
    """Every result to browse, labelled: the project's solutions (pinned first, as
    stored), then the front's candidates that are not also pinned."""
    out = [(result_label(s), s) for s in project.solutions]
    pinned = {s.x for s in pinned_results(project)}
    out += [(result_label(s), s) for s in front_candidates(project) if s.x not in pinned]
    return out


def with_pin(project: Project, solution: Solution, pinned: bool) -> tuple[Project, Solution]:
    """``project`` with ``solution`` pinned (or unpinned), and the stored copy. An
    unpinned point of the front leaves the solutions: it is shown through the front."""
    new = replace(solution, info=solution.info.but(pinned=pinned))
    others = tuple(s for s in project.solutions if s.x != solution.x)
    keep = pinned or not any(s.x == solution.x for s in front_candidates(project))
    return replace(project, solutions=others + ((new,) if keep else ())), new
