"""Which solution a report is about, and its light on every patch.

The light comes from ``study.solution_light`` (the project's ``LightModel``) with the
solution's own sources (as saved: tied rules already applied), so solutions whose
source order or subset differs from the design's (two-step fronts) are lit correctly;
its luminaire arrays add their light with every luminaire placed exactly.
"""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.design.solution import Solution
from lightinv_core.errors import LightInvError
from lightinv_core.light.field import LightField
from lightinv_core.project import Project


@dataclass(frozen=True)
class Chosen:
    """The solution a report shows and where it came from (``label``: "saved solution 1
    of 2", "Pareto front solution 3 of 5", "given solution")."""

    solution: Solution
    label: str
    pareto_index: int | None


def choose_solution(project: Project, solution: Solution | None = None) -> Chosen:
    """``solution`` if given, else the project's first saved solution, else the first of
    its Pareto front, else the same of its newest run (the window's run history); a
    ``LightInvError`` when the project holds no result."""
    front = project.pareto.solutions if project.pareto is not None else ()
    if solution is None and not project.solutions and not front and project.runs:
        run = project.runs[-1]
        found = run.solutions or (run.pareto.solutions if run.pareto is not None else ())
        if found:
            where = "front point" if not run.solutions else "best"
            label = f"run {run.number}, {where} 1 of {len(found)}"
            return Chosen(found[0], label, 0 if not run.solutions else None)
    if solution is None:
        if project.solutions:
            solution = project.solutions[0]
        elif front:
            solution = front[0]
        else:
            name = project.path.name if project.path is not None else "PROJECT.json"
            raise LightInvError(
                f"project {project.name!r} holds no solution to report on; run "
                f"'lightinv-cli solve {name} -o RESULT.json' first and report on RESULT.json"
            )
    pareto_index = next((i for i, s in enumerate(front) if s is solution), None)
    if pareto_index is None:
        pareto_index = next((i for i, s in enumerate(front) if s == solution), None)
    saved = next((i for i, s in enumerate(project.solutions) if s is solution), None)
    if saved is not None:
        label = f"saved solution {saved + 1} of {len(project.solutions)}"
    elif pareto_index is not None:
        label = f"Pareto front solution {pareto_index + 1} of {len(front)}"
    else:
        label = "given solution"
    return Chosen(solution, label, pareto_index)


def solution_field(project: Project, prepared, solution: Solution) -> LightField:
    """The light of the solution's sources on every patch (``prepared`` is a
    ``lightinv_core.study.Prepared``)."""
    from lightinv_core.study import solution_light

    return solution_light(prepared, project.design, solution).field
