"""Sun, blinds and glare metrics from hourly illuminance: cDA, ASE, LM-83 blinds, DGPs.

Inputs are illuminance (lux) per point and hour, ``(q, T)``, already restricted to the
hours the metric counts (the occupied hours). Definitions and sources (docs/daylight.md,
"Sun, blinds, EN 17037 and glare metrics", says more):

- **cDA** (continuous daylight autonomy, Rogers 2006): per point, the mean over the
  hours of min(E / threshold, 1): full credit at or above the threshold, partial
  credit E / threshold below it.
- **ASE1000,250h** (IES LM-83-12): per point, the hours whose *direct sun only*
  illuminance (no inter-reflection, blinds open) *exceeds* 1000 lux (E > 1000); ASE is
  the share of points where that count is *more than* 250 hours (> 250). Both are
  strict, as the IES definition says "exceeds ... more than a specified number of
  hours".
- **Operable blinds** (LM-83-12 section 2.2.6): blinds close in an hour when *more
  than* 2% of the analysis points receive direct sun, "direct sun" being 1000 lux
  *or more* (E >= 1000) of direct beam sunlight, excluding the blinds, zero bounce;
  blinds of the window groups "can close in any combination" until the criterion is
  met, each hour. ``blinds_closed`` is the rule for one group (or for groups judged
  apart); ``blinds_schedule`` is the combination rule over several groups.
- **DGPs** (simplified daylight glare probability, Wienold 2009): 6.22e-5 Ev + 0.184
  from the vertical eye illuminance Ev (lux) alone. It has no contrast term, so it
  misses glare from the sun or a bright specular source seen directly; the DGP model
  is fitted for DGP 0.2-0.8 (Wienold and Christoffersen 2006), i.e. Ev of about 260
  to 9900 lux here. Classes: imperceptible < 0.35 <= perceptible < 0.40 <= disturbing
  < 0.45 <= intolerable.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.metrics import daylight_metrics
from lightinv_core.errors import LightInvError

CDA_THRESHOLD = 300.0
ASE_LUX = 1000.0
ASE_HOURS = 250
BLINDS_SHARE = 0.02
BLINDS_LUX = 1000.0
MAX_EXHAUSTIVE_GROUPS = 6
"""Up to this many glazing groups every open/closed combination is tried each hour
(2^G of them); beyond it groups are closed greedily (see ``blinds_schedule``)."""

DGP_SLOPE = 6.22e-5
DGP_INTERCEPT = 0.184
DGP_CLASS_LIMITS = (0.35, 0.40, 0.45)
DGP_CLASS_NAMES = ("imperceptible", "perceptible", "disturbing", "intolerable")
GLARE_LEVELS = (("minimum", 0.45), ("medium", 0.40), ("high", 0.35))
"""EN 17037 glare protection: the DGP limit of each level, exceeded in no more than
``GLARE_TIME_SHARE`` of the occupied hours."""
GLARE_TIME_SHARE = 0.05


def _hourly(lux, what: str = "illuminance") -> np.ndarray:
    a = np.asarray(lux, dtype=float)
    if a.ndim != 2 or a.shape[0] == 0 or a.shape[1] == 0:
        raise LightInvError(f"{what} must be points x hours with at least one of each")
    if not np.isfinite(a).all():
        raise LightInvError(f"{what} has values that are not finite numbers")
    return a


def continuous_da(lux, threshold: float = CDA_THRESHOLD) -> np.ndarray:
    """cDA (0-1) per point of hourly illuminance ``lux`` (q, T) against ``threshold``
    (lux): the mean of min(E / threshold, 1) over the hours (Rogers 2006)."""
    lux = _hourly(lux)
    if not threshold > 0:
        raise LightInvError(f"the cDA threshold must be above 0 lux, got {threshold}")
    return np.clip(lux / threshold, 0.0, 1.0).mean(axis=1)


@dataclass(frozen=True)
class AseResult:
    """ASE per IES LM-83-12: ``hours`` (q,) per point with direct sun above ``lux``,
    ``share`` the fraction of points (0-1) with more than ``limit_hours`` of them."""

    hours: np.ndarray
    share: float
    lux: float
    limit_hours: float


def ase(direct_sun_lux, lux: float = ASE_LUX, hours: float = ASE_HOURS) -> AseResult:
    """Annual sunlight exposure from the direct-sun-only illuminance (lux) per point
    and occupied hour (q, T), blinds open: ASE1000,250h is ``ase(direct).share``."""
    direct = _hourly(direct_sun_lux, "direct sun illuminance")
    above = (direct > lux).sum(axis=1)
    return AseResult(above, float((above > hours).mean()), float(lux), float(hours))


def direct_sun_share(direct_sun_lux, lux: float = BLINDS_LUX) -> np.ndarray:
    """Per hour (T,), the fraction of points in direct sun: direct-only illuminance of
    ``lux`` or more (LM-83's definition of direct sun)."""
    return (_hourly(direct_sun_lux, "direct sun illuminance") >= lux).mean(axis=0)


def blinds_closed(
    direct_sun_lux, share: float = BLINDS_SHARE, lux: float = BLINDS_LUX
) -> np.ndarray:
    """LM-83's rule for one glazing group: closed (T,) in the hours when more than
    ``share`` of the points receive direct sun (``direct_sun_share``) from it."""
    return direct_sun_share(direct_sun_lux, lux) > share


def _group_parts(parts, what: str) -> np.ndarray:
    a = np.asarray(parts, dtype=float)
    if a.ndim != 3 or 0 in a.shape:
        raise LightInvError(f"{what} must be groups x points x hours")
    if not np.isfinite(a).all():
        raise LightInvError(f"{what} has values that are not finite numbers")
    return a


def blinds_schedule(
    direct_open,
    direct_closed=None,
    share: float = BLINDS_SHARE,
    lux: float = BLINDS_LUX,
    method: str = "auto",
) -> np.ndarray:
    """LM-83's blinds for several glazing groups: closed (G, T) per group and hour.

    ``direct_open`` (G, q, T) is each group's direct-sun illuminance with its blinds
    open, ``direct_closed`` with them closed (default 0: closed blinds stop the beam).
    Each hour the fewest groups are closed that leave no more than ``share`` of the
    points in direct sun (the sum over the groups, E >= ``lux``); among equal numbers,
    the combination leaving the most sun in (the least shaded, as Honeybee chooses),
    then the one closing the lowest-numbered groups. If no combination meets the
    rule, all are closed.
    ``method`` "exhaustive" tries every combination, "greedy" closes one group at a
    time (the one whose closing leaves the fewest points in sun), "auto" the first up
    to ``MAX_EXHAUSTIVE_GROUPS`` groups and the second beyond.
    """
    opened = _group_parts(direct_open, "direct sun with blinds open")
    shut = (
        np.zeros_like(opened)
        if direct_closed is None
        else _group_parts(direct_closed, "direct sun with blinds closed")
    )
    if shut.shape != opened.shape:
        raise LightInvError("direct sun with blinds open and closed must have one shape")
    if method not in ("auto", "exhaustive", "greedy"):
        raise LightInvError(f"unknown blinds method {method!r}: auto, exhaustive or greedy")
    groups = opened.shape[0]
    if method == "greedy" or (method == "auto" and groups > MAX_EXHAUSTIVE_GROUPS):
        return _greedy(opened, shut, share, lux)
    return _exhaustive(opened, shut, share, lux)


def _sun_share(opened, shut, closed_groups, lux) -> np.ndarray:
    total = np.zeros(opened.shape[1:])
    for g in range(opened.shape[0]):
        total += np.where(closed_groups[g], shut[g], opened[g])
    return (total >= lux).mean(axis=0)


def _exhaustive(opened, shut, share, lux) -> np.ndarray:
    groups, _, hours = opened.shape
    closed = np.zeros((groups, hours), dtype=bool)
    # Only the hours the open state fails need a search (usually a small part).
    todo = np.flatnonzero(_sun_share(opened, shut, closed, lux) > share)
    if todo.size == 0:
        return closed
    o, c = opened[:, :, todo], shut[:, :, todo]
    best = np.ones((groups, todo.size), dtype=bool)  # all closed unless one meets it
    best_count = np.full(todo.size, np.inf)
    best_share = np.full(todo.size, -1.0)
    for n in range(1, groups + 1):  # fewest closed first; group 0 before group 1
        for shut_groups in itertools.combinations(range(groups), n):
            combo = np.zeros(groups, dtype=bool)
            combo[list(shut_groups)] = True
            state = np.repeat(combo[:, None], todo.size, axis=1)
            s = _sun_share(o, c, state, lux)
            better = (s <= share) & ((n < best_count) | ((n == best_count) & (s > best_share)))
            best[:, better] = combo[:, None]
            best_count[better] = n
            best_share[better] = s[better]
    closed[:, todo] = best
    return closed


def _greedy(opened, shut, share, lux) -> np.ndarray:
    groups, _, hours = opened.shape
    closed = np.zeros((groups, hours), dtype=bool)
    s = _sun_share(opened, shut, closed, lux)
    for _ in range(groups):
        todo = s > share
        if not todo.any():
            break
        trial = np.full((groups, hours), np.inf)
        for g in range(groups):
            c = closed.copy()
            c[g] = True
            t = _sun_share(opened, shut, c, lux)
            trial[g] = np.where(closed[g], np.inf, t)  # only groups still open
        pick = np.argmin(trial, axis=0)
        closed[pick[todo], np.flatnonzero(todo)] = True
        s = _sun_share(opened, shut, closed, lux)
    return closed


def lux_with_blinds(open_parts, closed_parts, closed) -> np.ndarray:
    """Illuminance (q, T) with each group in its hour's state: ``open_parts`` and
    ``closed_parts`` (G, q, T) are each group's contribution with its blinds open and
    closed, ``closed`` (G, T) bool the state per group and hour."""
    opened = _group_parts(open_parts, "light with blinds open")
    shut = _group_parts(closed_parts, "light with blinds closed")
    state = np.asarray(closed, dtype=bool)
    if shut.shape != opened.shape or state.shape != (opened.shape[0], opened.shape[2]):
        raise LightInvError("open and closed parts must be G x q x T and the states G x T")
    total = np.zeros(opened.shape[1:])
    for g in range(opened.shape[0]):
        total += np.where(state[g], shut[g], opened[g])
    return total


@dataclass(frozen=True)
class BlindsDaylight:
    """sDA300/50% with LM-83 operable blinds: ``closed`` (G, T) the blinds per group
    and hour, ``da`` (q,) DA300 per point of the light with blinds, ``sda`` the share
    of points with DA300 >= 50%, ``closed_share`` the fraction of hours each group's
    blinds are closed (G,)."""

    closed: np.ndarray
    da: np.ndarray
    sda: float
    closed_share: np.ndarray


def sda_with_blinds(
    open_parts, closed_parts, direct_open, direct_closed=None, method: str = "auto"
) -> BlindsDaylight:
    """sDA300/50% per LM-83 with blinds operated by ``blinds_schedule`` from each
    group's direct sun (``direct_open``, ``direct_closed``, G x q x T, lux) and the
    total light of each group open and closed (``open_parts``, ``closed_parts``)."""
    closed = blinds_schedule(direct_open, direct_closed, method=method)
    metrics = daylight_metrics(lux_with_blinds(open_parts, closed_parts, closed))
    return BlindsDaylight(closed, metrics.da, metrics.sda, closed.mean(axis=1))


def dgp_simplified(ev, low_light_correction: bool = False) -> np.ndarray:
    """DGPs = 6.22e-5 Ev + 0.184 (Wienold 2009) of vertical eye illuminance ``ev``
    (lux, any shape), at most 1 (as evalglare caps DGP). With
    ``low_light_correction`` below 1000 lux it is multiplied by evalglare's factor
    exp(0.024 Ev - 4) / (1 + exp(0.024 Ev - 4)) (written for the full DGP)."""
    ev = np.asarray(ev, dtype=float)
    if not np.isfinite(ev).all() or (ev < 0).any():
        raise LightInvError("eye illuminance must be finite and at least 0 lux")
    dgp = np.minimum(DGP_SLOPE * ev + DGP_INTERCEPT, 1.0)
    if low_light_correction:
        x = np.exp(np.minimum(0.024 * ev - 4.0, 50.0))
        dgp = np.where(ev < 1000.0, dgp * x / (1.0 + x), dgp)
    return dgp


def dgp_class(dgp) -> np.ndarray:
    """Index into ``DGP_CLASS_NAMES`` per value: 0 below 0.35, 1 from 0.35, 2 from
    0.40, 3 from 0.45 (Wienold 2009)."""
    return np.searchsorted(np.asarray(DGP_CLASS_LIMITS), np.asarray(dgp, float), side="right")


def dgp_exceedance(ev, limit: float = 0.40, low_light_correction: bool = False) -> np.ndarray:
    """Per view point (v,), the fraction of hours of ``ev`` (v, T; vertical eye
    illuminance, lux, sun included) whose DGPs exceeds ``limit`` (DGPs > limit)."""
    ev = _hourly(ev, "eye illuminance")
    return (dgp_simplified(ev, low_light_correction) > limit).mean(axis=1)


@dataclass(frozen=True)
class GlareProtection:
    """EN 17037 glare protection per view point: ``exceedance`` (v, 3) the fraction of
    occupied hours above each level's DGP limit (minimum, medium, high), ``level``
    the best level met per view ("none" if even the minimum is not)."""

    exceedance: np.ndarray
    level: tuple[str, ...]


def glare_protection(ev, low_light_correction: bool = False) -> GlareProtection:
    """EN 17037 glare protection from DGPs of hourly eye illuminance ``ev`` (v, T):
    a level is met where its DGP limit is exceeded in no more than 5% of the hours."""
    ex = np.stack(
        [dgp_exceedance(ev, lim, low_light_correction) for _, lim in GLARE_LEVELS], axis=1
    )
    levels = []
    for row in ex:
        met = "none"
        for (name, _), share in zip(GLARE_LEVELS, row, strict=True):
            if share > GLARE_TIME_SHARE + 1e-12:
                break
            met = name
        levels.append(met)
    return GlareProtection(ex, tuple(levels))


def dgp_ev(dgp: float) -> float:
    """The eye illuminance (lux) at which DGPs equals ``dgp`` (the inverse formula)."""
    if not DGP_INTERCEPT <= dgp <= 1.0 or math.isnan(dgp):
        raise LightInvError(f"DGPs is from {DGP_INTERCEPT} to 1, got {dgp}")
    return (dgp - DGP_INTERCEPT) / DGP_SLOPE
