"""Luminous efficacy of daylight from irradiance: the Perez et al. (1990) model.

Weather files without usable illuminance columns (most EPW files from sources other
than the US TMY data sets have zeros or the missing-value marker there) still give
the three irradiance components. Perez, Ineichen, Seals, Michalsky and Stewart,
"Modeling daylight availability and irradiance components from direct and global
irradiance", Solar Energy 44(5), 1990, Table 4, model the luminous efficacy (lm/W) of
each component from the sky's clearness epsilon, its brightness Delta, the solar
zenith angle Z and the atmospheric precipitable water W (cm):

- global horizontal:  a + b W + c cos Z + d ln Delta
- diffuse horizontal: a + b W + c cos Z + d ln Delta
- direct normal:      a + b W + c exp(5.73 Z - 5) + d Delta   (Z in radians; >= 0)

with (a, b, c, d) from one of eight clearness bins, epsilon = ((DHI + DNI) / DHI +
1.041 Z^3) / (1 + 1.041 Z^3), Delta = DHI m / I0 (m the relative air mass, I0 the
extraterrestrial normal irradiance) and W = exp(0.07 Td - 0.075) from the dew point
Td (deg C), 2 cm where the file gives none. The NSRDB used this same model to make
the illuminance columns of the US TMY2/TMY3 files, so ``tests/core/test_weather.py``
checks it against those columns.
"""

from __future__ import annotations

import numpy as np

# Upper bounds of the eight clearness bins (the first starts at 1).
_BINS = np.array([1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200])

# Perez et al. 1990, Table 4: rows a, b, c, d; one column per clearness bin.
_GLOBAL = np.array(
    [
        [96.63, 107.54, 98.73, 92.72, 86.73, 88.34, 78.63, 99.65],
        [-0.47, 0.79, 0.70, 0.56, 0.98, 1.39, 1.47, 1.86],
        [11.50, 1.79, 4.40, 8.36, 7.10, 6.06, 4.93, -4.46],
        [-9.16, -1.19, -6.95, -8.31, -10.94, -7.60, -11.37, -3.15],
    ]
)
_DIFFUSE = np.array(
    [
        [97.24, 107.22, 104.97, 102.39, 100.71, 106.42, 141.88, 152.23],
        [-0.46, 1.15, 2.96, 5.59, 5.94, 3.83, 1.90, 0.35],
        [12.00, 0.59, -5.53, -13.95, -22.75, -36.15, -53.24, -45.27],
        [-8.91, -3.95, -8.77, -13.90, -23.74, -28.83, -14.03, -7.98],
    ]
)
_DIRECT = np.array(
    [
        [57.20, 98.99, 109.83, 110.34, 106.36, 107.19, 105.75, 101.18],
        [-4.55, -3.46, -4.90, -5.84, -3.97, -1.25, 0.77, 1.58],
        [-2.98, -1.21, -1.71, -1.99, -1.75, -1.51, -1.26, -1.10],
        [117.12, 12.38, -8.81, -4.56, -6.16, -26.73, -34.44, -8.29],
    ]
)

DEFAULT_PRECIPITABLE_WATER = 2.0
"""cm; used where the file gives no dew point."""


def precipitable_water(dew_point: np.ndarray) -> np.ndarray:
    """Atmospheric precipitable water (cm) from the dew point (deg C), Perez 1990;
    the default 2 cm where the dew point is unknown (NaN)."""
    td = np.asarray(dew_point, dtype=float)
    td = np.where((td > -90) & (td < 60), td, np.nan)  # beyond any weather: unknown
    w = np.exp(0.07 * td - 0.075)
    return np.where(np.isfinite(w), w, DEFAULT_PRECIPITABLE_WATER)


def perez_efficacy(
    dni: np.ndarray,
    dhi: np.ndarray,
    zenith_deg: np.ndarray,
    airmass: np.ndarray,
    dni_extra: np.ndarray,
    water_cm: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(global, diffuse, direct) luminous efficacy (lm/W) per hour; NaN where the sun
    is down or there is no diffuse light (the model has no answer there)."""
    dni = np.asarray(dni, dtype=float)
    dhi = np.asarray(dhi, dtype=float)
    z = np.radians(np.asarray(zenith_deg, dtype=float))
    up = (z < np.radians(90.0)) & (dhi > 0)
    safe_dhi = np.where(up, dhi, 1.0)
    z3 = 1.041 * z**3
    eps = ((safe_dhi + dni) / safe_dhi + z3) / (1 + z3)
    m = np.where(up, np.nan_to_num(np.asarray(airmass, float), nan=1.0), 1.0)
    delta = np.clip(safe_dhi * m / np.asarray(dni_extra, float), 1e-6, None)
    k = np.searchsorted(_BINS, eps, side="right")
    w = np.asarray(water_cm, dtype=float)

    def row(table: np.ndarray) -> tuple[np.ndarray, ...]:
        return tuple(table[i][k] for i in range(4))

    a, b, c, d = row(_GLOBAL)
    k_global = a + b * w + c * np.cos(z) + d * np.log(delta)
    a, b, c, d = row(_DIFFUSE)
    k_diffuse = a + b * w + c * np.cos(z) + d * np.log(delta)
    a, b, c, d = row(_DIRECT)
    k_direct = np.maximum(a + b * w + c * np.exp(5.73 * z - 5) + d * delta, 0.0)
    nan = np.full(len(dni), np.nan)
    return (
        np.where(up, k_global, nan),
        np.where(up, k_diffuse, nan),
        np.where(up, k_direct, nan),
    )
