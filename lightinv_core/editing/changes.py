"""What each event of the editing model carries: one frozen payload per event.

A view connected to an event (events.py) receives the new state of what changed, so it
need not read the model back: the new scene and patches, the light model once built,
the design and which of its fields changed, the picked patches, the light shown, the
file state, the results. Payloads are snapshots: the model's later edits make new ones
(the selection array is a read-only copy).
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.light.field import LightField
from lightinv_core.light.model import LightModel
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.project import OptimizerSettings
from lightinv_core.project.results import RunRecord
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches

CURRENT_SOURCE = "current_source"
"""The name ``DesignChanged.changed`` gives a change of the current source (not a field
of the design, but the design panels show it)."""


@dataclass(frozen=True, eq=False)
class SceneChanged:
    """A scene was opened, or re-meshed for an edit of the same project (``rebuilt``: a
    drawn zone, a reflectance, an undo; the view may keep its camera). The operator and
    the light are gone until ``OperatorChanged``."""

    scene: Scene
    patches: Patches
    rebuilt: bool


@dataclass(frozen=True, eq=False)
class OperatorChanged:
    """A radiosity operator of the patches was attached: light is available."""

    operator: RadiosityOperator
    light: LightModel


@dataclass(frozen=True)
class DesignChanged:
    """The design or the current source changed.

    ``changed``: the names of the ``Design`` fields that differ from the design of the
    previous design event ("sources", "rules", "intentions", "goals", "daylight", ...),
    plus ``CURRENT_SOURCE`` when the current source changed; every field for a project
    just opened. ``label``: the edit's name for the undo history ("add source L1"), ""
    when the change is not an edit (opening, undo, choosing the current source).
    """

    design: Design
    current_source: str | None
    changed: frozenset[str]
    label: str = ""


@dataclass(frozen=True, eq=False)
class SelectionChanged:
    """The picked patches: ``patches`` (k,) int64, sorted, unique, read-only."""

    patches: np.ndarray


@dataclass(frozen=True, eq=False)
class LightingChanged:
    """The light shown: ``field`` (lux and exitance on every patch), whether it is a
    previewed layout's (a running best's) rather than the design's, and how long the
    relight took (ms)."""

    field: LightField
    previewing: bool
    eval_ms: float


@dataclass(frozen=True)
class PathChanged:
    """The file state: where the project is saved (None: not yet), whether it has
    unsaved changes, its name and its run settings (a change of them marks it dirty)."""

    path: Path | None
    dirty: bool
    name: str
    optimizer: OptimizerSettings


@dataclass(frozen=True)
class ResultsChanged:
    """The results: the run history (oldest first), the saved results outside it and
    their front, the run browsed (a number, ``results.SAVED`` or ``results.ALL``) and
    the result loaded into the design (None once the design is edited)."""

    runs: tuple[RunRecord, ...]
    saved: tuple[Solution, ...]
    saved_front: ParetoFront | None
    browsed_run: int | None
    shown: Solution | None


def design_changes(before: Design | None, after: Design) -> frozenset[str]:
    """The names of the fields in which ``after`` differs from ``before`` (every field
    when there is no ``before``)."""
    names = [f.name for f in fields(Design)]
    if before is None:
        return frozenset(names)
    # Edits share unchanged fields with the design they came from: compare by identity
    # first, by value only when needed.
    return frozenset(
        n
        for n in names
        if getattr(before, n) is not getattr(after, n) and getattr(before, n) != getattr(after, n)
    )


def selection_snapshot(patch_ids: np.ndarray) -> np.ndarray:
    """A read-only copy of the picked patch ids, for a payload."""
    out = np.array(patch_ids, dtype=np.int64)
    out.setflags(write=False)
    return out
