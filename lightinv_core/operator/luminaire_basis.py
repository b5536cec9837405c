"""Responses of photometric luminaires where the optimiser reads the light.

Light is linear in each luminaire's dimming, so a layout of photometric luminaires
is a weighted sum of their responses at unit dimming. Precomputed once for a set
of candidate placements (positions and orientations), the responses make a
candidate cost O(rows x luminaires), not O(n), however fine the scene.

A placement's response is the illuminance it gives everywhere: its direct light H0
(shadow rays, ``transport.luminaires``) plus the light of H0 reflected, which
bounces like the zone basis's (docs/operator.md): with the first reflected
illuminance D1 = F R H0 and D(b+1) = F R D(b),

    H = H0 + D1 + D2 + D3 + Y V^T R D3

three bounces exact on the traced form factors, the smooth remainder from the
low-rank operator. Only the rows the optimiser reads are kept: receiver patches
(intentions) and work-plane points, whose light is their own direct light plus
``F_p R H`` (``transport.receivers``). Memory O((rows + points) x placements), never
O(n x placements): placements are processed in chunks.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from lightinv_core.errors import CancelledError
from lightinv_core.operator.lowrank import LowRank
from lightinv_core.operator.zone_basis import (
    EXACT_BOUNCES,
    more_bounces,
    sparse_dense_product,
    zone_basis,
)
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.formfactors import DEFAULT_RAYS
from lightinv_core.transport.luminaires import (
    PlacedLuminaire,
    direct_at_points,
    direct_on_patches,
)
from lightinv_core.transport.point_sets import PointSet, as_point_set
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors

BASIS_SAMPLES = 4
"""Points per patch for the direct light of a placement (2 x 2 stratified): the
reflected light it feeds is smooth; receivers get their direct light exactly."""
CHUNK = 64


@dataclass(frozen=True, eq=False)
class LuminaireResponses:
    """Illuminance (lux) of each placement at unit dimming: ``at_rows`` (p, L) at patch
    ids ``rows``, ``at_points`` (q, L) at the grid points (float32)."""

    rows: np.ndarray
    at_rows: np.ndarray
    at_points: np.ndarray
    names: tuple[str, ...]

    def evaluate(self, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(rows, points) illuminance of layouts given as ``weights`` (m, L): the dimming
        of each placement in each layout (0 where absent). Returns (p, m), (q, m)."""
        w = np.asarray(weights, dtype=np.float32).T
        return self.at_rows @ w, self.at_points @ w


def luminaire_responses(
    patches: Patches,
    F: sp.spmatrix,
    lowrank: LowRank,
    placements: Sequence[PlacedLuminaire],
    rows: np.ndarray,
    points: np.ndarray | PointSet | None = None,
    caster: RayCaster | None = None,
    rays: int = DEFAULT_RAYS,
    samples: int = BASIS_SAMPLES,
    seed: int = 0,
    bounces: int = EXACT_BOUNCES,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
) -> LuminaireResponses:
    """Responses of ``placements`` at patch ``rows`` and ``points`` (an array (q, 3):
    facing up, a work plane's grid; or a ``PointSet``, its values), on the traced form
    factors ``F`` and the operator's ``lowrank`` part (see the module). ``cancel()``
    returning True raises ``CancelledError`` between chunks."""
    caster = caster or RayCaster(patches)
    rows = np.asarray(rows, dtype=np.int64)
    ps = as_point_set(points)
    pts, normals = ps.points, ps.normals
    Rp = receiver_factors(pts, normals, caster, patches.n, rays, seed + 1)
    F32 = sp.csr_matrix(F).astype(np.float32)
    rho32 = patches.rho.astype(np.float32)[:, None]
    L = len(placements)
    at_rows = np.zeros((len(rows), L), np.float32)
    at_points = np.zeros((ps.size, L), np.float32)
    for start in range(0, L, CHUNK):
        if cancel is not None and cancel():
            raise CancelledError("luminaire responses cancelled")
        chunk = placements[start : start + CHUNK]
        H0 = np.column_stack(
            [direct_on_patches(patches, [lum], caster, samples, seed) for lum in chunk]
        ).astype(np.float32)
        first = sparse_dense_product(F32, rho32 * H0, cancel=cancel)
        exact, last = more_bounces(F32, patches.rho, first, bounces, cancel)
        H = zone_basis(exact, last, lowrank) + H0
        cols = slice(start, start + len(chunk))
        at_rows[:, cols] = H[rows]
        if len(pts):
            direct = np.column_stack(
                [direct_at_points(pts, normals, [lum], caster) for lum in chunk]
            )
            at_points[:, cols] = ps.values(direct + Rp @ (rho32 * H))
        if progress is not None:
            progress(min(1.0, (start + len(chunk)) / L))
    return LuminaireResponses(rows, at_rows, at_points, tuple(lum.name for lum in placements))
