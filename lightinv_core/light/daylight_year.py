"""The daylight year of a design, and annual statistics in O(log hours) per point.

Light is linear and every skylight emits filter x transmittance x the exterior
illuminance on its plane, so the daylight at a receiver in hour t is
``sum_g a_g E_g(t)``: per *sky group* g (the skylight zones facing one way) a
coefficient a_g (lux at the receiver per lux on the group's outside, from the
candidate's skylights) times that group's hourly exterior illuminance E_g(t) (Perez,
``climate.transposition``). With one sky group (every skylight on one roof plane, the
usual case) a point's daylight is a single a x E(t), so over the occupied hours

- hours with daylight >= L are the hours with E >= L / a: one ``searchsorted`` in
  the sorted E;
- daylight-linked dimming's level clip((target - b E) / A, min, 1) is 1 below one
  breakpoint of E, min above another and linear between, so its sum over the year is
  two ``searchsorted`` and a difference of prefix sums of the sorted E.

With several sky groups the statistics are counted hour by hour (exact, slower:
docs/daylight.md gives both speeds).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightinv_core.climate.control_modes import (
    DIMMING,
    ControlModeSpec,
    control_mode,
    day_starts,
    mode_levels,
)
from lightinv_core.climate.metrics import dimming_level
from lightinv_core.climate.sky import overcast_plane_illuminance
from lightinv_core.design.model import Daylight, Design
from lightinv_core.sources.types import diffusing

MAX_CACHED_YEARS = 4


@dataclass(frozen=True, eq=False)
class SkyGroups:
    """The design's skylight zones grouped by orientation: ``zones[g]`` the zone names
    of group g, ``outward`` (G, 3) unit normals away from the room, ``cols[g]`` their
    columns in the operator's zone patches, ``overcast`` (G,) the exterior lux on the
    group's plane per horizontal lux under the CIE overcast sky (ground included)."""

    zones: tuple[tuple[str, ...], ...]
    outward: np.ndarray
    cols: tuple[np.ndarray, ...]
    overcast: np.ndarray

    @property
    def count(self) -> int:
        """Number of groups."""
        return len(self.zones)


def sky_groups(light, design: Design) -> SkyGroups:
    """The sky groups of ``design``'s skylight sources on ``light``'s scene (a
    ``LightModel``)."""
    zones = sorted({s.zone for s in diffusing(design.sources)})
    keys: dict[tuple, list[str]] = {}
    normals: dict[tuple, np.ndarray] = {}
    for z in zones:
        ids = light.emission.grid(z).patch.ravel()
        n = light.patches.normal[ids].mean(axis=0)
        n = n / np.linalg.norm(n)
        key = tuple(np.round(n, 3))
        keys.setdefault(key, []).append(z)
        normals.setdefault(key, n)
    nz = len(light.op.zone_patches)
    out_zones, outward, cols = [], [], []
    for key, members in keys.items():
        out_zones.append(tuple(members))
        outward.append(-normals[key])
        c = np.concatenate([np.arange(nz)[light.emission.columns(z)] for z in members])
        cols.append(np.sort(c))
    outward_a = np.array(outward).reshape(-1, 3)
    over = (
        overcast_plane_illuminance(outward_a, 1.0, design.daylight.ground_reflectance)
        if len(outward_a)
        else np.zeros(0)
    )
    return SkyGroups(tuple(out_zones), outward_a, tuple(cols), np.asarray(over, float))


@dataclass(frozen=True, eq=False)
class DaylightYear:
    """Hourly exterior illuminance (lux) on each sky group's plane: ``every`` (G, 8760)
    for every hour of the file, ``occupied`` the mask of the schedule's hours and
    ``exterior`` (G, T) those hours; ``months`` (T,) 1-12 of each occupied hour;
    ``site`` names the weather. With one group, ``sorted`` (T,) is its exterior lux in
    increasing order and ``prefix`` (T + 1,) their cumulative sums. ``weather`` is
    ``Weather.describe()``: the format, the illuminance decision and the notes."""

    site: str
    source: str
    times: object
    every: np.ndarray
    occupied: np.ndarray
    exterior: np.ndarray
    months: np.ndarray
    sorted: np.ndarray | None
    prefix: np.ndarray | None
    weather: dict = field(default_factory=dict)

    @property
    def hours(self) -> int:
        """Occupied hours T."""
        return self.exterior.shape[1]

    @property
    def midpoints(self):
        """The middle of every hour of the file (``Weather.midpoints``)."""
        return self.times - np.timedelta64(30, "m")

    @property
    def day_starts(self) -> np.ndarray:
        """(T,) True at each occupied hour that begins a day (a dead band's state
        restarts there: ``climate.control_modes.switching_banded``)."""
        return day_starts(self.midpoints[np.asarray(self.occupied)])


def weather_path(daylight: Daylight) -> Path:
    """The weather file a daylight names ("builtin": the shipped TMY3)."""
    from lightinv_core.climate.weather import BUILTIN

    return BUILTIN if daylight.weather == "builtin" else Path(daylight.weather)


_YEARS: dict[tuple, DaylightYear] = {}


def daylight_year(groups: SkyGroups, daylight: Daylight) -> DaylightYear:
    """The year of ``groups`` under ``daylight``'s weather, orientation and schedule
    (remembered while the file is unchanged; pvlib is imported here only)."""
    from lightinv_core.climate.transposition import plane_illuminance, sun_and_sky
    from lightinv_core.climate.weather import WeatherError, load_weather

    weather = load_weather(weather_path(daylight))
    # The weather is one object while its file is unchanged: it keys the year.
    key = (
        weather,
        daylight.north_deg,
        daylight.ground_reflectance,
        daylight.occupancy,
        daylight.weekdays,
        groups.outward.tobytes(),
    )
    if key in _YEARS:
        return _YEARS[key]
    sky = sun_and_sky(weather)
    every = np.zeros((groups.count, weather.hours))
    for g, n in enumerate(groups.outward):
        every[g] = plane_illuminance(
            weather, sky, n, daylight.ground_reflectance, daylight.north_deg
        )
    mask = np.asarray(weather.occupied(*daylight.occupancy, weekdays=daylight.weekdays))
    if not mask.any():
        raise WeatherError("the occupancy schedule holds no hour of the weather file")
    exterior = np.ascontiguousarray(every[:, mask])
    mid = weather.midpoints
    months = np.asarray(mid.month)[mask].astype(np.int8)
    srt = prefix = None
    if groups.count == 1:
        srt = np.sort(exterior[0])
        prefix = np.concatenate([[0.0], np.cumsum(srt)])
    year = DaylightYear(
        weather.name,
        weather.source,
        weather.times,
        every,
        mask,
        exterior,
        months,
        srt,
        prefix,
        weather.describe(),
    )
    if len(_YEARS) >= MAX_CACHED_YEARS:
        _YEARS.pop(next(iter(_YEARS)))
    _YEARS[key] = year
    return year


# -- statistics over the occupied hours -----------------------------------------------------


def _thresholds(lux: float, a: np.ndarray) -> np.ndarray:
    """lux / a, +inf where a <= 0 (no daylight there reaches any positive level)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(a > 0, lux / np.where(a > 0, a, 1.0), np.inf)


def _count_hours(year: DaylightYear, a: np.ndarray, test) -> np.ndarray:
    """Occupied hours whose daylight passes ``test`` at receivers of coefficients ``a``
    (..., G), counted hour by hour: the way for several sky groups."""
    flat = a.reshape(-1, a.shape[-1])
    out = np.empty(len(flat), np.int64)
    for i in range(0, len(flat), 256):  # (256, T) lux at a time
        out[i : i + 256] = test(flat[i : i + 256] @ year.exterior).sum(axis=1)
    return out.reshape(a.shape[:-1])


def hours_from(year: DaylightYear, a: np.ndarray, lux: float) -> np.ndarray:
    """Occupied hours with daylight >= ``lux`` at receivers of coefficients ``a``
    (..., G): counts of shape a.shape[:-1]."""
    a = np.asarray(a, dtype=float)
    if year.sorted is not None:
        thr = _thresholds(lux, a[..., 0])
        return year.hours - np.searchsorted(year.sorted, thr, side="left")
    return _count_hours(year, a, lambda lux_t: lux_t >= lux)


def reaches_share(year: DaylightYear, a: np.ndarray, lux: float, share: float) -> np.ndarray:
    """Whether daylight >= ``lux`` for at least ``share`` of the occupied hours at
    receivers of coefficients ``a`` (..., G) (DA300 >= 50%: the sDA mark). With one sky
    group no search is needed: it holds where a x (the h-th largest exterior lux) >= lux,
    h = ceil(share x T)."""
    a = np.asarray(a, dtype=float)
    need = int(np.ceil(share * year.hours - 1e-9))
    if need <= 0:
        return np.ones(a.shape[:-1], bool)
    if year.sorted is not None:
        return a[..., 0] * year.sorted[year.hours - need] >= lux
    return hours_from(year, a, lux) >= need


def hours_within(year: DaylightYear, a: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """Occupied hours with ``lo`` <= daylight <= ``hi`` (counts, a.shape[:-1])."""
    a = np.asarray(a, dtype=float)
    if year.sorted is not None:
        upper = np.searchsorted(year.sorted, _thresholds(hi, a[..., 0]), side="right")
        return upper - np.searchsorted(year.sorted, _thresholds(lo, a[..., 0]), side="left")
    return _count_hours(year, a, lambda lux: (lux >= lo) & (lux <= hi))


def band_values(year: DaylightYear, a: np.ndarray, band) -> np.ndarray:
    """An annual daylight metric (a ``quantities.HourBand``) at receivers of coefficients
    ``a`` (..., G): the share of occupied hours with ``band.lo`` <= daylight <=
    ``band.hi``, or, with ``band.point_share``, 1.0 where at least that share counts
    and 0.0 elsewhere; shape a.shape[:-1]. Diffusing glazing lets no direct sun in, so a
    ``direct_sun`` band (ASE) is 0, and a band of another kind is counted hour by hour."""
    if band.direct_sun:
        return np.zeros(np.shape(a)[:-1])
    if band.above or band.point_hours is not None:
        return _count_band(year, np.asarray(a, dtype=float), band)
    if band.point_share is not None and band.hi == np.inf:
        return reaches_share(year, a, band.lo, band.point_share).astype(float)
    if band.hi == np.inf:
        hours = hours_from(year, a, band.lo)
    else:
        hours = hours_within(year, a, band.lo, band.hi)
    if band.point_share is not None:
        return (hours >= np.ceil(band.point_share * year.hours - 1e-9)).astype(float)
    return hours / year.hours


def _count_band(year: DaylightYear, a: np.ndarray, band) -> np.ndarray:
    """``band.of_hours`` of the daylight of coefficients ``a`` (..., G), hour by hour."""
    flat = a.reshape(-1, a.shape[-1])
    out = np.empty(len(flat))
    for i in range(0, len(flat), 256):
        out[i : i + 256] = band.of_hours(flat[i : i + 256] @ year.exterior)
    return out.reshape(a.shape[:-1])


def dimming_sum(
    year: DaylightYear,
    b: np.ndarray,
    full: np.ndarray,
    target: float,
    min_level: float,
    fixed: np.ndarray | None = None,
) -> np.ndarray:
    """Sum over the occupied hours of the dimming level clip((target - b.E(t) -
    fixed(t)) / full, min_level, 1) for m candidates: ``level_sum`` of continuous
    dimming (``climate.control_modes``)."""
    return level_sum(control_mode(DIMMING), year, b, full, target, min_level, fixed)


def level_sum(
    mode: ControlModeSpec,
    year: DaylightYear,
    b: np.ndarray,
    full: np.ndarray,
    target: float,
    min_level: float,
    fixed: np.ndarray | None = None,
    band: float = 0.0,
) -> np.ndarray:
    """(m,) the levels of ``mode`` summed over the occupied hours for m candidates: ``b``
    (m, G) the sensor's mean daylight per exterior lux of each sky group, ``full`` (m,)
    its own luminaires' mean lux at full output, ``fixed`` (T,) lux of daylight the
    same for every candidate (clear glazing), or (m, T) each candidate's (clear glazing
    whose shape moves), ``band`` a dead band (fraction of the target). One sky group
    alone, or fixed daylight alone, is summed over the sorted year (O(log hours));
    anything else, and a dead band (its state carries over the hours), hour by hour."""
    b = np.atleast_2d(np.asarray(b, dtype=float))
    A = np.maximum(np.asarray(full, dtype=float), 1e-9)
    if band > 0:
        day = b @ year.exterior if fixed is None else b @ year.exterior + fixed
        levels = mode_levels(mode, day, A[:, None], target, min_level, band, year.day_starts)
        return levels.sum(axis=1)
    if fixed is not None and b.shape[1] == 0 and np.ndim(fixed) == 1:
        s = np.sort(np.asarray(fixed, dtype=float))
        S = np.concatenate([[0.0], np.cumsum(s)])
        return mode.sorted_sum(s, S, np.ones(len(A)), A, target, min_level)
    if year.sorted is not None and fixed is None:
        return mode.sorted_sum(year.sorted, year.prefix, b[:, 0], A, target, min_level)
    day = b @ year.exterior
    if fixed is not None:
        day = day + fixed
    return mode.levels(day, A[:, None], target, min_level).sum(axis=1)


def dimming_levels(
    year: DaylightYear,
    b: np.ndarray,
    full: float,
    target: float,
    min_level: float,
    fixed: np.ndarray | None = None,
) -> np.ndarray:
    """The dimming level (0-1) of one layout in each occupied hour: ``b`` (G,), with
    ``fixed`` (T,) lux of clear glazing's daylight."""
    day = np.asarray(b, dtype=float) @ year.exterior
    if fixed is not None:
        day = day + fixed
    return dimming_level(day, max(float(full), 1e-9), target, min_level)
