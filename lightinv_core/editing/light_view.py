"""The light the document shows: the operator attached, the design's light or a preview,
the problem it poses, work-plane values and the light in every daylight scenario.

``LightView`` is the document's concern for light (a mixin over
``state.DocumentState``). All light comes from one ``LightModel`` (lighting.py's
``ShownLight``): the design's as written, a running best's preview, or other sources'
for the difference view.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.design.model import Source
from lightinv_core.design.solution import Solution, SolutionInfo
from lightinv_core.editing.changes import OperatorChanged
from lightinv_core.editing.lighting import ShownLight
from lightinv_core.editing.state import DocumentState
from lightinv_core.errors import DesignError
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.field import LightField
from lightinv_core.light.grids import DesignGrids
from lightinv_core.light.model import LightModel
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.study import Prepared


class LightView(DocumentState):
    """Attach the operator, light the design or a preview, and answer what the light is."""

    def set_operator(self, operator: RadiosityOperator) -> None:
        """Attach a built (or cached) operator of these patches; lighting becomes
        available (DesignError if it was built for another scene)."""
        self.light = LightModel(self.scene, self.patches, operator)
        self.operator, self._problem = operator, None
        self._light_shown = ShownLight(self.light)
        self.events.emit("operator", OperatorChanged(operator, self.light))
        self._relight()

    def prepared(self) -> Prepared:
        """The scene, patches and operator for a run or a report in a worker thread (its
        own light model: the zone tables fill lazily and are not shared across threads)."""
        return Prepared(self.scene, self.patches, self.operator, True, 0.0)

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

    def offending_patches(self) -> list[tuple[str, str, np.ndarray]]:
        """Where the design's light breaks its intentions: (intention, bound, patch ids)
        per violated bound; empty before the operator exists or when a geometric rule
        fails."""
        problem = self.problem()
        return [] if problem is None else problem.offending_patches(problem.vars.initial())

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

    def lighting_of(self, sources) -> np.ndarray | None:
        """Illuminance (lux) of every patch lit by ``sources`` (e.g. a pinned result's)
        under the design's tied rules; None before the operator exists."""
        if self._light_shown is None:
            return None
        return self._light_shown.of_sources(self.design, sources)

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
        preview, None before the operator exists."""
        if self.light is None:
            return None
        preview = self._preview if shown else None
        return self._daylight.get(self.light, self.design, preview)
