"""Source types: what each kind of source emits and draws, registered by kind.

Every kind of source the light model knows is one ``SourceType`` here, found by its
``SourceKind``. The zone emission, the power goals and every view ask the type, never
switch on the kind themselves, so a new kind is a new class plus one registry line.

Today's three kinds are Lambertian rectangles in an emitter zone:
- ``ZoneLuminaire``: exitance = flux / area (lm/m²), or a luminous panel's fixed
  exitance; electric power = flux / efficacy (W); on ceilings, roofs and walls;
- ``DiffusingGlazing`` (skylights): exitance = filter x glazing transmittance x exterior
  diffuse illuminance (``Daylight``); no electric power; on ceilings and roofs;
- ``WindowGlazing`` (windows): the same diffusing glazing on any planar face (a wall, a
  sloped roof): the sky groups (``light.daylight_year``) give it the light on its own
  plane, half the sky and half the ground for a wall.

Where a kind's zones may be drawn is its ``placement``: a set of ``CEILING``, ``WALL``
and ``FLOOR``, the classes of surface by the way their front faces (``surface_class``).
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from lightinv_core.design.model import Daylight, Source
from lightinv_core.errors import DesignError
from lightinv_core.kinds import GlazingKind, SourceKind, add_source_kind, remove_source_kind

CEILING = "ceiling"
"""A surface whose front faces down into the room: a ceiling, or a roof pitched up to
84° (the z of its unit front normal below ``FACES_DOWN``)."""
WALL = "wall"
"""A surface neither facing down nor up: a wall, seen from the room."""
FLOOR = "floor"
"""A surface whose front faces up (z of its normal at least ``FACES_UP``): a floor, a
desk top."""
FACES_DOWN = -0.1
FACES_UP = 0.5
OVERHEAD = frozenset({CEILING})
OVERHEAD_OR_WALL = frozenset({CEILING, WALL})
ANY_FACE = frozenset({CEILING, WALL, FLOOR})
PLACEMENT_TEXT = {
    OVERHEAD: "ceilings and roofs (surfaces facing down into the room)",
    OVERHEAD_OR_WALL: "ceilings and roofs (facing down), or walls seen from the room",
    ANY_FACE: "any planar face seen from the room (walls, ceilings, sloped roofs)",
}
"""How people read a placement, for the error when no such surface is under the cursor."""


def surface_class(normal) -> str:
    """``CEILING``, ``WALL`` or ``FLOOR``: the class of a surface by its unit front
    ``normal`` (z up)."""
    z = float(normal[2])
    return CEILING if z < FACES_DOWN else FLOOR if z >= FACES_UP else WALL


def placement_text(placement: frozenset[str]) -> str:
    """Where zones of a placement go, for people."""
    known = PLACEMENT_TEXT.get(frozenset(placement))
    return known or ", ".join(f"{c}s" for c in sorted(placement)) or "no surface"


def rect_areas(rect: np.ndarray) -> np.ndarray:
    """Areas (m²) of rectangles (..., 4) given by two diagonal corners."""
    return np.abs(rect[..., 2] - rect[..., 0]) * np.abs(rect[..., 3] - rect[..., 1])


class SourceType(Protocol):
    """What a kind of source emits (lm/m², lm) and draws (W), and how views name it.

    ``label``: its name for people ("Luminaire"); ``stem``: the prefix of the names the
    editor gives new sources ("L1", "L2"); ``electric``: it draws electric power (power
    and energy goals, dimming); ``daylit``: it lets daylight in, so its light follows
    the sky and the weather year (daylight scenarios, sDA, glazing area); ``strength``:
    the ``Source`` field that sets how much it emits (``"flux"``, lm, or ``"filter"``, a
    fraction), with ``strength_label`` its name for people; ``fields``: the ``Source``
    fields that belong to this kind alone (the project reader refuses them on another);
    ``placement``: the classes of surface (``CEILING``, ``WALL``, ``FLOOR``) its zones
    may be drawn on.
    """

    kind: str
    label: str
    stem: str
    electric: bool
    daylit: bool
    strength: str
    strength_label: str
    fields: tuple[str, ...]
    placement: frozenset[str]

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
    label = "Luminaire"
    stem = "L"
    electric = True
    daylit = False
    strength = "flux"
    strength_label = "Flux (lm)"
    fields = ("flux", "flux_range", "exitance", "efficacy", "control_group")
    placement = OVERHEAD_OR_WALL

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
    diffuse illuminance (lux) as a Lambertian exitance. With ``glazing`` clear it emits
    no exitance: its light is the sky and sun by direction (``light.clear_glazing``)."""

    kind = SourceKind.SKYLIGHT
    label = "Skylight"
    stem = "S"
    electric = False
    daylit = True
    strength = "filter"
    strength_label = "Filter"
    fields = ("filter", "glazing")
    placement = OVERHEAD

    def exitance(self, s, rect, flux, filt, daylight):
        if s.glazing == GlazingKind.CLEAR:
            return np.zeros(len(rect))
        return filt * daylight.transmittance * daylight.exterior_lux

    def largest_exitance(self, s, zone, daylight):
        return daylight.exterior_lux * daylight.transmittance

    def flux(self, s, daylight):
        return s.filter * daylight.transmittance * daylight.exterior_lux * s.area

    def electric_power(self, s, rect, flux):
        return np.zeros(len(rect))

    def largest_electric_power(self, s, zone):
        return 0.0


class WindowGlazing(DiffusingGlazing):
    """A window: diffusing glazing on any planar face, a wall's included. Its light is
    the sky and ground on its own plane (the sky groups), as a skylight's is; with
    ``glazing`` clear, the sky and sun by direction (``light.clear_glazing``)."""

    kind = SourceKind.WINDOW
    label = "Window (glazing)"
    stem = "W"
    placement = ANY_FACE


SOURCE_TYPES: dict[str, SourceType] = {
    str(t.kind): t for t in (ZoneLuminaire(), DiffusingGlazing(), WindowGlazing())
}
_BUILT_IN = tuple(SOURCE_TYPES)


def register_source_type(t: SourceType) -> SourceType:
    """Add a kind of source (ValueError when its kind is taken): projects may then name
    it and every view lists it. Returns ``t``."""
    if t.kind in SOURCE_TYPES:
        raise ValueError(f"source kind {t.kind!r} is already registered")
    add_source_kind(t.kind)
    SOURCE_TYPES[t.kind] = t
    return t


def unregister_source_type(kind: str) -> None:
    """Remove a kind added by ``register_source_type`` (the built-in ones stay)."""
    if kind in _BUILT_IN:
        raise ValueError(f"source kind {kind!r} is built in")
    remove_source_kind(kind)
    SOURCE_TYPES.pop(kind, None)


def source_type(kind: str) -> SourceType:
    """The registered type of source kind ``kind`` (DesignError for an unknown kind)."""
    try:
        return SOURCE_TYPES[kind]
    except KeyError:
        known = ", ".join(SOURCE_TYPES)
        raise DesignError(f"unknown source kind {kind!r} (kinds: {known})") from None


def source_types() -> tuple[SourceType, ...]:
    """Every kind of source, the built-in ones first."""
    return tuple(SOURCE_TYPES.values())


def daylit(sources) -> tuple:
    """The sources that let daylight in (skylights and other glazing), in order."""
    return tuple(s for s in sources if source_type(s.kind).daylit)


def diffusing(sources) -> tuple:
    """The daylit sources whose glazing glows (not clear: ``light.clear_glazing``)."""
    return tuple(s for s in daylit(sources) if getattr(s, "glazing", None) != GlazingKind.CLEAR)


def electric(sources) -> tuple:
    """The sources that draw electric power (luminaires), in order."""
    return tuple(s for s in sources if source_type(s.kind).electric)
