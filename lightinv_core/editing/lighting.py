"""``ShownLight``: the light an editor shows, all of it from one ``LightModel``.

Three layouts are lit: the design as written (its tied rules applied), a previewed
layout (a running optimisation's best, without touching the design), and other sources
under the design's rules (a pinned result, for the difference view; its light is kept
until its sources or the rules change, since the view asks on every edit).
"""

from __future__ import annotations

import time

import numpy as np

from lightinv_core.design.model import Design, Source
from lightinv_core.light.field import LightField
from lightinv_core.light.model import LightModel


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

    def relight(self, design: Design, preview: tuple[Source, ...] | None = None) -> LightField:
        """Light ``preview`` (sources as lit) if given, else ``design`` as written; the
        result becomes ``field``."""
        t0 = time.perf_counter()
        if preview is not None:
            self.field = self.model.field(preview, design.daylight)
        else:
            self.field = self.model.design_field(design)
        self.previewing = preview is not None
        self.last_eval_ms = 1e3 * (time.perf_counter() - t0)
        return self.field

    def layout(self, design: Design) -> tuple[Source, ...]:
        """The design's sources as lit (mirrored and centred ones placed by their rules)."""
        if not self.previewing and self.field is not None:
            return self.field.sources  # the field shown is the design's: no new work
        return self.model.layout(design)

    def design_field(self, design: Design) -> LightField:
        """The light of the design as written, even while a preview is shown."""
        if not self.previewing and self.field is not None:
            return self.field
        return self.model.design_field(design)

    def of_sources(self, design: Design, sources) -> np.ndarray:
        """Illuminance (n,) lux of ``sources`` under ``design``'s tied rules and daylight."""
        key = (tuple(sources), design.rules, design.daylight)
        if self._compared is None or self._compared[0] != key:
            field = self.model.design_field(design, tuple(sources))
            self._compared = (key, field.illuminance)
        return self._compared[1]
