"""Simplified DGP at the design's observers and its annual exceedance (issue #30,
docs/daylight.md "Simplified DGP at observers in a project").

At each observer's eye, on a plane facing its view, the vertical eye illuminance Ev
(lux) of every occupied hour of the weather year, sun included; DGPs = 6.22e-5 Ev +
0.184 (``climate.sun_metrics.dgp_simplified``, Wienold 2009); the quantity is the share
of the occupied hours whose DGPs exceeds ``daylight.dgp_limit`` (0.40 by default,
strictly above, as ``climate.sun_metrics.dgp_exceedance``), and EN 17037's glare
protection level is the best of 0.45 / 0.40 / 0.35 exceeded in no more than 5% of them.

Ev is a sum of parts, each the light model's:

- **clear glazing** (fixed, ``light.clear_build``): the eye reads the same columns as a
  work-plane point: its own view of the sky and the ground through the panes (traced
  from the eye, ``transport.clear_glazing.receiver_sky_rays``), the room's radiosity
  of each sky and sun column through the eye's form factors, and the sun's beam traced
  at each hour's own sun (``sun_on_points``); the blinds as the design's LM-83
  schedule sets them (closed: no beam, the panes glow);
- **diffusing glazing** (the candidates' skylights and windows): per sky group and
  exterior lux, the glazing the eye sees (its exitance through the eye's form factors)
  and the room's reflections of it (the radiosity operator's rows where the eye looks),
  times the group's exterior lux of each hour (``light.daylight_year``). This part
  changes with a candidate's diffusing glazing, so the optimiser judges the intention.
- **electric light is left out**: DGP is a daylight glare model (fitted on daylit
  offices, Wienold and Christoffersen 2006) and EN 17037 rates the daylight's glare
  protection; in the hours that could exceed 0.40 (Ev above 3,470 lux) daylight-linked
  dimming has the luminaires low or off; the luminaires' glare is rated by UGR
  (``light.glare``). So the value does not change with the luminaires.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field, replace
from types import SimpleNamespace

import numpy as np

from lightinv_core.climate.sun_metrics import (
    DGP_INTERCEPT,
    DGP_SLOPE,
    GLARE_LEVELS,
    GLARE_TIME_SHARE,
    dgp_simplified,
)
from lightinv_core.design.model import Daylight, Design, DesignError, Intention
from lightinv_core.errors import LightInvError
from lightinv_core.light.arrays import caster_for
from lightinv_core.light.clear_build import GLASS_SAMPLES, POINT_RAYS, clear_glass, clear_light
from lightinv_core.light.clear_glazing import (
    BLIND_TRANSMITTANCE,
    ClearLight,
    clear_sources,
    clear_transmittance,
)
from lightinv_core.light.daylight_year import daylight_year, sky_groups, weather_path
from lightinv_core.light.glare import Eyes, observer_eyes
from lightinv_core.quantities import quantity_spec
from lightinv_core.sources.types import source_types
from lightinv_core.transport.clear_glazing import (
    receiver_sky_rays,
    sun_on_points,
    to_geographic,
    to_scene,
)
from lightinv_core.transport.formfactors import DEFAULT_RAYS
from lightinv_core.transport.receivers import receiver_factors

EYE_SEED_OFFSET = 13  # the eyes' rays draw from a stream of their own
BATCH_BYTES = 64 << 20
"""Largest (eyes, candidates, hours) array a batch makes at once; more is chunked."""

_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def ev_limit(dgp_limit: float) -> float:
    """The eye illuminance (lux) above which DGPs exceeds ``dgp_limit``."""
    return (float(dgp_limit) - DGP_INTERCEPT) / DGP_SLOPE


@dataclass(frozen=True, eq=False)
class EyeDaylight:
    """The daylight at the design's eyes over the occupied hours (see the module).

    ``clear`` (k, T) lux of the fixed clear glazing with the LM-83 blinds; per sky group
    of the diffusing glazing, ``exterior`` (G, T) lux on its plane and ``cols`` its zone
    columns; ``direct`` (k, nz) the eyes' form factors to the zone patches (their
    exitance seen directly), ``taps`` (k, s) form factors x reflectance to the patches
    ``receivers.rows`` the eyes see (the room's reflections); ``clear_light`` the clear
    glazing's columns at the eyes (None without), every hour and blinds state; ``rows``
    (k, nz) the two together per unit exitance of each zone patch (None when the zone
    basis's rows at the patches seen would not fit: then each batch is lit from
    ``receivers``); ``seen`` the patches the eyes see (the columns of ``taps``)."""

    eyes: Eyes
    daylight: Daylight
    clear: np.ndarray
    exterior: np.ndarray
    cols: tuple[np.ndarray, ...]
    direct: np.ndarray
    taps: np.ndarray
    receivers: object
    light: object
    clear_light: ClearLight | None = None
    rows: np.ndarray | None = None
    seen: np.ndarray | None = None
    _memo: dict = field(default_factory=dict, repr=False)

    @property
    def index(self) -> dict[str, int]:
        """{observer name: row}."""
        return {n: i for i, n in enumerate(self.eyes.names)}

    def sky_at_eyes(self, V: np.ndarray) -> np.ndarray:
        """(G, k, m) lux at each eye per exterior lux of each sky group, for diffusing
        glazing emitting V (nz, m) lm/m² per exterior lux (every sky group's zones).
        With ``rows`` (the eyes' light per unit exitance of each zone patch, made once)
        a batch costs k x (the group's emitting patches) x m."""
        V = np.asarray(V, dtype=np.float32)
        out = np.zeros((len(self.cols), len(self.eyes.names), V.shape[1]))
        for g, cols in enumerate(self.cols):
            on = cols[np.any(V[cols] != 0, axis=1)]
            if not len(on):
                continue
            if self.rows is not None:
                out[g] = self.rows[:, on] @ V[on].astype(float)
                continue
            Vg = np.zeros_like(V)
            Vg[on] = V[on]
            H = self.light.illuminance(Vg, self.receivers, on)
            out[g] = self.direct[:, on] @ Vg[on].astype(float) + self.taps @ H.astype(float)
        return out

    def ev(self, V: np.ndarray | None = None) -> np.ndarray:
        """(k, m, T) hourly eye illuminance (lux): the clear glazing plus the diffusing
        glazing of V (nz, m) per exterior lux (None: no diffusing glazing, m = 1)."""
        if V is None or not len(self.cols):
            m = 1 if V is None else V.shape[1]
            return np.repeat(self.clear[:, None, :], m, axis=1)
        sky = self.sky_at_eyes(V)
        return self.clear[:, None, :] + np.einsum("gkm,gt->kmt", sky, self.exterior)

    def exceedance(self, V: np.ndarray | None = None, limit: float | None = None) -> np.ndarray:
        """(k, m) share of the occupied hours with DGPs above ``limit`` (default the
        design's ``dgp_limit``): Ev above ``ev_limit(limit)``."""
        limit = self.daylight.dgp_limit if limit is None else limit
        lux = ev_limit(limit)
        k, T = self.clear.shape
        m = 1 if V is None else V.shape[1]
        if limit >= 1.0 or T == 0:  # DGPs is capped at 1: never above; or no hours
            return np.zeros((k, m))
        if V is None or not len(self.cols):
            share = (self.clear > lux).mean(axis=1)
            return np.repeat(share[:, None], m, axis=1)
        sky = self.sky_at_eyes(V)
        if len(self.cols) == 1:
            return self._one_group(sky[0], lux)
        out = np.empty((k, m))
        step = max(1, BATCH_BYTES // (8 * k * T))
        for a in range(0, m, step):
            ev = self.clear[:, None, :] + np.einsum("gkm,gt->kmt", sky[:, :, a : a + step],
                                                    self.exterior)  # fmt: skip
            out[:, a : a + step] = (ev > lux).mean(axis=2)
        return out

    def _one_group(self, sky: np.ndarray, lux: float) -> np.ndarray:
        """``exceedance`` with one sky group, sky (k, m) lux per exterior lux at the
        eyes: an hour t of exterior lux x_t > 0 counts when clear_t + s x_t > lux, i.e.
        when s > (lux - clear_t) / x_t, so the hours are counted by a binary search in
        those thresholds, sorted once per eye (O(m log T), not O(m T)); an hour without
        exterior light counts when the clear glazing alone exceeds."""
        key = ("one_group", lux)
        if key not in self._memo:
            x = self.exterior[0]
            lit = x > 0
            always = (self.clear[:, ~lit] > lux).sum(axis=1)
            thresholds = np.sort((lux - self.clear[:, lit]) / x[lit], axis=1)
            self._memo[key] = (always, thresholds)
        always, thresholds = self._memo[key]
        counts = np.stack(
            [np.searchsorted(thr, s, side="left") for thr, s in zip(thresholds, sky, strict=True)]
        )
        return (always[:, None] + counts) / self.clear.shape[1]

    def values_of(self, lit) -> np.ndarray:
        """(k, m) the share of hours above the design's limit at every eye for a
        batch's light ``lit`` (``optimize.candidate_light.Lit``, or any object with its
        ``V`` and ``by_kind``: the sources' zone emission at the design's exterior lux)."""
        return self.exceedance(_unit_sky(lit, self.daylight, bool(self.cols)))

    def values(self, intention: Intention, lit) -> np.ndarray:
        """(k', m) the intention's quantity (``QuantitySpec.from_eyes``) at its observers."""
        idx = [self.index[o] for o in intention.observers]
        return np.asarray(quantity_spec(intention.quantity).from_eyes(self, lit))[idx]


def _unit_sky(lit, daylight: Daylight, any_sky: bool) -> np.ndarray | None:
    """The daylit sources' zone emission per exterior lux (nz, m) of a batch."""
    if not any_sky:
        return None
    daylit = [str(t.kind) for t in source_types() if t.daylit]
    parts = [lit.by_kind[k] for k in daylit if k in lit.by_kind]
    if not parts:
        return np.zeros((lit.V.shape[0], lit.V.shape[1]), np.float32)
    if daylight.exterior_lux <= 0:
        raise DesignError(
            "simplified DGP with diffusing glazing: set daylight exterior_lux above 0 "
            "(the batch's glazing is read at it)"
        )
    return sum(parts[1:], parts[0]) / np.float32(daylight.exterior_lux)


def eye_daylight(light, design: Design) -> EyeDaylight:
    """The daylight at ``design``'s eyes on ``light`` (a ``LightModel``), made once per
    operator, observers, glazing, work planes and daylight (DesignError when an eye is
    outside the room)."""
    memo = _CACHE.setdefault(light.op, {})
    glazing = tuple((s.kind, s.zone, s.glazing) for s in design.sources)
    key = (design.observers, glazing, clear_sources(design), tuple(design.workplanes),
           replace(design.daylight, dgp_limit=0.4, en17037_basis="points"))  # fmt: skip
    if key not in memo:
        memo.clear()
        memo[key] = _build(light, design)
    return memo[key]


def _occupied(d: Daylight) -> np.ndarray:
    from lightinv_core.climate.weather import load_weather

    w = load_weather(weather_path(d))
    return np.asarray(w.occupied(*d.occupancy, weekdays=d.weekdays), bool)


def _build(light, design: Design) -> EyeDaylight:
    d = design.daylight
    eyes = observer_eyes(light.patches, design.observers)
    op = light.op
    rays = max(POINT_RAYS, int(op.info.get("rays", DEFAULT_RAYS)))
    seed = int(op.info.get("seed", 0)) + EYE_SEED_OFFSET
    caster = caster_for(light.patches)
    F = receiver_factors(eyes.points, eyes.views, caster, light.n, rays, seed).tocsr()
    occ = _occupied(d)
    at_eyes = clear_at_eyes(light, design, eyes, F, caster)
    clear = np.zeros((len(eyes.names), int(occ.sum())))
    if at_eyes is not None:  # with the LM-83 blinds, as the work plane's annual light
        clear = at_eyes.lux(slice(None), occ)
    groups = sky_groups(light, design)
    exterior = np.zeros((groups.count, int(occ.sum())))
    if groups.count:
        year = daylight_year(groups, d)
        exterior = np.asarray(year.every, float)[:, occ]
    seen = np.unique(F.indices).astype(np.int64)
    rho = op.rho
    taps = np.asarray(F[:, seen].multiply(rho[seen][None, :]).todense())
    direct = np.asarray(F[:, op.zone_patches].todense())
    receivers, rows = None, None
    if groups.count:
        receivers = light.receivers(seen)
        if receivers.Phi_rows is not None:  # the eyes' rows of the zone basis, once
            rows = direct + taps @ receivers.Phi_rows.astype(float)
            receivers = None  # (seen x nz: not kept)
    return EyeDaylight(
        eyes, d, clear, exterior, tuple(groups.cols), direct, taps, receivers, light,
        at_eyes, rows, seen,
    )  # fmt: skip


def _suns(d: Daylight):
    """(geographic unit suns (H, 3), direct normal lux (H,), sun up (H,)) every hour."""
    from lightinv_core.climate.transposition import sun_and_sky
    from lightinv_core.climate.weather import load_weather

    weather = load_weather(weather_path(d))
    sky = sun_and_sky(weather)
    zen, az = np.radians(sky.zenith), np.radians(sky.azimuth)
    geo = np.stack([np.sin(zen) * np.sin(az), np.sin(zen) * np.cos(az), np.cos(zen)], axis=1)
    dn = np.asarray(weather.dn_lux, dtype=float)
    up = (sky.zenith < 90.0) & (dn > 0)
    return geo, np.where(up, dn, 0.0), up


def clear_at_eyes(light, design: Design, eyes: Eyes, F, caster) -> ClearLight | None:
    """The fixed clear glazing's light at the eyes (None without clear glazing): the
    columns of ``clear_light`` read as a work-plane point reads them (see
    ``light.clear_build``), the beam traced at each hour's own sun (``direct``). ``F``
    (k, n): the eyes' form factors to the patches; ``caster`` the scene's."""
    from lightinv_core.climate.skydome import reinhart

    k = len(eyes.names)
    built = clear_light(light, design)
    if built is None:
        return None
    d = design.daylight
    sources = clear_sources(design)
    cols, P = built.patches.columns, built.patches.coefficients
    G = len(sources)
    dome = reinhart(d.sky_subdivision)  # the build's sky patches
    K0 = len(dome.solid_angles)
    B = (cols.count - G) // G
    S = (B - K0 - 1) // 2
    glass = clear_glass(light, sources, clear_transmittance(d))
    rho = light.patches.rho.copy()
    rho[glass.idx] = 0.0  # the panes pass light and reflect none
    lit = replace(light.patches, rho=rho)
    E_closed = np.zeros((light.n, G))
    E_closed[glass.idx, glass.group] = BLIND_TRANSMITTANCE * glass.transmittance
    seen = receiver_sky_rays(eyes.points, eyes.views, lit, glass, caster, GLASS_SAMPLES, 0)
    own = np.zeros((G, k, K0 + 1))
    if len(seen.weight):
        b = dome.patch_of(to_geographic(seen.direction, d.north_deg))
        b = np.where(b < 0, K0, b)
        np.add.at(own, (seen.group, seen.target, b), seen.weight)
    coeffs = np.zeros((k, cols.count))
    for g in range(G):
        blk = P[:, g * B : (g + 1) * B]
        first = blk[:, : K0 + 1 + S].copy()
        first[:, K0 + 1 :] += blk[:, K0 + 1 + S :]  # the sun's beam lights the room too
        c = np.asarray(F @ (rho[:, None] * first))
        c[:, : K0 + 1] += own[g]
        coeffs[:, g * B : g * B + K0 + 1 + S] = c  # the beam's columns stay 0: traced
    coeffs[:, G * B :] = np.asarray(F @ (E_closed + rho[:, None] * P[:, G * B :]))
    geo, dn, up = _suns(d)
    direct = np.zeros((G, k, len(dn)), np.float32)
    hours = np.flatnonzero(up)
    if len(hours):
        beam = sun_on_points(eyes.points, eyes.views, lit, glass, caster,
                             to_scene(geo[hours], d.north_deg))  # fmt: skip
        direct[:, :, hours] = beam * dn[hours]
    return ClearLight(cols, coeffs, direct)


def layout_lit(light, design: Design, sources) -> SimpleNamespace:
    """One layout's light as a batch of one: its sources' zone emission ``V`` (nz, 1)
    and ``by_kind`` at the design's daylight (what ``from_eyes`` reads)."""
    from lightinv_core.sources.emission import source_stack

    nz = len(light.op.zone_patches)
    if not sources:
        return SimpleNamespace(V=np.zeros((nz, 1), np.float32), by_kind={})
    V, by_kind = light.zone_emission(
        sources, *source_stack(sources), design.daylight, split_kinds=True
    )
    return SimpleNamespace(V=V, by_kind=by_kind)


def observer_dgp(light, design: Design, sources=None) -> dict[str, dict]:
    """{observer: figures} of one layout (``sources`` as lit, default the design's):
    ``exceedance`` the share of occupied hours with DGPs above ``limit``
    (``daylight.dgp_limit``); as the forward study's views (``study.clear_metrics``):
    ``dgp_over_0.35``, ``dgp_over_0.40``, ``dgp_over_0.45``, ``en17037_glare`` (EN
    17037's glare protection level: "none", "minimum", "medium" or "high"), ``dgp_max``
    and ``ev_max_lux``; and ``hours`` (the occupied hours)."""
    from lightinv_core.sources.emission import source_stack
    from lightinv_core.sources.types import diffusing

    eyes = eye_daylight(light, design)
    sources = light.layout(design) if sources is None else tuple(sources)
    V = None
    glow = diffusing(sources)
    if glow and eyes.cols:
        unit = replace(design.daylight, exterior_lux=1.0)
        V = light.zone_emission(glow, *source_stack(glow), unit)[:, :1]
    ev = eyes.ev(V)[:, 0, :]
    limit = float(design.daylight.dgp_limit)
    out = {}
    for i, name in enumerate(eyes.eyes.names):
        e = ev[i]
        dgp = dgp_simplified(e) if e.size else np.full(1, DGP_INTERCEPT)
        row = {"exceedance": float((dgp > limit).mean()), "limit": limit}
        level = "none"
        for lname, lim in GLARE_LEVELS:  # minimum, medium, high: each stricter
            row[f"dgp_over_{lim:.2f}"] = share = float((dgp > lim).mean())
            if share <= GLARE_TIME_SHARE + 1e-12 and level == GLARE_LEVELS_ORDER[lname]:
                level = lname
        row["en17037_glare"] = level
        row["dgp_max"] = float(dgp.max())
        row["ev_max_lux"] = float(e.max()) if e.size else 0.0
        row["hours"] = int(e.size)
        out[name] = row
    return out


GLARE_LEVELS_ORDER = {"minimum": "none", "medium": "minimum", "high": "medium"}
"""Each glare protection level and the one below it: a level is met when its limit is
kept and every laxer one is met (as ``climate.sun_metrics.glare_protection``)."""


def layout_eye_daylight(light, design: Design, sources, specs) -> tuple:
    """(DGP figures, why not, {quantity: {observer: value}}) of one layout's sources for
    the ``from_eyes`` quantities among ``specs`` (the design's observer intentions'):
    (None, "", None) without any; the light of the rest stands when this fails."""
    wanted = [q for q in specs if q.from_eyes is not None]
    if not wanted:
        return None, "", None
    try:
        figures = observer_dgp(light, design, sources)
        eyes = eye_daylight(light, design)
        lit = layout_lit(light, design, sources)
        eyed = {}
        for q in wanted:
            values = np.asarray(q.from_eyes(eyes, lit))[:, 0]
            eyed[q.name] = dict(zip(eyes.eyes.names, map(float, values), strict=True))
    except LightInvError as exc:
        return None, str(exc), None
    return figures, "", eyed


def eyed_values(eyed: dict | None, why: str, intention: Intention) -> np.ndarray:
    """(k,) a layout's ``from_eyes`` quantity at the intention's observers, from
    ``layout_eye_daylight``'s values; DesignError saying ``why`` when there are none."""
    if eyed is None or intention.quantity not in eyed:
        why = why or "the daylight at the eyes was not computed"
        raise DesignError(f"intention {intention.name!r}: {why}")
    got = eyed[intention.quantity]
    return np.array([got[o] for o in intention.observers], dtype=float)
