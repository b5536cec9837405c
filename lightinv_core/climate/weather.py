"""Hourly weather for daylight: EPW and TMY3 files read with pvlib (an optional extra).

A ``Weather`` holds, per hour, the solar irradiance components (W/m²) and the
measured or modelled illuminance components (lux) of the file, with the site. Hours
are labelled as in the files: the hour *ending* at the time stamp, local standard
time; solar positions are taken at the middle of each hour.

Shipped: ``resources/weather/greensboro-nc-tmy3.csv``, the TMY3 file for Greensboro,
North Carolina (USAF 723170; 36.1 N, 79.95 W, 273 m, UTC-5) that pvlib ships as
``pvlib/data/723170TYA.CSV`` (NREL's TMY3 data set, 1991-2005; pvlib is BSD-3). TMY3
files give illuminance in hundreds of lux: the reader multiplies by 100 (checked:
the global illuminance is then 107 lm/W of the global irradiance on average).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lightinv_core.errors import LightInvError

BUILTIN = Path(__file__).resolve().parents[2] / "resources" / "weather" / "greensboro-nc-tmy3.csv"
"""The shipped weather file (see the module)."""
MAX_BYTES = 64 * 2**20


class WeatherError(LightInvError):
    """A weather file cannot be read or used."""


def require_pvlib():
    """The pvlib module, or a WeatherError saying how to install it."""
    try:
        import pvlib
    except ImportError:
        raise WeatherError(
            "climate-based daylight needs pvlib: install the climate extra "
            "(pip install 'lightinv[climate]'; ./dev.sh does)"
        ) from None
    return pvlib


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

    @property
    def hours(self) -> int:
        """Number of hours."""
        return len(self.ghi)

    def occupied(self, start_h: float = 8.0, end_h: float = 18.0, weekdays: bool = True):
        """Mask of the hours in the occupancy schedule: local hours whose middle falls
        in [start_h, end_h), Monday to Friday if ``weekdays`` (default 8-18 weekdays)."""
        if not 0 <= start_h < end_h <= 24:
            raise WeatherError(f"occupancy must be 0 <= start < end <= 24 h, got {start_h}-{end_h}")
        mid = self.times - np.timedelta64(30, "m")
        hour = mid.hour + mid.minute / 60.0
        mask = (np.asarray(hour) >= start_h) & (np.asarray(hour) < end_h)
        if weekdays:
            mask &= np.asarray(mid.day_of_week) < 5
        return mask


def _column(df, names: tuple[str, ...], source: str) -> np.ndarray:
    for n in names:
        if n in df.columns:
            v = np.asarray(df[n], dtype=float)
            return np.where(np.isfinite(v) & (v >= 0), v, 0.0)
    raise WeatherError(f"{source}: no column {names[0]!r}; is it an EPW or TMY3 weather file?")


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


def read_weather(path: str | os.PathLike) -> Weather:
    """Read an EPW (``.epw``) or TMY3 (``.csv``) weather file; ``"builtin"`` reads the
    shipped Greensboro TMY3 file."""
    path = BUILTIN if str(path) == "builtin" else Path(path)
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
    pvlib = require_pvlib()
    try:
        if path.suffix.lower() == ".epw":
            df, meta = pvlib.iotools.read_epw(path)
            gh = _column(df, ("global_hor_illum",), name)
            dn = _column(df, ("direct_normal_illum",), name)
            dh = _column(df, ("diffuse_horizontal_illum",), name)
            site = str(meta.get("city", path.stem))
            tz = float(meta["TZ"])
        else:
            df, meta = pvlib.iotools.read_tmy3(path, map_variables=True)
            # TMY3 illuminance is in hundreds of lux.
            gh = 100 * _column(df, ("GH illum (lx)", "GHillum"), name)
            dn = 100 * _column(df, ("DN illum (lx)", "DNillum"), name)
            dh = 100 * _column(df, ("DH illum (lx)", "DHillum"), name)
            site = str(meta.get("Name", path.stem)).strip('"')
            tz = float(meta["TZ"])
        lat, lon = float(meta["latitude"]), float(meta["longitude"])
        alt = float(meta.get("altitude", 0.0))
    except WeatherError:
        raise
    except Exception as exc:  # pvlib's parsers raise many kinds on a bad file
        why = f"{type(exc).__name__}: {exc}".splitlines()[0]
        raise WeatherError(f"{name}: not a readable EPW or TMY3 weather file ({why})") from None
    ghi = _column(df, ("ghi",), name)
    if len(ghi) < 24 or not (-90 <= lat <= 90 and -180 <= lon <= 180):
        raise WeatherError(f"{name}: {len(ghi)} hours at ({lat}, {lon}) is not a usable year")
    return Weather(
        site,
        lat,
        lon,
        alt,
        tz,
        df.index,
        ghi,
        _column(df, ("dni",), name),
        _column(df, ("dhi",), name),
        gh,
        dn,
        dh,
        str(path),
    )
