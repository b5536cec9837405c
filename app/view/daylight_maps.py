"""The view's daylight maps (View > Colour by): the light in each scenario (night,
overcast, and any registered one), each daylight metric (DF, DA300, UDI, sDA, and any
registered one) and the light of one hour of the year, each of the layout shown, on the
patches and on the work planes' points; the lists come from the scenario and quantity
registries; and the maps at the observers (simplified DGP over the year,
``observer_maps``), which colour the observers' glyphs, not the patches.

Each is read from the layout's light in every scenario (``DocumentModel.layout_daylight``,
built once per design change); what cannot be computed is said in the map's caption.
"""

from __future__ import annotations

import numpy as np

from app.document import Document
from app.view import observer_maps
from lightinv_core.editing.climate import hour_state
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Scenario
from lightinv_core.quantities import is_quantity, quantity_spec, quantity_specs
from lightinv_core.scenarios import is_scenario, scenario_spec, scenario_specs

HOUR = "hour"
"""The key of the map of one hour of the weather year."""


def maps() -> dict[str, tuple[str, str, str]]:
    """The view's daylight maps, key -> (Colour by text, colour bar title, its label
    format): every scenario with an illuminance but the design one (the view's own),
    every daylight metric of the quantity registry (DF, then the annual ones: shares
    drawn in %), and the hour of the year."""
    out = {
        s.name: (f"illuminance, {s.label} (lux)", f"lux, {s.name}", "%.0f")
        for s in scenario_specs()
        if s.lux is not None and s.name != Scenario.DESIGN
    }
    for q in quantity_specs():
        for key, text, _ in q.point_maps:  # per-point maps of a plane's figure
            out[key] = (text, f"{key.rsplit('_', 1)[-1]} lux %", "%.0f")
        if q.plane:
            continue  # one figure of a whole work plane: its point maps above show it
        if q.hours is not None:
            out[q.name] = (_annual_text(q), f"{q.metric.split()[0]} %", "%.0f")
        elif q.from_scenarios is not None:
            out[q.name] = (q.label, f"{q.metric} {q.unit}".strip(), f"%.{q.decimals - 1}f")
    out.update(observer_maps.observer_maps())
    out[HOUR] = ("illuminance at the hour of the year (lux)", "lux", "%.0f")
    return out


def _point_map(key: str):
    """(quantity spec, Colour-by text, fn) of a quantity's per-point map, or None."""
    for q in quantity_specs():
        for k, text, fn in q.point_maps:
            if k == key:
                return q, text, fn
    return None


def _annual_text(q) -> str:
    """An annual metric's Colour by entry: its name, then what its % means."""
    if q.hours.point_share is None and q.hours.point_hours is None:
        return f"{q.noun} {q.metric} (% of occupied hours)"
    return f"{q.noun} {q.metric} (100 % where a point counts)"


class MapResult:
    """A daylight map for the view: ``values`` per patch (None: nothing to show), the
    colour bar's ``units`` and label ``fmt``, a ``caption``, a fixed ``clim`` (None:
    the view's range) and the work planes' ``grids`` with the same quantity at their
    points (``grid_values``; None without work planes); ``observers`` the colours of
    the observers' glyphs (``observer_maps.ObserverColours``; None: drawn plain)."""

    def __init__(self, values, units: str, fmt: str, caption: str | None, clim=None):
        self.values, self.units, self.fmt = values, units, fmt
        self.caption, self.clim = caption, clim
        self.grids, self.grid_values = None, None
        self.observers: observer_maps.ObserverColours | None = None

    @property
    def label_format(self) -> str:
        """The iso-lines' label format (str.format) matching the colour bar's."""
        return "{:" + self.fmt.lstrip("%") + "}"


def map_values(doc: Document, key: str, hour: int) -> MapResult:
    """The map ``key`` (a key of ``maps()``) of the layout shown, on the patches and the
    work planes' points; its values None and the caption saying why when it cannot be
    computed (no light model, an unreadable weather file)."""
    text, units, fmt = maps()[key]
    try:
        if key in observer_maps.observer_maps():
            return _at_observers(doc, key, units, fmt)
        ld = doc.layout_daylight(shown=True)
        if ld is None:
            return MapResult(None, units, fmt, None)
        shown = _map(ld, doc, key, hour, units, fmt)
        if ld.points is not None:
            shown.grids = ld.grids
            shown.grid_values = _on(ld.points, ld, key, hour)
        return shown
    except LightInvError as exc:
        return MapResult(None, units, fmt, f"{text}: {exc}")


def _at_observers(doc: Document, key: str, units: str, fmt: str) -> MapResult:
    """A map at the observers: the patches in their materials (values None), the
    observers' colours and the caption saying what they mean."""
    if doc.light is None:
        return MapResult(None, units, fmt, None)
    figures, left_out = doc.observer_dgp(shown=True)
    shown = MapResult(None, units, fmt, observer_maps.caption(key, figures, left_out))
    if figures:
        shown.observers = observer_maps.observer_colours(key, figures)
    return shown


def _map(ld, doc: Document, key: str, hour: int, units: str, fmt: str) -> MapResult:
    p = ld.patches
    values = _on(p, ld, key, hour)
    hint = "\nThe design has no skylights: no daylight." if not p.daylit else ""
    if is_scenario(key):
        light = _capital(scenario_spec(key).describe(doc.design.daylight))
        return MapResult(values, units, fmt, light + hint)
    if _point_map(key) is not None:
        text = _point_map(key)[1]
        return MapResult(values, units, fmt, text + hint, (0.0, 100.0))
    if is_quantity(key):
        q = quantity_spec(key)
        if q.hours is None:
            where = f"{_capital(q.noun)}, {scenario_spec(q.default_scenario).name} scenario"
            return MapResult(values, units, fmt, where + hint)
        over = f" of {p.year().hours:,} occupied hours" if p.daylit else ""
        band = q.hours
        what = (
            f"with {band.lo:g} lux of daylight or more"
            if band.hi == np.inf
            else f"with {band.lo:g}-{band.hi:g} lux of daylight"
        )
        if band.direct_sun:
            over = " of the area" if p.daylit else ""
            what = (
                f"direct sun above {band.lo:g} lux in more than {band.point_hours} "
                "occupied hours (clear glazing, blinds open)"
            )
        caption = f"{q.metric}: share{over}\n{what}" + hint
        return MapResult(values, units, fmt, caption, (0.0, 100.0))
    state = hour_state(ld, _weather_or_none(doc), hour)
    return MapResult(values, units, fmt, state.text())


def design_caption(doc: Document, what: str) -> str:
    """The caption of the design's own light (``what``: "Illuminance", "Radiosity B"):
    the scenario it is in and what lights it there (the view named no scenario)."""
    light = scenario_spec(Scenario.DESIGN).describe(doc.design.daylight)
    return f"{what}, {Scenario.DESIGN} scenario: {light}"


def _capital(text: str) -> str:
    return text[:1].upper() + text[1:]


def _on(light, ld, key: str, hour: int) -> np.ndarray:
    """The map ``key`` at the receivers of ``light`` (the layout's patches or points)."""
    if is_scenario(key):
        return light.lux(key)[:, 0]
    if _point_map(key) is not None:
        return 100.0 * _point_map(key)[2](light, slice(None))[:, 0]
    if is_quantity(key):
        q = quantity_spec(key)
        if q.hours is not None:
            return 100.0 * light.band(q.hours)[:, 0]
        return q.from_scenarios(light, slice(None))[:, 0]
    if light is ld.patches:
        return ld.hour_lux(hour)
    # The same sum as ``LayoutDaylight.hour_lux``, at the work planes' points.
    return ld.hour_electric(hour, at_points=True) + light.hour_daylight(hour)


def _weather_or_none(doc: Document):
    try:
        return doc.weather()
    except LightInvError:
        return None
