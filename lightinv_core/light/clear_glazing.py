"""Clear glazing in a design: its daylight as fixed sky and sun columns (issue #30).

A clear skylight or window (``Source.glazing == "clear"``) passes the sky's luminance
pattern and the sun's beam by direction (``transport.clear_glazing``: Radiance's glass).
This version keeps clear glazing fixed (a clear source frees no variable), so its light
at the receivers is the same for every candidate: it is computed once per light model,
clear sources and daylight settings, and cached.

Its light at a receiver in hour t is ``sum_k c_k w_k(t)`` over K columns:

- the 145 Tregenza sky patches, w_k(t) the patch's Perez luminance of the hour (cd/m²,
  scaled to the file's diffuse horizontal illuminance), and the ground, w = rho_g E_gh / pi;
- the sun's light reflected in the room, on a Reinhart MF:2 basis of sun positions
  (about 6 degrees; a bin's direction is the mean of its hours' suns), w = the hour's
  direct normal illuminance in its bin's column, 0 in the others;
- the sun's direct light: at the patches on the same bins; at work-plane points traced
  at each hour's own sun (``direct``, as ``study.clear_year`` does: ASE reads it).

The first hit is ray-traced (``transport.daylight_coefficients``); the inter-reflections
use the design's light model: two exact bounces over the traced form factors F (the
clear panes black, as they pass light and reflect none) and the radiosity operator for
the rest. ``overcast`` (K,) is the CIE overcast sky per horizontal lux (sun columns 0):
the ``overcast`` and ``design`` scenarios light clear glazing with it.
"""

from __future__ import annotations

import math
import warnings
import weakref
from dataclasses import dataclass, field, replace

import numpy as np

from lightinv_core.design.model import Daylight, Design
from lightinv_core.kinds import GlazingKind
from lightinv_core.light.arrays import caster_for
from lightinv_core.light.grids import GRID_SEED_OFFSET, design_grids
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
from lightinv_core.transport.daylight_coefficients import _binned
from lightinv_core.transport.formfactors import DEFAULT_RAYS
from lightinv_core.transport.receivers import receiver_factors

SUN_BASIS_MF = 2
"""Reinhart subdivision of the sun positions (as ``study.clear_year``)."""
GLASS_SAMPLES = 6
"""Per side: glass samples per pane patch for the receivers' view and the sun's beam."""
ROOM_RAYS = 256
"""Rays per pane patch into the room (the first hit of the sky on the room)."""


def is_clear(source) -> bool:
    """Whether ``source`` is clear glazing (a daylit source whose glazing is clear)."""
    return getattr(source, "glazing", None) == GlazingKind.CLEAR


def clear_sources(design: Design) -> tuple:
    """The design's clear glazing sources, in order."""
    return tuple(s for s in design.sources if is_clear(s))


def clear_transmittance(daylight: Daylight) -> float:
    """The clear glass's normal transmittance: ``daylight.transmittance``, capped (with a
    warning) at what glass can pass (``MAX_CLEAR_TRANSMITTANCE``)."""
    t = float(daylight.transmittance)
    if t > MAX_CLEAR_TRANSMITTANCE:
        warnings.warn(
            f"clear glazing: glass passes at most {MAX_CLEAR_TRANSMITTANCE:.3f} at normal "
            f"incidence; the transmittance {t:g} is taken as {MAX_CLEAR_TRANSMITTANCE:.3f}",
            stacklevel=2,
        )
    return min(t, MAX_CLEAR_TRANSMITTANCE)


@dataclass(frozen=True, eq=False)
class ClearColumns:
    """The K columns of the clear glazing's light: ``every`` (K, H) weights for every
    hour of the weather file, ``overcast`` (K,) the CIE overcast sky per horizontal lux,
    ``sun_direct`` the slice of the sun's direct columns, ``sun_up`` (H,) the hours with
    sun traced."""

    every: np.ndarray
    overcast: np.ndarray
    sun_direct: slice
    sun_up: np.ndarray

    @property
    def count(self) -> int:
        """Number of columns K."""
        return self.every.shape[0]


@dataclass(frozen=True, eq=False)
class ClearLight:
    """The clear glazing's daylight at R receivers: ``coefficients`` (R, K) lux per unit
    of each column (``columns``), and ``direct`` (R_d, H) lux, the direct sun traced
    hour by hour at the last R_d receivers (work-plane points, whose sun columns are 0;
    None when none is traced)."""

    columns: ClearColumns
    coefficients: np.ndarray
    direct: np.ndarray | None = None
    _memo: dict = field(default_factory=dict, repr=False)

    def hours(self, idx, mask: np.ndarray, sun_only: bool = False) -> np.ndarray:
        """(R', T) lux at receivers idx in the hours of ``mask`` (the direct sun alone
        with ``sun_only``), remembered: every candidate reads the same."""
        key = (_index_key(idx), mask.tobytes(), sun_only)
        if key not in self._memo:
            if len(self._memo) >= 32:
                self._memo.clear()
            got = self.sun(idx, mask) if sun_only else self.lux(idx, mask)
            self._memo[key] = np.ascontiguousarray(got)
        return self._memo[key]

    def band(self, band, idx, mask: np.ndarray) -> np.ndarray:
        """(R',) an annual metric (``quantities.HourBand``) of this light alone."""
        key = (_index_key(idx), mask.tobytes(), band)
        if key not in self._memo:
            self._memo[key] = band.of_hours(self.hours(idx, mask, band.direct_sun))
        return self._memo[key]

    def overcast(self, idx=slice(None)) -> np.ndarray:
        """(R',) lux per horizontal exterior lux under the CIE overcast sky."""
        return self.coefficients[idx] @ self.columns.overcast

    def _traced(self, idx, hours) -> np.ndarray | None:
        """(R', h) the hour-by-hour direct sun at receivers idx (0 where not traced)."""
        if self.direct is None:
            return None
        R, off = len(self.coefficients), len(self.coefficients) - len(self.direct)
        rows = np.arange(R)[idx]
        out = np.zeros((len(rows), len(np.arange(self.columns.every.shape[1])[hours])))
        on = rows >= off
        out[on] = self.direct[rows[on] - off][:, hours]
        return out

    def sun(self, idx=slice(None), hours=slice(None)) -> np.ndarray:
        """(R', h) the direct sun alone (lux) in ``hours`` (blinds open: ASE)."""
        c = self.columns
        out = self.coefficients[idx][:, c.sun_direct] @ c.every[c.sun_direct][:, hours]
        traced = self._traced(idx, hours)
        return out if traced is None else out + traced

    def lux(self, idx=slice(None), hours=slice(None)) -> np.ndarray:
        """(R', h) the clear glazing's daylight (lux) in ``hours``, sun included."""
        out = self.coefficients[idx] @ self.columns.every[:, hours]
        traced = self._traced(idx, hours)
        return out if traced is None else out + traced


def stacked(patches: ClearLight, rows: np.ndarray, points: ClearLight | None) -> ClearLight:
    """The clear light at patches ``rows`` followed by the work-plane points (an
    optimisation level's receivers)."""
    coeffs = [patches.coefficients[rows]]
    direct = None
    if points is not None:
        coeffs.append(points.coefficients)
        direct = points.direct
    return ClearLight(patches.columns, np.concatenate(coeffs), direct)


def _index_key(idx) -> tuple:
    """A hashable key of receivers idx (a slice or an index array)."""
    if isinstance(idx, slice):
        return ("slice", idx.start, idx.stop, idx.step)
    a = np.asarray(idx)
    return ("rows", a.dtype.str, a.tobytes())


@dataclass(frozen=True, eq=False)
class ClearDesignLight:
    """The clear glazing of a design at its ``patches`` (n receivers) and its work-plane
    ``points`` (None without work planes), and the build's ``seconds``."""

    patches: ClearLight
    points: ClearLight | None
    seconds: float


_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def clear_light(light, design: Design) -> ClearDesignLight | None:
    """The clear glazing's light of ``design`` on ``light`` (a ``LightModel``), made once
    per operator, clear sources, work planes and daylight; None without clear glazing."""
    sources = clear_sources(design)
    if not sources:
        return None
    d = design.daylight
    key = (
        sources,
        tuple(design.workplanes),
        d.weather,
        d.north_deg,
        d.ground_reflectance,
        d.transmittance,
    )
    memo = _CACHE.setdefault(light.op, {})
    if key not in memo:
        memo.clear()  # one clear glazing at a time per operator
        memo[key] = _build(light, design, sources)
    return memo[key]


def _glass(light, sources, tau: float) -> Glass:
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


def _weather_columns(d: Daylight, dome):
    """(every (K0, H) sky and ground luminances, the sun's data) of the weather."""
    from lightinv_core.climate.sky_luminance import hourly_sky_luminance
    from lightinv_core.climate.transposition import sun_and_sky
    from lightinv_core.climate.weather import load_weather
    from lightinv_core.light.daylight_year import weather_path

    weather = load_weather(weather_path(d))
    sky = sun_and_sky(weather)
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


def _sun_bins(geo: np.ndarray, up: np.ndarray):
    """(S, 3) geographic mean sun direction of each MF:2 bin used, each hour's bin."""
    from lightinv_core.climate.skydome import reinhart

    b = np.full(len(geo), -1)
    b[up] = reinhart(SUN_BASIS_MF).patch_of(geo[up])
    used, inverse = np.unique(b[up], return_inverse=True)
    mean = np.zeros((len(used), 3))
    np.add.at(mean, inverse, geo[up])
    mean /= np.linalg.norm(mean, axis=1)[:, None]
    hour_bin = np.full(len(geo), -1)
    hour_bin[up] = inverse
    return mean, hour_bin


def _reflected(light, rho: np.ndarray, H: np.ndarray) -> np.ndarray:
    """(n, c) irradiance (lux) from the room's reflections of first-hit irradiance H
    (n, c): two exact bounces over F (reflectances ``rho``, the panes 0), then the
    radiosity operator for the rest."""
    F = light.op.F
    E1 = rho[:, None] * H
    H1 = np.asarray(F @ E1)
    H2 = np.asarray(F @ (rho[:, None] * H1))
    rest = np.asarray(light.op.illuminance(rho[:, None] * H2), dtype=float)
    return H1 + H2 + rest


def _build(light, design: Design, sources) -> ClearDesignLight:
    import time

    from lightinv_core.climate.sky_luminance import cie_overcast, scaled_sky
    from lightinv_core.climate.skydome import tregenza

    t0 = time.process_time()
    d = design.daylight
    patches, op = light.patches, light.op
    glass = _glass(light, sources, clear_transmittance(d))
    rho = patches.rho.copy()
    rho[glass.idx] = 0.0  # the clear panes pass light and reflect none
    lit = replace(patches, rho=rho)
    caster = caster_for(patches)
    dome = tregenza()
    K0 = len(dome.solid_angles)
    north = d.north_deg

    def bins(dirs):
        k = dome.patch_of(to_geographic(dirs, north))
        return np.where(k < 0, K0, k)

    sky_every, geo, dn, up = _weather_columns(d, dome)
    mean, hour_bin = _sun_bins(geo, up)
    S = len(mean)
    suns = to_scene(mean, north)
    # The columns: sky patches and ground (K0 + 1), sun reflected (S), sun direct (S).
    sun_w = np.zeros((S, len(dn)))
    hours = np.flatnonzero(up)
    sun_w[hour_bin[hours], hours] = dn[hours]
    every = np.concatenate([sky_every, sun_w, sun_w], axis=0)
    over = np.concatenate(
        [scaled_sky(dome, cie_overcast, 1.0), [d.ground_reflectance / math.pi], np.zeros(2 * S)]
    )
    columns = ClearColumns(every, over, slice(K0 + 1 + S, K0 + 1 + 2 * S), up)
    # First hit on the room's patches: the sky by bins, the sun's beam per sun bin.
    room = room_sky_rays(lit, glass, caster, ROOM_RAYS, 0)
    H_sky = _binned(room, len(glass.groups), bins, K0 + 1).sum(axis=0)
    H_sun = sun_on_room(lit, glass, caster, suns, GLASS_SAMPLES, 0).sum(axis=0)
    first = np.concatenate([H_sky, H_sun], axis=1)  # (n, K0 + 1 + S)
    H = first + _reflected(light, rho, first)
    at_patches = np.concatenate([H, H_sun], axis=1)
    # The patches' columns: sky and ground, sun reflected (its first hit is direct), direct.
    at_patches[:, K0 + 1 : K0 + 1 + S] -= H_sun
    patches_light = ClearLight(columns, at_patches)
    points_light = None
    if design.workplanes:
        grids = design_grids(light, design.workplanes)
        pts = grids.points
        nrm = np.broadcast_to([0.0, 0.0, 1.0], pts.shape)
        rays = int(op.info.get("rays", DEFAULT_RAYS))
        seed = int(op.info.get("seed", 0)) + GRID_SEED_OFFSET
        Fp = receiver_factors(pts, nrm, caster, patches.n, rays, seed)
        B = rho[:, None] * H  # the room's radiosity; nothing in it emits
        direct = receiver_sky_rays(pts, nrm, lit, glass, caster, GLASS_SAMPLES, 0)
        sky_direct = _binned(direct, len(glass.groups), bins, K0 + 1).sum(axis=0)
        c = np.asarray(Fp @ B)
        c[:, : K0 + 1] += sky_direct
        coeffs = np.concatenate([c, np.zeros((len(pts), S))], axis=1)
        sun_hours = np.zeros((len(pts), len(dn)), np.float32)
        if len(hours):
            exact = sun_on_points(pts, nrm, lit, glass, caster, to_scene(geo[hours], north))
            sun_hours[:, hours] = exact.sum(axis=0) * dn[hours]
        points_light = ClearLight(columns, coeffs, sun_hours)
    return ClearDesignLight(patches_light, points_light, time.process_time() - t0)
