"""``DocumentModel``: the open project as an editor sees it, with every editing rule.

Plain Python (the desktop window adapts it to Qt signals in ``app/document.py``; a
script or a test drives it directly). It holds the project, its scene and patches, the
radiosity operator and light model once built, the selection, the current source, the
file path and dirty flag, the result shown and the layout previewed. Each setter applies
its rule (the cascades are in rules.py, the results' bookkeeping in results.py), then
emits the named events of what changed (events.py). All light comes from the
``LightModel``: the design's as written, a running best's preview, or other sources'
for the difference view.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from datetime import datetime
from pathlib import Path

import numpy as np

from lightinv_core.design.model import ARRAY_RULES, Design, Goal, Intention, Rule, Source
from lightinv_core.design.solution import ParetoFront, Solution, SolutionInfo
from lightinv_core.editing import results as _results
from lightinv_core.editing import rules
from lightinv_core.editing import zones as _zones
from lightinv_core.editing.climate import DaylightCache, weather_of
from lightinv_core.editing.events import Events
from lightinv_core.editing.lighting import ShownLight
from lightinv_core.errors import DesignError, LightInvError
from lightinv_core.kinds import GoalKind
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.field import LightField
from lightinv_core.light.model import LightModel
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.optimize.mop import front_pair
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.quality import FrontQuality, front_quality, front_scales
from lightinv_core.project import (
    OperatorSettings,
    OptimizerSettings,
    Project,
    SceneSpec,
    load_project,
    save_project,
)
from lightinv_core.project.results import RunRecord
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.scene.model import Rect, Scene
from lightinv_core.scene.patches import Patches, mesh_patches
from lightinv_core.scene.zone_grid import zone_grid
from lightinv_core.study import Prepared


class DocumentModel:
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
        # Called after every edit with (label, project before, project after): the app
        # keeps them for undo and redo (a QUndoStack); ``restore`` puts a state back.
        self.on_edit: Callable[[str, Project, Project], None] | None = None

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
            self._browsed, self._run_mark = _results.ALL, 1
        self.selection = np.zeros(0, np.int64)
        self.current_source = project.design.sources[0].name if project.design.sources else None
        self.path, self.dirty = path, False
        for name in ("scene", "design", "selection", "path", "results"):
            self.events.emit(name)

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
        self.path, self.dirty = path, False
        self.events.emit("path")
        return path

    def mark_dirty(self) -> None:
        """Flag unsaved changes (e.g. work recovered from an autosave)."""
        self.dirty = True
        self.events.emit("path")

    def set_operator(self, operator: RadiosityOperator) -> None:
        """Attach a built (or cached) operator of these patches; lighting becomes
        available (DesignError if it was built for another scene)."""
        self.light = LightModel(self.scene, self.patches, operator)
        self.operator, self._problem = operator, None
        self._light_shown = ShownLight(self.light)
        self.events.emit("operator")
        self._relight()

    def prepared(self) -> Prepared:
        """The scene, patches and operator for a run or a report in a worker thread (its
        own light model: the zone tables fill lazily and are not shared across threads)."""
        return Prepared(self.scene, self.patches, self.operator, True, 0.0)

    # -- design edits ---------------------------------------------------------------------------
    def _set_design(self, design: Design, label: str = "edit the design") -> None:
        before = self._project
        self._project = replace(self._project, design=design)
        self._problem = None
        self.shown = None  # an edited design is no longer the loaded result
        self.dirty = True
        self.events.emit("design")
        self._relight()
        self._edited(label, before)

    def _edited(self, label: str, before: Project) -> None:
        if self.on_edit is not None and self._project is not before:
            self.on_edit(label, before, self._project)

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
            self.events.emit("design")
            self.events.emit("results")
            self._relight()
        self.mark_dirty()

    def zone_kind(self, zone: str) -> str:
        """The kind of source ("skylight" or "luminaire") an emitter zone takes."""
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

    def add_source(self, zone: str, name: str | None = None) -> Source:
        """A new source centred in ``zone`` (see ``rules.new_source``); it becomes the
        current one."""
        src = rules.new_source(
            self.design,
            zone,
            self.zone_kind(zone),
            self.zone_size(zone),
            name,
            self.zone_outline(zone),
        )
        design = rules.with_source(self.design, src)
        self.current_source = src.name
        self._set_design(design, f"add source {src.name}")
        return src

    def update_source(self, name: str, **fields) -> None:
        """Change fields of a source (rect, flux, filter, free, ...); DesignError on a bad
        value, leaving the design unchanged."""
        self._set_design(
            rules.with_source_fields(self.design, name, **fields), f"edit source {name}"
        )

    def move_source(self, name: str, du: float, dv: float) -> None:
        """Shift a source by (du, dv) metres, kept inside its zone."""
        s = self.design.source(name)
        rect = rules.moved_rect(s, du, dv, self.zone_size(s.zone), self.zone_outline(s.zone))
        self._set_design(rules.with_source_fields(self.design, name, rect=rect), f"move {name}")

    def remove_source(self, name: str) -> None:
        """Delete a source and the rules that name it."""
        design = rules.without_source(self.design, name)
        if self.current_source == name:
            self.current_source = design.sources[0].name if design.sources else None
        self._set_design(design, f"remove source {name}")

    def set_centred(self, name: str, centred: bool) -> None:
        """Tie (or untie) a source to the centre of its zone."""
        self._set_design(
            rules.with_centred(self.design, name, centred),
            f"{'centre' if centred else 'free'} {name}",
        )

    def set_mirror(self, name: str, original: str | None, axis: str = "u") -> None:
        """Make source ``name`` the mirror image of ``original`` along a zone axis (None:
        free again)."""
        self._set_design(
            rules.with_mirror(self.design, name, original, axis),
            f"mirror {name}" if original else f"unmirror {name}",
        )

    def centred(self, name: str) -> bool:
        """Whether a centred rule ties ``name``."""
        return rules.is_centred(self.design, name)

    def mirror_of(self, name: str) -> tuple[str, str] | None:
        """(original, axis) if ``name`` mirrors another source."""
        return rules.mirror_of(self.design, name)

    def add_rule(self, rule: Rule) -> None:
        """Append a geometric rule (DesignError if it names unknown sources or clashes)."""
        self._set_design(
            replace(self.design, rules=(*self.design.rules, rule)),
            f"add rule {rules.rule_text(rule)[0]}",
        )

    def remove_rule(self, index: int) -> None:
        """Delete the rule at ``index`` of the design's rules."""
        rule = self.design.rules[index]
        kept = self.design.rules[:index] + self.design.rules[index + 1 :]
        self._set_design(
            replace(self.design, rules=kept), f"remove rule {rules.rule_text(rule)[0]}"
        )

    def set_arrays(self, arrays, label: str = "edit luminaire arrays") -> None:
        """Replace the design's luminaire arrays (DesignError if a rule or name clashes):
        add, edit and remove are this with another tuple. Rules on arrays that are gone
        go with them."""
        arrays = tuple(arrays)
        names = {a.name for a in arrays}
        kept = tuple(
            r for r in self.design.rules if r.kind not in ARRAY_RULES or set(r.sources) <= names
        )
        self._set_design(replace(self.design, arrays=arrays, rules=kept), label)

    def set_workplanes(self, workplanes, label: str = "edit work planes") -> None:
        """Replace the design's work planes; intentions on a removed one go with it."""
        workplanes = tuple(workplanes)
        names = {w.name for w in workplanes}
        its = tuple(i for i in self.design.intentions if i.grid is None or i.grid in names)
        daylight = self.design.daylight
        if daylight.workplane is not None and daylight.workplane not in names:
            daylight = replace(daylight, workplane=None)  # dimming reads the first again
        self._set_design(
            replace(self.design, workplanes=workplanes, intentions=its, daylight=daylight), label
        )

    def grid_stats(self) -> dict[str, dict[str, float]]:
        """EN 12464-1 values (points, Em, Emin, Emax lux, U0) of each work plane in the
        light shown; empty before the operator exists or without work planes."""
        return {} if self._light_shown is None else self._light_shown.grid_stats()

    def shown_grids(self):
        """(grids, lux at their points) of the light shown, or (None, None)."""
        if self._light_shown is None:
            return None, None
        return self._light_shown.grids, self._light_shown.grid_lux

    def set_daylight(self, **fields) -> None:
        """Change the design's daylight and climate (weather, north_deg, occupancy,
        weekdays, ground_reflectance, overcast_lux, target_lux, min_level, standby_w,
        workplane, exterior_lux, transmittance: ``design.model.Daylight``); DesignError on
        a bad value, leaving the design unchanged. The weather file is not read here
        (``weather``)."""
        daylight = replace(self.design.daylight, **fields)
        if daylight != self.design.daylight:
            self._set_design(
                replace(self.design, daylight=daylight), f"climate: {', '.join(sorted(fields))}"
            )

    def weather(self):
        """The design's weather file, read (``climate.weather.Weather``: site, hours);
        WeatherError when it cannot be read."""
        return weather_of(self.design.daylight)

    def layout_daylight(self, shown: bool = False) -> LayoutDaylight | None:
        """The light of the design as written (``shown``: of the layout shown, a running
        best's when previewed) in every scenario, with its daylight metrics, hours and
        annual energy (``light.daylight.LayoutDaylight``); built once per design or
        preview, None before the operator exists."""
        if self.light is None:
            return None
        preview = self._preview if shown else None
        return self._daylight.get(self.light, self.design, preview)

    def set_goal(self, kind: str, on: bool) -> None:
        """Add goal ``kind`` (both power goals give a Pareto front) or remove it;
        DesignError when no goal would be left."""
        design = rules.with_goal(self.design, kind, on)
        if design != self.design:
            self._set_design(design, f"{'add' if on else 'remove'} goal {kind}")

    def add_intention(self, intention: Intention) -> None:
        """Append a lighting intention (DesignError if its name is taken)."""
        self._set_design(
            replace(self.design, intentions=(*self.design.intentions, intention)),
            f"add intention {intention.name}",
        )

    def replace_intention(self, name: str, intention: Intention) -> None:
        """Put ``intention`` in place of the one called ``name`` (same position);
        DesignError if there is none or the new name is another intention's."""
        names = [i.name for i in self.design.intentions]
        if name not in names:
            raise DesignError(f"no lighting intention {name!r}")
        if intention.name != name and intention.name in names:
            raise DesignError(f"another lighting intention is already called {intention.name!r}")
        its = tuple(intention if i.name == name else i for i in self.design.intentions)
        self._set_design(replace(self.design, intentions=its), f"edit intention {name}")

    def remove_intention(self, name: str) -> None:
        """Delete a lighting intention."""
        its = tuple(i for i in self.design.intentions if i.name != name)
        self._set_design(replace(self.design, intentions=its), f"remove intention {name}")

    def set_primary_goal(self, kind: str) -> None:
        """Make ``kind`` the goal a single-objective run optimises (the others stay)."""
        design = rules.with_primary_goal(self.design, kind)
        if design is not self.design:
            self._set_design(design, f"goal {kind}")

    def set_optimizer(self, **fields) -> None:
        """Change run settings (method, seed, max_evals, time_limit, ...); ProjectError on
        a bad value, leaving the project unchanged."""
        opt = replace(self._project.optimizer, **fields)
        if opt != self._project.optimizer:
            before = self._project
            self._project = replace(self._project, optimizer=opt)
            self.mark_dirty()
            self._edited("run settings", before)

    def set_selection(self, patch_ids) -> None:
        """Replace the picked patches (ids, any order, repeats dropped)."""
        self.selection = np.unique(np.asarray(patch_ids, dtype=np.int64))
        self.events.emit("selection")

    def set_current_source(self, name: str | None) -> None:
        """Which source the source panel edits and the viewport drags."""
        self.current_source = name
        self.events.emit("design")

    # -- emitter zones drawn by the user ------------------------------------------------------
    @property
    def user_zones(self) -> tuple[ZoneEdit, ...]:
        """Zones the project adds to its scene."""
        return self._project.scene.zones

    def drawable_surface(self, patch: int) -> tuple[str, Rect] | None:
        """(surface name, Rect) under a patch if a zone may be drawn there, else None."""
        return _zones.drawable_surface(self.scene, self.patches, patch)

    def zone_surface(
        self, kind: str, origin, direction, seen: int | None = None
    ) -> tuple[str, Rect]:
        """(surface name, Rect) a zone of ``kind`` drawn along a view ray goes on: the
        patch ``seen`` under the cursor's surface if it suits, else the first along the
        ray (``zones.zone_surface``); DesignError saying where such zones go if none."""
        return _zones.zone_surface(self.scene, self.patches, kind, origin, direction, seen)

    def new_zone_name(self) -> str:
        """A free name for a drawn zone (Z1, Z2, ...)."""
        return _zones.new_zone_name(self.scene)

    def set_user_zones(self, zones) -> None:
        """Replace the drawn zones: the scene is rebuilt and re-meshed (the operator must
        be built again) and sources in a zone that goes are removed with their rules.
        SceneError on a bad zone, leaving the project unchanged."""
        zones = tuple(zones)
        names = _zones.zone_names_after(self.scene, self.user_zones, zones)
        project = replace(
            self._project,
            scene=replace(self._project.scene, zones=zones),
            design=rules.only_in_zones(self.design, names),
        )
        before = self._project
        # Loads the scene first: an error changes nothing.
        self.set_project(project, self.path, rebuild=True)
        self.mark_dirty()
        self._edited("drawn zones", before)

    def reflectance(self, group: str) -> float:
        """The area-weighted reflectance of a lighting group's surfaces (0 to 1)."""
        surfaces = [x for x in self.scene.surfaces if x.group == group]
        if not surfaces:
            raise DesignError(f"no lighting group {group!r} in the scene")
        area = sum(x.area for x in surfaces)
        return sum(x.reflectance * x.area for x in surfaces) / area

    def set_reflectance(self, group: str, value: float | None) -> None:
        """Give a lighting group's surfaces ``value`` (None: the scene's own again). The
        patches change, so the operator is built again (or loaded from the cache);
        SceneError or ProjectError on a bad value, leaving the project unchanged."""
        current = dict(self._project.scene.reflectances)
        if value is None:
            current.pop(group, None)
        else:
            current[group] = float(value)
        spec = replace(self._project.scene, reflectances=tuple(sorted(current.items())))
        if spec == self._project.scene:
            return
        before = self._project
        self.set_project(replace(self._project, scene=spec), self.path, rebuild=True)
        self.mark_dirty()
        self._edited(f"reflectance of {group}", before)

    def add_user_zone(self, name: str, kind: str, surface: str, rect) -> ZoneEdit:
        """Draw a new zone ``name`` of ``kind`` on ``surface`` at ``rect`` (u0, v0, u1, v1)
        metres of the surface; SceneError on a bad zone, leaving the project unchanged."""
        edit = ZoneEdit(name, kind, surface, tuple(rect))
        self.set_user_zones((*self.user_zones, edit))
        return edit

    # -- lighting -----------------------------------------------------------------------------
    def problem(self) -> DesignProblem | None:
        """The design bound to the light model (None before the operator exists)."""
        if self.light is None:
            return None
        if self._problem is None:
            self._problem = DesignProblem(self.design, self.light)
        return self._problem

    def design_solution(self) -> Solution:
        """The design on screen judged as a solution (its achieved values and violations),
        for a report of a hand-tuned design; DesignError before the operator exists."""
        problem = self.problem()
        if problem is None:
            raise DesignError("the radiosity operator is not ready yet")
        return problem.solution(problem.vars.initial(), SolutionInfo())

    def effective_sources(self) -> tuple[Source, ...]:
        """The design's sources as lit: mirrored and centred ones placed by their rules."""
        if self._light_shown is None or not self.design.sources:
            return self.design.sources
        return self._light_shown.layout(self.design)

    @property
    def field(self) -> LightField | None:
        """The light shown: a running best's if previewed, else the design's (None
        before the operator exists)."""
        return None if self._light_shown is None else self._light_shown.field

    @property
    def last_eval_ms(self) -> float:
        """Time (ms) of the last relight."""
        return float("nan") if self._light_shown is None else self._light_shown.last_eval_ms

    def lighting(self) -> np.ndarray | None:
        """Illuminance (lux) of every patch as shown, or None."""
        field = self.field
        return None if field is None else field.illuminance

    def design_field(self) -> LightField | None:
        """The light of the design as written (tied rules applied), even while a preview
        is shown; None before the operator exists."""
        return None if self._light_shown is None else self._light_shown.design_field(self.design)

    def lighting_of(self, sources) -> np.ndarray | None:
        """Illuminance (lux) of every patch lit by ``sources`` (e.g. a pinned result's)
        under the design's tied rules; None before the operator exists."""
        if self._light_shown is None:
            return None
        return self._light_shown.of_sources(self.design, sources)

    def offending_patches(self) -> list[tuple[str, str, np.ndarray]]:
        """Where the design's light breaks its intentions: (intention, bound, patch ids)
        per violated bound; empty before the operator exists or when a geometric rule
        fails."""
        problem = self.problem()
        return [] if problem is None else problem.offending_patches(problem.vars.initial())

    def set_preview(self, sources=None) -> None:
        """Light the view with ``sources`` as lit (a running best) without changing the
        design; None returns to the design's own light."""
        self._preview = None if sources is None else tuple(sources)
        self._relight()

    def preview_sources(self) -> tuple[Source, ...] | None:
        """The previewed layout's sources (rules applied), or None."""
        return self._preview

    def _relight(self) -> None:
        if self._light_shown is not None:
            self._light_shown.relight(self.design, self._preview)
            self.events.emit("lighting")

    # -- results ------------------------------------------------------------------------------
    def apply_solution(self, solution: Solution) -> None:
        """Load a result into the design: each source takes the result's rectangle, flux
        and filter (which variables are free, the rules and the intentions stay), and the
        result becomes the shown one. DesignError if it was found for other sources."""
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
        # Arrays take the result's layout (rows, columns, rectangle, rotation, dimming);
        # product, ranges and which variables are free stay the design's.
        laid = {a.name: a for a in solution.arrays}
        arrays = tuple(
            replace(
                a,
                rect=laid[a.name].rect,
                rows=laid[a.name].rows,
                columns=laid[a.name].columns,
                rotation=laid[a.name].rotation,
                dimming=laid[a.name].dimming,
            )
            if a.name in laid
            else a
            for a in self.design.arrays
        )
        self._preview = None
        self._set_design(replace(self.design, sources=sources, arrays=arrays), "load a result")
        self.shown = solution
        self.events.emit("results")

    @property
    def browsed_run(self) -> int | None:
        """The run whose results are listed: its number, ``results.SAVED`` (the saved
        results) or ``results.ALL`` (every run's); ALL once the run chosen is gone (an
        undo, a redo of its deletion)."""
        b, p = self._browsed, self._project
        if b is _results.ALL or p is None:
            return _results.ALL
        if b == _results.SAVED:
            return b if p.solutions or p.pareto is not None else _results.ALL
        return b if any(r.number == b for r in p.runs) else _results.ALL

    @property
    def runs(self) -> tuple[RunRecord, ...]:
        """The project's optimisation runs, oldest first."""
        return self._project.runs

    def add_run(
        self,
        solutions: tuple[Solution, ...],
        pareto: ParetoFront | None,
        *,
        settings: OptimizerSettings,
        seeds=(),
        status: str = "",
        evaluations: int = 0,
        seconds: float = 0.0,
        time: str | None = None,
    ) -> RunRecord:
        """Keep a finished run's results as the next run of the history (earlier runs
        stay); its results are then the ones browsed. ``time``: when it ended (ISO 8601;
        default now). Not an edit (undo leaves it)."""
        number = _results.next_run_number(self._project, self._run_mark)
        run = RunRecord(
            number=number,
            method=settings.method,
            time=time or datetime.now().isoformat(timespec="seconds"),
            settings=settings,
            seeds=tuple(seeds),
            goals=tuple(g.kind for g in self.design.goals),
            status=status,
            evaluations=int(evaluations),
            seconds=float(seconds),
            solutions=tuple(solutions),
            pareto=pareto,
        )
        self._project = _results.with_run(self._project, run)
        self._run_mark = number + 1
        self._browsed = number
        self.mark_dirty()
        self.events.emit("results")
        return run

    def delete_run(self, number: int) -> None:
        """Delete run ``number`` and its results (its pinned ones are kept as saved
        results); an edit, so Edit > Undo brings it back. DesignError if there is none."""
        before = self._project
        self._project = _results.without_run(self._project, number)
        if self.browsed_run == number:
            self._browsed = _results.ALL
        self.mark_dirty()
        self.events.emit("results")
        self._edited(f"delete run {number}", before)

    def browse_run(self, number: int | None) -> None:
        """List run ``number``'s results (``results.SAVED``: the saved ones; None: every
        run's); DesignError for a run the project does not have."""
        if number is not _results.ALL and number != _results.SAVED:
            _results.find_run(self._project, number)
        self._browsed = number
        self.events.emit("results")

    def run_summary(self, number: int) -> str:
        """One line on what run ``number`` was asked and did."""
        return _results.run_summary(_results.find_run(self._project, number))

    def results(self) -> list[_results.Entry]:
        """The results browsed, labelled (see ``results.browse``)."""
        return _results.browse(self._project, self.browsed_run)

    def front(self) -> ParetoFront | None:
        """The Pareto front of the results browsed (see ``results.front_of``)."""
        return _results.front_of(self._project, self.browsed_run)

    def front_quality(self) -> FrontQuality | None:
        """Hypervolume and spacing of the front browsed (None without a front or a light
        model, or when the design's goals no longer make that front: its scales are the
        design's, power and light or annual energy and glazing area)."""
        front = self.front() if self._project is not None else None
        if front is None or not front.solutions or self.light is None:
            return None
        if tuple(front.objectives) != tuple(map(str, front_pair(self.design))):
            return None
        try:
            scales = front_scales(self._project.design, self.light)
        except LightInvError:  # the climate scales read the weather file
            return None
        return front_quality(front.solutions, scales)

    def on_front(self, solution: Solution) -> bool:
        """Whether ``solution`` is on one of the project's Pareto fronts."""
        return _results.on_front(self._project, solution)

    def pin(self, solution: Solution, pinned: bool = True) -> Solution:
        """Pin (offer for comparison, keep when its run is deleted; saved with the
        project) or unpin a result; returns the pinned copy."""
        self._project, new = _results.with_pin(self._project, solution, pinned)
        if self.shown is not None and self.shown.x == solution.x:
            self.shown = new
        self.mark_dirty()
        self.events.emit("results")
        return new

    def pinned(self) -> list[Solution]:
        """The pinned results, each layout once."""
        return _results.pinned_results(self._project)


def blank_project(scene_name: str, resolution: float | None = None) -> Project:
    """A new project on a built-in scene: no sources yet, goal least electric power."""
    return Project(
        name=f"New {scene_name} project",
        scene=SceneSpec(builtin=scene_name, resolution=resolution),
        design=Design((), (Goal(GoalKind.MIN_ELECTRIC_POWER),)),
    )


def load_scene_of(project: Project, path: Path | None = None) -> tuple[Scene, Patches]:
    """The scene of ``project`` (saved at ``path``: relative model paths are resolved
    from its folder) and its patches; SceneError or ObjImportError on a bad one."""
    scene = project.scene.load(path.parent if path is not None else None)
    return scene, mesh_patches(scene)


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
        design=Design((), (Goal(GoalKind.MIN_ELECTRIC_POWER),)),
    )
