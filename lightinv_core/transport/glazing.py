"""Glazing groups lit by a sky: what they let into the room.

Every glazing patch is taken as **diffusing** glazing: the light falling on its
outside (sky and ground, ``climate.sky``) times its transmittance leaves its inside
face as a Lambertian exitance (lm/m²). Clear glass would instead pass a view of the
sky's luminance pattern; for an overcast sky, whose luminance varies by a factor of
three, diffusing glazing is the usual first approximation (stated in
docs/daylight.md). The glazing is black inside: it emits, it reflects nothing back
(its reflectance is set to 0), so light reaching it from the room leaves.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from lightinv_core.climate.sky import overcast_plane_illuminance
from lightinv_core.errors import LightInvError
from lightinv_core.scene.patches import Patches


def glazing_emission(
    patches: Patches,
    glazing: dict[str, float],
    horizontal_lux: float,
    ground_reflectance: float,
    outside: Callable[[np.ndarray], np.ndarray] | None = None,
) -> tuple[np.ndarray, Patches]:
    """Exitance (lm/m², n) of the ``glazing`` groups (name -> transmittance 0..1) under
    the CIE overcast sky giving ``horizontal_lux`` outside (or, given ``outside``, the
    lux that function gives on the outward normals (m, 3): another sky), and the
    patches with the glazing made black inside (reflectance 0)."""
    E = np.zeros(patches.n)
    rho = patches.rho.copy()
    for group, t in glazing.items():
        if not 0.0 <= t <= 1.0:
            raise LightInvError(f"transmittance of glazing {group!r} must be from 0 to 1, got {t}")
        idx = patches.group_index(group)
        if outside is None:
            lux = overcast_plane_illuminance(
                -patches.normal[idx], horizontal_lux, ground_reflectance
            )
        else:
            lux = outside(-patches.normal[idx])
        E[idx] = t * lux
        rho[idx] = 0.0
    return E, replace(patches, rho=rho)


def black_inside(patches: Patches, groups) -> Patches:
    """``patches`` with the ``groups``' reflectance set to 0 (glazing: light from the
    room reaching it leaves)."""
    rho = patches.rho.copy()
    for group in groups:
        rho[patches.group_index(group)] = 0.0
    return replace(patches, rho=rho)
