"""Accuracy of an operator against the reference solver, on sampled emission vectors.

The error is the relative L2 error of the reflected exitance C = B - E over all
patches (C, not B: E alone would hide errors on the emitting patches), for
emission vectors like the optimizer's: one to three random rectangles in random
emitter zones, each covering 2-20% of its zone, at 1,000 lm/m².
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.sparse as sp

from lightinv_core.errors import CancelledError
from lightinv_core.operator.zone_basis import sparse_dense_product
from lightinv_core.scene.patches import Patches
from lightinv_core.scene.zone_grid import random_rectangles, rectangle_emission, zone_grid


def sample_emissions(patches: Patches, count: int, seed: int) -> np.ndarray:
    """(n, count) emission vectors, lm/m², from random zone rectangles (random patch
    groups of about 1% of the patches when the scene has no zones)."""
    rng = np.random.default_rng(seed)
    E = np.zeros((patches.n, count))
    grids = [zone_grid(patches, z) for z in patches.zone_names]
    for q in range(count):
        if not grids:
            E[rng.choice(patches.n, max(1, patches.n // 100), replace=False), q] = 1000.0
            continue
        for g in rng.choice(len(grids), size=rng.integers(1, 4)):
            u0, v0, u1, v1 = random_rectangles(grids[g], rng, 1)[0]
            idx, val = rectangle_emission(grids[g], u0, v0, u1, v1, 1000.0)
            E[idx, q] += val
    return E


def reference_reflected(
    F: sp.csr_matrix,
    rho: np.ndarray,
    E: np.ndarray,
    tol: float = 1e-6,
    max_iter: int = 500,
    cancel: Callable[[], bool] | None = None,
) -> np.ndarray:
    """C = B - E of the reference (Jacobi on the sparse F, float32 products) for a stack
    of emission vectors (n, m), to ``tol`` relative per column. ``cancel()`` is polled
    every sweep; True raises ``CancelledError``."""
    F32 = F.astype(np.float32, copy=False)
    B = E.astype(np.float32)
    E32 = B.copy()
    r = rho.astype(np.float32)[:, None]
    scale = np.abs(E32).max(axis=0) + 1e-30
    for _ in range(max_iter):
        if cancel is not None and cancel():
            raise CancelledError("operator build cancelled")
        B_new = E32 + r * sparse_dense_product(F32, B)
        delta = (np.abs(B_new - B).max(axis=0) / scale).max()
        B = B_new
        if delta <= tol:
            break
    return (B - E32).astype(np.float64)


def relative_errors(C: np.ndarray, C_ref: np.ndarray) -> np.ndarray:
    """||C - C_ref|| / ||C_ref|| per column; 0 where both are zero (a scene that reflects
    no light, e.g. a lone patch, is reproduced exactly), inf where only C_ref is."""
    diff = np.linalg.norm(C - C_ref, axis=0)
    ref = np.linalg.norm(C_ref, axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(diff == 0, 0.0, diff / ref)
