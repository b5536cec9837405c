"""Clear glazing: the sky and the sun seen through glass, direction kept.

A clear pane passes the light arriving from outside in the direction it came, weighted
by the glass's angular transmittance; unlike diffusing glazing (``transport.glazing``)
it shows the sky's luminance pattern and lets the sun's beam draw a patch of light.

The angular transmittance is Radiance's ``glass`` material: one uncoated pane of
refractive index 1.52 whose internal transmissivity ``tn`` is chosen so that the
transmittance at normal incidence is the pane's visible transmittance; at incidence
theta each polarisation passes (1 - r)² tn^(1/cos theta_t) / (1 - r² tn^(2/cos theta_t))
(Fresnel reflectance r, refraction angle theta_t, multiple reflections inside the
pane), averaged over the two.

The rays here are gathered once per scene and read by ``transport.daylight_coefficients``
two ways: binned by sky patch (daylight coefficients, the year) or weighted by a sky's
luminance in their own direction (a point in time). Directions are in the scene's
frame; ``to_geographic`` turns them to compass axes (x east, y north, z up).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.raycast import RayCaster, patch_points, sample_rays

REFRACTIVE_INDEX = 1.52
"""Of float glass, as Radiance's ``glass`` takes it."""

OUTSIDE_M = 1e4
"""Metres; an obstruction farther from the glass than this is no obstruction."""

SAMPLE_BUDGET = 4096
"""Glass samples per receiver at most (memory: the rays are kept, 30 bytes each)."""

_CHUNK = 2**18
"""Rays traced at a time (memory: a few tens of MB)."""


def transmissivity(transmittance: float) -> float:
    """The pane's internal transmissivity giving normal-incidence ``transmittance``
    (Radiance's conversion for n = 1.52; 0 for 0)."""
    t = float(transmittance)
    if not 0.0 <= t <= 1.0:
        raise LightInvError(f"glass transmittance must be from 0 to 1, got {t}")
    if t == 0.0:
        return 0.0
    tn = (math.sqrt(0.8402528435 + 0.0072522239 * t * t) - 0.9166530661) / 0.0036261119 / t
    return min(tn, 1.0)


def _transmissivities(t: np.ndarray) -> np.ndarray:
    """``transmissivity`` of an array of transmittances (already in range)."""
    safe = np.where(t > 0, t, 1.0)
    tn = (np.sqrt(0.8402528435 + 0.0072522239 * safe * safe) - 0.9166530661) / 0.0036261119 / safe
    return np.where(t > 0, np.minimum(tn, 1.0), 0.0)


MAX_CLEAR_TRANSMITTANCE = 0.9184
"""The normal-incidence transmittance of lossless glass of n = 1.52, (1 - r) / (1 + r):
clear glass cannot pass more (Radiance caps it alike)."""


def clear_glass_warnings(glazing: dict[str, float]) -> list[str]:
    """Warnings for clear glazing groups asked to pass more than glass can."""
    return [
        f"clear glazing {g!r}: glass passes at most {MAX_CLEAR_TRANSMITTANCE:.3f} at normal "
        f"incidence; its {t:g} is taken as {MAX_CLEAR_TRANSMITTANCE:.3f}"
        for g, t in glazing.items()
        if t > MAX_CLEAR_TRANSMITTANCE
    ]


def glass_transmittance(transmittance, cos_incidence) -> np.ndarray:
    """Transmittance of clear glass of normal ``transmittance`` at incidence angles of
    cosine ``cos_incidence`` (either sign: the pane is symmetric); broadcasts."""
    t = np.asarray(transmittance, dtype=float)
    if np.any((t < 0) | (t > 1)):
        raise LightInvError(f"glass transmittance must be from 0 to 1, got {t.min()}..{t.max()}")
    tn = _transmissivities(t)
    ci = np.clip(np.abs(np.asarray(cos_incidence, dtype=float)), 1e-9, 1.0)
    n = REFRACTIVE_INDEX
    ct = np.sqrt(1.0 - (1.0 - ci * ci) / (n * n))
    path = np.power(np.maximum(tn, 1e-300), 1.0 / ct) * (tn > 0)
    total = 0.0
    for r in (
        ((ci - n * ct) / (ci + n * ct)) ** 2,  # s-polarised
        ((ct - n * ci) / (ct + n * ci)) ** 2,  # p-polarised
    ):
        total = total + (1.0 - r) ** 2 * path / (1.0 - r * r * path * path)
    return 0.5 * total


def to_geographic(directions: np.ndarray, north_deg: float) -> np.ndarray:
    """Scene directions (m, 3) in compass axes (x east, y north, z up), the scene's +y
    pointing ``north_deg`` clockwise from north."""
    a = math.radians(north_deg)
    c, s = math.cos(a), math.sin(a)
    d = np.asarray(directions, dtype=float)
    # A bearing b from +y (towards +x) is compass azimuth b + north.
    return np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1], d[:, 2]], axis=1)


def to_scene(directions: np.ndarray, north_deg: float) -> np.ndarray:
    """Compass-axis directions (m, 3) in the scene's frame (``to_geographic``'s inverse)."""
    return to_geographic(directions, -north_deg)


@dataclass(frozen=True)
class Glass:
    """The clear panes of a scene: patch ids ``idx``, each one's normal-incidence
    ``transmittance`` and ``group`` (an index into ``groups``, the glazing group names)."""

    idx: np.ndarray
    transmittance: np.ndarray
    group: np.ndarray
    groups: tuple[str, ...]

    @property
    def count(self) -> int:
        """Number of glass patches."""
        return len(self.idx)


def clear_glass(patches: Patches, glazing: dict[str, float]) -> Glass:
    """The ``glazing`` groups (name -> normal transmittance 0..1) as clear panes."""
    idx, tau, grp = [], [], []
    for g, (name, t) in enumerate(glazing.items()):
        transmissivity(t)  # checks the range
        ids = patches.group_index(name)
        idx.append(ids)
        tau.append(np.full(len(ids), float(t)))
        grp.append(np.full(len(ids), g))
    if not idx:
        return Glass(np.zeros(0, int), np.zeros(0), np.zeros(0, int), ())
    return Glass(np.concatenate(idx), np.concatenate(tau), np.concatenate(grp), tuple(glazing))


@dataclass(frozen=True)
class SkyRays:
    """Rays that reach the sky (or the ground) through clear glass: ``target`` the
    receiver (a point or a room patch) each one lights, ``direction`` (m, 3) unit,
    scene frame, pointing out to the sky, ``weight`` (m,) the illuminance (lux) at the
    target per cd/m² of sky luminance in that direction, ``group`` the glazing group."""

    target: np.ndarray
    direction: np.ndarray
    weight: np.ndarray
    group: np.ndarray
    targets: int


def _unobstructed(caster: RayCaster, start: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """Whether nothing lies beyond the glass from ``start`` (just outside it) outwards."""
    free = np.empty(len(start), bool)
    for i in range(0, len(start), _CHUNK):
        sl = slice(i, i + _CHUNK)
        free[sl] = ~caster.occluded(start[sl], direction[sl], np.full(len(start[sl]), OUTSIDE_M))
    return free


def receiver_sky_rays(
    points: np.ndarray,
    normals: np.ndarray,
    patches: Patches,
    glass: Glass,
    caster: RayCaster,
    per_side: int = 4,
    seed: int = 0,
) -> SkyRays:
    """Rays from receiver points (q, 3) facing ``normals`` to the sky through the glass.

    The glass is sampled by area (``per_side``² stratified points per glass patch, fewer
    when the glass has many patches: at most ``SAMPLE_BUDGET`` per receiver, at least
    2 x 2 per patch), so
    a ray to a point x on pane j stands for the solid angle A_j cos(theta_j) / (s r²);
    its weight is that times the glass's transmittance at theta_j and the cosine at
    the receiver. A ray counts when nothing in the room hides x from the receiver
    and nothing outside hides the sky beyond x."""
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    nrm = np.asarray(normals, dtype=float).reshape(-1, 3)
    nrm = nrm / np.linalg.norm(nrm, axis=1)[:, None]
    per_side = max(2, min(per_side, math.isqrt(SAMPLE_BUDGET // max(glass.count, 1))))
    s = per_side * per_side
    if glass.count == 0 or len(pts) == 0:
        return SkyRays(np.zeros(0, int), np.zeros((0, 3)), np.zeros(0), np.zeros(0, int), len(pts))
    rng = np.random.default_rng(seed)
    x = patch_points(patches, glass.idx, s, rng).reshape(-1, 3)  # (J s, 3)
    jn = np.repeat(patches.normal[glass.idx], s, axis=0)  # into the room
    ja = np.repeat(patches.area[glass.idx] / s, s)
    jt = np.repeat(glass.transmittance, s)
    jg = np.repeat(glass.group, s)
    off = caster.offset
    out_t, out_d, out_w, out_g = [], [], [], []
    block = max(1, _CHUNK // len(x))
    for start in range(0, len(pts), block):
        p = pts[start : start + block]
        pn = nrm[start : start + block]
        v = x[None] - p[:, None]  # (b, Js, 3)
        r = np.linalg.norm(v, axis=2)
        d = v / np.maximum(r, 1e-12)[..., None]
        cos_r = np.einsum("bkc,bc->bk", d, pn)
        cos_g = -np.einsum("bkc,kc->bk", d, jn)
        ok = (cos_r > 0) & (cos_g > 0) & (r > 2 * off)
        bi, ki = np.nonzero(ok)
        if not len(bi):
            continue
        dd = d[bi, ki]
        origin = p[bi] + off * pn[bi]
        # Embree may report the pane itself as in the way when the segment ends
        # within a few float32 ulps of it (seen at 4 m): stop 1e-4 of the way short.
        length = r[bi, ki] * (1 - 1e-4) - 2 * off
        seen = ~caster.occluded(origin, dd, length)
        bi, ki, dd = bi[seen], ki[seen], dd[seen]
        free = _unobstructed(caster, x[ki] - off * jn[ki], dd)
        bi, ki, dd = bi[free], ki[free], dd[free]
        cg = cos_g[bi, ki]
        w = ja[ki] * cg / r[bi, ki] ** 2 * cos_r[bi, ki] * glass_transmittance(jt[ki], cg)
        out_t.append((start + bi).astype(np.int32))
        out_d.append(dd.astype(np.float32))
        out_w.append(w)
        out_g.append(jg[ki].astype(np.int16))
    return _rays(out_t, out_d, out_w, out_g, len(pts))


def room_sky_rays(
    patches: Patches, glass: Glass, caster: RayCaster, rays: int = 256, seed: int = 0
) -> SkyRays:
    """Rays entering the room through the glass and the room patch each first lights.

    ``rays`` per glass patch leave it cosine-weighted into the room; each stands for
    pi A_j / rays of (area x projected solid angle) of the sky in the opposite
    direction, so its weight on the room patch i it hits, per cd/m² of that sky, is
    pi A_j T(theta) / (rays A_i) lux."""
    if glass.count == 0:
        return SkyRays(np.zeros(0, int), np.zeros((0, 3)), np.zeros(0), np.zeros(0, int), patches.n)
    rng = np.random.default_rng(seed)
    origin, d = sample_rays(patches, glass.idx, rays, rng, caster.offset)
    d = d.astype(float)
    jn = np.repeat(patches.normal[glass.idx], rays, axis=0)
    ja = np.repeat(patches.area[glass.idx], rays)
    jt = np.repeat(glass.transmittance, rays)
    jg = np.repeat(glass.group, rays)
    hit = np.concatenate(
        [
            caster.hit_patches(origin[i : i + _CHUNK], d[i : i + _CHUNK])
            for i in range(0, len(d), _CHUNK)
        ]
    )
    sky = -d
    free = (hit >= 0) & _unobstructed(caster, origin - 2 * caster.offset * jn, sky)
    cos_g = np.einsum("ij,ij->i", d, jn)
    w = np.pi * ja * glass_transmittance(jt, cos_g) / (rays * patches.area[np.maximum(hit, 0)])
    return SkyRays(hit[free], sky[free], w[free], jg[free], patches.n)


def _rays(t, d, w, g, targets: int) -> SkyRays:
    if not t:
        return SkyRays(np.zeros(0, int), np.zeros((0, 3)), np.zeros(0), np.zeros(0, int), targets)
    return SkyRays(
        np.concatenate(t), np.concatenate(d), np.concatenate(w), np.concatenate(g), targets
    )


def exit_pane(
    origins: np.ndarray,
    directions: np.ndarray,
    patches: Patches,
    glass: Glass,
    caster: RayCaster,
) -> tuple[np.ndarray, np.ndarray]:
    """For rays from inside the room (origins (m, 3), unit ``directions`` (m, 3)): the
    glass slot (index into ``glass.idx``) each leaves through with nothing beyond it
    outside, else -1; and the cosine of its incidence on that pane."""
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    d = np.asarray(directions, dtype=float).reshape(-1, 3)
    slot = np.full(patches.n, -1)
    slot[glass.idx] = np.arange(glass.count)
    out = np.full(len(o), -1)
    cos = np.zeros(len(o))
    for i in range(0, len(o), _CHUNK):
        sl = slice(i, i + _CHUNK)
        hit = caster.hit_patches(o[sl], d[sl])
        j = np.where(hit >= 0, slot[np.maximum(hit, 0)], -1)
        k = np.nonzero(j >= 0)[0]
        if not len(k):
            continue
        jj = j[k]
        jn = patches.normal[glass.idx[jj]]
        ok, dk = o[sl][k], d[sl][k]
        # The pane's plane, reached along d: where the ray leaves the room.
        dn = np.einsum("ij,ij->i", dk, jn)
        dist = np.einsum("ij,ij->i", patches.centroid[glass.idx[jj]] - ok, jn) / dn
        free = _unobstructed(caster, ok + dk * dist[:, None] - caster.offset * jn, dk)
        out[i + k[free]] = jj[free]
        cos[i + k[free]] = -dn[free]
    return out, cos


def sun_on_points(
    points: np.ndarray,
    normals: np.ndarray,
    patches: Patches,
    glass: Glass,
    caster: RayCaster,
    sun: np.ndarray,
) -> np.ndarray:
    """Direct sun (lux per lux of direct normal illuminance) at receivers (q, 3) facing
    ``normals``, for unit scene sun directions ``sun`` (T, 3): T(theta) cos at the
    receiver where the ray to the sun leaves through a clear pane and meets nothing
    outside; (G, q, T) by glazing group."""
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    nrm = np.asarray(normals, dtype=float).reshape(-1, 3)
    nrm = nrm / np.linalg.norm(nrm, axis=1)[:, None]
    sun = np.asarray(sun, dtype=float).reshape(-1, 3)
    out = np.zeros((len(glass.groups), len(pts), len(sun)))
    if glass.count == 0:
        return out
    cos_r = nrm @ sun.T  # (q, T)
    qi, ti = np.nonzero((cos_r > 0) & (sun[:, 2] > 0)[None])
    j, cos_g = exit_pane(pts[qi] + caster.offset * nrm[qi], sun[ti], patches, glass, caster)
    ok = j >= 0
    qi, ti, j, cos_g = qi[ok], ti[ok], j[ok], cos_g[ok]
    tau = glass_transmittance(glass.transmittance[j], cos_g)
    np.add.at(out, (glass.group[j], qi, ti), tau * cos_r[qi, ti])
    return out


def sun_on_room(
    patches: Patches,
    glass: Glass,
    caster: RayCaster,
    sun: np.ndarray,
    per_side: int = 4,
    seed: int = 0,
) -> np.ndarray:
    """Irradiance of the sun's beam first landing on each room patch (lux per lux of
    direct normal illuminance), (G, n, S), for unit scene sun directions ``sun`` (S, 3):
    the beam through ``per_side``² stratified points of each glass patch, each carrying
    A_j cos(theta_j) T(theta_j) / s lumens per lux, deposited on the patch it hits."""
    sun = np.asarray(sun, dtype=float).reshape(-1, 3)
    G = len(glass.groups)
    out = np.zeros((G, patches.n, len(sun)))
    if glass.count == 0 or not len(sun):
        return out
    s = per_side * per_side
    rng = np.random.default_rng(seed)
    x = patch_points(patches, glass.idx, s, rng).reshape(-1, 3)
    jn = np.repeat(patches.normal[glass.idx], s, axis=0)
    ja = np.repeat(patches.area[glass.idx] / s, s)
    jt = np.repeat(glass.transmittance, s)
    jg = np.repeat(glass.group, s)
    off = caster.offset
    for k, sd in enumerate(sun):
        cos_g = -(jn @ sd)  # the beam travels along -sd into the room
        live = np.nonzero((cos_g > 0) & (sd[2] > 0))[0]
        if not len(live):
            continue
        into = np.broadcast_to(-sd, (len(live), 3))
        free = _unobstructed(caster, x[live] - off * jn[live], np.broadcast_to(sd, (len(live), 3)))
        live, into = live[free], into[free]
        hit = caster.hit_patches(x[live] + off * jn[live], into)
        ok = hit >= 0
        live, hit = live[ok], hit[ok]
        flux = ja[live] * cos_g[live] * glass_transmittance(jt[live], cos_g[live])
        np.add.at(out, (jg[live], hit, k), flux / patches.area[hit])
    return out
