"""``ShownLight``: the light an editor shows, all of it from one ``LightModel``.

Three layouts are lit: the design as written (its tied rules applied), a previewed
layout (a running optimisation's best, without touching the design), and other sources
under the design's rules (a pinned result, for the difference view; its light is kept
until its sources or the rules change, since the view asks on every edit).

Fixed clear glazing adds its light in the design scenario (``light.clear_build``); with
``defer_clear`` (a window that traces it in a worker) a clear glazing not yet built is
left out rather than built here.
Luminaire arrays add their light placed exactly (``light.arrays.arrays_field``: about
a second for a room's arrays, so it is kept until the arrays change), and the design's
work planes their grids: ``grid_lux`` and ``grid_stats`` are the values shown (EN
12464-1's Em, Emin, Emax, U0), maintained.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from lightinv_core.design.model import Design, LuminaireArray, Source
from lightinv_core.errors import LightInvError
from lightinv_core.light.arrays import arrays_field
from lightinv_core.light.clear_build import clear_light, clear_light_ready
from lightinv_core.light.field import LightField
from lightinv_core.light.grids import DesignGrids, design_receivers
from lightinv_core.light.model import LightModel
from lightinv_core.transport.workplane import grid_statistics


class ShownLight:
    """The light model of the open scene and the field last shown."""

    def __init__(self, light: LightModel):
        self.model = light
        self.field: LightField | None = None
        """The light shown: the preview's if there is one, else the design's."""
        self.previewing = False
        self.last_eval_ms = float("nan")
        """Time (ms) of the last relight."""
        self._compared: tuple | None = None
        self._arrays: tuple | None = None  # (arrays, grids, H on patches, lux at points)
        self.grids: DesignGrids | None = None
        """The design's work-plane grids (None without work planes)."""
        self.grid_lux: np.ndarray | None = None
        """Illuminance (lux, maintained) at every grid point of the layout shown."""
        self.defer_clear = False
        """True: a clear glazing whose light is not built yet is left out, not built here
        (the window builds it in a worker: about 20 s on the flagship office)."""

    def relight(self, design: Design, preview: tuple[Source, ...] | None = None) -> LightField:
        """Light ``preview`` (sources as lit) if given, else ``design`` as written; the
        result becomes ``field``."""
        t0 = time.perf_counter()
        if preview is not None:
            self.field = self.model.field(preview, design.daylight)
        else:
            self.field = self.model.design_field(design)
        self.grids = design_receivers(self.model, design)
        self.grid_lux = None
        if self.grids is not None:
            lux = self.grids.Phi.astype(float) @ self.field.emission[self.model.op.zone_patches]
            self.grid_lux = lux
        if design.arrays:
            H, at_points = self._arrays_light(design.arrays)
            self.field = replace(self.field, illuminance=self.field.illuminance + H)
            if self.grid_lux is not None:
                self.grid_lux = self.grid_lux + at_points
        clear = self._clear_light(design)
        if clear is not None:
            self.field = replace(self.field, illuminance=self.field.illuminance + clear[0])
            if self.grid_lux is not None and clear[1] is not None:
                self.grid_lux = self.grid_lux + clear[1]
        self.previewing = preview is not None
        self.last_eval_ms = 1e3 * (time.perf_counter() - t0)
        return self.field

    def _arrays_light(self, arrays: tuple[LuminaireArray, ...]) -> tuple[np.ndarray, np.ndarray]:
        """Light of ``arrays`` on the patches and at the grid points (kept until they or
        the grids change)."""
        # The grids by identity (``design_grids`` keeps one per set of work planes): a
        # dataclass of numpy arrays compared with == raised once a second plane was added.
        kept = self._arrays
        if kept is None or kept[0] != arrays or kept[1] is not self.grids:
            points = None if self.grids is None else self.grids.samples
            H, at_points = arrays_field(self.model.patches, self.model.op, arrays, points)
            self._arrays = (arrays, self.grids, H, at_points)
        return self._arrays[2], self._arrays[3]

    def _clear_light(self, design: Design) -> tuple | None:
        """The fixed clear glazing's light in the design scenario (the CIE overcast sky
        of ``exterior_lux`` horizontal) on the patches and at the grid points, or None
        (``light.clear_build``: built once per clear glazing, a few seconds). Without a
        readable weather file (its sun is part of the build) the view goes without it:
        the climate panel says why."""
        if self.defer_clear and not clear_light_ready(self.model, design):
            return None
        try:
            clear = clear_light(self.model, design)
        except LightInvError:
            return None
        if clear is None:
            return None
        ext = design.daylight.exterior_lux
        points = None if clear.points is None else ext * clear.points.overcast()
        return ext * clear.patches.overcast(), points

    def grid_stats(self) -> dict[str, dict[str, float]]:
        """EN 12464-1 values (points, Em, Emin, Emax lux, U0) of each work plane shown."""
        if self.grids is None or self.grid_lux is None:
            return {}
        return {n: grid_statistics(self.grid_lux[s]) for n, s in self.grids.spans.items()}

    def layout(self, design: Design) -> tuple[Source, ...]:
        """The design's sources as lit (mirrored and centred ones placed by their rules)."""
        if not self.previewing and self.field is not None:
            return self.field.sources  # the field shown is the design's: no new work
        return self.model.layout(design)

    def design_field(self, design: Design) -> LightField:
        """The light of the design as written, even while a preview is shown."""
        if not self.previewing and self.field is not None:
            return self.field
        field = self.model.design_field(design)
        if design.arrays:
            H, _ = self._arrays_light(design.arrays)
            field = replace(field, illuminance=field.illuminance + H)
        clear = self._clear_light(design)
        if clear is not None:
            field = replace(field, illuminance=field.illuminance + clear[0])
        return field

    def of_sources(self, design: Design, sources) -> np.ndarray:
        """Illuminance (n,) lux of ``sources`` under ``design``'s tied rules and daylight."""
        key = (tuple(sources), design.rules, design.daylight)
        if self._compared is None or self._compared[0] != key:
            field = self.model.design_field(design, tuple(sources))
            self._compared = (key, field.illuminance)
        return self._compared[1]
