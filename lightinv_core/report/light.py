"""The light field of a saved solution, and which solution a report is about.

A solution is judged again on every patch with the project's operator: its sources'
exitances are spread over their zones' grids (as in the optimiser) and the illuminance
is H = Phi @ V (lux). Sources are taken by name from the solution itself, so solutions
whose source order differs from the design's (two-step fronts) are evaluated correctly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.design.model import Design, Goal, Intention
from lightinv_core.design.solution import Solution
from lightinv_core.errors import LightInvError
from lightinv_core.project import Project
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.emission import EmissionBuilder


@dataclass(frozen=True)
class Chosen:
    """The solution a report shows and where it came from (``label``: "saved solution 1
    of 2", "Pareto front solution 3 of 5", "given solution")."""

    solution: Solution
    label: str
    pareto_index: int | None


def choose_solution(project: Project, solution: Solution | None = None) -> Chosen:
    """``solution`` if given, else the project's first saved solution, else the first of
    its Pareto front; a ``LightInvError`` when the project holds no result."""
    front = project.pareto.solutions if project.pareto is not None else ()
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


def solution_emission(design: Design, scene, patches: Patches, operator, solution: Solution):
    """V (nz,) float32: the zone-patch exitances (lm/m²) of the solution's sources."""
    sources = tuple(solution.sources)
    if not sources:
        return np.zeros(len(operator.zone_patches), np.float32)
    # A design holding exactly the solution's sources: its emission builder knows their
    # zones (checked against the scene) whatever order or subset the solution has.
    own = Design(sources, (Goal("min_electric_power"),), daylight=design.daylight)
    builder = EmissionBuilder(own, scene, patches, operator)
    rect, flux, filt, _ = builder.decode_sources(sources)
    return builder.matrix(rect, flux, filt)[:, 0]


def solution_field(project: Project, prepared, solution: Solution) -> np.ndarray:
    """H (n,) float64: the illuminance (lux) of every patch under the solution's sources."""
    op, patches = prepared.operator, prepared.patches
    if op.n != patches.n or op.digest != patches.digest():
        raise LightInvError("the radiosity operator was built for another scene")
    V = solution_emission(project.design, prepared.scene, patches, op, solution)
    return np.asarray(op.Phi @ V, dtype=np.float64)


def intention_patches(intention: Intention, patches: Patches) -> np.ndarray:
    """The patch ids an intention bounds (its group, ``"*"``, or its listed patches)."""
    if intention.patches is not None:
        idx = np.unique(np.asarray(intention.patches, dtype=np.int64))
        if idx.min() < 0 or idx.max() >= patches.n:
            raise LightInvError(
                f"intention {intention.name!r}: patch ids must be in 0..{patches.n - 1}"
            )
        return idx
    if intention.group == "*":
        return np.arange(patches.n)
    return patches.group_index(intention.group)
