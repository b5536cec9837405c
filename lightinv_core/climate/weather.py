"""Hourly weather for daylight: EPW, TMY3 and TMY2 files, checked and in one convention.

**Time convention.** Each record covers the hour [t - 1 h, t) in local standard time
and is labelled by its end t (``Weather.times``); the sun and the occupancy schedule
are taken at its middle, t - 30 min (``Weather.midpoints``). EPW, TMY3 and TMY2 all
number hours 1-24, hour 1 being 00:00-01:00, and their readers
(``climate.weather_formats``) keep that number: no format is shifted in secret.
(pvlib's ``read_epw`` labels records by their start; LightInv does not use it.)

**Units.** Irradiance in W/m²; illuminance in lux, decided from the data (lux or
hundreds of lux) or modelled where the file has none (``weather_checks``); the
decision is ``Weather.illuminance``, what was filled or doubtful is ``Weather.notes``.

Shipped: ``resources/weather/greensboro-nc-tmy3.csv``, the TMY3 file for Greensboro,
North Carolina (USAF 723170; 36.1 N, 79.95 W, 273 m, UTC-5) that pvlib ships as
``pvlib/data/723170TYA.CSV`` (NREL's TMY3 data set, 1991-2005; pvlib is BSD-3). Its
illuminance is in hundreds of lux (the data says so: 1.07 lux per W/m²).
"""

from __future__ import annotations

import os
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightinv_core.climate import weather_checks as checks
from lightinv_core.climate.weather_formats import WeatherError, read_records, require_pvlib
from lightinv_core.textcodec import decode_text

__all__ = ["BUILTIN", "Weather", "WeatherError", "load_weather", "read_weather", "require_pvlib"]

BUILTIN = Path(__file__).resolve().parents[2] / "resources" / "weather" / "greensboro-nc-tmy3.csv"
"""The shipped weather file (see the module)."""
MAX_BYTES = 64 * 2**20


@dataclass(frozen=True, eq=False)
class Weather:
    """Hourly weather at a site (see the module). Arrays have one value per hour."""

    name: str
    latitude: float
    longitude: float
    altitude: float
    utc_offset_h: float
    times: object  # pandas DatetimeIndex, local standard time, hour ending
    ghi: np.ndarray
    dni: np.ndarray
    dhi: np.ndarray
    gh_lux: np.ndarray
    dn_lux: np.ndarray
    dh_lux: np.ndarray
    source: str
    format: str = "TMY3"
    illuminance: str = ""
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def hours(self) -> int:
        """Number of hours."""
        return len(self.ghi)

    @property
    def midpoints(self):
        """The middle of each record's hour (local standard time): where the sun and
        the occupancy schedule are taken."""
        return self.times - np.timedelta64(30, "m")

    def occupied(self, start_h: float = 8.0, end_h: float = 18.0, weekdays: bool = True):
        """Mask of the hours in the occupancy schedule: local hours whose middle falls
        in [start_h, end_h), Monday to Friday if ``weekdays`` (default 8-18 weekdays;
        the weekday of each record's own date, as the file gives its year)."""
        if not 0 <= start_h < end_h <= 24:
            raise WeatherError(f"occupancy must be 0 <= start < end <= 24 h, got {start_h}-{end_h}")
        mid = self.midpoints
        hour = np.asarray(mid.hour + mid.minute / 60.0)
        mask = (hour >= start_h) & (hour < end_h)
        if weekdays:
            mask &= np.asarray(mid.day_of_week) < 5
        return mask

    def describe(self) -> dict:
        """What was read and decided, for ``--json``, the report and the window."""
        return {
            "site": self.name,
            "latitude": self.latitude,
            "longitude": self.longitude,
            "utc_offset_h": self.utc_offset_h,
            "file": self.source,
            "format": self.format,
            "hours": self.hours,
            "time_convention": "hour ending, local standard time; sun at mid-hour",
            "illuminance": self.illuminance,
            "annual_ghi_kwh_m2": round(float(self.ghi.sum()) / 1000.0, 1),
            "notes": list(self.notes),
        }


_LOADED: dict[tuple, Weather] = {}
MAX_LOADED = 4


def load_weather(path: str | os.PathLike) -> Weather:
    """``read_weather``, remembered while the file is unchanged (its path, size and
    modification time): the optimiser's year and the window read a file once."""
    p = BUILTIN if str(path) == "builtin" else Path(path)
    try:
        stat = p.stat()
    except OSError:
        return read_weather(p)  # says why: missing or unreadable
    key = (str(p), stat.st_mtime_ns, stat.st_size)
    if key not in _LOADED:
        weather = read_weather(p)
        if len(_LOADED) >= MAX_LOADED:
            _LOADED.pop(next(iter(_LOADED)))
        _LOADED[key] = weather
    return _LOADED[key]


def _read_text(path: Path) -> tuple[str, str]:
    name = path.name
    try:
        size = path.stat().st_size
    except FileNotFoundError:
        raise WeatherError(f"weather file '{path}' does not exist; check the path") from None
    except OSError as exc:
        raise WeatherError(f"cannot read weather file '{path}': {exc.strerror}") from None
    if not path.is_file():
        raise WeatherError(f"weather file '{path}' is not a file")
    if size > MAX_BYTES:
        raise WeatherError(f"{name}: {size / 2**20:.0f} MB is too big for an hourly weather file")
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise WeatherError(f"cannot read weather file '{path}': {exc.strerror}") from None
    if not data.strip():
        raise WeatherError(f"{name}: the file is empty")
    text, encoding = decode_text(data)
    if "\0" in text:
        raise WeatherError(f"{name}: binary data (NUL bytes), not a weather file")
    return text, encoding


def read_weather(path: str | os.PathLike) -> Weather:
    """Read and check an EPW, TMY3 or TMY2 weather file (see the module);
    ``"builtin"`` reads the shipped Greensboro TMY3 file. WeatherError says why a file
    cannot be used."""
    path = BUILTIN if str(path) == "builtin" else Path(path)
    name = path.name
    text, encoding = _read_text(path)
    pvlib = require_pvlib()
    rec = read_records(text, path, name)
    notes = list(rec.notes) + checks.check_site(rec, name)
    times, more = checks.calendar(rec, name)
    notes += more
    start, middle, end = checks.sun_elevation(times, rec)
    night = (start < -0.5) & (end < -0.5)
    notes += checks.fill_irradiance(rec, night, name)
    notes += checks.clock_check(rec, times, start, end, name)
    zenith = 90.0 - middle
    airmass = np.asarray(pvlib.atmosphere.get_relative_airmass(np.minimum(zenith, 90.0)), float)
    with warnings.catch_warnings():
        # pvlib's own use of pandas APIs that pandas deprecates: not the user's concern.
        warnings.simplefilter("ignore", DeprecationWarning)
        warnings.simplefilter("ignore", FutureWarning)
        extra = np.asarray(pvlib.irradiance.get_extra_radiation(times - np.timedelta64(30, "m")))
    illuminance, more = checks.decide_illuminance(rec, zenith, airmass, extra, name)
    notes += more
    if encoding not in ("utf-8", "ascii"):
        notes.append(f"read as {encoding} text")
    v = rec.values
    return Weather(
        rec.site,
        rec.latitude,
        rec.longitude,
        rec.altitude,
        rec.utc_offset_h,
        times,
        v["ghi"],
        v["dni"],
        v["dhi"],
        v["gh_lux"],
        v["dn_lux"],
        v["dh_lux"],
        str(path),
        rec.format,
        illuminance,
        tuple(notes),
    )
