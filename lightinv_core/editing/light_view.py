"""The light the document shows: the operator attached, the design's light or a preview,
the problem it poses, work-plane values and the light in every daylight scenario.

``LightView`` is the document's concern for light (a mixin over
``state.DocumentState``). All light comes from one ``LightModel`` (lighting.py's
``ShownLight``): the design's as written, a running best's preview, or other sources'
for the difference view.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy.spatial import cKDTree

from lightinv_core.design.model import Source
from lightinv_core.design.solution import Solution, SolutionInfo
from lightinv_core.editing.changes import OperatorChanged
from lightinv_core.editing.lighting import ShownLight
from lightinv_core.editing.state import DocumentState
from lightinv_core.errors import DesignError, LightInvError
from lightinv_core.light.arrays import arrays_field
from lightinv_core.light.clear_build import clear_light_ready
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.dgp_observers import observer_dgp
from lightinv_core.light.field import LightField
from lightinv_core.light.glare import observer_eyes
from lightinv_core.light.grids import DesignGrids, grid_light
from lightinv_core.light.intentions import bound_checks, intention_stats, offending
from lightinv_core.light.model import LightModel
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.study import Prepared

CLEAR_PENDING = (
    "the clear glazing's light is being traced in the background (the status bar shows "
    "how far); its daylight figures follow once it is done"
)
"""Why a figure that needs the clear glazing's light is not there yet (``clear_pending``)."""


class LightView(DocumentState):
    """Attach the operator, light the design or a preview, and answer what the light is."""

    def clear_pending(self) -> bool:
        """Whether the design's clear glazing waits for its light to be built elsewhere
        (``clear_elsewhere``): the light shown leaves it out, and the daylight figures and
        the problem raise DesignError(``clear_note`` or ``CLEAR_PENDING``) until it is
        built (``clear_light_changed``)."""
        return (
            self.clear_elsewhere
            and self.light is not None
            and not clear_light_ready(self.light, self.design)
        )

    def clear_light_changed(self, note: str = "", daylight: LayoutDaylight | None = None) -> None:
        """The clear glazing's light was built (a worker's ``clear_light`` on this
        operator), or its trace given up (``note`` says why, in what raises while it is
        pending): light the design again and let every view read it again. ``daylight``:
        the design's light in every scenario, made by the same worker (kept when it is
        of the design as it is now: the views need not build it here)."""
        self.clear_note = note
        self._problem = None
        self._daylight.clear()
        if daylight is not None and daylight.design is self.design and self.light is not None:
            self._daylight.put(self.light, self.design, daylight)
        self._relight()

    def set_operator(
        self,
        operator: RadiosityOperator,
        shown: ShownLight | None = None,
        daylight: LayoutDaylight | None = None,
    ) -> None:
        """Attach a built (or cached) operator of these patches; lighting becomes
        available (DesignError if it was built for another scene). ``shown``: its light
        already laid out elsewhere (a worker's ``ShownLight`` on this operator: the
        work planes' grids and the arrays' light, seconds on an office), and
        ``daylight`` the design's light in every scenario made there; each is used only
        if of this operator (and of the design as it is now)."""
        if shown is not None and shown.model.op is operator and shown.model.patches is self.patches:
            self.light, self._light_shown = shown.model, shown
        else:
            self.light = LightModel(self.scene, self.patches, operator)
            self._light_shown = ShownLight(self.light)
        self.operator, self._problem = operator, None
        self._daylight.clear()
        if daylight is not None and daylight.design is self.design:
            self._daylight.put(self.light, self.design, daylight)
        self.events.emit("operator", OperatorChanged(operator, self.light))
        self._relight()

    def prepared(self) -> Prepared:
        """The scene, patches and operator for a run or a report in a worker thread (its
        own light model: the zone tables fill lazily and are not shared across threads)."""
        return Prepared(self.scene, self.patches, self.operator, True, 0.0)

    def problem(self) -> DesignProblem | None:
        """The design bound to the light model (None before the operator exists;
        DesignError while its clear glazing's light is pending, ``clear_pending``)."""
        if self.light is None:
            return None
        if self._problem is None:
            if self.clear_pending():
                raise DesignError(self.clear_note or CLEAR_PENDING)
            self._problem = DesignProblem(self.design, self.light)
        return self._problem

    def design_solution(self) -> Solution:
        """The design on screen judged as a solution (its achieved values and violations),
        for a report of a hand-tuned design; DesignError before the operator exists."""
        problem = self.problem()
        if problem is None:
            raise DesignError("the radiosity operator is not ready yet")
        return problem.solution(problem.vars.initial(), SolutionInfo())

    def offending_patches(self) -> list[tuple[str, str, np.ndarray]]:
        """Where the design's light breaks its intentions: (intention, bound, patch ids)
        per violated bound (a work plane's: the floor patches under its points that
        break it, ``offending_points``); empty before the operator exists, while the
        clear glazing's light is pending or when a geometric rule fails."""
        if self.clear_pending():
            return []
        problem = self.problem()
        if problem is None:
            return []
        x = problem.vars.initial()
        if np.any(problem.rule_violations(x[None]) > 0):
            return []
        out = problem.offending_patches(x)
        for name, bound, plane, points in self.offending_points():
            out.append((name, bound, self._patches_under(plane, points)))
        return out

    def offending_points(self) -> list[tuple[str, str, str, np.ndarray]]:
        """Where the design's light breaks its work-plane intentions: (intention, bound,
        work plane, grid point indices into ``shown_grids``'s points) per violated bound,
        judged in the intention's scenario (an EN 12464-1 preset's: night); a short
        average marks every point of its plane. Empty before the operator exists."""
        gridded = [it for it in self.design.intentions if it.grid is not None]
        ld = self.layout_daylight() if gridded and not self.clear_pending() else None
        if ld is None or ld.grids is None:
            return []
        out = []
        for it in gridded:
            try:
                q, w = ld.quantity(it)
            except LightInvError:
                continue  # a metric that cannot be had (no weather): judged elsewhere
            stats = intention_stats(q[:, None], w)
            first = ld.grids.span(it.grid).start
            for check in bound_checks(it, stats):
                if not check.met[0]:
                    mask = offending(check, q, float(stats.average[0]))
                    out.append((it.name, str(check.bound), it.grid, first + np.flatnonzero(mask)))
        return out

    def _patches_under(self, plane: str, points: np.ndarray) -> np.ndarray:
        """The patches of work plane ``plane``'s floor group straight under grid
        ``points`` (their indices): the nearest in plan."""
        grids, _ = self.shown_grids()
        group = next(w.group for w in self.design.workplanes if w.name == plane)
        floor = self.patches.group_index(group)
        if grids is None or not len(points) or not len(floor):
            return np.zeros(0, np.int64)
        tree = cKDTree(self.patches.centroid[floor, :2])
        _, nearest = tree.query(grids.points[points, :2])
        return np.unique(floor[nearest]).astype(np.int64)

    # -- the light shown ------------------------------------------------------------------------
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

    def lighting_of(self, sources, arrays=()) -> np.ndarray | None:
        """Illuminance (lux) of every patch lit by ``sources`` and luminaire ``arrays``
        (e.g. a pinned result's, as the design shown is lit by its own arrays too) under
        the design's tied rules; None before the operator exists."""
        if self._light_shown is None:
            return None
        lux = self._light_shown.of_sources(self.design, sources)
        arrays = tuple(arrays)
        if not arrays:
            return lux
        memo = getattr(self, "_arrays_compared", None)
        if memo is None or memo[0] != (self.light, arrays):
            H, _ = arrays_field(self.patches, self.light.op, arrays)
            self._arrays_compared = memo = ((self.light, arrays), H)
        return lux + memo[1]

    def set_preview(self, sources=None) -> None:
        """Light the view with ``sources`` as lit (a running best) without changing the
        design; None returns to the design's own light."""
        self._preview = None if sources is None else tuple(sources)
        self._relight()

    def preview_sources(self) -> tuple[Source, ...] | None:
        """The previewed layout's sources (rules applied), or None."""
        return self._preview

    # -- work planes and daylight ---------------------------------------------------------------
    def grid_stats(self) -> dict[str, dict[str, float]]:
        """EN 12464-1 values (points, Em, Emin, Emax lux, U0) of each work plane in the
        light shown; empty before the operator exists or without work planes."""
        return {} if self._light_shown is None else self._light_shown.grid_stats()

    def shown_grids(self) -> tuple[DesignGrids | None, np.ndarray | None]:
        """(grids, lux at their points) of the light shown, or (None, None)."""
        if self._light_shown is None:
            return None, None
        return self._light_shown.grids, self._light_shown.grid_lux

    def layout_daylight(self, shown: bool = False) -> LayoutDaylight | None:
        """The light of the design as written (``shown``: of the layout shown, a running
        best's when previewed) in every scenario, with its daylight metrics, hours and
        annual energy (``light.daylight.LayoutDaylight``); built once per design or
        preview, None before the operator exists; DesignError while the clear glazing's
        light is pending (``clear_pending``)."""
        if self.light is None:
            return None
        if self.clear_pending():
            raise DesignError(self.clear_note or CLEAR_PENDING)
        preview = self._preview if shown else None
        return self._daylight.get(self.light, self.design, preview)

    def grid_lux_of(self, sources, arrays=()) -> np.ndarray | None:
        """Illuminance (lux) at the work planes' grid points (``shown_grids``' order) lit
        by ``sources`` and ``arrays`` (a pinned result's, for the difference view), in
        the design scenario; None before the operator exists or without work planes."""
        grids, _ = self.shown_grids()
        if grids is None or self.light is None:
            return None
        key = (grids, tuple(sources), tuple(arrays), self.design.daylight)
        memo = getattr(self, "_grid_compared", None)
        if memo is None or memo[0] != key:
            lux = grid_light(self.light, grids, tuple(sources), tuple(arrays), self.design.daylight)
            self._grid_compared = memo = (key, lux)
        return memo[1]

    def observer_dgp(self, shown: bool = False) -> tuple[dict[str, dict], tuple[str, ...]]:
        """({observer: simplified DGP figures}, the observers left out) of the design as
        written (``shown``: of the layout shown) at every observer inside the room, with or
        without a ``dgp`` intention (``light.dgp_observers.observer_dgp``: the share of the
        occupied hours above ``daylight.dgp_limit``, EN 17037's glare protection level, the
        largest DGPs and Ev, lux); ({}, ()) before the operator exists; made once per design
        or preview; DesignError while the clear glazing's light is pending."""
        if self.light is None or not self.design.observers:
            return {}, ()
        if self.clear_pending():
            raise DesignError(self.clear_note or CLEAR_PENDING)
        preview = self._preview if shown else None
        key = (self.light, self.design, preview)
        memo = getattr(self, "_dgp_shown", None)
        if memo is None or any(a is not b for a, b in zip(memo[0], key, strict=True)):
            inside, out = [], []
            for ob in self.design.observers:
                try:
                    observer_eyes(self.patches, (ob,))
                    inside.append(ob)
                except LightInvError:
                    out.append(ob.name)  # outside the room: not drawn, not rated
            design = replace(self.design, observers=tuple(inside))
            figures = observer_dgp(self.light, design, preview) if inside else {}
            self._dgp_shown = memo = (key, (figures, tuple(out)))
        return memo[1]
