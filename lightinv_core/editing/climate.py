"""The climate as an editor sees it: the weather's site, the hours of its year, and one
layout's light in every scenario built once per design (not once per look).

``DaylightCache`` keeps the ``LayoutDaylight`` of the design as written and of the
layout shown (a running best's preview); ``weather_of`` reads a daylight's weather file
once while it is unchanged; ``hour_index`` / ``hour_date`` turn a calendar day and an
hour into the hour of the weather year (0-8759) and back; ``hour_state`` says what the
sky and the dimming do in one hour (docs/daylight.md).
"""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.weather import Weather, load_weather
from lightinv_core.design.model import Daylight, Design
from lightinv_core.light.daylight import LayoutDaylight, layout_daylight
from lightinv_core.light.daylight_year import weather_path

MONTHS = ("Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec")
HOURS_PER_YEAR = 8760
_YEAR = 2001  # a year that is not a leap year: a weather file's calendar has 365 days


def hour_index(month: int, day: int, hour: int) -> int:
    """The hour of the year (0-8759) that starts at ``hour`` o'clock (0-23) on ``day``
    of ``month`` (1-12); a day past the month's end is its last day."""
    month = min(max(int(month), 1), 12)
    day = min(max(int(day), 1), month_days(month))
    doy = (_dt.date(_YEAR, month, day) - _dt.date(_YEAR, 1, 1)).days
    return doy * 24 + min(max(int(hour), 0), 23)


def hour_date(index: int) -> tuple[int, int, int]:
    """(month, day, hour of day) of hour ``index`` of the year (the inverse of
    ``hour_index``)."""
    index = min(max(int(index), 0), HOURS_PER_YEAR - 1)
    day = _dt.date(_YEAR, 1, 1) + _dt.timedelta(days=index // 24)
    return day.month, day.day, index % 24


def month_days(month: int) -> int:
    """Days in ``month`` (1-12) of a year that is not a leap year."""
    nxt = _dt.date(_YEAR + (month == 12), month % 12 + 1, 1)
    return (nxt - _dt.date(_YEAR, month, 1)).days


def weather_of(daylight: Daylight) -> Weather:
    """The weather file ``daylight`` names, read once while the file is unchanged
    (WeatherError when it cannot be read)."""
    return load_weather(weather_path(daylight))


def site_text(weather: Weather) -> str:
    """A weather file's site in two lines: its name; latitude, longitude, time zone and
    the file's format (``weather.illuminance`` says where its illuminance comes from)."""
    ns = "N" if weather.latitude >= 0 else "S"
    ew = "E" if weather.longitude >= 0 else "W"
    return (
        f"{weather.name.title()}\n{abs(weather.latitude):.2f}° {ns}, "
        f"{abs(weather.longitude):.2f}° {ew}, UTC{weather.utc_offset_h:+g} h, {weather.format}"
    )


def weather_notes(weather: Weather) -> list[str]:
    """What reading the weather file filled, decided or doubts, one line each."""
    return [f"Weather file: {note}." for note in weather.notes]


@dataclass(frozen=True)
class HourState:
    """One hour of the weather year: ``hour`` (0-based), ``when`` in words ("Wed 21 Jun
    12:00-13:00"), whether it is ``occupied``, the global horizontal illuminance of the
    weather file (lux), the exterior lux on each sky group's glazing and the luminaires'
    dimming ``level`` (0-1, 0 when unoccupied)."""

    hour: int
    when: str
    occupied: bool
    horizontal_lux: float
    glazing_lux: tuple[float, ...]
    level: float

    def text(self) -> str:
        """The hour in two lines, as the view's caption shows it."""
        glazing = ", ".join(f"{x:,.0f}" for x in self.glazing_lux)
        sky = f"Exterior {self.horizontal_lux:,.0f} lux"
        if glazing:
            sky += f" (on the glazing {glazing} lux)"
        use = (
            f"occupied: luminaires at {100 * self.level:.0f}%"
            if self.occupied
            else "unoccupied: luminaires off"
        )
        return f"{self.when}, {use}\n{sky}"


def hour_state(ld: LayoutDaylight, weather: Weather | None, hour: int) -> HourState:
    """What happens in hour ``hour`` of the year to the layout ``ld`` (its weather year
    read on first use: WeatherError when it cannot be)."""
    year = ld.patches.year()
    hour = min(max(int(hour), 0), year.every.shape[1] - 1)
    start = year.times[hour] - np.timedelta64(60, "m")
    when = f"{start:%a %d %b %H:00}-{(start.hour + 1) % 24:02d}:00"
    horizontal = float(weather.gh_lux[hour]) if weather is not None else float("nan")
    return HourState(
        hour,
        when,
        bool(year.occupied[hour]),
        horizontal,
        tuple(float(x) for x in year.every[:, hour]),
        ld.level_at(hour),
    )


class DaylightCache:
    """The ``LayoutDaylight`` of the design as written and of the layout shown, each
    rebuilt only when the design, the layout previewed or the light model changes."""

    def __init__(self) -> None:
        self._slots: dict[bool, tuple[object, Design, object, LayoutDaylight]] = {}

    def get(self, light, design: Design, preview=None) -> LayoutDaylight:
        """The light of ``design`` (or of the ``preview`` sources, as lit) in every
        scenario on ``light``'s patches."""
        slot = preview is not None
        held = self._slots.get(slot)
        if held is not None and held[0] is light and held[1] is design and held[2] is preview:
            return held[3]
        ld = layout_daylight(light, design, sources=preview)
        self._slots[slot] = (light, design, preview, ld)
        return ld

    def put(self, light, design: Design, ld: LayoutDaylight) -> None:
        """Keep ``ld``, the light of ``design`` as written made elsewhere (a worker's, on
        another light model of the same operator), as if ``get`` had built it."""
        self._slots[False] = (light, design, None, ld)

    def clear(self) -> None:
        """Forget both (a new scene or light model)."""
        self._slots.clear()
