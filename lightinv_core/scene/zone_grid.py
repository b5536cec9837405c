"""Emitter zones as grids, and the emission of rectangular sources placed in them.

A source is an axis-aligned rectangle (u0, v0)-(u1, v1) in zone coordinates
(metres along the zone's u and v edges). Its exitance (lm/m²) is spread over
the zone's patches by overlap area, so a source covering a third of a patch
gives that patch a third of its exitance and the emitted flux is exact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.scene.patches import Patches


@dataclass(frozen=True)
class ZoneGrid:
    """The patches of one emitter zone laid out as its (nu, nv) grid.

    patch : (nu, nv) int, patch index of each cell
    du, dv : cell size in metres along u and v
    """

    name: str
    patch: np.ndarray
    du: float
    dv: float

    @property
    def size(self) -> tuple[float, float]:
        """Zone extent (m) along u and v."""
        return self.patch.shape[0] * self.du, self.patch.shape[1] * self.dv


def zone_grid(patches: Patches, name: str) -> ZoneGrid:
    """The grid of emitter zone ``name``."""
    idx = patches.zone_index(name)
    surface = patches.surface_names[patches.surface_id[idx[0]]]
    nu, nv = patches.grid_shape[surface]
    grid = np.empty((nu, nv), np.int64)
    ij = patches.grid_ij[idx]
    grid[ij[:, 0], ij[:, 1]] = idx
    du = float(np.linalg.norm(patches.edge1[idx[0]]))
    dv = float(np.linalg.norm(patches.edge2[idx[0]]))
    return ZoneGrid(name, grid, du, dv)


def rectangle_emission(
    grid: ZoneGrid, u0: float, v0: float, u1: float, v1: float, exitance: float
) -> tuple[np.ndarray, np.ndarray]:
    """Patches covered by the rectangle and their exitance (lm/m²), by overlap area.

    Returns ``(idx, values)`` for the covered patches only (the sparse E).
    """
    lo_u, hi_u = sorted((u0, u1))
    lo_v, hi_v = sorted((v0, v1))
    su, sv = grid.size
    if lo_u < -1e-9 or lo_v < -1e-9 or hi_u > su + 1e-9 or hi_v > sv + 1e-9:
        raise LightInvError(f"source ({u0}, {v0})-({u1}, {v1}) m lies outside zone {grid.name!r}")
    nu, nv = grid.patch.shape
    eu = np.arange(nu + 1) * grid.du
    ev = np.arange(nv + 1) * grid.dv
    ou = np.clip(np.minimum(eu[1:], hi_u) - np.maximum(eu[:-1], lo_u), 0, None) / grid.du
    ov = np.clip(np.minimum(ev[1:], hi_v) - np.maximum(ev[:-1], lo_v), 0, None) / grid.dv
    iu, iv = np.flatnonzero(ou), np.flatnonzero(ov)
    frac = np.outer(ou[iu], ov[iv])
    return grid.patch[np.ix_(iu, iv)].ravel(), (exitance * frac).ravel()


def random_rectangles(
    grid: ZoneGrid,
    rng: np.random.Generator,
    count: int,
    min_frac: float = 0.02,
    max_frac: float = 0.2,
) -> np.ndarray:
    """``count`` random rectangles (u0, v0, u1, v1) in the zone covering between
    ``min_frac`` and ``max_frac`` of its area: test and calibration emitters."""
    su, sv = grid.size
    out = np.empty((count, 4))
    for q in range(count):
        frac = rng.uniform(min_frac, max_frac)
        aspect = rng.uniform(0.5, 2.0)
        w = min(su, np.sqrt(frac * su * sv * aspect))
        h = min(sv, frac * su * sv / w)
        u0, v0 = rng.uniform(0, su - w), rng.uniform(0, sv - h)
        out[q] = (u0, v0, u0 + w, v0 + h)
    return out


def random_zone_emissions(
    patches: Patches, count: int, seed: int, exitance: float = 1000.0
) -> list[tuple[np.ndarray, np.ndarray]]:
    """``count`` sparse emissions (idx, values), each one random rectangle (2-20% of a
    random emitter zone) at ``exitance`` lm/m²: what the optimizer evaluates, for
    benchmarks and tests."""
    rng = np.random.default_rng(seed)
    grids = [zone_grid(patches, z) for z in patches.zone_names]
    out = []
    for _ in range(count):
        g = grids[rng.integers(len(grids))]
        out.append(rectangle_emission(g, *random_rectangles(g, rng, 1)[0], exitance))
    return out
