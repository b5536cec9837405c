"""EN 17037 daylight provision (illuminance method) and sunlight exposure, as arithmetic.

**Daylight provision** (EN 17037:2018+A1:2021, Annex A, method 2 on hourly
illuminance). Each level has a target illuminance E_T over a fraction of the reference
plane and a minimum target illuminance E_TM over 95% of it, each for at least half of
the daylight hours (F_time = 50%):

| level | E_T (lux) | E_TM (lux) |
|---|---|---|
| minimum | 300 | 100 |
| medium | 500 | 300 |
| high | 750 | 500 |

with E_T over 50% of the plane for daylight openings in vertical and inclined
surfaces, and for horizontal openings (rooflights) E_T over 95% and no separate E_TM
criterion. "Reaching" is E >= E_T, "at least" is >=. Two readings of "a fraction of the
plane for a fraction of the time" are in use (``basis``): "points" (Honeybee; the
reading that the standard's daylight-factor method D_T = E_T / E_v,d,med stands for):
each point reaches E_T in at least half the daylight hours, and those points cover at
least the plane fraction; "hours" (ClimateStudio's description): each hour at least the
plane fraction reaches E_T, in at least half the daylight hours.

**Daylight hours**: the 4380 hours (half the year) with the highest diffuse horizontal
illuminance (Mardaljevic's climate-based reading behind EN 17037, used by ClimateStudio
and Honeybee; ``daylight_hours``); or, as an option, the hours with the sun up.

**Sunlight exposure** (EN 17037 Annex A, Table A.5 levels 1.5, 3 and 4 hours): the time
on one day from 1 February to 21 March that the sun, above a minimum altitude, is seen
from a reference point through the glazing. The sun's position is pvlib's (NREL SPA,
geometric altitude: no refraction). The standard sets the minimum altitude by site; its
table was not available to us, so ``min_altitude_deg`` is the caller's to give.
"""

from __future__ import annotations

import datetime as dt
import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.weather import require_pvlib
from lightinv_core.errors import LightInvError

PROVISION_LEVELS = (("minimum", 300.0, 100.0), ("medium", 500.0, 300.0), ("high", 750.0, 500.0))
"""(level, E_T, E_TM) in lux (EN 17037 Table A.1)."""
F_TIME = 0.5
F_PLANE_TARGET = 0.5
F_PLANE_MINIMUM = 0.95
F_PLANE_HORIZONTAL = 0.95
SUNLIGHT_LEVELS = (("minimum", 1.5), ("medium", 3.0), ("high", 4.0))
"""(level, hours of sunlight exposure) (EN 17037 Table A.5)."""
SUNLIGHT_FIRST = (2, 1)
SUNLIGHT_LAST = (3, 21)


@dataclass(frozen=True)
class Criterion:
    """One illuminance criterion of a level: ``lux`` reached over ``plane`` of the
    reference plane for ``time`` of the daylight hours; ``achieved`` is the figure the
    basis compares (the plane fraction on basis "points", the time fraction on
    "hours") and ``required`` its requirement."""

    lux: float
    plane: float
    time: float
    achieved: float
    required: float

    @property
    def met(self) -> bool:
        return self.achieved >= self.required


@dataclass(frozen=True)
class LevelCheck:
    """A provision level and its criteria (E_T; E_TM unless horizontal openings)."""

    name: str
    criteria: tuple[Criterion, ...]

    @property
    def met(self) -> bool:
        return all(c.met for c in self.criteria)


@dataclass(frozen=True)
class ProvisionResult:
    """EN 17037 daylight provision: ``level`` the highest level met in order
    (minimum, medium, high; "none" if the minimum is not), ``checks`` the figures."""

    level: str
    checks: tuple[LevelCheck, ...]
    horizontal_openings: bool
    basis: str
    hours: int

    def summary(self) -> dict:
        """The level and, per level and criterion, the figure and its requirement."""
        out: dict = {"en17037_provision": self.level, "basis": self.basis, "hours": self.hours}
        for check in self.checks:
            for c in check.criteria:
                out[f"{check.name}_{int(c.lux)}"] = round(c.achieved, 4)
        return out


def _criterion(lux: np.ndarray, e: float, plane: float, basis: str) -> Criterion:
    reached = lux >= e
    if basis == "points":
        achieved = float((reached.mean(axis=1) >= F_TIME).mean())
        return Criterion(e, plane, F_TIME, achieved, plane)
    achieved = float((reached.mean(axis=0) >= plane).mean())
    return Criterion(e, plane, F_TIME, achieved, F_TIME)


def daylight_provision(
    lux, horizontal_openings: bool = False, basis: str = "points"
) -> ProvisionResult:
    """EN 17037 daylight provision of illuminance ``lux`` (q, T) on the reference plane
    over the daylight hours (``daylight_hours``), q points of equal area (see the
    module for the criteria and the two bases)."""
    lux = np.asarray(lux, dtype=float)
    if lux.ndim != 2 or 0 in lux.shape:
        raise LightInvError("daylight provision needs points x daylight hours, one of each")
    if not np.isfinite(lux).all():
        raise LightInvError("illuminance has values that are not finite numbers")
    if basis not in ("points", "hours"):
        raise LightInvError(f"unknown basis {basis!r}: points or hours")
    checks = []
    for name, target, minimum in PROVISION_LEVELS:
        if horizontal_openings:
            crit = (_criterion(lux, target, F_PLANE_HORIZONTAL, basis),)
        else:
            crit = (
                _criterion(lux, target, F_PLANE_TARGET, basis),
                _criterion(lux, minimum, F_PLANE_MINIMUM, basis),
            )
        checks.append(LevelCheck(name, crit))
    level = "none"
    for check in checks:
        if not check.met:
            break
        level = check.name
    return ProvisionResult(level, tuple(checks), bool(horizontal_openings), basis, lux.shape[1])


def daylight_hours(
    diffuse_horizontal_lux, method: str = "brightest-half", sun_altitude_deg=None
) -> np.ndarray:
    """Mask (T,) of EN 17037's daylight hours in a year of hourly values.

    "brightest-half": the T // 2 hours (4380 of 8760) with the highest diffuse
    horizontal illuminance ``diffuse_horizontal_lux`` (ties to the earlier hour);
    "sun-up": the hours whose sun altitude ``sun_altitude_deg`` (at mid-hour) is above
    0. See the module for the sources."""
    if method == "brightest-half":
        dh = np.asarray(diffuse_horizontal_lux, dtype=float).ravel()
        if dh.size < 2 or not np.isfinite(dh).all():
            raise LightInvError("daylight hours need the diffuse illuminance of each hour")
        order = np.argsort(-dh, kind="stable")
        mask = np.zeros(dh.size, dtype=bool)
        mask[order[: dh.size // 2]] = True
        return mask
    if method == "sun-up":
        if sun_altitude_deg is None:
            raise LightInvError("daylight hours by 'sun-up' need the sun's altitude per hour")
        return np.asarray(sun_altitude_deg, dtype=float).ravel() > 0.0
    raise LightInvError(f"unknown daylight hours {method!r}: brightest-half or sun-up")


@dataclass(frozen=True)
class ExposureResult:
    """EN 17037 sunlight exposure at a reference point on ``date``: ``hours`` with
    the sun above ``min_altitude_deg`` and seen, ``level`` ("none" below 1.5 h),
    ``sun_hours`` with the sun above the minimum altitude, seen or not."""

    hours: float
    level: str
    sun_hours: float
    date: dt.date
    min_altitude_deg: float
    step_minutes: float


def sunlight_level(hours: float) -> str:
    """The EN 17037 level of ``hours`` of sunlight exposure (at least 1.5, 3, 4 h)."""
    level = "none"
    for name, need in SUNLIGHT_LEVELS:
        if hours >= need - 1e-9:
            level = name
    return level


def _as_date(date) -> dt.date:
    if isinstance(date, dt.datetime):
        return date.date()
    if isinstance(date, dt.date):
        return date
    try:
        return dt.date.fromisoformat(str(date))
    except ValueError:
        raise LightInvError(f"sunlight exposure date must be YYYY-MM-DD, got {date!r}") from None


def sun_directions(
    latitude: float,
    longitude: float,
    date,
    step_minutes: float = 1.0,
    utc_offset_h: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The sun over one local day: unit directions (n, 3) in the geographic frame (x
    east, y north, z up) and geometric altitudes (n,) in degrees, at the middle of
    each ``step_minutes`` step from local midnight. The day is in local standard time
    of ``utc_offset_h`` (default longitude / 15: local mean time)."""
    if not -90.0 <= latitude <= 90.0 or not -180.0 <= longitude <= 180.0:
        raise LightInvError("site must be latitude -90..90, longitude -180..180 deg")
    steps = 1440.0 / step_minutes if step_minutes > 0 else 0.0
    if not 1.0 <= steps <= 1440.0 * 60 or abs(steps - round(steps)) > 1e-9:
        raise LightInvError(f"the step must divide the day (1440 min), got {step_minutes}")
    import pandas as pd

    pvlib = require_pvlib()
    day = _as_date(date)
    offset = longitude / 15.0 if utc_offset_h is None else float(utc_offset_h)
    start = pd.Timestamp(day.isoformat(), tz="UTC") - pd.Timedelta(hours=offset)
    times = start + pd.to_timedelta((np.arange(round(steps)) + 0.5) * step_minutes, unit="min")
    with warnings.catch_warnings():
        # pvlib's own use of pandas APIs that pandas deprecates: not the user's concern.
        warnings.simplefilter("ignore", DeprecationWarning)
        pos = pvlib.solarposition.get_solarposition(times, latitude, longitude)
    alt = np.radians(np.asarray(pos["elevation"], dtype=float))
    az = np.radians(np.asarray(pos["azimuth"], dtype=float))  # clockwise from north
    d = np.stack([np.cos(alt) * np.sin(az), np.cos(alt) * np.cos(az), np.sin(alt)], axis=1)
    return d, np.degrees(alt)


def sunlight_exposure(
    visible: Callable[[np.ndarray], np.ndarray],
    latitude: float,
    longitude: float,
    date,
    *,
    min_altitude_deg: float,
    step_minutes: float = 1.0,
    utc_offset_h: float | None = None,
) -> ExposureResult:
    """EN 17037 sunlight exposure at a reference point: the time on ``date`` (1
    February to 21 March) the sun is above ``min_altitude_deg`` and ``visible``.

    ``visible`` takes unit sun directions (m, 3), x east, y north, z up, and returns
    (m,) bool: whether the sun is seen from the reference point (through the glazing,
    unobstructed). Time is counted in ``step_minutes`` steps (see ``sun_directions``).
    """
    day = _as_date(date)
    if not SUNLIGHT_FIRST <= (day.month, day.day) <= SUNLIGHT_LAST:
        raise LightInvError(
            f"EN 17037 assesses sunlight exposure on a date from 1 February to 21 March, "
            f"got {day.isoformat()}"
        )
    if not math.isfinite(min_altitude_deg) or not -5.0 <= min_altitude_deg < 90.0:
        raise LightInvError(f"minimum sun altitude must be -5 to 90 deg, got {min_altitude_deg}")
    d, alt = sun_directions(latitude, longitude, day, step_minutes, utc_offset_h)
    up = alt > min_altitude_deg
    seen = np.zeros(len(d), dtype=bool)
    if up.any():
        answer = np.asarray(visible(d[up]))
        if answer.shape != (int(up.sum()),):
            raise LightInvError(
                f"visible() must return one bool per direction ({int(up.sum())}), "
                f"got shape {answer.shape}"
            )
        seen[up] = answer.astype(bool)
    hours = float(seen.sum()) * step_minutes / 60.0
    return ExposureResult(
        hours,
        sunlight_level(hours),
        float(up.sum()) * step_minutes / 60.0,
        day,
        float(min_altitude_deg),
        float(step_minutes),
    )
