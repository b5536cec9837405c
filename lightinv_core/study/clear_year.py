"""The weather year through clear glazing: hour by hour, sun and sky apart.

Each clear glazing group's light at the work plane in hour t is

    sum_k D_gk L_k(t)  +  S_g(t) E_dn(t)  +  R_g,b(t) E_dn(t)

with D the daylight coefficients of the sky patches and the ground
(``transport.daylight_coefficients``; the sky's patch luminances L_k(t) from the Perez
all-weather model scaled to the file's diffuse horizontal illuminance, the ground's
rho_g E_gh / pi), S the direct sun traced at the hour's own sun position, R the sun's
inter-reflected light for the sun-position bin b(t) of a Reinhart MF:2 subdivision
(577 patches, about 6 degrees) and E_dn the file's direct normal illuminance.

Operable blinds (IES LM-83, per glazing group): a group's blinds are closed in the
hours where its direct sun exceeds the rule (``climate.sun_metrics.blinds_closed``);
the group then passes ``BLIND_TRANSMITTANCE`` of its light as a diffusing glow (the
paper's diffusing glazing at that share of the glass's transmittance).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.skydome import SUN_BASIS_MF, sun_bins
from lightinv_core.design.model import Daylight
from lightinv_core.errors import LightInvError
from lightinv_core.light.daylight_year import daylight_year, weather_path
from lightinv_core.study.annual import glazing_groups
from lightinv_core.transport.annual import orientations
from lightinv_core.transport.clear_glazing import to_geographic, to_scene
from lightinv_core.transport.daylight_coefficients import ClearDaylight

_SKIES: dict = {}
"""The last weather's sun and sky patches (``clear_year``)."""

SKY_SUBDIVISIONS = (1, 2, 4)
"""Reinhart subdivisions of the sky a year may use (1: Tregenza)."""


BLIND_TRANSMITTANCE = 0.2
"""Share of a clear group's transmittance its closed blinds pass, as a diffusing glow
(LightInv's decision, docs/daylight.md: LM-83 leaves the blind's optics to the model)."""


@dataclass(frozen=True)
class ClearYear:
    """The year at q receivers, every hour of the file (T): ``open`` (G, q, T) each
    clear group's light with its blinds open, ``closed`` (G, q, T) with them closed,
    ``direct_sun`` (G, q, T) its direct sun alone (no reflections), ``other`` (q, T)
    the diffusing glazing's light, ``sun_up`` (T,) the hours the sun is above the
    horizon with direct light; ``occupied`` (T,) the schedule's mask; ``year`` the
    ``DaylightYear`` of the weather (times, site, notes)."""

    groups: tuple[str, ...]
    open: np.ndarray
    closed: np.ndarray
    direct_sun: np.ndarray
    other: np.ndarray
    sun_up: np.ndarray
    occupied: np.ndarray
    year: object
    weather: object
    north_deg: float
    horizontal_openings: bool

    def total(self, blinds: np.ndarray | None = None) -> np.ndarray:
        """(q, T) daylight with each group's blinds ``blinds`` (G, T) closed where True
        (default: all open)."""
        lux = self.other + self.open.sum(axis=0)
        if blinds is not None:
            swap = (self.closed - self.open) * blinds[:, None, :]
            lux = lux + swap.sum(axis=0)
        return lux


def _sky_vectors(weather, sky, daylight: Daylight, mf: int):
    """(T, K) patch luminances of the Reinhart MF:``mf`` sky (1: Tregenza's 145
    patches), (T,) ground luminance, the dome."""
    from lightinv_core.climate.sky_luminance import hourly_sky_luminance
    from lightinv_core.climate.skydome import reinhart

    dome = reinhart(mf)
    L = hourly_sky_luminance(
        dome, weather.dni, weather.dhi, weather.dh_lux, sky.zenith, sky.azimuth, sky.dni_extra
    )
    ground = daylight.ground_reflectance * np.asarray(weather.gh_lux, dtype=float) / math.pi
    return np.asarray(L, dtype=float), ground, dome


def _suns(sky, weather, north_deg: float):
    """Scene sun directions (T, 3) and the mask of hours with sun to trace."""
    zen, az = np.radians(sky.zenith), np.radians(sky.azimuth)
    geo = np.stack([np.sin(zen) * np.sin(az), np.sin(zen) * np.cos(az), np.cos(zen)], axis=1)
    up = (sky.zenith < 90.0) & (np.asarray(weather.dn_lux, dtype=float) > 0)
    return to_scene(geo, north_deg), geo, up


def _sun_basis(geo: np.ndarray, up: np.ndarray, north_deg: float):
    """(S, 3) scene directions of the sun bins used, and each hour's bin (-1: none)."""
    mean, hour_bin = sun_bins(geo, up, SUN_BASIS_MF)
    return to_scene(mean, north_deg), hour_bin


HORIZONTAL_TILT_DEG = 10.0
"""Glazing whose outward normal is within this of the zenith is a horizontal opening
(EN 17037's rooflights); steeper glazing is vertical or inclined."""


def _horizontal(clear: ClearDaylight, diffusing_tilts) -> bool:
    """Whether every pane (clear and diffusing) is a horizontal opening."""
    normals = clear.lit.normal[clear.glass.idx]  # into the room: down for a rooflight
    tilts = np.degrees(np.arccos(np.clip(-normals[:, 2], -1, 1)))
    return bool(np.all(tilts < HORIZONTAL_TILT_DEG)) and all(
        t < HORIZONTAL_TILT_DEG for t in diffusing_tilts
    )


def clear_year(
    clear: ClearDaylight,
    daylight: Daylight,
    diffusing_lux: np.ndarray | None = None,
    blind_transmittance: float = BLIND_TRANSMITTANCE,
    diffusing_tilts: tuple[float, ...] = (),
    sky_mf: int = 1,
) -> ClearYear:
    """The year of ``daylight``'s weather through the clear glazing of ``clear`` at its
    receivers; ``diffusing_lux`` (q, T) the diffusing glazing's light each hour, from
    panes tilted ``diffusing_tilts`` (deg from the zenith); the sky in Reinhart MF:``sky_mf``
    patches (1: Tregenza's 145, 2: 577, 4: 2,305)."""
    if sky_mf not in SKY_SUBDIVISIONS:
        raise LightInvError(
            f"sky subdivision must be one of {', '.join(map(str, SKY_SUBDIVISIONS))}, got {sky_mf}"
        )
    from lightinv_core.climate.transposition import sun_and_sky
    from lightinv_core.climate.weather import load_weather

    weather = load_weather(weather_path(daylight))
    # The sun and the sky's patches are the weather's alone: a study's work plane and
    # view points read the same ones (the weather is one object while its file is
    # unchanged, so it keys them).
    key = (weather, sky_mf, daylight.ground_reflectance)
    if key not in _SKIES:
        sky = sun_and_sky(weather)
        _SKIES.clear()
        _SKIES[key] = (sky, _sky_vectors(weather, sky, daylight, sky_mf))
    sky, (L, ground, dome) = _SKIES[key]
    north = daylight.north_deg
    K = len(dome.solid_angles)

    def bins(d):
        k = dome.patch_of(to_geographic(d, north))
        return np.where(k < 0, K, k)

    D = clear.sky(bins, K + 1)  # (G, q, K + 1)
    vec = np.concatenate([L, ground[:, None]], axis=1)  # (T, K + 1)
    open_ = D @ vec.T  # (G, q, T)
    suns, geo, up = _suns(sky, weather, north)
    dn = np.where(up, np.asarray(weather.dn_lux, dtype=float), 0.0)
    direct = np.zeros_like(open_)
    hours = np.nonzero(up)[0]
    direct[:, :, hours] = clear.sun_direct(suns[hours]) * dn[hours]
    basis, hour_bin = _sun_basis(geo, up, north)
    reflected = clear.sun_reflected(basis)  # (G, q, S)
    open_[:, :, hours] += reflected[:, :, hour_bin[hours]] * dn[hours] + direct[:, :, hours]
    closed = _closed(clear, daylight, blind_transmittance)
    year_groups = glazing_groups(closed[1], daylight)
    year = daylight_year(year_groups, daylight)
    closed_lux = np.stack([c @ year.every for c in closed[0]]) if len(closed[0]) else open_ * 0
    other = np.zeros(open_.shape[1:]) if diffusing_lux is None else diffusing_lux
    return ClearYear(
        clear.glass.groups,
        open_,
        closed_lux,
        direct,
        other,
        up,
        np.asarray(year.occupied),
        year,
        weather,
        north,
        _horizontal(clear, diffusing_tilts),
    )


def _closed(clear: ClearDaylight, daylight: Daylight, share: float):
    """Per clear group, (q, O) lux per exterior lux on each of the year's orientations
    when its blinds are closed (the group's panes of that orientation glowing as
    diffusing glass of ``share`` x their transmittance), and the orientations."""
    tau = dict(zip(clear.glass.groups, _group_tau(clear), strict=True))
    orients = orientations(clear.lit, {g: share * t for g, t in tau.items()})
    G, n_or = len(clear.glass.groups), len(orients)
    E = np.zeros((clear.lit.n, G * n_or))
    for o, orient in enumerate(orients):
        for pane in orient.panes:
            g = clear.glass.groups.index(pane.group)
            E[pane.idx, g * n_or + o] = pane.transmittance  # lm/m² per lux outside
    lux = clear.emitted(E).reshape(len(clear.points), G, n_or)
    return [lux[:, g, :] for g in range(G)], orients


def _group_tau(clear: ClearDaylight) -> list[float]:
    g = clear.glass
    return [float(g.transmittance[g.group == i].mean()) for i in range(len(g.groups))]


class Receivers:
    """Points and normals (m, 3) as ``orientation_coefficients`` reads a grid."""

    def __init__(self, points: np.ndarray, normals: np.ndarray) -> None:
        self.points, self.normals = points, normals
