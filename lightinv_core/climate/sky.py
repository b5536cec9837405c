"""Illuminance on the outside of a glazing plane under a sky, with ground reflection.

Skies here are distributions of luminance over the upper hemisphere, scaled so the
unobstructed horizontal illuminance is ``E_h`` lux. The CIE standard overcast sky
(Moon and Spencer, CIE S 011/E:2003 sky type 1) has luminance

    L(gamma) = L_z (1 + 2 sin gamma) / 3        (gamma: altitude)

independent of azimuth, so the light on a plane depends only on its tilt beta (the
angle of its outward normal from the zenith): ``E_sky(beta)``, integrated numerically
once on a fine grid (7 pi L_z / 9 = E_h at beta = 0; 0.396 E_h on a vertical plane,
the classical value). The ground is a Lambertian plane of reflectance ``rho_g`` lit by
E_h; a plane tilted beta sees it with view factor (1 - cos beta) / 2.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from lightinv_core.errors import LightInvError

_STEPS = 360
"""Altitude and azimuth steps of the numerical integration (0.25 and 1 degree): the
factor is exact to 1e-5 (tests/core/test_daylight.py)."""


@lru_cache(maxsize=1)
def _overcast_grid() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Directions (k, 3), relative luminance (k,) and solid angles (k,) of the sky."""
    alt = (np.arange(_STEPS) + 0.5) * (math.pi / 2) / _STEPS
    az = (np.arange(_STEPS) + 0.5) * (2 * math.pi) / _STEPS
    a, z = np.meshgrid(alt, az, indexing="ij")
    d = np.stack([np.cos(a) * np.cos(z), np.cos(a) * np.sin(z), np.sin(a)], axis=-1)
    lum = (1 + 2 * np.sin(a)) / 3
    solid = np.cos(a) * (math.pi / 2 / _STEPS) * (2 * math.pi / _STEPS)
    return d.reshape(-1, 3), lum.reshape(-1), solid.reshape(-1)


def overcast_sky_factor(tilt_deg: float) -> float:
    """Sky illuminance on a plane tilted ``tilt_deg`` from facing the zenith, as a
    fraction of the horizontal illuminance, under the CIE overcast sky (1 at 0 deg)."""
    d, lum, solid = _overcast_grid()
    t = math.radians(tilt_deg)
    normal = np.array([math.sin(t), 0.0, math.cos(t)])
    cos = np.maximum(d @ normal, 0.0)
    horizontal = float((lum * d[:, 2] * solid).sum())
    return float((lum * cos * solid).sum()) / horizontal


def overcast_plane_illuminance(
    outward_normals: np.ndarray, horizontal_lux: float, ground_reflectance: float
) -> np.ndarray:
    """Exterior illuminance (lux) on planes with unit ``outward_normals`` (m, 3) under
    the CIE overcast sky giving ``horizontal_lux`` on open ground of reflectance
    ``ground_reflectance``: sky part plus ground-reflected part."""
    if not (0 <= horizontal_lux <= 2e5 and math.isfinite(horizontal_lux)):
        raise LightInvError(
            f"exterior illuminance must be from 0 to 200,000 lux, got {horizontal_lux!r}"
        )
    if not 0 <= ground_reflectance < 1:
        raise LightInvError(
            f"ground reflectance must be from 0 to below 1, got {ground_reflectance!r}"
        )
    n = np.asarray(outward_normals, dtype=float).reshape(-1, 3)
    cos_tilt = np.clip(n[:, 2] / np.linalg.norm(n, axis=1), -1.0, 1.0)
    # Glazing comes in a few orientations: integrate once per distinct tilt (0.01 deg).
    tilt = np.round(np.degrees(np.arccos(cos_tilt)), 2)
    values, inverse = np.unique(tilt, return_inverse=True)
    sky = np.array([overcast_sky_factor(float(t)) for t in values])[inverse]
    ground = ground_reflectance * (1 - cos_tilt) / 2
    return horizontal_lux * (sky + ground)
