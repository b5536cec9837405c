"""EN 17037 daylight provision of a layout on a work plane, as a score the optimiser
can follow (issue #30, docs/daylight.md "EN 17037 in a project").

The standard's arithmetic is ``climate.en17037`` (levels, plane and time fractions, the
"points" basis, the daylight hours); this module feeds it the layout's light and turns
its pass/fail into a continuous figure:

- the light: every diffusing sky group's coefficients times the exterior illuminance on
  its plane, plus the clear glazing's light with **every blind open** (the standard
  counts the daylight available), in EN 17037's daylight hours: the half of the year
  with the most diffuse horizontal illuminance (``climate.en17037.daylight_hours``);
- per point and criterion (E lux over a plane fraction F), t_p = the share of the
  daylight hours with E_p >= E; the criterion holds when the points with t_p >= 1/2
  cover at least F of the plane (points of equal area);
- a criterion's shortfall: 0 when it holds, else ``FLOOR`` + (1 - ``FLOOR``) (a + b) / 2
  with a = (F - the share reached) / F (how far the plane fraction falls short) and
  b = (1/2 - t_k) / (1/2), t_k the time share of the k-th best point, k = ceil(F n): how
  far the point that must reach falls short in time. a moves in steps of one point, b
  in steps of one hour, so the optimiser sees progress between points. ``FLOOR`` keeps
  a failed criterion at least 1% short, so no tolerance can judge it met;
- the score: the highest level met in order (0 none, 1 minimum, 2 medium, 3 high) plus
  1 minus the next level's shortfall (its largest criterion's). It reaches k exactly
  when level k is met, so "at least level k" is the bound ``min`` = k on it, with the
  relative violation (k - score) / k.
"""

from __future__ import annotations

import math

import numpy as np

from lightinv_core.climate.en17037 import (
    F_PLANE_HORIZONTAL,
    F_PLANE_MINIMUM,
    F_PLANE_TARGET,
    F_TIME,
    PROVISION_LEVELS,
    daylight_hours,
)

FLOOR = 0.01
"""The least shortfall of a criterion that does not hold (see the module)."""
HORIZONTAL_TILT_DEG = 10.0
"""Glazing whose outward normal is within this of the zenith is a horizontal opening
(a rooflight: E_T over 95% of the plane), as ``study.clear_year`` decides."""

_HOURS: dict = {}


def level_criteria(horizontal: bool) -> tuple[tuple[str, tuple[tuple[float, float], ...]], ...]:
    """Per level (minimum, medium, high): its criteria (lux, plane fraction)."""
    out = []
    for name, target, minimum in PROVISION_LEVELS:
        if horizontal:
            out.append((name, ((target, F_PLANE_HORIZONTAL),)))
        else:
            out.append((name, ((target, F_PLANE_TARGET), (minimum, F_PLANE_MINIMUM))))
    return tuple(out)


def provision_lux() -> tuple[float, ...]:
    """Every illuminance (lux) a criterion of some level reads."""
    return tuple(sorted({e for _, t, m in PROVISION_LEVELS for e in (t, m)}))


def daylight_mask(light) -> np.ndarray:
    """(H,) EN 17037's daylight hours of the weather year of ``light`` (a
    ``ScenarioLight``): the brightest half by diffuse horizontal illuminance."""
    from lightinv_core.climate.weather import load_weather
    from lightinv_core.light.daylight_year import weather_path

    weather = load_weather(weather_path(light.daylight))
    if weather not in _HOURS:
        _HOURS.clear()
        _HOURS[weather] = daylight_hours(weather.dh_lux)
    return _HOURS[weather]


def horizontal_openings(light) -> bool:
    """Whether every glazing of ``light`` (its diffusing sky groups and clear sources)
    is a horizontal opening (outward normal within ``HORIZONTAL_TILT_DEG`` of up)."""
    normals = [np.asarray(light.groups.outward).reshape(-1, 3)]
    if light.clear is not None and light.clear.columns.outward is not None:
        normals.append(np.asarray(light.clear.columns.outward).reshape(-1, 3))
    n = np.concatenate(normals)
    if not len(n):
        return False
    return bool(np.all(n[:, 2] > math.cos(math.radians(HORIZONTAL_TILT_DEG))))


def reach_shares(light, idx, levels) -> np.ndarray:
    """(L, R', m) per illuminance of ``levels`` (lux): the share of the daylight hours
    each receiver idx gets at least that much daylight, every blind open."""
    levels = np.asarray(levels, dtype=float)
    mask = daylight_mask(light)
    hours = int(mask.sum())
    a = light.coefficients(idx)  # (R', m, G)
    fixed = None
    if light.clear is not None:
        fixed = light.clear.open_hours(idx, mask)  # (R', Hd), or (R', m, Hd) moving
    moving = fixed is not None and fixed.ndim == 3  # (R', m, Hd): clear shapes that move
    if fixed is not None and a.shape[-1] == 0:
        if moving:
            return (fixed[None] >= levels[:, None, None, None]).sum(axis=-1) / hours
        own = (fixed[None] >= levels[:, None, None]).sum(axis=2) / hours
        return np.repeat(own[:, :, None], a.shape[1], axis=2)
    ext = light.year().every[:, mask]  # (G, Hd)
    if fixed is None and a.shape[-1] == 1:
        # One sky group: E_p(t) = a_p E(t); hours with a_p E >= L in the sorted E.
        srt = np.sort(ext[0])
        a0 = a[..., 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            thr = np.where(a0 > 0, levels[:, None, None] / np.where(a0 > 0, a0, 1.0), np.inf)
        return (hours - np.searchsorted(srt, thr, side="left")) / hours
    out = np.empty((len(levels), *a.shape[:2]))
    for j in range(a.shape[1]):  # one layout at a time: (R', Hd) lux
        lux = a[:, j, :] @ ext
        if fixed is not None:
            lux = lux + (fixed[:, j] if moving else fixed)
        out[:, :, j] = (lux[None] >= levels[:, None, None]).sum(axis=2) / hours
    return out


def shortfall(t: np.ndarray, plane: float) -> np.ndarray:
    """(m,) a criterion's shortfall (see the module) from the points' time shares t
    (n, m) at its illuminance and its plane fraction ``plane``."""
    n = t.shape[0]
    achieved = (t >= F_TIME).mean(axis=0)
    k = min(n, max(1, math.ceil(plane * n - 1e-9)))
    t_k = -np.partition(-t, k - 1, axis=0)[k - 1]  # the k-th largest share
    a = np.maximum(0.0, plane - achieved) / plane
    b = np.maximum(0.0, F_TIME - t_k) / F_TIME
    return np.where(achieved >= plane, 0.0, FLOOR + (1.0 - FLOOR) * (a + b) / 2.0)


def score_of(shares: dict, horizontal: bool) -> np.ndarray:
    """(m,) the provision score (see the module) from ``shares`` {lux: (n, m) time
    shares} of one plane."""
    m = next(iter(shares.values())).shape[1]
    score = np.zeros(m)
    going = np.ones(m, bool)
    for k, (_, crits) in enumerate(level_criteria(horizontal)):
        v = np.max([shortfall(shares[e], f) for e, f in crits], axis=0)
        score = np.where(going, np.where(v == 0.0, k + 1.0, k + 1.0 - v), score)
        going &= v == 0.0
    return score


def plane_score(light, idx) -> np.ndarray:
    """(R', m) the provision score of the receivers idx as one work plane (the same at
    each of them)."""
    lux = provision_lux()
    got = reach_shares(light, idx, lux)
    score = score_of(dict(zip(lux, got, strict=True)), horizontal_openings(light))
    return np.broadcast_to(score, got.shape[1:]).copy()


def plane_figures(light, idx) -> dict:
    """EN 17037 daylight provision of the first layout at receivers idx, as the study's
    ``en17037_provision`` block: the level reached and, per level and criterion, the
    share of the plane reaching its illuminance in half of the daylight hours
    (``climate.en17037.ProvisionResult.summary``), plus the score."""
    lux = provision_lux()
    got = reach_shares(light, idx, lux)[:, :, :1]
    shares = dict(zip(lux, got, strict=True))
    horizontal = horizontal_openings(light)
    out: dict = {"level": "none", "horizontal_openings": horizontal}
    out["daylight_hours"] = int(daylight_mask(light).sum())
    going = True
    for name, crits in level_criteria(horizontal):
        met = True
        for e, f in crits:
            achieved = float((shares[e][:, 0] >= F_TIME).mean())
            out[f"{name}_{int(e)}"] = round(achieved, 4)
            met = met and achieved >= f
        going = going and met
        if going:
            out["level"] = name
    out["score"] = float(score_of(shares, horizontal)[0])
    return out
