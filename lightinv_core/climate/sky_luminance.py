"""Sky luminance distributions: CIE overcast, CIE clear (type 12), Perez all-weather.

Directions are unit vectors (m, 3) in the geographic frame of ``skydome`` (x east,
y north, z up; azimuth the compass bearing). Relative luminances are 0 at and below
the horizon. The absolute scale of a sky on a dome comes from the diffuse horizontal
illuminance: patch luminances ``L_k`` (cd/m2, the distribution averaged over the
patch's subsamples) are scaled so that

    sum_k L_k * P_k = E_dh,     P_k = integral over patch k of sin(alt) d omega,

the illuminance the patches give on an unobstructed horizontal plane.

References: CIE S 011/E:2003 (ISO 15469:2004) for the CIE skies; Perez, Ineichen,
Seals, Michalsky and Stewart 1990 (Solar Energy 44(5)) for the sky clearness and
brightness; Perez, Seals and Michalsky 1993 (Solar Energy 50(3), Table 1, Eqs. 6-8)
for the all-weather model, its coefficients as transcribed in Radiance's
``src/gen/gendaymtx.c`` (I. Ashdown) and ``gendaylit.c``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from lightinv_core.climate.skydome import SkyDome, unit_directions

_HORIZON_SIN = 0.01
"""The gradation exp(b / cos Z) is evaluated at cos Z >= 0.01 (as Radiance's
perezlum.cal), so it stays finite at the horizon."""

_KAPPA = 1.041
"""Perez 1990's constant in the sky clearness (Z in radians)."""

_EPSILON_BOUNDS = np.array([1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200])
"""Upper bounds of the first seven sky clearness bins (Perez 1990, Table 1)."""

_EPSILON_RANGE = (1.0, 12.0)
_DELTA_RANGE = (0.01, 0.6)
"""Clearness and brightness are clamped to these ranges before the luminance model,
as gendaylit does (its check_parametrization)."""

_MAX_SUN_ZENITH = 96.0
"""Hours with the sun more than 6 degrees below the horizon (civil twilight) have no
sky; between 90 and 96 degrees the model is evaluated with the sun on the horizon."""

# Perez, Seals and Michalsky 1993, Table 1: per clearness bin, the rows a, b, c, d, e
# and in each row x1..x4 of x = x1 + x2 Z + delta (x3 + x4 Z).
_PEREZ_1993 = np.array(
    [
        [
            [1.3525, -0.2576, -0.2690, -1.4366],
            [-0.7670, 0.0007, 1.2734, -0.1233],
            [2.8000, 0.6004, 1.2375, 1.0000],
            [1.8734, 0.6297, 0.9738, 0.2809],
            [0.0356, -0.1246, -0.5718, 0.9938],
        ],
        [
            [-1.2219, -0.7730, 1.4148, 1.1016],
            [-0.2054, 0.0367, -3.9128, 0.9156],
            [6.9750, 0.1774, 6.4477, -0.1239],
            [-1.5798, -0.5081, -1.7812, 0.1080],
            [0.2624, 0.0672, -0.2190, -0.4285],
        ],
        [
            [-1.1000, -0.2515, 0.8952, 0.0156],
            [0.2782, -0.1812, -4.5000, 1.1766],
            [24.7219, -13.0812, -37.7000, 34.8438],
            [-5.0000, 1.5218, 3.9229, -2.6204],
            [-0.0156, 0.1597, 0.4199, -0.5562],
        ],
        [
            [-0.5484, -0.6654, -0.2672, 0.7117],
            [0.7234, -0.6219, -5.6812, 2.6297],
            [33.3389, -18.3000, -62.2500, 52.0781],
            [-3.5000, 0.0016, 1.1477, 0.1062],
            [0.4659, -0.3296, -0.0876, -0.0329],
        ],
        [
            [-0.6000, -0.3566, -2.5000, 2.3250],
            [0.2937, 0.0496, -5.6812, 1.8415],
            [21.0000, -4.7656, -21.5906, 7.2492],
            [-3.5000, -0.1554, 1.4062, 0.3988],
            [0.0032, 0.0766, -0.0656, -0.1294],
        ],
        [
            [-1.0156, -0.3670, 1.0078, 1.4051],
            [0.2875, -0.5328, -3.8500, 3.3750],
            [14.0000, -0.9999, -7.1406, 7.5469],
            [-3.4000, -0.1078, -1.0750, 1.5702],
            [-0.0672, 0.4016, 0.3017, -0.4844],
        ],
        [
            [-1.0000, 0.0211, 0.5025, -0.5119],
            [-0.3000, 0.1922, 0.7023, -1.6317],
            [19.0000, -5.0000, 1.2438, -1.9094],
            [-4.0000, 0.0250, 0.3844, 0.2656],
            [1.0468, -0.3788, -2.4517, 1.4656],
        ],
        [
            [-1.0500, 0.0289, 0.4260, 0.3590],
            [-0.3250, 0.1156, 0.7781, 0.0025],
            [31.0625, -14.5000, -46.1148, 55.3750],
            [-7.2312, 0.4050, 13.3500, 0.6234],
            [1.5000, -0.6426, 1.8564, 0.5636],
        ],
    ]
)


def sun_direction(zenith_deg: np.ndarray, azimuth_deg: np.ndarray) -> np.ndarray:
    """(T, 3) unit vectors towards the sun from its zenith angle and compass azimuth
    (degrees, pvlib's convention)."""
    return unit_directions(90.0 - np.asarray(zenith_deg, float), np.asarray(azimuth_deg, float))


def cie_overcast(directions: np.ndarray) -> np.ndarray:
    """(m,) CIE standard overcast sky (Moon and Spencer; CIE S 011/E:2003 gives it
    beside its 15 general skies, whose type 1 approximates it) relative to the zenith:
    (1 + 2 sin(alt)) / 3; 0 below the horizon."""
    z = np.asarray(directions, float)[..., 2]
    return np.where(z > 0.0, (1.0 + 2.0 * np.clip(z, 0.0, 1.0)) / 3.0, 0.0)


def _cie_gradation(cos_z: np.ndarray, a: float, b: float) -> np.ndarray:
    safe = np.maximum(cos_z, 1e-12)
    return np.where(cos_z > 0.0, 1.0 + a * np.exp(b / safe), 1.0)


def _cie_indicatrix(chi: np.ndarray, c: float, d: float, e: float) -> np.ndarray:
    return 1.0 + c * (np.exp(d * chi) - np.exp(d * np.pi / 2)) + e * np.cos(chi) ** 2


def cie_clear(directions: np.ndarray, sun: np.ndarray) -> np.ndarray:
    """(m,) CIE standard general sky type 12 (clear, low illuminance turbidity;
    gradation group 5, indicatrix group 6 of CIE S 011/E:2003) relative to the zenith
    luminance, for the unit sun vector ``sun`` (3,); 0 below the horizon.

        L / L_z = phi(Z) f(chi) / (phi(0) f(Z_s)),
        phi(Z) = 1 + a exp(b / cos Z),  f(chi) = 1 + c (exp(d chi) - exp(d pi/2))
                 + e cos^2 chi,  (a, b, c, d, e) = (-1, -0.32, 10, -3, 0.45)."""
    a, b, c, d, e = -1.0, -0.32, 10.0, -3.0, 0.45
    dirs = np.asarray(directions, float)
    s = np.asarray(sun, float).reshape(3)
    chi = np.arccos(np.clip(dirs @ s, -1.0, 1.0))
    sun_z = np.arccos(np.clip(s[2], -1.0, 1.0))
    zenith = _cie_gradation(np.array(1.0), a, b) * _cie_indicatrix(sun_z, c, d, e)
    rel = _cie_gradation(dirs[..., 2], a, b) * _cie_indicatrix(chi, c, d, e) / zenith
    return np.where(dirs[..., 2] > 0.0, rel, 0.0)


def air_mass(sun_zenith_deg: np.ndarray) -> np.ndarray:
    """Relative optical air mass (Kasten 1966, as Perez 1990 and gendaylit use), the
    zenith angle capped at 90 degrees."""
    z = np.clip(np.asarray(sun_zenith_deg, float), 0.0, 90.0)
    return 1.0 / (np.cos(np.radians(z)) + 0.15 * (93.885 - z) ** -1.253)


def perez_parameters(
    dhi: np.ndarray, dni: np.ndarray, sun_zenith_deg: np.ndarray, dni_extra: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Sky clearness epsilon and brightness delta per hour (Perez 1990) from the
    diffuse horizontal and direct normal irradiance and the extraterrestrial normal
    irradiance (W/m2); Z is the sun zenith angle in radians, capped at pi/2.

        epsilon = ((dhi + dni) / dhi + 1.041 Z^3) / (1 + 1.041 Z^3)
        delta = dhi * air_mass(Z) / dni_extra

    Not clamped (the luminance model clamps); epsilon = 1 and delta = 0 where
    dhi <= 0, so the outputs are finite."""
    dhi = np.asarray(dhi, float)
    dni = np.maximum(np.asarray(dni, float), 0.0)
    z = np.radians(np.clip(np.asarray(sun_zenith_deg, float), 0.0, 90.0))
    k = _KAPPA * z**3
    ok = dhi > 0.0
    safe = np.where(ok, dhi, 1.0)
    epsilon = np.where(ok, ((safe + dni) / safe + k) / (1.0 + k), 1.0)
    extra = np.asarray(dni_extra, float)
    delta = np.where(
        ok & (extra > 0), safe * air_mass(sun_zenith_deg) / np.where(extra > 0, extra, 1.0), 0.0
    )
    return epsilon, delta


def clearness_bin(epsilon: np.ndarray) -> np.ndarray:
    """Perez clearness bin 0..7 (bin 1..8 of the paper) of each epsilon."""
    return np.searchsorted(_EPSILON_BOUNDS, np.asarray(epsilon, float), side="right")


def perez_coefficients(
    sun_zenith_deg: np.ndarray, epsilon: np.ndarray, delta: np.ndarray
) -> np.ndarray:
    """(T, 5) the all-weather model's a, b, c, d, e per hour (Perez 1993, Eqs. 6-8).

    epsilon and delta are first clamped to [1, 12] and [0.01, 0.6], and delta is raised
    to 0.2 when 1.065 < epsilon < 2.8 (as gendaylit and gendaymtx do: smaller values
    there give a brightening horizon the data did not support); the zenith angle is
    capped at 90 degrees. Bin 1 has its own forms of c and d (Eqs. 7 and 8)."""
    eps = np.clip(np.atleast_1d(np.asarray(epsilon, float)), *_EPSILON_RANGE)
    dl = np.clip(np.atleast_1d(np.asarray(delta, float)), *_DELTA_RANGE)
    dl = np.where((eps > 1.065) & (eps < 2.8), np.maximum(dl, 0.2), dl)
    z = np.radians(np.clip(np.atleast_1d(np.asarray(sun_zenith_deg, float)), 0.0, 90.0))
    x = _PEREZ_1993[clearness_bin(eps)]  # (T, 5, 4)
    zz, dd = z[:, None], dl[:, None]
    coef = x[..., 0] + x[..., 1] * zz + dd * (x[..., 2] + x[..., 3] * zz)
    first = clearness_bin(eps) == 0
    if first.any():
        x0, z0, d0 = x[first], z[first], dl[first]
        coef[first, 2] = (
            np.exp((d0 * (x0[:, 2, 0] + x0[:, 2, 1] * z0)) ** x0[:, 2, 2]) - x0[:, 2, 3]
        )
        coef[first, 3] = (
            -np.exp(d0 * (x0[:, 3, 0] + x0[:, 3, 1] * z0)) + x0[:, 3, 2] + d0 * x0[:, 3, 3]
        )
    return coef


def perez_all_weather(
    directions: np.ndarray,
    sun: np.ndarray,
    sun_zenith_deg: np.ndarray,
    epsilon: np.ndarray,
    delta: np.ndarray,
) -> np.ndarray:
    """(T, m) relative luminance of the Perez all-weather model in unit ``directions``
    (m, 3) for T hours with unit sun vectors ``sun`` (T, 3):

        lv = (1 + a exp(b / cos zeta)) (1 + c exp(d gamma) + e cos^2 gamma)

    zeta the direction's zenith angle (cos zeta >= 0.01), gamma its angle from the sun;
    negative values are set to 0, and directions below the horizon are 0."""
    dirs = np.asarray(directions, float)
    s = np.atleast_2d(np.asarray(sun, float))
    coef = perez_coefficients(sun_zenith_deg, epsilon, delta)
    return _perez_lv(dirs, s, coef)


def _perez_lv(
    dirs: np.ndarray, sun: np.ndarray, coef: np.ndarray, dtype: type = np.float64
) -> np.ndarray:
    """(T, m) Perez relative luminance; ``dtype`` float32 makes the annual sky ten
    times faster (its 1e-7 relative precision is far below the model's)."""
    dirs = dirs.astype(dtype, copy=False)
    coef = coef.astype(dtype, copy=False)
    a, b, c, d, e = (coef[:, i : i + 1] for i in range(5))
    # The gradation depends on the altitude only: evaluate it once per distinct one.
    cz, inverse = np.unique(np.maximum(dirs[:, 2], dtype(_HORIZON_SIN)), return_inverse=True)
    gradation = (1.0 + a * np.exp(b / cz[None, :]))[:, inverse.reshape(-1)]
    cos_gamma = np.clip(sun.astype(dtype, copy=False) @ dirs.T, -1.0, 1.0)
    lv = np.exp(d * np.arccos(cos_gamma))
    lv *= c
    lv += 1.0 + e * cos_gamma**2
    lv *= gradation
    lv[:, dirs[:, 2] <= 0.0] = 0.0
    return np.maximum(np.nan_to_num(lv, nan=0.0, posinf=0.0, neginf=0.0), 0.0)


def hourly_sky_luminance(
    dome: SkyDome,
    dni: np.ndarray,
    dhi: np.ndarray,
    dh_lux: np.ndarray,
    sun_zenith_deg: np.ndarray,
    sun_azimuth_deg: np.ndarray,
    dni_extra: np.ndarray,
    per_side: int = 4,
) -> np.ndarray:
    """(T, K) luminance (cd/m2) of each patch in each hour under the Perez all-weather
    sky, scaled so that sum_k L_k P_k equals ``dh_lux`` (diffuse horizontal
    illuminance, lux; P_k the patch's horizontal projected solid angle).

    Irradiances in W/m2, angles in degrees (pvlib's zenith and compass azimuth). An hour
    is 0 when dh_lux <= 0 (or not finite) or the sun is more than 6 degrees below the
    horizon; between 0 and 6 degrees below, the sun is put on the horizon. An hour
    whose distribution integrates to nothing (a degenerate coefficient set) falls back
    to the CIE overcast distribution, so the illuminance is always kept.

    ``per_side``: each patch is averaged over per_side**2 stratified subsamples
    (``SkyDome.subsamples``); 0 takes the value at the patch centre, as Radiance's
    gendaymtx does (which then agrees with gendaymtx patch by patch)."""
    zen = np.asarray(sun_zenith_deg, float)
    lux = np.nan_to_num(np.asarray(dh_lux, float), nan=0.0)
    active = np.flatnonzero((lux > 0.0) & (zen < _MAX_SUN_ZENITH) & np.isfinite(zen))
    out = np.zeros((zen.shape[0], dome.count))
    if active.size == 0:
        return out
    z = np.minimum(zen[active], 90.0)
    sun = sun_direction(z, np.asarray(sun_azimuth_deg, float)[active])
    eps, dl = perez_parameters(
        np.nan_to_num(np.asarray(dhi, float)[active]),
        np.nan_to_num(np.asarray(dni, float)[active]),
        z,
        np.asarray(dni_extra, float)[active],
    )
    coef = perez_coefficients(z, eps, dl)
    dirs = _patch_samples(dome, per_side)
    flat = dirs.reshape(-1, 3)
    s = dirs.shape[1]
    proj = dome.horizontal_solid_angles
    overcast = _patch_average(cie_overcast(flat), dome.count, s)
    chunk = max(1, 4_000_000 // flat.shape[0])
    for start in range(0, active.size, chunk):
        sl = slice(start, start + chunk)
        lv = _perez_lv(flat, sun[sl], coef[sl], np.float32)
        rel = lv.reshape(lv.shape[0], dome.count, s).mean(axis=2, dtype=np.float64)
        total = rel @ proj
        bad = ~(total > 0.0) | ~np.isfinite(total)
        rel[bad] = overcast
        total[bad] = overcast @ proj
        out[active[sl]] = rel * (lux[active[sl]] / total)[:, None]
    return out


def _patch_samples(dome: SkyDome, per_side: int) -> np.ndarray:
    """(K, s, 3) equal-weight directions in each patch: the stratified subsamples, or
    with per_side = 0 the patch centres alone (gendaymtx's sampling)."""
    if per_side == 0:
        return dome.directions[:, None, :]
    return dome.subsamples(per_side)[0]


def _patch_average(values: np.ndarray, count: int, s: int) -> np.ndarray:
    return values.reshape(count, s).mean(axis=1)


def scaled_sky(
    dome: SkyDome,
    relative: Callable[[np.ndarray], np.ndarray] | np.ndarray,
    horizontal_lux: float,
    per_side: int = 4,
) -> np.ndarray:
    """(K,) patch luminances (cd/m2) of a sky giving ``horizontal_lux`` on an
    unobstructed horizontal plane: ``relative`` is either a function of unit
    directions (m, 3), averaged over each patch's subsamples, or the (K,) relative
    patch luminances themselves. E.g. ``scaled_sky(dome, cie_overcast, 10_000)`` or
    ``scaled_sky(dome, lambda d: cie_clear(d, sun), 8_000)``."""
    if callable(relative):
        dirs = _patch_samples(dome, per_side)
        rel = _patch_average(
            np.asarray(relative(dirs.reshape(-1, 3)), float), dome.count, dirs.shape[1]
        )
    else:
        rel = np.asarray(relative, float).reshape(dome.count)
    total = float(rel @ dome.horizontal_solid_angles)
    if not total > 0.0:
        return np.zeros(dome.count)
    return rel * (float(horizontal_lux) / total)
