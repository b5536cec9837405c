"""Weather file formats: each reader turns one format into the same ``Records``.

A reader takes the file's text and gives the site and, per record, its calendar stamp
(year, month, day, hour 1-24 as the file writes it) and the values LightInv uses.
Every format in the registry labels a record by the *end* of its hour in local
standard time (EPW, TMY3 and TMY2 all do: hour 1 is 00:00-01:00), so the stamps need
no shift; ``weather.read_weather`` builds the times and checks the year from them.

Values a file marks as missing, or leaves empty, become NaN; text that is not a
number is refused with its line. Registered formats: EPW, TMY3 (the NREL CSV), TMY2
(fixed columns, read with pvlib). A new format is one reader and one ``FORMATS`` row.
"""

from __future__ import annotations

import csv
import datetime as dt
import math
import os
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from lightinv_core.errors import LightInvError

COLUMNS = ("ghi", "dni", "dhi", "gh_lux", "dn_lux", "dh_lux", "dew_point")
"""What a reader gives per record: irradiance (W/m²), illuminance (lux or hundreds of
lux, as the file has it; decided later from the data) and the dew point (deg C)."""


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


@dataclass
class Records:
    """One file's site and hourly records (see the module); ``lines`` the file's line
    number of each record (for messages), ``notes`` what the reader had to decide."""

    format: str
    site: str
    latitude: float
    longitude: float
    utc_offset_h: float
    altitude: float
    stamps: np.ndarray  # (n, 4) int: year, month, day, hour-ending 1-24
    values: dict[str, np.ndarray]
    lines: np.ndarray
    notes: list[str] = field(default_factory=list)


def _number(text: str, source: str, line: int, what: str) -> float:
    """A float from a file's field (NaN for an empty one: a missing value), or a
    WeatherError naming the line."""
    if not text.strip():
        return math.nan
    try:
        v = float(text)
    except ValueError:
        raise WeatherError(
            f"{source}: line {line}: {what} {text.strip()[:20]!r} is not a number"
        ) from None
    if math.isnan(v):
        return v
    if not math.isfinite(v):
        raise WeatherError(f"{source}: line {line}: {what} {text.strip()[:20]!r} is not finite")
    return v


def _missing(v: float, markers: tuple[float, ...]) -> float:
    return math.nan if v in markers else v


def _header_number(text: str, source: str, what: str) -> float:
    try:
        v = float(text.strip().strip('"'))
    except ValueError:
        raise WeatherError(
            f"{source}: the header's {what} {text.strip()!r} is not a number"
        ) from None
    if not math.isfinite(v):
        raise WeatherError(f"{source}: the header's {what} {text.strip()!r} is not finite")
    return v


# -- EPW ------------------------------------------------------------------------------

# Field positions of an EPW data line (EnergyPlus Auxiliary Programs, "EPW data dictionary").
_EPW_FIELDS = {
    "dew_point": 7,
    "ghi": 13,
    "dni": 14,
    "dhi": 15,
    "gh_lux": 16,
    "dn_lux": 17,
    "dh_lux": 18,
}
_EPW_MISSING = {
    "dew_point": (99.9,),
    "ghi": (9999.0,),
    "dni": (9999.0,),
    "dhi": (9999.0,),
    "gh_lux": (999999.0,),
    "dn_lux": (999999.0,),
    "dh_lux": (999999.0,),
}
_EPW_MIN_FIELDS = 19


def read_epw(text: str, source: str) -> Records:
    """The records of an EnergyPlus weather (EPW) file's text."""
    lines = text.splitlines()
    if not lines or not lines[0].upper().startswith("LOCATION"):
        raise WeatherError(f"{source}: an EPW file starts with a LOCATION line; this one does not")
    loc = next(csv.reader([lines[0]]))
    if len(loc) < 10:
        raise WeatherError(f"{source}: the LOCATION line has {len(loc)} fields; EPW gives 10")
    site = ", ".join(p.strip().strip('"').strip() for p in loc[1:4] if p.strip().strip('"'))
    lat = _header_number(loc[6], source, "latitude")
    lon = _header_number(loc[7], source, "longitude")
    tz = _header_number(loc[8], source, "time zone")
    alt = _header_number(loc[9], source, "elevation")
    start = next(
        (i + 1 for i, s in enumerate(lines[:20]) if s.upper().startswith("DATA PERIODS")), None
    )
    if start is None:
        raise WeatherError(f"{source}: no DATA PERIODS line in the EPW header")
    periods = next(csv.reader([lines[start - 1]]))
    if len(periods) > 2 and periods[2].strip() not in ("", "1"):
        raise WeatherError(
            f"{source}: {periods[2].strip()} records an hour: only hourly EPW files are read"
        )
    stamps, rows, numbers = [], [], {k: [] for k in COLUMNS}
    for i in range(start, len(lines)):
        raw = lines[i]
        if not raw.strip():
            continue
        line = i + 1
        f = raw.split(",")
        if len(f) < _EPW_MIN_FIELDS:
            raise WeatherError(
                f"{source}: line {line} has {len(f)} fields where an EPW record has 35: "
                "the file may be cut short"
            )
        stamp = [
            _number(f[j], source, line, what)
            for j, what in enumerate(("year", "month", "day", "hour"))
        ]
        if any(not float(s).is_integer() for s in stamp):
            raise WeatherError(f"{source}: line {line}: the date and hour must be whole numbers")
        stamps.append([int(s) for s in stamp])
        rows.append(line)
        for k, j in _EPW_FIELDS.items():
            numbers[k].append(_missing(_number(f[j], source, line, k.upper()), _EPW_MISSING[k]))
    return _records("EPW", site, lat, lon, tz, alt, stamps, numbers, rows, source)


# -- TMY3 -----------------------------------------------------------------------------

_TMY3_COLUMNS = {
    "ghi": "GHI (W/m^2)",
    "dni": "DNI (W/m^2)",
    "dhi": "DHI (W/m^2)",
    "gh_lux": "GH illum (lx)",
    "dn_lux": "DN illum (lx)",
    "dh_lux": "DH illum (lx)",
    "dew_point": "Dew-point (C)",
}
_TMY3_MISSING = (-9900.0, -999.0)


def read_tmy3(text: str, source: str) -> Records:
    """The records of an NREL TMY3 CSV file's text."""
    rows = list(csv.reader(text.splitlines()))
    if len(rows) < 3 or len(rows[0]) < 7:
        raise WeatherError(
            f"{source}: a TMY3 file starts with a 7-field site line and a column line"
        )
    meta = rows[0]
    site = ", ".join(p.strip() for p in meta[1:3] if p.strip())
    tz = _header_number(meta[3], source, "time zone")
    lat = _header_number(meta[4], source, "latitude")
    lon = _header_number(meta[5], source, "longitude")
    alt = _header_number(meta[6], source, "elevation")
    names = [n.strip() for n in rows[1]]
    where = {}
    for key, name in _TMY3_COLUMNS.items():
        # By the name up to its unit: real files carry typos in units ("(W/m^2))").
        found = [j for j, n in enumerate(names) if n.split("(")[0] == name.split("(")[0]]
        if found:
            where[key] = found[0]
        elif key in ("ghi", "dni", "dhi"):
            raise WeatherError(f"{source}: no column {name!r}: is it a TMY3 weather file?")
    stamps, lines, numbers = [], [], {k: [] for k in COLUMNS}
    width = len(names)
    for i, f in enumerate(rows[2:], start=3):
        if not any(x.strip() for x in f):
            continue
        if len(f) < min(width, max(where.values()) + 1):
            raise WeatherError(
                f"{source}: line {i} has {len(f)} fields where the column line has {width}: "
                "the file may be cut short"
            )
        try:
            month, day, year = (int(p) for p in f[0].split("/"))
            hour, minute = (int(p) for p in f[1].split(":"))
        except ValueError:
            raise WeatherError(
                f"{source}: line {i}: date {f[0]!r} {f[1]!r} is not MM/DD/YYYY HH:MM"
            ) from None
        if minute != 0:
            raise WeatherError(
                f"{source}: line {i}: {f[1]!r} is not on the hour; only hourly files are read"
            )
        if hour == 0:  # "00:00" of a day, as some writers give it, is hour 24 of the day before
            prev = (
                dt.date(year, month, day) - dt.timedelta(days=1)
                if is_date(year, month, day)
                else None
            )
            if prev is not None:
                year, month, day, hour = prev.year, prev.month, prev.day, 24
        stamps.append([year, month, day, hour])
        lines.append(i)
        for k in COLUMNS:
            if k in where:
                v = _number(f[where[k]], source, i, _TMY3_COLUMNS[k])
                numbers[k].append(_missing(v, _TMY3_MISSING))
            else:
                numbers[k].append(math.nan)
    return _records("TMY3", site, lat, lon, tz, alt, stamps, numbers, lines, source)


def is_date(year: int, month: int, day: int) -> bool:
    """Whether year-month-day is a day of the calendar."""
    try:
        dt.date(year, month, day)
    except ValueError:
        return False
    return True


# -- TMY2 (pvlib) ---------------------------------------------------------------------


def read_tmy2(path: str | os.PathLike, source: str) -> Records:
    """The records of an NREL TMY2 file, read with pvlib's parser (fixed columns)."""
    pvlib = require_pvlib()
    try:
        df, meta = pvlib.iotools.read_tmy2(str(path))
    except Exception as exc:  # pvlib's fixed-column parser raises many kinds
        why = f"{type(exc).__name__}: {exc}".splitlines()[0]
        raise WeatherError(f"{source}: not a readable TMY2 file ({why})") from None
    names = {"ghi": "GHI", "dni": "DNI", "dhi": "DHI", "gh_lux": "GHillum"}
    names |= {"dn_lux": "DNillum", "dh_lux": "DHillum", "dew_point": "DewPoint"}
    numbers = {k: np.asarray(df[n], dtype=float) for k, n in names.items()}
    numbers["dew_point"] = numbers["dew_point"] / 10.0  # TMY2 gives tenths of a degree
    stamps = np.column_stack(
        [np.asarray(df[c], dtype=int) for c in ("year", "month", "day", "hour")]
    )
    stamps[:, 0] += np.where(stamps[:, 0] < 100, 1900, 0)  # TMY2 writes two-digit years
    return _records(
        "TMY2",
        str(meta.get("City", "")).strip(),
        float(meta["latitude"]),
        float(meta["longitude"]),
        float(meta["TZ"]),
        float(meta.get("altitude", 0.0)),
        stamps,
        numbers,
        np.arange(len(stamps)) + 2,
        source,
    )


def _records(fmt, site, lat, lon, tz, alt, stamps, numbers, lines, source) -> Records:
    if len(stamps) == 0:
        raise WeatherError(f"{source}: the {fmt} file holds no hourly records")
    return Records(
        fmt,
        site or "unnamed site",
        lat,
        lon,
        tz,
        alt,
        np.asarray(stamps, dtype=np.int64).reshape(-1, 4),
        {k: np.asarray(numbers[k], dtype=float) for k in COLUMNS},
        np.asarray(lines, dtype=np.int64),
    )


# -- the registry ---------------------------------------------------------------------


@dataclass(frozen=True)
class Format:
    """A weather format: ``looks_like(text, suffix)`` tells it from its first line and
    file name suffix; ``read(text, path, source)`` gives its ``Records``."""

    name: str
    looks_like: Callable[[str, str], bool]
    read: Callable[[str, os.PathLike, str], Records]


def _epw_like(first: str, suffix: str) -> bool:
    return suffix == ".epw" or first.upper().startswith("LOCATION")


def _tmy3_like(first: str, suffix: str) -> bool:
    parts = next(csv.reader([first]), [])
    return suffix == ".csv" or (len(parts) == 7 and parts[0].strip().isdigit())


def _tmy2_like(first: str, suffix: str) -> bool:
    return suffix == ".tm2" or (
        len(first) >= 50 and first[:6].strip().isdigit() and "," not in first
    )


FORMATS: tuple[Format, ...] = (
    Format("EPW", _epw_like, lambda t, p, s: read_epw(t, s)),
    Format("TMY2", _tmy2_like, lambda t, p, s: read_tmy2(p, s)),
    Format("TMY3", _tmy3_like, lambda t, p, s: read_tmy3(t, s)),
)


def read_records(text: str, path: os.PathLike, source: str) -> Records:
    """The records of a weather file of any registered format (told from its first line
    and its name), or a WeatherError naming the formats read."""
    first = text.lstrip("\ufeff").split("\n", 1)[0].strip("\r")
    suffix = os.path.splitext(str(path))[1].lower()
    for fmt in FORMATS:
        if fmt.looks_like(first, suffix):
            return fmt.read(text, path, source)
    names = ", ".join(f.name for f in FORMATS)
    raise WeatherError(
        f"{source}: not a weather file LightInv reads ({names}): its first line is {first[:40]!r}"
    )
