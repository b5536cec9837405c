"""The open project as the GUI sees it: a Qt object holding the core's data, with signals.

Widgets never keep state of their own: they read the document and call its
setters; the document emits a signal and every view refreshes (napari's model/view
split). All heavy numbers come from ``lightinv_core``; the only computation here is
``lighting()``, one small GEMM through the operator's zone basis.
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from PySide6 import QtCore

from lightinv_core.design.model import Design, DesignError, Goal, Intention, Source
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.project import (
    OperatorSettings,
    Project,
    SceneSpec,
    load_project,
    save_project,
)
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches, mesh_patches
from lightinv_core.sources.zones import zone_grid


def blank_project(scene_name: str, resolution: float | None = None) -> Project:
    """A new project on a built-in scene: no sources yet, goal least electric power."""
    return Project(
        name=f"New {scene_name} project",
        scene=SceneSpec(builtin=scene_name, resolution=resolution),
        design=Design((), (Goal("min_electric_power"),)),
    )


class Document(QtCore.QObject):
    """The project, its scene, patches and operator, the selection and the lighting."""

    sceneChanged = QtCore.Signal()
    operatorChanged = QtCore.Signal()
    designChanged = QtCore.Signal()
    selectionChanged = QtCore.Signal()
    lightingChanged = QtCore.Signal()
    pathChanged = QtCore.Signal()
    resultsChanged = QtCore.Signal()

    def __init__(self, parent: QtCore.QObject | None = None):
        super().__init__(parent)
        self.project: Project | None = None
        self.scene: Scene | None = None
        self.patches: Patches | None = None
        self.operator: RadiosityOperator | None = None
        self.selection = np.zeros(0, np.int64)
        self.current_source: str | None = None
        self.path: Path | None = None
        self.dirty = False
        self._problem: DesignProblem | None = None
        self._lux: np.ndarray | None = None
        self.last_eval_ms = float("nan")
        self.shown: Solution | None = None  # the result last loaded into the design
        self.preview: tuple[DesignProblem, np.ndarray] | None = None  # a running best
        self._compared: tuple | None = None  # (key, lux) of the last lux_of_sources

    # -- loading ------------------------------------------------------------------------------
    def set_project(self, project: Project, path: Path | None = None) -> None:
        """Make ``project`` the open one (loads its scene and meshes it)."""
        base = path.parent if path is not None else None
        scene = project.scene.load(base)
        patches = mesh_patches(scene)
        self.project, self.scene, self.patches = project, scene, patches
        self.operator, self._problem, self._lux = None, None, None
        self.shown, self.preview, self._compared = None, None, None
        self.selection = np.zeros(0, np.int64)
        self.current_source = project.design.sources[0].name if project.design.sources else None
        self.path, self.dirty = path, False
        self.sceneChanged.emit()
        self.designChanged.emit()
        self.selectionChanged.emit()
        self.pathChanged.emit()
        self.resultsChanged.emit()

    def open(self, path: str | Path) -> None:
        """Open a project file (ProjectError on a bad file; nothing changes then)."""
        path = Path(path)
        self.set_project(load_project(path), path)

    def new_from_scene(self, name: str, resolution: float | None = None) -> None:
        """A new, unsaved project on a built-in scene."""
        self.set_project(blank_project(name, resolution))

    def save(self, path: str | Path | None = None) -> Path:
        """Save atomically to ``path`` (default: where it came from)."""
        path = Path(path) if path is not None else self.path
        if path is None:
            raise ValueError("no file name yet: use Save As")
        save_project(self.project, path)
        self.path, self.dirty = path, False
        self.pathChanged.emit()
        return path

    def set_operator(self, operator: RadiosityOperator) -> None:
        """Attach a built (or cached) operator; lighting becomes available."""
        self.operator = operator
        self._problem, self._compared = None, None
        self.operatorChanged.emit()
        self._relight()

    @property
    def operator_settings(self) -> OperatorSettings:
        """How the operator is built for this project."""
        return self.project.operator

    # -- design edits ---------------------------------------------------------------------------
    @property
    def design(self) -> Design:
        """The project's design."""
        return self.project.design

    def _set_design(self, design: Design) -> None:
        self.project = replace(self.project, design=design)
        self._problem = None
        self.shown = None  # an edited design is no longer the loaded result
        self.dirty = True
        self.designChanged.emit()
        self._relight()

    def zone_kind(self, zone: str) -> str:
        """ "skylight" or "luminaire" for an emitter zone of the scene."""
        return self.scene.zone(zone).kind

    def zone_size(self, zone: str) -> tuple[float, float]:
        """(width, height) in metres of an emitter zone."""
        return zone_grid(self.patches, zone).size

    def add_source(self, zone: str, name: str | None = None) -> Source:
        """A new source centred in ``zone``: a 1 x 1 m (or smaller) rectangle with a
        typical flux (3,000 lm luminaire) or filter 1 (skylight)."""
        kind = self.zone_kind(zone)
        w, h = self.zone_size(zone)
        sw, sh = min(1.0, w), min(1.0, h)
        rect = ((w - sw) / 2, (h - sh) / 2, (w + sw) / 2, (h + sh) / 2)
        taken = {s.name for s in self.design.sources}
        if name is None:
            stem = "L" if kind == "luminaire" else "S"
            name = next(f"{stem}{i}" for i in range(1, 10_000) if f"{stem}{i}" not in taken)
        free = ("u0", "v0", "u1", "v1")
        src = (
            Source(name, zone, kind, rect, free=free, flux=3000.0)
            if kind == "luminaire"
            else Source(name, zone, kind, rect, free=free)
        )
        self.current_source = name
        self._set_design(replace(self.design, sources=(*self.design.sources, src)))
        return src

    def update_source(self, name: str, **fields) -> None:
        """Change fields of a source (rect, flux, filter, ...); validated by the model."""
        new = tuple(replace(s, **fields) if s.name == name else s for s in self.design.sources)
        self._set_design(replace(self.design, sources=new))

    def move_source(self, name: str, du: float, dv: float) -> None:
        """Shift a source by (du, dv) metres, kept inside its zone."""
        s = self.design.source(name)
        w, h = self.zone_size(s.zone)
        (a, b), (c, d) = s.u_range, s.v_range
        du = float(np.clip(du, -a, w - b))
        dv = float(np.clip(dv, -c, h - d))
        self.update_source(name, rect=(a + du, c + dv, b + du, d + dv))

    def remove_source(self, name: str) -> None:
        """Delete a source and the rules that name it."""
        d = self.design
        rules = tuple(r for r in d.rules if name not in r.sources)
        sources = tuple(s for s in d.sources if s.name != name)
        if self.current_source == name:
            self.current_source = sources[0].name if sources else None
        self._set_design(replace(d, sources=sources, rules=rules))

    def set_centred(self, name: str, centred: bool) -> None:
        """Tie (or untie) a source to the centre of its zone."""
        from lightinv_core.design.model import Rule

        d = self.design
        rules = tuple(r for r in d.rules if not (r.kind == "centred" and name in r.sources))
        if centred:
            rules += (Rule("centred", (name,)),)
        self._set_design(replace(d, rules=rules))

    def set_mirror(self, name: str, original: str | None, axis: str = "u") -> None:
        """Make source ``name`` the mirror image of ``original`` along a zone axis (None:
        free again). Its zone may be another one, e.g. the symmetric zone across a hall."""
        from lightinv_core.design.model import Rule

        d = self.design
        rules = tuple(r for r in d.rules if not (r.kind == "mirror" and r.sources[0] == name))
        if original is not None:
            rules += (Rule("mirror", (name, original), axis=axis),)
        self._set_design(replace(d, rules=rules))

    def centred(self, name: str) -> bool:
        """Whether a centred rule ties ``name``."""
        return any(r.kind == "centred" and name in r.sources for r in self.design.rules)

    def mirror_of(self, name: str) -> tuple[str, str] | None:
        """(original, axis) if ``name`` mirrors another source."""
        for r in self.design.rules:
            if r.kind == "mirror" and r.sources[0] == name:
                return r.sources[1], r.axis
        return None

    def set_optimizer(self, **fields) -> None:
        """Change run settings (method, seed, max_evals, time_limit, ...); ProjectError on
        a bad value, leaving the project unchanged."""
        opt = replace(self.project.optimizer, **fields)
        if opt != self.project.optimizer:
            self.project = replace(self.project, optimizer=opt)
            self.dirty = True
            self.pathChanged.emit()

    def set_primary_goal(self, kind: str) -> None:
        """Make ``kind`` the goal a single-objective run optimises (first in the list); the
        other goals stay, as secondary objectives reported with each solution."""
        goals = self.design.goals
        first = next((g for g in goals if g.kind == kind), None) or Goal(kind)
        if goals and goals[0] == first:
            return
        self._set_design(replace(self.design, goals=(first, *(g for g in goals if g != first))))

    # -- emitter zones drawn by the user ------------------------------------------------------
    @property
    def user_zones(self) -> tuple:
        """Zones the project adds to its scene (``ZoneEdit``s)."""
        return self.project.scene.zones

    def drawable_surface(self, patch: int):
        """(surface name, Rect) under a patch if a zone may be drawn there, else None."""
        name = self.patches.surface_names[self.patches.surface_id[patch]]
        surface = self.scene.surface(name)
        zone_surfaces = {z.surface for z in self.scene.zones}
        if surface.rect is None or name in zone_surfaces or surface.grid is not None:
            return None
        return name, surface.rect

    def set_user_zones(self, zones) -> None:
        """Replace the drawn zones: the scene is rebuilt and re-meshed (the operator must be
        precomputed again; sources in a removed zone are removed). SceneError on a bad zone,
        leaving the project unchanged."""
        spec = replace(self.project.scene, zones=tuple(zones))
        names = {
            z.name for z in self.scene.zones if z.name not in {u.name for u in self.user_zones}
        } | {z.name for z in zones}
        design = self.design
        kept = tuple(s for s in design.sources if s.zone in names)
        rules = tuple(r for r in design.rules if set(r.sources) <= {s.name for s in kept})
        project = replace(
            self.project, scene=spec, design=replace(design, sources=kept, rules=rules)
        )
        self.set_project(project, self.path)  # loads the scene first: an error changes nothing
        self.dirty = True
        self.pathChanged.emit()

    def add_intention(self, intention: Intention) -> None:
        """Append a lighting intention."""
        self._set_design(replace(self.design, intentions=(*self.design.intentions, intention)))

    def remove_intention(self, name: str) -> None:
        """Delete a lighting intention."""
        its = tuple(i for i in self.design.intentions if i.name != name)
        self._set_design(replace(self.design, intentions=its))

    def set_selection(self, patch_ids) -> None:
        """Replace the picked patches."""
        self.selection = np.unique(np.asarray(patch_ids, dtype=np.int64))
        self.selectionChanged.emit()

    def set_current_source(self, name: str | None) -> None:
        """Which source the source panel edits and the viewport drags."""
        self.current_source = name
        self.designChanged.emit()

    # -- lighting -----------------------------------------------------------------------------
    def problem(self) -> DesignProblem | None:
        """The design bound to the operator (None before the operator exists)."""
        if self.operator is None:
            return None
        if self._problem is None:
            self._problem = DesignProblem(self.design, self.scene, self.patches, self.operator)
        return self._problem

    def effective_sources(self) -> tuple:
        """The sources as lit: mirrored and centred ones placed by their rules."""
        problem = self.problem()
        if problem is None or not self.design.sources:
            return self.design.sources
        return problem.sources_at(problem.vars.initial())

    def lighting(self) -> np.ndarray | None:
        """Illuminance (lux) of every patch for the current sources, or None."""
        return self._lux

    def lux_at(self, problem: DesignProblem, x: np.ndarray) -> np.ndarray:
        """Illuminance (lux) of every patch for layout x of ``problem`` (one sparse GEMV
        through the zone basis; zero where no source is)."""
        if not problem.design.sources:
            return np.zeros(self.patches.n, np.float32)
        rect, flux, filt = problem.vars.decode(np.asarray(x, dtype=float)[None])
        V = problem.emission.matrix(rect, flux, filt)
        cols = np.flatnonzero(V[:, 0])
        return self.operator.Phi[:, cols] @ V[cols, 0]

    def lux_of_sources(self, sources: tuple) -> np.ndarray | None:
        """Illuminance (lux) of every patch lit by ``sources`` (e.g. a pinned solution's)
        with the design's tied rules; None before the operator exists."""
        if self.operator is None:
            return None
        # The difference view asks on every edit of the loaded layout; the pinned one's
        # light changes only with its sources and the rules, so keep the last answer.
        key = (tuple(sources), self.design.rules)
        if self._compared is None or self._compared[0] != key:
            problem = DesignProblem(
                replace(self.design, sources=tuple(sources)),
                self.scene,
                self.patches,
                self.operator,
            )
            self._compared = (key, self.lux_at(problem, problem.vars.initial()))
        return self._compared[1]

    def _relight(self) -> None:
        problem = self.problem()
        if problem is None:
            return
        t0 = time.perf_counter()
        if self.preview is not None:
            # A running optimisation's best layout, shown without touching the design.
            self._lux = self.lux_at(*self.preview)
        else:
            # The design as written, with the tied rules (mirror, centred) applied.
            self._lux = self.lux_at(problem, problem.vars.initial())
        self.last_eval_ms = 1e3 * (time.perf_counter() - t0)
        self.lightingChanged.emit()

    # -- results --------------------------------------------------------------------------
    def set_preview(self, problem: DesignProblem | None, x: np.ndarray | None = None) -> None:
        """Light the view with layout x of ``problem`` (a run's best so far) without
        changing the design; None returns to the design's own lighting."""
        self.preview = None if problem is None else (problem, np.asarray(x, dtype=float))
        self._relight()

    def preview_sources(self) -> tuple | None:
        """The previewed layout's sources (rules applied), or None."""
        if self.preview is None:
            return None
        return self.preview[0].sources_at(self.preview[1])

    def apply_solution(self, solution: Solution) -> None:
        """Load a result into the design: each source takes the result's rectangle, flux
        and filter (which variables are free, the rules and the intentions stay), and the
        result becomes the shown solution (violations, comparisons)."""
        found = {s.name: s for s in solution.sources}
        if set(found) != {s.name for s in self.design.sources}:
            raise DesignError(
                "this solution was found for other sources "
                f"({', '.join(found)}); it cannot be loaded"
            )
        sources = tuple(
            replace(
                s, rect=found[s.name].rect, flux=found[s.name].flux, filter=found[s.name].filter
            )
            for s in self.design.sources
        )
        self.preview = None
        self._set_design(replace(self.design, sources=sources))
        self.shown = solution
        self.resultsChanged.emit()

    def set_results(self, solutions: tuple[Solution, ...], pareto: ParetoFront | None) -> None:
        """Store a run's results in the project (pinned solutions of earlier runs are
        kept ahead of them)."""
        pinned = tuple(s for s in self.project.solutions if s.info.get("pinned"))
        self.project = replace(self.project, solutions=pinned + tuple(solutions), pareto=pareto)
        self.dirty = True
        self.pathChanged.emit()
        self.resultsChanged.emit()

    def results(self) -> list[tuple[str, Solution]]:
        """Every result to browse, labelled: the project's solutions (pinned first as
        stored), then the Pareto front's candidates that are not also pinned."""
        out = [(_label(s), s) for s in self.project.solutions]
        pinned = {s.x for s in self.project.solutions if s.info.get("pinned")}
        if self.project.pareto is not None:
            cands = self.project.pareto.candidates or self.project.pareto.solutions
            out += [(_label(s), s) for s in cands if s.x not in pinned]
        return out

    def on_front(self, solution: Solution) -> bool:
        """Whether ``solution`` is on the project's Pareto front."""
        front = self.project.pareto
        return front is not None and any(s.x == solution.x for s in front.solutions)

    def pin(self, solution: Solution, pinned: bool = True) -> Solution:
        """Pin (keep across runs, offer for comparison) or unpin a result; returns the
        stored copy. Pinned results are saved with the project."""
        new = replace(solution, info={**solution.info, "pinned": pinned})
        others = tuple(s for s in self.project.solutions if s.x != solution.x)
        # An unpinned point of the front goes back to being shown through the front.
        keep = pinned or not self._from_front(solution)
        sols = others + ((new,) if keep else ())
        self.project = replace(self.project, solutions=sols)
        if self.shown is not None and self.shown.x == solution.x:
            self.shown = new
        self.dirty = True
        self.pathChanged.emit()
        self.resultsChanged.emit()
        return new

    def _from_front(self, solution: Solution) -> bool:
        front = self.project.pareto
        cands = () if front is None else (front.candidates or front.solutions)
        return any(s.x == solution.x for s in cands)

    def pinned(self) -> list[Solution]:
        """The pinned results."""
        return [s for s in self.project.solutions if s.info.get("pinned")]


def _label(s: Solution) -> str:
    """A short name for a result: which run found it."""
    info = s.info
    if "epsilon" in info:
        return f"epsilon {info['epsilon']:,.0f} lm"
    if "step1_light_power" in info:
        return f"two-step seed {info.get('seed', '?')}"
    if "seed" in info:
        return f"seed {info['seed']}"
    return "result"
