"""``DocumentState``: what the editing model holds, and the transitions every concern uses.

The concerns of the document (project_file.py, scene_edits.py, source_edits.py,
intent_edits.py, light_view.py, run_history.py) are mixins over this one base: they
read and change the state declared here, and call only the methods defined here
(``set_project``, ``mark_dirty``, ``_set_design``, ``_edited``, ``_relight``, the zone
geometry and the ``_emit_*`` helpers), never one another's. Each change emits the
event of what changed with its payload (changes.py, events.py).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.design.model import Design, Source
from lightinv_core.design.solution import Solution
from lightinv_core.editing import results as _results
from lightinv_core.editing.changes import (
    CURRENT_SOURCE,
    DesignChanged,
    LightingChanged,
    PathChanged,
    ResultsChanged,
    SceneChanged,
    SelectionChanged,
    design_changes,
    selection_snapshot,
)
from lightinv_core.editing.climate import DaylightCache
from lightinv_core.editing.events import Events
from lightinv_core.editing.lighting import ShownLight
from lightinv_core.light.model import LightModel
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.project import OperatorSettings, Project
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches, mesh_patches
from lightinv_core.scene.zone_grid import zone_grid


class DocumentState:
    """The project, its scene, patches and light model, the selection and the results."""

    def __init__(self) -> None:
        self.events = Events()
        self._project: Project | None = None
        self.scene: Scene | None = None
        self.patches: Patches | None = None
        self.operator: RadiosityOperator | None = None
        self.light: LightModel | None = None
        self.selection = np.zeros(0, np.int64)
        self.current_source: str | None = None
        self.path: Path | None = None
        self.dirty = False
        # The project as its file holds it (opened or saved; None: no file holds this
        # work, e.g. recovered from an autosave): back to it by undo, nothing is unsaved.
        self._saved: Project | None = None
        self.shown: Solution | None = None  # the result last loaded into the design
        self._browsed: int | None = _results.ALL  # the run whose results are listed
        self._run_mark = 1  # the next run's number at least: a deleted run's is not reused
        # True while the scene shown was re-meshed for an edit of the same project (a drawn
        # zone, a reflectance, an undo) rather than opened: the view may keep the old light.
        self.rebuilt = False
        self._problem: DesignProblem | None = None
        self._light_shown: ShownLight | None = None  # the light model and the light shown
        self._preview: tuple[Source, ...] | None = None  # a running best's sources, as lit
        self._daylight = DaylightCache()  # one layout's light in every scenario
        # The design and current source the last design event announced: the next one
        # says which fields changed since.
        self._announced: tuple[Design | None, str | None] = (None, None)
        # Called after every edit with (label, project before, project after): the app
        # keeps them for undo and redo (a QUndoStack); ``restore`` puts a state back.
        self.on_edit: Callable[[str, Project, Project], None] | None = None
        # True: the clear glazing's light (``light.clear_build``, seconds to tens of
        # seconds) is built elsewhere, in a worker (the window); until then the light
        # shown leaves it out and what needs it says it is pending (``clear_pending``).
        self.clear_elsewhere = False
        self.clear_note = ""  # why it is still missing, if not being built (a cancel)

    # -- the project --------------------------------------------------------------------------
    @property
    def project(self) -> Project | None:
        """The open project (None before one is opened)."""
        return self._project

    @project.setter
    def project(self, project: Project) -> None:
        # Direct replacement (scripts, tests): no event, but nothing stale is kept.
        self._project, self._problem = project, None

    @property
    def design(self) -> Design:
        """The project's design."""
        return self._project.design

    @property
    def operator_settings(self) -> OperatorSettings:
        """How the operator is built for this project."""
        return self._project.operator

    def set_project(
        self,
        project: Project,
        path: Path | None = None,
        rebuild: bool = False,
        loaded: tuple[Scene, Patches] | None = None,
    ) -> None:
        """Make ``project`` the open one: its scene is loaded and meshed first, so a
        SceneError changes nothing. The operator is dropped (build it again).
        ``rebuild``: the same project re-meshed after an edit (its browsing state stays).
        ``loaded``: its scene and patches, already made (``load_scene_of``; the window
        loads a model file off its GUI thread)."""
        scene, patches = loaded if loaded is not None else load_scene_of(project, path)
        self._project, self.scene, self.patches = project, scene, patches
        self.operator, self.light, self._problem, self._light_shown = None, None, None, None
        self.shown, self._preview, self.rebuilt = None, None, rebuild
        self._daylight.clear()  # it holds the old light model
        if not rebuild:
            self._saved = project
            self._browsed, self._run_mark = _results.ALL, 1
            self._announced = (None, None)  # another project: every field is new
        self.selection = np.zeros(0, np.int64)
        self.current_source = project.design.sources[0].name if project.design.sources else None
        self.path, self.dirty = path, False
        self.events.emit("scene", SceneChanged(scene, patches, rebuild))
        self._emit_design()
        self._emit_selection()
        self._emit_path()
        self._emit_results()

    def mark_dirty(self) -> None:
        """Flag unsaved changes."""
        self.dirty = True
        self._emit_path()

    def is_saved(self, project: Project) -> bool:
        """Whether ``project`` is what the file holds (the state last opened or saved)."""
        if self._saved is None:
            return False
        if project is self._saved:
            return True
        try:
            return bool(project == self._saved)
        except (TypeError, ValueError):  # a field that does not compare (an array): unsaved
            return False

    # -- the design -----------------------------------------------------------------------------
    def _set_design(self, design: Design, label: str = "edit the design") -> None:
        before = self._project
        self._project = replace(self._project, design=design)
        self._problem = None
        self.shown = None  # an edited design is no longer the loaded result
        self.dirty = True
        self._emit_design(label)
        self._relight()
        self._edited(label, before)

    def _edited(self, label: str, before: Project) -> None:
        if self.on_edit is not None and self._project is not before:
            self.on_edit(label, before, self._project)

    def _relight(self) -> None:
        if self._light_shown is not None:
            shown = self._light_shown
            shown.defer_clear = self.clear_elsewhere
            shown.relight(self.design, self._preview)
            self.events.emit(
                "lighting", LightingChanged(shown.field, shown.previewing, shown.last_eval_ms)
            )

    # -- the zones, as the rules need them ------------------------------------------------------
    def zone_kind(self, zone: str) -> str:
        """The kind of source ("skylight", "luminaire", ...) an emitter zone takes."""
        return self.scene.zone(zone).kind

    def zone_size(self, zone: str) -> tuple[float, float]:
        """(width, height) in metres of an emitter zone."""
        if self.light is not None:
            return self.light.zone_size(zone)
        return zone_grid(self.patches, zone).size

    def zone_outline(self, zone: str) -> np.ndarray | None:
        """The polygon (k, 2) in zone metres that sources in ``zone`` must lie inside, or
        None when the zone is its whole rectangle."""
        return self.scene.zone(zone).outline

    # -- events with their payloads -------------------------------------------------------------
    def _emit_design(self, label: str = "") -> None:
        before, source_before = self._announced
        changed = design_changes(before, self.design)
        if before is None or source_before != self.current_source:
            changed |= {CURRENT_SOURCE}
        self._announced = (self.design, self.current_source)
        self.events.emit("design", DesignChanged(self.design, self.current_source, changed, label))

    def _emit_selection(self) -> None:
        self.events.emit("selection", SelectionChanged(selection_snapshot(self.selection)))

    def _emit_path(self) -> None:
        p = self._project
        self.events.emit("path", PathChanged(self.path, self.dirty, p.name, p.optimizer))

    def _emit_results(self) -> None:
        p = self._project
        payload = ResultsChanged(
            p.runs, p.solutions, p.pareto, _results.browsed(p, self._browsed), self.shown
        )
        self.events.emit("results", payload)


def load_scene_of(project: Project, path: Path | None = None) -> tuple[Scene, Patches]:
    """The scene of ``project`` (saved at ``path``: relative model paths are resolved
    from its folder) and its patches; SceneError or ObjImportError on a bad one."""
    scene = project.scene.load(path.parent if path is not None else None)
    return scene, mesh_patches(scene)
