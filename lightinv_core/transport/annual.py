"""Annual daylight on a work plane, without a radiosity solve per hour.

Light transport is linear and each glazing pane's exitance is its transmittance
times the exterior illuminance on its plane, so the daylight at grid point p in
hour t is ``sum_g c_pg E_g(t)``: one coefficient per pane (lux at the point per lux
on the pane's outside) times that pane's hourly exterior illuminance
(``climate.transposition``). A pane is a glazing group's patches of one orientation
(a group spanning two facades makes two panes). The coefficients cost one reference
solve per pane; the year is then a (points x panes) @ (panes x hours) product.
``tests/core/test_annual.py`` checks it against solving hour by hour.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from lightinv_core.climate.transposition import plane_illuminance, sun_and_sky
from lightinv_core.climate.weather import Weather
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.scene_light import light_grid, light_scene
from lightinv_core.transport.workplane import Grid


@dataclass(frozen=True)
class Pane:
    """Patches ``idx`` of glazing ``group`` facing one way: ``outward`` unit normal
    (away from the room) and visible ``transmittance``."""

    group: str
    idx: np.ndarray
    outward: np.ndarray
    transmittance: float


def panes(patches: Patches, glazing: dict[str, float]) -> list[Pane]:
    """The glazing groups split by orientation (normals equal to 1e-3)."""
    out = []
    for group, t in glazing.items():
        idx = patches.group_index(group)
        keys = np.round(patches.normal[idx], 3)
        for key in np.unique(keys, axis=0):
            sel = idx[np.all(keys == key, axis=1)]
            n = patches.normal[sel].mean(axis=0)
            out.append(Pane(group, sel, -n / np.linalg.norm(n), float(t)))
    return out


@dataclass(frozen=True)
class AnnualDaylight:
    """``coefficients`` (q, P): grid lux per exterior lux on each pane; ``exterior``
    (P, h) lux per hour on each pane's outside; ``lux`` (q, h) the daylight per hour."""

    panes: list[Pane]
    coefficients: np.ndarray
    exterior: np.ndarray

    @property
    def lux(self) -> np.ndarray:
        """Daylight (lux) per grid point and hour."""
        return self.coefficients @ self.exterior


def annual_daylight(
    lit: Patches,
    F: sp.spmatrix,
    caster: RayCaster,
    glazing: dict[str, float],
    weather: Weather,
    grid: Grid,
    factors: sp.spmatrix,
    ground_reflectance: float = 0.2,
    north_deg: float = 0.0,
) -> AnnualDaylight:
    """Coefficients and hourly exterior light of every pane (see the module); ``lit``
    are the patches with the glazing black inside, ``factors`` the grid's traced form
    factors."""
    sky = sun_and_sky(weather)
    ps = panes(lit, glazing)
    coefficients = np.zeros((len(grid.points), len(ps)))
    exterior = np.zeros((len(ps), weather.hours))
    for k, pane in enumerate(ps):
        E = np.zeros(lit.n)
        E[pane.idx] = pane.transmittance  # 1 lux outside
        light = light_scene(lit, F, caster, E, [])
        coefficients[:, k] = light_grid(grid, light, caster, [], 1, factors=factors).lux
        exterior[k] = plane_illuminance(weather, sky, pane.outward, ground_reflectance, north_deg)
    return AnnualDaylight(ps, coefficients, exterior)
