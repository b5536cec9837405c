"""Daylight coefficients of clear glazing: receivers' light per unit of sky and sun.

Light is linear in the sky's luminance, so a receiver's illuminance under any sky is
sum_k D_k L_k over sky patches k (and the ground), plus the sun's part per lux of direct
normal illuminance. Each coefficient has two parts:

- **direct**: the receiver's own view of the sky through the glass (``clear_glazing``'s
  receiver rays, area-sampled over the panes);
- **inter-reflected**: the sky's light first landing on the room's patches (the room
  rays) is the emission rho x H of a radiosity solve, one right-hand side per sky patch
  (and per sun position), read at the receivers through their traced form factors.

The sun: its direct light at the receivers is traced hour by hour exactly
(``sun_on_points``); its inter-reflected light is solved for a basis of sun positions
(the hours' suns binned on a fine sky subdivision) and each hour takes its bin's.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from lightinv_core.scene.patches import Patches
from lightinv_core.transport.clear_glazing import (
    Glass,
    SkyRays,
    receiver_sky_rays,
    room_sky_rays,
    sun_on_points,
    sun_on_room,
)
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.solver import DENSE_LIMIT

Bins = Callable[[np.ndarray], np.ndarray]
"""Scene directions (m, 3) -> bin index (m,) in [0, bins)."""


def factor(F: sp.spmatrix, rho: np.ndarray):
    """The LU factors of I - rho F for ``bounce`` (None above ``DENSE_LIMIT`` patches)."""
    n = F.shape[0]
    if n > DENSE_LIMIT:
        return None
    # I - rho F built in place: one dense n x n array, factored where it lies.
    A = F.toarray() if sp.issparse(F) else np.array(F, dtype=float)
    A *= -rho[:, None]
    A[np.diag_indices(n)] += 1.0
    return la.lu_factor(A, overwrite_a=True, check_finite=False)


def radiosity(F: sp.spmatrix, rho: np.ndarray, E: np.ndarray, lu=None) -> np.ndarray:
    """Radiosity B (n, c) of patches emitting ``E`` (n, c) lm/m²: (I - rho F) B = E,
    every column at once (as ``bounce``)."""
    n = F.shape[0]
    if n <= DENSE_LIMIT:
        return la.lu_solve(factor(F, rho) if lu is None else lu, E)
    F = sp.csr_matrix(F)
    B = np.array(E, dtype=float)
    scale = max(float(np.abs(B).max()), 1e-300)
    for _ in range(10_000):
        B_new = E + rho[:, None] * (F @ B)
        if float(np.abs(B_new - B).max()) <= 1e-10 * scale:
            return B_new
        B = B_new
    return B


def bounce(F: sp.spmatrix, rho: np.ndarray, H: np.ndarray, lu=None) -> np.ndarray:
    """Radiosity B (n, c) of the room whose patches first receive irradiance ``H``
    (n, c) lux: (I - rho F) B = rho H, every column at once (by the LU factors ``lu``
    of ``factor``, made here when not given, up to ``DENSE_LIMIT`` patches; Jacobi
    sweeps above)."""
    return radiosity(F, rho, rho[:, None] * H, lu)


def _binned(rays: SkyRays, groups: int, bins: Bins, nbins: int) -> np.ndarray:
    """(G, targets, nbins) sums of the rays' weights by group, target and bin."""
    out = np.zeros(groups * rays.targets * nbins)
    if len(rays.weight):
        b = np.asarray(bins(rays.direction))
        g, t = rays.group.astype(np.int64), rays.target.astype(np.int64)
        key = (g * rays.targets + t) * nbins + b
        out += np.bincount(key, rays.weight, minlength=len(out))
    return out.reshape(groups, rays.targets, nbins)


def _weighted(rays: SkyRays, groups: int, luminance: Callable) -> np.ndarray:
    """(G, targets) sums of the rays' weights times the luminance in their direction."""
    out = np.zeros(groups * rays.targets)
    if len(rays.weight):
        L = np.asarray(luminance(rays.direction), dtype=float)
        key = rays.group.astype(np.int64) * rays.targets + rays.target.astype(np.int64)
        out += np.bincount(key, rays.weight * L, len(out))
    return out.reshape(groups, rays.targets)


@dataclass
class ClearDaylight:
    """Clear glazing ``glass`` in a room (``lit``: the patches, glazing black inside;
    ``F`` their form factors; ``caster``), read at receivers ``points``/``normals``
    through ``factors`` (q, n): the rays are traced once, on first use."""

    lit: Patches
    F: sp.spmatrix
    caster: RayCaster
    glass: Glass
    points: np.ndarray
    normals: np.ndarray
    factors: sp.spmatrix
    per_side: int = 6
    room_rays: int = 256
    seed: int = 0
    _cache: dict = field(default_factory=dict, repr=False)

    @property
    def groups(self) -> int:
        """Number of clear glazing groups G."""
        return len(self.glass.groups)

    def _rays(self) -> tuple[SkyRays, SkyRays]:
        if "rays" not in self._cache:
            direct = receiver_sky_rays(
                self.points, self.normals, self.lit, self.glass, self.caster,
                self.per_side, self.seed,
            )  # fmt: skip
            room = room_sky_rays(self.lit, self.glass, self.caster, self.room_rays, self.seed)
            self._cache["rays"] = (direct, room)
        return self._cache["rays"]

    def emitted(self, E: np.ndarray) -> np.ndarray:
        """(q, c) lux at the receivers when the room's patches emit ``E`` (n, c) lm/m²
        (e.g. glazing glowing as diffusing glass), by the room's one LU."""
        return self.factors @ radiosity(self.F, self.lit.rho, E, self._lu())

    def share_room(self, other: ClearDaylight) -> None:
        """Reuse ``other``'s factors of the same room (its LU) for these receivers."""
        if other.lit is self.lit and other.F is self.F:
            self._cache["lu"] = other._lu()

    def _lu(self):
        """The room's LU factors, made once (``factor``)."""
        if "lu" not in self._cache:
            self._cache["lu"] = factor(self.F, self.lit.rho)
        return self._cache["lu"]

    def _reflected(self, H: np.ndarray) -> np.ndarray:
        """(G, q, c) light at the receivers from first-hit irradiance H (G, n, c)."""
        G, n, c = H.shape
        if c == 0:  # e.g. a year whose file has no direct sun at all
            return np.zeros((G, self.factors.shape[0], 0))
        flat = np.moveaxis(H, 0, 1).reshape(n, G * c)
        B = bounce(self.F, self.lit.rho, flat, self._lu())
        return np.moveaxis((self.factors @ B).reshape(-1, G, c), 1, 0)

    def sky(self, bins: Bins, nbins: int) -> np.ndarray:
        """Daylight coefficients (G, q, nbins): lux at each receiver per cd/m² of the sky
        (or ground) in each bin of directions."""
        direct, room = self._rays()
        G = self.groups
        return _binned(direct, G, bins, nbins) + self._reflected(_binned(room, G, bins, nbins))

    def under(self, luminance: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """Illuminance (G, q) under one sky, ``luminance(scene directions) -> cd/m²``
        (below the horizon: the ground's), each ray weighted by its own direction's."""
        direct, room = self._rays()
        G = self.groups
        return (
            _weighted(direct, G, luminance)
            + self._reflected(_weighted(room, G, luminance)[..., None])[..., 0]
        )

    def direct_under(self, luminance: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """(G, q) the receivers' own view of one sky through the glass (no reflections:
        those reach them through the room's radiosity, ``room_under``)."""
        direct, _ = self._rays()
        return _weighted(direct, self.groups, luminance)

    def sun_direct(self, sun: np.ndarray) -> np.ndarray:
        """(G, q, T) direct sun per lux of direct normal illuminance, suns (T, 3)."""
        return sun_on_points(self.points, self.normals, self.lit, self.glass, self.caster, sun)

    def sun_reflected(self, sun: np.ndarray) -> np.ndarray:
        """(G, q, S) inter-reflected sun per lux of direct normal illuminance, suns (S, 3)."""
        H = sun_on_room(self.lit, self.glass, self.caster, sun, self.per_side, self.seed)
        return self._reflected(H)

    def room_under(
        self, luminance: Callable[[np.ndarray], np.ndarray], sun: np.ndarray | None, sun_lux: float
    ) -> tuple[np.ndarray, np.ndarray]:
        """Illuminance (lux) of the room's patches under one sky and sun (a unit scene
        vector or None; ``sun_lux`` its direct normal illuminance), every group: (the
        light first landing through the glass (n,), that plus its inter-reflections
        (n,))."""
        _, room = self._rays()
        H = _weighted(room, self.groups, luminance).sum(axis=0)
        if sun is not None and sun_lux > 0:
            beam = sun_on_room(self.lit, self.glass, self.caster, sun, self.per_side, self.seed)
            H = H + sun_lux * beam[..., 0].sum(axis=0)
        B = bounce(self.F, self.lit.rho, H[:, None], self._lu())[:, 0]
        return H, H + self.F @ B

    def sun(self, sun: np.ndarray) -> np.ndarray:
        """(G, q, T) the sun's light (direct and reflected) per lux of direct normal
        illuminance, each sun direction solved exactly: for a few hours."""
        return self.sun_direct(sun) + self.sun_reflected(sun)
