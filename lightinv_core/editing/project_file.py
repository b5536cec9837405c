"""The open project as a file: new, open, save, the dirty flag, run settings, undo.

``ProjectFile`` is the document's concern for the project as a whole (a mixin over
``state.DocumentState``); ``blank_project`` and ``obj_project`` make new projects.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from lightinv_core.design.model import Design, Goal
from lightinv_core.editing import results as _results
from lightinv_core.editing.state import DocumentState
from lightinv_core.kinds import GoalKind
from lightinv_core.project import Project, SceneSpec, load_project, save_project

NEW_PROJECT_GOAL = GoalKind.MIN_ELECTRIC_POWER
"""The goal of a new project (the user adds sources and intentions, then runs)."""


class ProjectFile(DocumentState):
    """Open, save, flag unsaved work, change run settings, step back and forth."""

    def open(self, path: str | Path) -> None:
        """Open a project file (ProjectError on a bad file; nothing changes then)."""
        path = Path(path)
        self.set_project(load_project(path), path)

    def new_from_scene(self, name: str, resolution: float | None = None) -> None:
        """A new, unsaved project on a built-in scene."""
        self.set_project(blank_project(name, resolution))

    def save(self, path: str | Path | None = None) -> Path:
        """Save atomically to ``path`` (default: where it came from); ValueError when the
        project has no file yet."""
        path = Path(path) if path is not None else self.path
        if path is None:
            raise ValueError("no file name yet: use Save As")
        save_project(self._project, path)
        self.path, self.dirty, self._saved = path, False, self._project
        self._emit_path()
        return path

    def set_optimizer(self, **fields) -> None:
        """Change run settings (method, seed, max_evals, time_limit, ...); ProjectError on
        a bad value, leaving the project unchanged."""
        opt = replace(self._project.optimizer, **fields)
        if opt != self._project.optimizer:
            before = self._project
            self._project = replace(self._project, optimizer=opt)
            self.mark_dirty()
            self._edited("run settings", before)

    def restore(self, project: Project, source: Project | None = None) -> None:
        """Make ``project``, an earlier (undo) or later (redo) state of the open one,
        current: its design, run settings and drawn zones. ``source`` is the state the
        step goes from (undo: the project after the edit): the results take only that
        step's change (a deleted run comes back), so runs made and results pinned since
        stay; without it the results stay as they are. A change of drawn zones re-meshes
        the scene (the operator is built again or loaded from the cache); anything else
        just relights. Not itself an edit."""
        project = _results.carried_over(self._project, source or project, project)
        if project.scene != self._project.scene:
            self.set_project(project, self.path, rebuild=True)
        else:
            self._project, self._problem, self.shown, self._preview = project, None, None, None
            names = [x.name for x in project.design.sources]
            if self.current_source not in names:
                self.current_source = names[0] if names else None
            self._emit_design()
            self._emit_results()
            self._relight()
        # Undoing every edit since the file was opened or saved leaves nothing unsaved
        # (unless a run or a pin since is carried over: then the project differs).
        self.dirty = not self.is_saved(self._project)
        self._emit_path()

    def mark_unsaved(self) -> None:
        """Flag work that no file holds (recovered from an autosave): unsaved until
        saved, even once every later edit is undone."""
        self._saved = None
        self.mark_dirty()


def blank_project(scene_name: str, resolution: float | None = None) -> Project:
    """A new project on a built-in scene: no sources yet, goal least electric power."""
    return Project(
        name=f"New {scene_name} project",
        scene=SceneSpec(builtin=scene_name, resolution=resolution),
        design=Design((), (Goal(NEW_PROJECT_GOAL),)),
    )


def obj_project(path: str | Path, **options) -> Project:
    """A new project on a model file, OBJ, glTF/GLB, PLY or IFC (groups, materials and
    zones from the file); ``options`` are the scene's import settings: ``scale`` (metres
    per model unit), ``up`` ("z" or "y"; None: the format's), ``materials`` (a
    reflectance JSON file), ``resolution`` (m), ``skip_degenerate``, ``group_by`` (glTF:
    "node" or "material") (ProjectError on a bad value)."""
    if options.get("materials"):
        options["materials"] = str(Path(options["materials"]).resolve())
    return Project(
        name=Path(path).stem,
        scene=SceneSpec(obj=str(Path(path).resolve()), **options),
        design=Design((), (Goal(NEW_PROJECT_GOAL),)),
    )
