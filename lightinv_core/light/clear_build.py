"""The clear glazing's light in a design, built once: rays, reflections, blinds.

``clear_light(light, design)`` gives the fixed clear glazing's columns and coefficients
(``light.clear_glazing``) at every patch and work-plane point, cached per operator,
clear sources, work planes and daylight. How:

- the panes: the zone patches each clear source covers, its transmittance the design's
  ``daylight.transmittance`` (capped at what glass passes) x the source's filter x the
  share of the patch covered; black inside (they pass light and reflect none);
- the first hit, ray-traced as the forward study does (``transport.clear_glazing``):
  the sky's light landing on the room's patches binned by Tregenza patch, the sun's
  beam per sun bin, the work-plane points' own view of the sky through the glass, and
  their direct sun at each hour's own sun;
- the inter-reflections by the design's light model: two exact bounces over the traced
  form factors F, then the radiosity operator (``op.illuminance``) for the rest; the
  points read the room's radiosity through their traced form factors (as
  ``light.grids`` does);
- the blinds (IES LM-83, per clear source): closed, in the fewest combination, in the
  occupied hours when more than 2% of the control work plane's points would get
  direct sun of 1,000 lux or more (``climate.sun_metrics.blinds_schedule``); a closed
  source's panes glow as diffusing glazing of ``BLIND_TRANSMITTANCE`` x their
  transmittance times the exterior lux on their plane, reflected as above.
"""

from __future__ import annotations

import math
import time
import weakref
from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from lightinv_core.climate.skydome import SUN_BASIS_MF, sun_bins
from lightinv_core.design.model import Daylight, Design
from lightinv_core.kinds import GlazingKind
from lightinv_core.light.arrays import caster_for
from lightinv_core.light.clear_glazing import (
    BLIND_TRANSMITTANCE,
    ClearColumns,
    ClearDesignLight,
    ClearLight,
    clear_sources,
    clear_transmittance,
)
from lightinv_core.light.daylight_year import daylight_year, sky_groups
from lightinv_core.light.grids import GRID_SEED_OFFSET, design_receivers
from lightinv_core.transport.clear_glazing import (
    MAX_CLEAR_TRANSMITTANCE,
    Glass,
    receiver_sky_rays,
    room_sky_rays,
    sun_on_points,
    sun_on_room,
    to_geographic,
    to_scene,
)
from lightinv_core.transport.formfactors import DEFAULT_RAYS
from lightinv_core.transport.receivers import receiver_factors

GLASS_SAMPLES = 6
"""Per side: glass samples per pane patch for the receivers' view and the sun's beam."""
ROOM_RAYS = 256
"""Rays per pane patch into the room (the first hit of the sky on the room)."""
POINT_RAYS = 4096
"""Rays per work-plane point for its view of the room (at least the operator's): the
sun's reflections light the room unevenly (a bright patch on a wall), and fewer rays
left the points' annual means 5-10% apart (docs/daylight.md)."""

REFLECT_WORK = 3e8
"""Multiply-adds of the reflections between two progress calls (a cancel waits for at
most one block): on the flagship office (2,152 patches, rank 294) 107 of its 1,725
columns a block, about 0.07 s of CPU (bench/open_cancel.py)."""
MIN_REFLECT_COLUMNS = 8

_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def clear_light(light, design: Design, progress=None) -> ClearDesignLight | None:
    """The clear glazing's light of ``design`` on ``light`` (a ``LightModel``), made once
    per operator, clear sources, work planes and daylight; None without clear glazing.
    ``progress(fraction)`` (0-1) is called between the build's steps; an exception it
    raises (a ``CancelledError``) stops the build and leaves the cache as it was."""
    sources = clear_sources(design)
    if not sources:
        return None
    key = clear_light_key(design)
    memo = _CACHE.setdefault(light.op, {})
    if key not in memo:
        built = _build(light, design, sources, progress or (lambda f: None))
        memo.clear()  # one clear glazing at a time per operator
        memo[key] = built
    return memo[key]


def clear_light_key(design: Design) -> tuple | None:
    """What the clear glazing's light of ``design`` depends on (None without clear
    glazing): equal keys share one build."""
    sources = clear_sources(design)
    if not sources:
        return None
    return (sources, tuple(design.workplanes), _traced(design.daylight))


def clear_light_ready(light, design: Design) -> bool:
    """Whether ``clear_light(light, design)`` returns at once: no clear glazing, or its
    light already built on ``light``'s operator (an editor builds it elsewhere first)."""
    key = clear_light_key(design)
    return key is None or key in _CACHE.get(light.op, {})


def _traced(d: Daylight) -> Daylight:
    """``d`` without the fields the build does not read (the dimming's target, least
    level and standby, EN 17037's sunlight day, altitude and provision basis, the DGP
    limit): editing them in the Climate tab must not trace the glazing again (about
    20 s on the flagship office)."""
    return replace(
        d, target_lux=0.0, min_level=0.0, standby_w=0.0, sunlight_date="03-21",
        sunlight_min_altitude=None, dgp_limit=0.4, en17037_basis="points",
    )  # fmt: skip


def clear_glass(light, sources, tau: float) -> Glass:
    """The panes: the zone patches each clear source covers, with the transmittance
    times the source's filter times the share of the patch it covers."""
    from lightinv_core.sources.emission import source_stack

    share = np.zeros(light.n)
    group = np.full(light.n, -1)
    unit = Daylight(exterior_lux=1.0, transmittance=1.0)
    for g, s in enumerate(sources):
        diffusing = replace(s, glazing=GlazingKind.DIFFUSING)
        V = light.zone_emission((diffusing,), *source_stack((diffusing,)), unit)[:, 0]
        on = np.flatnonzero(V > 0)
        ids = light.op.zone_patches[on]
        share[ids] += V[on]  # filter x covered share of the patch
        group[ids] = g
    idx = np.flatnonzero(share > 0)
    t = np.clip(tau * share[idx], 0.0, MAX_CLEAR_TRANSMITTANCE)
    return Glass(idx, t, group[idx], tuple(s.name for s in sources))


def _weather(d: Daylight, dome, progress=lambda f: None):
    """(sky and ground luminances (K0 + 1, H), geographic suns (H, 3), direct normal
    lux (H,) where the sun is traced, that mask (H,)); ``progress(fraction)`` between
    its three steps (the file, the sun's path, the sky's luminance)."""
    from lightinv_core.climate.sky_luminance import hourly_sky_luminance
    from lightinv_core.climate.transposition import sun_and_sky
    from lightinv_core.climate.weather import load_weather
    from lightinv_core.light.daylight_year import weather_path

    weather = load_weather(weather_path(d))
    progress(0.2)
    sky = sun_and_sky(weather)
    progress(0.4)
    L = hourly_sky_luminance(
        dome, weather.dni, weather.dhi, weather.dh_lux, sky.zenith, sky.azimuth, sky.dni_extra
    )
    ground = d.ground_reflectance * np.asarray(weather.gh_lux, dtype=float) / math.pi
    zen, az = np.radians(sky.zenith), np.radians(sky.azimuth)
    geo = np.stack([np.sin(zen) * np.sin(az), np.sin(zen) * np.cos(az), np.cos(zen)], axis=1)
    dn = np.asarray(weather.dn_lux, dtype=float)
    up = (sky.zenith < 90.0) & (dn > 0)
    every = np.concatenate([np.asarray(L, dtype=float).T, ground[None]], axis=0)
    return every, geo, np.where(up, dn, 0.0), up


def _binned(rays, groups: int, bins, nbins: int) -> np.ndarray:
    """(G, targets, nbins) the rays' weights (lux per cd/m²) summed by glazing group,
    target and sky bin (``bins(directions) -> bin``)."""
    out = np.zeros(groups * rays.targets * nbins)
    if len(rays.weight):
        key = rays.group.astype(np.int64) * rays.targets + rays.target.astype(np.int64)
        key = key * nbins + np.asarray(bins(rays.direction))
        out += np.bincount(key, rays.weight, minlength=len(out))
    return out.reshape(groups, rays.targets, nbins)


def _reflected(light, rho: np.ndarray, H: np.ndarray) -> np.ndarray:
    """(n, c) irradiance (lux) from the room's reflections of first-hit irradiance H
    (n, c): two exact bounces over F (reflectances ``rho``, the panes 0), then the
    radiosity operator for the rest."""
    F = light.op.F
    H1 = np.asarray(F @ (rho[:, None] * H))
    H2 = np.asarray(F @ (rho[:, None] * H1))
    rest = np.asarray(light.op.illuminance(rho[:, None] * H2), dtype=float)
    return H1 + H2 + rest


def reflect_columns(light) -> int:
    """How many columns of first-hit light ``_reflections`` reflects between two progress
    calls: about ``REFLECT_WORK`` multiply-adds (two passes over F, the operator's rank-k
    rows), at least ``MIN_REFLECT_COLUMNS``."""
    op = light.op
    rank = int(getattr(op, "k", 0) or 0)
    per_column = 2 * op.F.nnz + 2 * light.n * max(rank, 1)
    return max(MIN_REFLECT_COLUMNS, int(REFLECT_WORK // max(per_column, 1)))


def _reflections(light, rho: np.ndarray, H: np.ndarray, progress) -> np.ndarray:
    """``_reflected`` of H (n, c) a block of columns at a time (each column reflects
    alone: the same light as in one go), ``progress(fraction of the columns done)``
    called between blocks, so that a cancel (an exception it raises) stops the longest
    step of the build within a fraction of a second of CPU (bench/open_cancel.py)."""
    c = H.shape[1]
    step = reflect_columns(light)
    if c <= step:
        return _reflected(light, rho, H)
    out = np.empty((H.shape[0], c))
    for a in range(0, c, step):
        b = min(c, a + step)
        out[:, a:b] = _reflected(light, rho, H[:, a:b])
        progress(b / c)
    return out


def _closed(light, design: Design, sources, glass: Glass):
    """Per clear source with its blinds closed: its panes' exitance per exterior lux on
    their plane (n, G) (``BLIND_TRANSMITTANCE`` x their transmittance), that
    exterior lux every hour (G, H) (``light.daylight_year``: Perez, ground included)
    and each source's outward normal (G, 3)."""
    d = design.daylight
    E = np.zeros((light.n, len(sources)))
    E[glass.idx, glass.group] = BLIND_TRANSMITTANCE * glass.transmittance
    outside, outward = [], []
    for s in sources:
        glow = replace(s, glazing=GlazingKind.DIFFUSING)
        groups = sky_groups(light, SimpleNamespace(sources=(glow,), daylight=d))
        outside.append(daylight_year(groups, d).every[0])
        outward.append(groups.outward[0])
    return E, np.array(outside), np.array(outward)


def _blinds(design: Design, grids, direct: np.ndarray, H: int) -> np.ndarray:
    """(G, H) each source's LM-83 blinds closed, from its direct sun (G, q, H) at the
    points; open outside the occupied hours and without a control work plane."""
    from lightinv_core.climate.sun_metrics import blinds_schedule
    from lightinv_core.climate.weather import load_weather
    from lightinv_core.light.daylight_year import weather_path

    closed = np.zeros((direct.shape[0], H), bool)
    plane = design.control_plane
    if plane is None or grids is None:
        return closed
    d = design.daylight
    occ = np.asarray(load_weather(weather_path(d)).occupied(*d.occupancy, weekdays=d.weekdays))
    if occ.any():
        closed[:, occ] = blinds_schedule(direct[:, grids.spans[plane.name]][:, :, occ])
    return closed


def _build(light, design: Design, sources, progress) -> ClearDesignLight:
    from lightinv_core.climate.sky_luminance import cie_overcast, scaled_sky
    from lightinv_core.climate.skydome import reinhart

    t0 = time.process_time()
    d = design.daylight
    patches, op = light.patches, light.op
    glass = clear_glass(light, sources, clear_transmittance(d))
    rho = patches.rho.copy()
    rho[glass.idx] = 0.0  # the clear panes pass light and reflect none
    lit = replace(patches, rho=rho)
    caster = caster_for(patches)
    dome = reinhart(d.sky_subdivision)  # Tregenza's 145 patches at MF:1
    K0, G = len(dome.solid_angles), len(sources)
    north = d.north_deg

    def bins(dirs):
        k = dome.patch_of(to_geographic(dirs, north))
        return np.where(k < 0, K0, k)

    progress(0.02)
    sky_w, geo, dn, up = _weather(d, dome, lambda f: progress(0.02 + 0.1 * f))
    progress(0.12)
    H = len(dn)
    mean, hour_bin = sun_bins(geo, up, SUN_BASIS_MF)
    S = len(mean)
    hours = np.flatnonzero(up)
    sun_w = np.zeros((S, H))
    sun_w[hour_bin[hours], hours] = dn[hours]
    B = K0 + 1 + 2 * S  # one source's block: sky and ground, sun reflected, sun direct
    # First hit on the room's patches, per source: the sky by bins, the beam per sun bin.
    room = room_sky_rays(lit, glass, caster, ROOM_RAYS, 0)
    progress(0.15)
    H_sky = _binned(room, G, bins, K0 + 1)  # (G, n, K0 + 1)
    H_sun = sun_on_room(lit, glass, caster, to_scene(mean, north), GLASS_SAMPLES, 0)
    first = np.concatenate([H_sky, H_sun], axis=2)  # (G, n, K0 + 1 + S)
    # Closed blinds: the panes glow (emission E), their first light F E.
    progress(0.2)
    E_closed, outside, outward = _closed(light, design, sources, glass)
    progress(0.22)
    flat = np.moveaxis(first, 0, 1).reshape(patches.n, -1)
    flat = np.concatenate([flat, np.asarray(op.F @ E_closed)], axis=1)
    got = flat + _reflections(light, rho, flat, lambda f: progress(0.22 + 0.33 * f))
    progress(0.55)
    lit_H, H_closed = got[:, :-G].reshape(patches.n, G, -1), got[:, -G:]
    grids = design_receivers(light, design)
    progress(0.7)
    at_patches = np.zeros((patches.n, G * B + G))
    for g in range(G):
        block = np.concatenate([lit_H[:, g], H_sun[g]], axis=1)
        block[:, K0 + 1 : K0 + 1 + S] -= H_sun[g]  # reflected only: the beam is direct
        at_patches[:, g * B : (g + 1) * B] = block
    at_patches[:, G * B :] = H_closed
    points_light, direct = None, np.zeros((G, 0, H), np.float32)
    at_points = None
    if grids is not None:
        samples = grids.samples  # a cylinder's ring of vertical samples, reduced below
        pts, nrm = samples.points, samples.normals
        rays = max(POINT_RAYS, int(op.info.get("rays", DEFAULT_RAYS)))
        seed = int(op.info.get("seed", 0)) + GRID_SEED_OFFSET
        Fp = receiver_factors(pts, nrm, caster, patches.n, rays, seed)
        progress(0.85)
        seen = receiver_sky_rays(pts, nrm, lit, glass, caster, GLASS_SAMPLES, 0)
        own = _binned(seen, G, bins, K0 + 1)  # the points' own view of the sky
        at_points = np.zeros((len(pts), G * B + G))
        for g in range(G):
            c = np.asarray(Fp @ (rho[:, None] * lit_H[:, g]))  # the room's radiosity
            c[:, : K0 + 1] += own[g]
            at_points[:, g * B : g * B + K0 + 1 + S] = c
        at_points[:, G * B :] = np.asarray(Fp @ (E_closed + rho[:, None] * H_closed))
        direct = np.zeros((G, len(pts), H), np.float32)
        if len(hours):
            exact = sun_on_points(pts, nrm, lit, glass, caster, to_scene(geo[hours], north))
            direct[:, :, hours] = exact * dn[hours]
        at_points = samples.values(at_points)
        direct = np.stack([samples.values(x) for x in direct]) if G else direct[:, : samples.size]
    progress(0.95)
    closed = _blinds(design, grids, direct, H)
    every = np.zeros((G * B + G, H), np.float32)
    blinds = np.zeros_like(every)
    over = np.zeros(G * B + G)
    over0 = np.concatenate([scaled_sky(dome, cie_overcast, 1.0), [d.ground_reflectance / math.pi]])
    for g in range(G):
        rows = slice(g * B, (g + 1) * B)
        every[rows] = np.concatenate([sky_w, sun_w, sun_w], axis=0)
        blinds[rows] = every[rows] * ~closed[g]
        every[G * B + g] = outside[g]
        blinds[G * B + g] = every[G * B + g] * closed[g]
        over[g * B : g * B + K0 + 1] = over0
    sun_cols = np.concatenate([np.arange(g * B + K0 + 1 + S, (g + 1) * B) for g in range(G)])
    columns = ClearColumns(every, blinds, over, sun_cols, closed, outward)
    patches_light = ClearLight(columns, at_patches)
    if at_points is not None:
        points_light = ClearLight(columns, at_points, direct)
    return ClearDesignLight(patches_light, points_light, time.process_time() - t0)
