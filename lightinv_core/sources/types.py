"""Source types: what each kind of source emits and draws, registered by kind.

Every kind of source the light model knows is one ``SourceType`` here, found by its
``SourceKind``. The zone emission, the power goals and every view ask the type, never
switch on the kind themselves, so a new kind is a new class plus one registry line.

Today's two kinds are both Lambertian rectangles in an emitter zone:
- ``ZoneLuminaire``: exitance = flux / area (lm/m²), or a luminous panel's fixed
  exitance; electric power = flux / efficacy (W);
- ``DiffusingGlazing`` (skylights): exitance = filter x glazing transmittance x exterior
  diffuse illuminance (``Daylight``); no electric power.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from lightinv_core.design.model import Daylight, Source
from lightinv_core.errors import DesignError
from lightinv_core.kinds import SourceKind


def rect_areas(rect: np.ndarray) -> np.ndarray:
    """Areas (m²) of rectangles (..., 4) given by two diagonal corners."""
    return np.abs(rect[..., 2] - rect[..., 0]) * np.abs(rect[..., 3] - rect[..., 1])


class SourceType(Protocol):
    """What a kind of source emits (lm/m², lm) and draws (W)."""

    kind: SourceKind
    electric: bool

    def exitance(
        self, s: Source, rect: np.ndarray, flux: np.ndarray, filt: np.ndarray, daylight: Daylight
    ) -> np.ndarray:
        """Exitance (lm/m²) per candidate (rect (m, 4) m, flux (m,) lm, filt (m,))."""
        ...

    def largest_exitance(self, s: Source, zone: tuple[float, float], daylight: Daylight) -> float:
        """Exitance (lm/m²) covering the whole zone ((width, height) m) at the largest
        setting: the scale of the light-power goal."""
        ...

    def flux(self, s: Source, daylight: Daylight) -> float:
        """Luminous flux (lm) the source emits as placed."""
        ...

    def electric_power(self, s: Source, rect: np.ndarray, flux: np.ndarray) -> np.ndarray:
        """Electric power (W) per candidate."""
        ...

    def largest_electric_power(self, s: Source, zone: tuple[float, float]) -> float:
        """Electric power (W) at the largest setting: the scale of the power goal."""
        ...


class ZoneLuminaire:
    """A Lambertian luminaire rectangle with a flux (lm), or a luminous panel with a
    fixed exitance (lm/m²); efficacy in lm/W."""

    kind = SourceKind.LUMINAIRE
    electric = True

    def exitance(self, s, rect, flux, filt, daylight):
        if s.exitance is not None:
            return np.full(len(rect), s.exitance)
        return flux / np.maximum(rect_areas(rect), 1e-12)

    def largest_exitance(self, s, zone, daylight):
        w, h = zone
        return s.exitance if s.exitance is not None else s.flux_range[1] / (w * h)

    def flux(self, s, daylight):
        return s.flux if s.flux is not None else s.exitance * s.area

    def electric_power(self, s, rect, flux):
        if s.exitance is not None:
            return s.exitance * rect_areas(rect) / s.efficacy
        return flux / s.efficacy

    def largest_electric_power(self, s, zone):
        w, h = zone
        flux = s.exitance * w * h if s.exitance is not None else s.flux_range[1]
        return flux / s.efficacy


class DiffusingGlazing:
    """A skylight: diffusing glazing passing filter x transmittance of the exterior
    diffuse illuminance (lux) as a Lambertian exitance."""

    kind = SourceKind.SKYLIGHT
    electric = False

    def exitance(self, s, rect, flux, filt, daylight):
        return filt * daylight.transmittance * daylight.exterior_lux

    def largest_exitance(self, s, zone, daylight):
        return daylight.exterior_lux * daylight.transmittance

    def flux(self, s, daylight):
        return s.filter * daylight.transmittance * daylight.exterior_lux * s.area

    def electric_power(self, s, rect, flux):
        return np.zeros(len(rect))

    def largest_electric_power(self, s, zone):
        return 0.0


SOURCE_TYPES: dict[str, SourceType] = {
    str(t.kind): t for t in (ZoneLuminaire(), DiffusingGlazing())
}


def source_type(kind: str) -> SourceType:
    """The registered type of source kind ``kind`` (DesignError for an unknown kind)."""
    try:
        return SOURCE_TYPES[kind]
    except KeyError:
        known = ", ".join(SOURCE_TYPES)
        raise DesignError(f"unknown source kind {kind!r} (kinds: {known})") from None
