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
- on the "hours" basis (``daylight.en17037_basis``; the standard's other reading,
  ClimateStudio's): per hour and criterion, s_t = the share of the plane's points with
  E_p >= E; the criterion holds when the hours with s_t >= F are at least half of the
  daylight hours. Its shortfall swaps the two roles: a = (1/2 - the share of hours
  reached) / (1/2), b = (F - s_k) / F, s_k the plane share of the k-th best hour,
  k = ceil(Hd / 2). With one diffusing sky group and no clear glazing, E_p(t) = a_p
  E(t) ranks the points alike in every hour, so the k-th best point's time share is the
  share of hours in which k points reach, and the median hour's plane share the share
  of points reaching in half the hours: the two shortfalls swap their terms and the
  scores are equal (tested); the optimiser then scores on the points basis's faster
  path, and only the figures differ;
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


def hour_shares(light, idx, levels) -> np.ndarray:
    """(L, Hd, m) per illuminance of ``levels`` (lux) and daylight hour: the share of
    the receivers idx (a plane's points) with at least that much daylight, every blind
    open (the "hours" basis)."""
    levels = np.asarray(levels, dtype=float)
    mask = daylight_mask(light)
    a = light.coefficients(idx)  # (R', m, G)
    n, m = a.shape[0], a.shape[1]
    fixed = None if light.clear is None else light.clear.open_hours(idx, mask)
    ext = light.year().every[:, mask] if a.shape[-1] else None  # (G, Hd)
    hours = int(mask.sum())
    out = np.empty((len(levels), hours, m))
    for j in range(m):
        if fixed is None and a.shape[-1] == 1:
            # One sky group: E_p(t) = a_p E(t) >= L when E(t) >= L / a_p, so the points
            # lit are counted by a binary search in their sorted thresholds.
            a0 = a[:, j, 0]
            for i, lev in enumerate(levels):
                with np.errstate(divide="ignore"):
                    thr = np.sort(np.where(a0 > 0, lev / np.where(a0 > 0, a0, 1.0), np.inf))
                out[i, :, j] = np.searchsorted(thr, ext[0], side="right") / n
            continue
        lux = np.zeros((n, hours)) if ext is None else a[:, j, :] @ ext
        if fixed is not None:
            lux = lux + fixed
        out[:, :, j] = (lux[None] >= levels[:, None, None]).mean(axis=1)
    return out


def _short(values: np.ndarray, reach: float, need: float) -> np.ndarray:
    """(m,) shortfall of a criterion whose rows (points or hours) reach when their value
    is at least ``reach`` and which holds when at least ``need`` of the rows reach."""
    n = values.shape[0]
    achieved = (values >= reach).mean(axis=0)
    k = min(n, max(1, math.ceil(need * n - 1e-9)))
    v_k = -np.partition(-values, k - 1, axis=0)[k - 1]  # the k-th largest value
    a = np.maximum(0.0, need - achieved) / need
    b = np.maximum(0.0, reach - v_k) / reach
    return np.where(achieved >= need, 0.0, FLOOR + (1.0 - FLOOR) * (a + b) / 2.0)


def shortfall(t: np.ndarray, plane: float) -> np.ndarray:
    """(m,) a criterion's shortfall (see the module) from the points' time shares t
    (n, m) at its illuminance and its plane fraction ``plane``."""
    return _short(t, F_TIME, plane)


def hours_shortfall(s: np.ndarray, plane: float) -> np.ndarray:
    """(m,) a criterion's shortfall on the "hours" basis from the hours' plane shares s
    (Hd, m) at its illuminance and its plane fraction ``plane``."""
    return _short(s, plane, F_TIME)


def score_of(shares: dict, horizontal: bool, basis: str = "points") -> np.ndarray:
    """(m,) the provision score (see the module) from ``shares`` {lux: (n, m) time
    shares per point}, or on the "hours" basis {lux: (Hd, m) plane shares per hour},
    of one plane."""
    short = hours_shortfall if basis == "hours" else shortfall
    m = next(iter(shares.values())).shape[1]
    score = np.zeros(m)
    going = np.ones(m, bool)
    for k, (_, crits) in enumerate(level_criteria(horizontal)):
        v = np.max([short(shares[e], f) for e, f in crits], axis=0)
        score = np.where(going, np.where(v == 0.0, k + 1.0, k + 1.0 - v), score)
        going &= v == 0.0
    return score


def plane_score(light, idx) -> np.ndarray:
    """(R', m) the provision score of the receivers idx as one work plane (the same at
    each of them)."""
    lux = provision_lux()
    basis = light.daylight.en17037_basis
    if basis == "hours" and light.clear is None and light.coefficients(idx).shape[-1] == 1:
        basis = "points"  # one diffusing sky group: the same score, faster (the module)
    got = (hour_shares if basis == "hours" else reach_shares)(light, idx, lux)
    score = score_of(dict(zip(lux, got, strict=True)), horizontal_openings(light), basis)
    receivers = light.coefficients(idx).shape[0]
    return np.broadcast_to(score, (receivers, got.shape[2])).copy()


def plane_figures(light, idx) -> dict:
    """EN 17037 daylight provision of the first layout at receivers idx, as the study's
    ``en17037_provision`` block: the level reached and, per level and criterion, the
    share of the plane reaching its illuminance in half of the daylight hours
    (``climate.en17037.ProvisionResult.summary``), plus the score."""
    lux = provision_lux()
    basis = light.daylight.en17037_basis
    hours = basis == "hours"
    got = (hour_shares if hours else reach_shares)(light, idx, lux)[:, :, :1]
    shares = dict(zip(lux, got, strict=True))
    horizontal = horizontal_openings(light)
    out: dict = {"level": "none", "horizontal_openings": horizontal, "basis": basis}
    out["daylight_hours"] = int(daylight_mask(light).sum())
    going = True
    for name, crits in level_criteria(horizontal):
        met = True
        for e, f in crits:
            # points: the share of the plane reaching e in half the hours; hours: the
            # share of the hours with f of the plane reaching e
            reach, need = (f, F_TIME) if hours else (F_TIME, f)
            achieved = float((shares[e][:, 0] >= reach).mean())
            out[f"{name}_{int(e)}"] = round(achieved, 4)
            met = met and achieved >= need
        going = going and met
        if going:
            out["level"] = name
    out["score"] = float(score_of(shares, horizontal, basis)[0])
    return out
