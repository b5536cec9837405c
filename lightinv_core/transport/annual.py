"""Daylight coefficients of glazing groups on a work plane, by the reference solver.

Light transport is linear and each glazing patch's exitance is its transmittance times
the exterior illuminance on its plane, so the daylight at grid point p in hour t is
``sum_g c_pg E_g(t)``: one coefficient per *orientation* g (lux at the point per lux on
the outside of the glazing facing that way) times that orientation's hourly exterior
illuminance. The coefficients cost one reference solve per orientation; the year
(``light.daylight_year``, the optimiser's sky groups) and its statistics are then the
same as the optimiser's. A *pane* is one glazing group's patches of one orientation (a
group spanning two facades makes two panes; two groups in one roof make one
orientation). ``tests/core/test_annual.py`` checks the coefficients against solving
hour by hour.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from lightinv_core.scene.patches import Patches
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.scene_light import light_grid, light_scene
from lightinv_core.transport.workplane import Grid

NORMAL_DECIMALS = 3
"""Patches whose normals agree to this many decimals face the same way."""


@dataclass(frozen=True)
class Pane:
    """Patches ``idx`` of glazing ``group`` facing one way: ``outward`` unit normal
    (away from the room) and visible ``transmittance``."""

    group: str
    idx: np.ndarray
    outward: np.ndarray
    transmittance: float


def _outward(patches: Patches, idx: np.ndarray) -> np.ndarray:
    n = patches.normal[idx].mean(axis=0)
    return -n / np.linalg.norm(n)


def panes(patches: Patches, glazing: dict[str, float]) -> list[Pane]:
    """The glazing groups (name -> transmittance) split by orientation."""
    out = []
    for group, t in glazing.items():
        idx = patches.group_index(group)
        keys = np.round(patches.normal[idx], NORMAL_DECIMALS)
        for key in np.unique(keys, axis=0):
            sel = idx[np.all(keys == key, axis=1)]
            out.append(Pane(group, sel, _outward(patches, sel), float(t)))
    return out


@dataclass(frozen=True)
class Orientation:
    """The panes facing one way and their common ``outward`` unit normal."""

    panes: tuple[Pane, ...]
    outward: np.ndarray

    @property
    def idx(self) -> np.ndarray:
        """Patch ids of every pane."""
        return np.concatenate([q.idx for q in self.panes])


def orientations(patches: Patches, glazing: dict[str, float]) -> list[Orientation]:
    """The panes of ``glazing`` grouped by orientation, in the order first met."""
    keyed: dict[tuple, list[Pane]] = {}
    for q in panes(patches, glazing):
        keyed.setdefault(tuple(np.round(-q.outward, NORMAL_DECIMALS)), []).append(q)
    out = []
    for group in keyed.values():
        idx = np.concatenate([q.idx for q in group])
        outward = group[0].outward if len(group) == 1 else _outward(patches, idx)
        out.append(Orientation(tuple(group), outward))
    return out


def orientation_coefficients(
    lit: Patches,
    F: sp.spmatrix,
    caster: RayCaster,
    orients: list[Orientation],
    grid: Grid,
    factors: sp.spmatrix,
) -> np.ndarray:
    """(q, G) lux at the grid's points per lux on the outside of each orientation's
    glazing: one reference solve each. ``lit`` are the patches with the glazing black
    inside, ``factors`` the grid's traced form factors (``receiver_factors``)."""
    out = np.zeros((len(grid.points), len(orients)))
    for g, o in enumerate(orients):
        E = np.zeros(lit.n)
        for q in o.panes:
            E[q.idx] = q.transmittance  # 1 lux outside
        light = light_scene(lit, F, caster, E, [])
        out[:, g] = light_grid(grid, light, caster, [], 1, factors=factors).lux
    return out
