"""The view's daylight maps (View > Colour by): DF, DA300, UDI, the light at night or
under the overcast sky, and the light of one hour of the year, each of the layout shown,
on the patches and on the work planes' points.

Each is read from the layout's light in every scenario (``DocumentModel.layout_daylight``,
built once per design change); what cannot be computed is said in the map's caption.
"""

from __future__ import annotations

import numpy as np

from app.document import Document
from lightinv_core.editing.climate import hour_state
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Scenario

MAPS = {
    # key: (Colour by text, colour bar title, its label format)
    "night": ("illuminance at night: luminaires only (lux)", "lux, night", "%.0f"),
    "overcast": ("illuminance under the overcast sky (lux)", "lux, overcast", "%.0f"),
    "df": ("daylight factor DF (%)", "DF %", "%.1f"),
    "da": ("daylight autonomy DA300 (% of occupied hours)", "DA300 %", "%.0f"),
    "udi": ("useful daylight UDI 100-3000 lux (% of hours)", "UDI %", "%.0f"),
    "hour": ("illuminance at the hour of the year (lux)", "lux", "%.0f"),
}
"""The view's daylight maps, each from the layout shown's ``LayoutDaylight``."""
PERCENT_MAPS = ("da", "udi")  # drawn 0-100 % whatever the range set


class MapResult:
    """A daylight map for the view: ``values`` per patch (None: nothing to show), the
    colour bar's ``units`` and label ``fmt``, a ``caption``, a fixed ``clim`` (None:
    the view's range) and the work planes' ``grids`` with the same quantity at their
    points (``grid_values``; None without work planes)."""

    def __init__(self, values, units: str, fmt: str, caption: str | None, clim=None):
        self.values, self.units, self.fmt = values, units, fmt
        self.caption, self.clim = caption, clim
        self.grids, self.grid_values = None, None

    @property
    def label_format(self) -> str:
        """The iso-lines' label format (str.format) matching the colour bar's."""
        return "{:" + self.fmt.lstrip("%") + "}"


def map_values(doc: Document, key: str, hour: int) -> MapResult:
    """The map ``key`` (a key of ``MAPS``) of the layout shown, on the patches and the
    work planes' points; its values None and the caption saying why when it cannot be
    computed (no light model, an unreadable weather file)."""
    _, units, fmt = MAPS[key]
    try:
        ld = doc.layout_daylight(shown=True)
        if ld is None:
            return MapResult(None, units, fmt, None)
        shown = _map(ld, doc, key, hour, units, fmt)
        if ld.points is not None:
            shown.grids = ld.grids
            shown.grid_values = _on(ld.points, ld, key, hour)
        return shown
    except LightInvError as exc:
        return MapResult(None, units, fmt, f"{MAPS[key][0]}: {exc}")


def _map(ld, doc: Document, key: str, hour: int, units: str, fmt: str) -> MapResult:
    p = ld.patches
    values = _on(p, ld, key, hour)
    hint = "\nThe design has no skylights: no daylight." if not p.groups.count else ""
    if key in (Scenario.NIGHT, Scenario.OVERCAST):
        cap = "Luminaires only" if key == Scenario.NIGHT else "Luminaires + the CIE overcast sky"
        return MapResult(values, units, fmt, cap + hint)
    if key == "df":
        return MapResult(values, units, fmt, "Daylight factor, CIE overcast sky" + hint)
    if key in PERCENT_MAPS:
        over = f" of {p.year().hours:,} occupied hours" if p.groups.count else ""
        what = "with 300 lux of daylight" if key == "da" else "with 100-3000 lux of daylight"
        head = "DA300" if key == "da" else "UDI 100-3000"
        return MapResult(values, units, fmt, f"{head}: share{over}\n{what}" + hint, (0.0, 100.0))
    state = hour_state(ld, _weather_or_none(doc), hour)
    return MapResult(values, units, fmt, state.text())


def _on(light, ld, key: str, hour: int) -> np.ndarray:
    """The map ``key`` at the receivers of ``light`` (the layout's patches or points)."""
    if key in (Scenario.NIGHT, Scenario.OVERCAST):
        return light.lux(key)[:, 0]
    if key == "df":
        return 100.0 * light.overcast_daylight()[:, 0]
    if key in PERCENT_MAPS:
        return 100.0 * (light.da() if key == "da" else light.udi())[:, 0]
    if light is ld.patches:
        return ld.hour_lux(hour)
    # The same sum as ``LayoutDaylight.hour_lux``, at the work planes' points.
    year = light.year()
    day = np.tensordot(year.every[:, hour], light.sky[:, :, 0], axes=1) if light.groups.count else 0
    return light.electric[:, 0] * ld.level_at(hour) + day


def _weather_or_none(doc: Document):
    try:
        return doc.weather()
    except LightInvError:
        return None
