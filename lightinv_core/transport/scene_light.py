"""A forward simulation with everything that emits: luminous groups, photometric
luminaires, and work-plane grids reading the result (the reference solver's path).

With direct illuminance ``H0`` from the luminaires (``transport.luminaires``) and
group exitance ``E``, the radiosity B solves ``B = E + R (H0 + F B)``, i.e. the
reference solve with emission ``E + R H0``; the illuminance of the patches is
``H = H0 + F B``. Grid points add their own direct light to ``F_p B``
(``transport.receivers``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from lightinv_core.atomic import atomic_writer
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.luminaires import (
    DIRECT_SAMPLES,
    PlacedLuminaire,
    direct_at_points,
    direct_on_patches,
)
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors
from lightinv_core.transport.solver import solve
from lightinv_core.transport.workplane import Grid


@dataclass(frozen=True)
class SceneLight:
    """Patches: self-emission ``E``, direct luminaire light ``H0``, radiosity ``B``
    (lm/m²) and illuminance ``H`` (lux); the flux budget (lm)."""

    E: np.ndarray
    H0: np.ndarray
    B: np.ndarray
    H: np.ndarray
    emitted_lm: float
    absorbed_lm: float

    @property
    def imbalance(self) -> float:
        """(emitted - absorbed) / emitted: light escaping, plus sampling error."""
        return (self.emitted_lm - self.absorbed_lm) / self.emitted_lm if self.emitted_lm else 0.0


def light_scene(
    patches: Patches,
    F: sp.spmatrix,
    caster: RayCaster,
    E: np.ndarray,
    luminaires: list[PlacedLuminaire],
    samples: int = DIRECT_SAMPLES,
    seed: int = 0,
) -> SceneLight:
    """Solve the scene lit by groups emitting ``E`` (lm/m²) and by ``luminaires``."""
    H0 = (
        direct_on_patches(patches, luminaires, caster, samples, seed)
        if luminaires
        else np.zeros(patches.n)
    )
    sol = solve(F, patches.rho, E + patches.rho * H0)
    H = H0 + sol.H
    emitted = float(E @ patches.area) + sum(lum.lumens for lum in luminaires)
    absorbed = float(((1.0 - patches.rho) * H) @ patches.area)
    return SceneLight(E, H0, sol.B, H, emitted, absorbed)


@dataclass(frozen=True)
class GridLight:
    """Illuminance (lux) at a grid's points: ``direct`` from luminaires, ``indirect``
    from the patches (their emission and reflections); ``lux`` is the sum."""

    points: np.ndarray
    direct: np.ndarray
    indirect: np.ndarray

    @property
    def lux(self) -> np.ndarray:
        """Total illuminance (lux) per point."""
        return self.direct + self.indirect


def light_grid(
    grid: Grid,
    light: SceneLight,
    caster: RayCaster,
    luminaires: list[PlacedLuminaire],
    rays: int,
    seed: int = 0,
    factors: sp.spmatrix | None = None,
) -> GridLight:
    """The grid's illuminance in the solved scene ``light``; ``factors`` reuses the
    grid's traced form factors (``receiver_factors``) from an earlier call."""
    R = factors
    if R is None:
        R = receiver_factors(grid.points, grid.normals, caster, len(light.B), rays, seed)
    direct = direct_at_points(grid.points, grid.normals, luminaires, caster)
    return GridLight(grid.points, direct, R @ light.B)


def write_grid_csv(
    path, points: np.ndarray, lux: np.ndarray, columns: dict[str, np.ndarray] | None = None
) -> None:
    """One row per grid point: ``x,y,z`` (m), ``lux``, then any further ``columns``
    (name -> one value per point, e.g. ``df`` in %)."""
    extra = columns or {}
    with atomic_writer(path, "w", newline="") as fh:
        fh.write(",".join(["x", "y", "z", "lux", *extra]) + "\n")
        for k, ((x, y, z), e) in enumerate(zip(points, lux, strict=True)):
            more = "".join(f",{v[k]:.6g}" for v in extra.values())
            fh.write(f"{x:.6g},{y:.6g},{z:.6g},{e:.6g}{more}\n")
