"""Checks and decisions on a weather file's records, before any light is computed.

- the calendar: one record for every hour of one year (8,760, or 8,784 with 29
  February), none repeated; a partial year is refused, since every annual figure
  (DA, sDA, UDI, kWh) would silently count only part of one;
- the site: latitude, longitude and time zone in range, and the time zone within 3 h
  of the longitude's solar time (else a note: a sign or a header slip);
- missing values: irradiance missing in hours with the sun down is 0; in daylight a
  few hours (at most 1% of them) are filled from their neighbours, with a note; more
  is refused. Out-of-range numbers are refused with their line;
- illuminance units, decided from the data: the ratio of global illuminance to
  global irradiance is about 110 lm/W; a file in hundreds of lux gives about 1.1.
  Without usable illuminance the Perez (1990) efficacy model gives it (``efficacy``);
- the clock: hours with direct sun (DNI > 50 W/m²) while the sun is below the
  horizon all hour long mean the records are shifted or in another time zone.
"""

from __future__ import annotations

import datetime as dt
import warnings

import numpy as np

from lightinv_core.climate.efficacy import perez_efficacy, precipitable_water
from lightinv_core.climate.weather_formats import Records, WeatherError, is_date, require_pvlib

LIMITS = {"ghi": 1500.0, "dni": 1400.0, "dhi": 1000.0}
"""W/m²: irradiance above these is no measurement (the extraterrestrial normal
irradiance is at most about 1,415 W/m²)."""
MAX_LUX = 250_000.0
"""lux: daylight above this is no measurement (the sun outside the atmosphere gives
about 135,000 lux)."""
FILL_SHARE = 0.01
"""Most daylight hours of one irradiance column that may be missing and filled."""
DIRECT_SUN = 50.0
"""W/m² of DNI that counts as direct sun for the clock check."""
NIGHT_SUN_HOURS = 10
"""Hours of direct sun with the sun below the horizon above which the file's clock is
called shifted."""
NAMES = {"ghi": "GHI", "dni": "DNI", "dhi": "DHI"}


def _fmt_stamp(stamp) -> str:
    return f"{int(stamp[1]):02d}-{int(stamp[2]):02d} {int(stamp[3]):02d}:00"


def _in_calendar_order(rec: Records) -> list[str]:
    """Sort the records by month, day and hour (in place): a file's rows out of order
    still give each hour its own sun. (Not by year: typical years mix years.)"""
    _, m, d, h = rec.stamps.T
    key = (m * 32 + d) * 25 + h
    order = np.argsort(key, kind="stable")
    if np.all(order == np.arange(len(order))):
        return []
    rec.stamps, rec.lines = rec.stamps[order], rec.lines[order]
    rec.values = {k: v[order] for k, v in rec.values.items()}
    return ["the records were not in calendar order: they were sorted"]


def calendar(rec: Records, source: str):
    """(times, notes): the records' hour-ending times (a pandas DatetimeIndex at the
    file's fixed UTC offset), the records sorted into calendar order; a WeatherError
    for a bad date, a repeated or a missing hour."""
    import pandas as pd

    y, m, d, h = rec.stamps.T
    bad = (m < 1) | (m > 12) | (d < 1) | (d > 31) | (h < 1) | (h > 24) | (y < 1800) | (y > 2200)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise WeatherError(
            f"{source}: line {rec.lines[i]}: year {y[i]}, month {m[i]}, day {d[i]}, hour {h[i]} "
            "is no date (hours run 1-24, each the end of its hour)"
        )
    try:
        pd.to_datetime({"year": y, "month": m, "day": d}, errors="raise")
    except (ValueError, OverflowError):
        ok = [is_date(*(int(x) for x in s)) for s in rec.stamps[:, :3]]
        i = ok.index(False)
        raise WeatherError(
            f"{source}: line {rec.lines[i]}: {y[i]}-{m[i]:02d}-{d[i]:02d} is not a date"
        ) from None
    notes = _in_calendar_order(rec)
    y, m, d, h = rec.stamps.T
    key = (m * 32 + d) * 25 + h
    _, first, counts = np.unique(key, return_index=True, return_counts=True)
    if (counts > 1).any():
        again = np.setdiff1d(np.arange(len(key)), first)
        i = int(again[0])
        raise WeatherError(
            f"{source}: {len(again)} records repeat an hour already given (first: line "
            f"{rec.lines[i]}, {_fmt_stamp(rec.stamps[i])}): a weather year gives each hour once"
        )
    leap = bool(((m == 2) & (d == 29)).any())
    full = 8784 if leap else 8760
    if len(key) != full:
        year = pd.date_range("2004-01-01" if leap else "2001-01-01", periods=full // 24, freq="D")
        want = (
            np.repeat(np.asarray(year.month), 24) * 32 + np.repeat(np.asarray(year.day), 24)
        ) * 25
        want = want + np.tile(np.arange(1, 25), len(year))
        gone = np.setdiff1d(want, key)
        g = int(gone[0]) if len(gone) else 0
        first_gone = f"{g // 25 // 32:02d}-{g // 25 % 32:02d} {g % 25:02d}:00"
        raise WeatherError(
            f"{source}: {len(key)} hourly records where a year has {full}: {len(gone)} hours "
            f"are missing (first: {first_gone}); annual figures need the whole year"
        )
    stamps = pd.to_datetime({"year": y, "month": m, "day": d}) + pd.to_timedelta(h, unit="h")
    offset = dt.timezone(dt.timedelta(hours=rec.utc_offset_h))
    return pd.DatetimeIndex(stamps).tz_localize(offset), notes


def check_site(rec: Records, source: str) -> list[str]:
    """Notes on the site, or a WeatherError for a latitude, longitude or time zone out
    of range."""
    if not -90 <= rec.latitude <= 90:
        raise WeatherError(f"{source}: latitude {rec.latitude:g} is not within -90 to 90 degrees")
    if not -180 <= rec.longitude <= 180:
        raise WeatherError(
            f"{source}: longitude {rec.longitude:g} is not within -180 to 180 degrees"
        )
    if not -500 <= rec.altitude <= 9000:
        raise WeatherError(f"{source}: elevation {rec.altitude:g} m is not within -500 to 9,000 m")
    if not -12 <= rec.utc_offset_h <= 14:
        raise WeatherError(
            f"{source}: time zone UTC{rec.utc_offset_h:+g} h is not within -12 to +14 h"
        )
    apart = rec.longitude / 15.0 - rec.utc_offset_h
    apart = (apart + 12) % 24 - 12
    if abs(apart) > 3:
        return [
            f"the time zone UTC{rec.utc_offset_h:+g} h is {abs(apart):.1f} h from the solar "
            f"time of longitude {rec.longitude:g} (east positive): check the header"
        ]
    return []


def sun_elevation(times, rec: Records, shift_h: float = 0.0) -> tuple[np.ndarray, ...]:
    """Apparent solar elevation (deg) at the start, middle and end of each hour (the
    hours moved by ``shift_h`` when testing another clock)."""
    pvlib = require_pvlib()
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        for minutes in (60, 30, 0):
            at = times - np.timedelta64(int(minutes - 60 * shift_h), "m")
            pos = pvlib.solarposition.get_solarposition(
                at, rec.latitude, rec.longitude, altitude=rec.altitude
            )
            out.append(np.asarray(pos["apparent_elevation"], dtype=float))
    return out[0], out[1], out[2]


def _quick_elevation(times, rec: Records, shift_h: float) -> np.ndarray:
    """Solar elevation (deg, about 0.5 degree accurate: Spencer's declination and
    equation of time) at ``times`` moved by ``shift_h``: cheap enough to try every
    clock from -12 to +12 h."""
    sp = require_pvlib().solarposition
    doy = np.asarray(times.day_of_year, dtype=float)
    hours = np.asarray(times.hour + times.minute / 60.0, dtype=float) + shift_h
    solar = hours + sp.equation_of_time_spencer71(doy) / 60 + rec.longitude / 15 - rec.utc_offset_h
    decl = sp.declination_spencer71(doy)
    lat = np.radians(rec.latitude)
    ha = np.radians(15.0 * (solar - 12.0))
    sin_el = np.sin(lat) * np.sin(decl) + np.cos(lat) * np.cos(decl) * np.cos(ha)
    return np.degrees(np.arcsin(np.clip(sin_el, -1.0, 1.0)))


def _night_sun(dni: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    return (dni > DIRECT_SUN) & (start < -0.5) & (end < -0.5)


def clock_check(rec: Records, times, start: np.ndarray, end: np.ndarray, source: str) -> list[str]:
    """Notes on direct sun while the sun is below the horizon all hour long: a clock
    that is off (the records fit the sun better moved by a whole hour or two) or a
    defect of the data. Either way that beam cannot light anything: it is set to 0
    (in ``rec.values``), and the count is said."""
    dni = rec.values["dni"]
    wrong = _night_sun(dni, start, end)
    count = int(wrong.sum())
    notes = []
    if count > NIGHT_SUN_HOURS:
        tried = {}
        for shift in range(-12, 13):
            if shift:
                s, e = (_quick_elevation(times, rec, shift - k) for k in (1, 0))
                tried[shift] = int(_night_sun(dni, s, e).sum())
        best = min(tried, key=lambda k: (tried[k], abs(k)))
        if tried[best] <= max(NIGHT_SUN_HOURS, count // 4):
            notes.append(
                f"{count} hours have direct sun (DNI > {DIRECT_SUN:g} W/m²) while the sun is "
                f"below the horizon; the data fit the sun with every record {abs(best)} h "
                f"{'later' if best > 0 else 'earlier'} than its time stamp: the file's clock or "
                f"its time zone (UTC{rec.utc_offset_h:+g} h) is off; that direct light was dropped"
            )
        else:
            notes.append(
                f"{count} hours have direct sun (DNI > {DIRECT_SUN:g} W/m²) while the sun is "
                "below the horizon, at any clock: a defect of the file's data; that direct light "
                "was dropped"
            )
    dni[(start < -0.5) & (end < -0.5)] = 0.0
    return notes


def fill_irradiance(rec: Records, night: np.ndarray, source: str) -> list[str]:
    """Irradiance: missing values at night become 0, a few in daylight are filled from
    their neighbours; out-of-range values are refused. Changes ``rec.values``."""
    notes = []
    for key, name in NAMES.items():
        v = rec.values[key]
        v = np.where(v < 0, np.nan, v)  # a negative irradiance is a missing one
        over = np.flatnonzero(v > LIMITS[key])
        if len(over):
            i = int(over[0])
            raise WeatherError(
                f"{source}: line {rec.lines[i]}: {name} {v[i]:g} W/m² is beyond any sunlight "
                f"(at most {LIMITS[key]:g}); {len(over)} such values"
            )
        gap = ~np.isfinite(v)
        v[gap & night] = 0.0
        day_gap = gap & ~night
        n = int(day_gap.sum())
        if n:
            allowed = int(FILL_SHARE * (~night).sum())
            if n > allowed:
                i = int(np.flatnonzero(day_gap)[0])
                raise WeatherError(
                    f"{source}: {name} is missing in {n} daylight hours (first: line "
                    f"{rec.lines[i]}); at most {allowed} can be filled"
                )
            ok = np.flatnonzero(~day_gap)
            v[day_gap] = np.interp(np.flatnonzero(day_gap), ok, v[ok])
            notes.append(
                f"{name} was missing in {n} daylight hours: filled from the neighbouring hours"
            )
        rec.values[key] = v
    return notes


def decide_illuminance(
    rec: Records, zenith, airmass, dni_extra, source: str
) -> tuple[str, list[str]]:
    """Turn the illuminance columns into lux (in place): in lux, in hundreds of lux,
    or modelled (Perez 1990) where the file has none; returns (the decision, notes)."""
    v = rec.values
    ghi, gh = v["ghi"], v["gh_lux"]
    lit = (ghi > 50) & np.isfinite(gh) & (gh > 0)
    bright = int((ghi > 50).sum())
    ratio = (
        float(np.median(gh[lit] / ghi[lit])) if lit.sum() >= 0.5 * max(bright, 1) else float("nan")
    )
    kg, kd, kb = perez_efficacy(
        v["dni"], v["dhi"], zenith, airmass, dni_extra, precipitable_water(v["dew_point"])
    )
    model = {"gh_lux": kg * v["ghi"], "dn_lux": kb * v["dni"], "dh_lux": kd * v["dhi"]}
    if 50 <= ratio <= 250:
        scale, decision = 1.0, f"lux, as in the file (global {ratio:.0f} lm/W of the irradiance)"
    elif 0.5 <= ratio <= 2.5:
        scale = 100.0
        decision = f"hundreds of lux in the file, multiplied by 100 (global {100 * ratio:.0f} lm/W)"
    else:
        for key, lux in model.items():
            v[key] = np.nan_to_num(lux, nan=0.0)
        why = (
            "no usable illuminance columns"
            if np.isnan(ratio)
            else f"illuminance {ratio:.3g} times the irradiance fits no unit"
        )
        return f"modelled from the irradiance (Perez 1990 luminous efficacy; {why})", []
    notes = []
    for key, lux in model.items():
        col = v[key] * scale
        gap = ~np.isfinite(col)
        col[gap] = np.nan_to_num(lux[gap], nan=0.0)
        if gap.any():
            notes.append(
                f"{int(gap.sum())} hours without {key.split('_')[0].upper()} illuminance: "
                "modelled (Perez 1990)"
            )
        if (col > MAX_LUX).any():
            i = int(np.argmax(col))
            raise WeatherError(
                f"{source}: line {rec.lines[i]}: {col[i]:,.0f} lux is beyond any daylight "
                f"(at most {MAX_LUX:,.0f})"
            )
        v[key] = col
    return decision, notes
