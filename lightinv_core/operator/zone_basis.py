"""The zone response basis: illuminance per unit exitance of each emitter-zone patch.

Sources only ever sit in emitter zones, so every emission the optimizer tries
is a combination of the nz zone patches. Column j of Phi is the illuminance H
(lux) everywhere when zone patch j has exitance 1 lm/m²:

    Phi = D1 + D2 + D3 + Y V^T R D3,   D1 = F[:, zone],  D(b+1) = F R D(b)

the first three bounces exact from the traced form factors and the smooth
remainder from the low-rank operator. Measured (docs/operator.md): on office at
k = n/16 the LRR alone errs by 7.7% in C, exact direct light brings it to 2.1%
and two exact bounces to 0.4%; on patio, whose arcade makes a strong near
field, two exact bounces leave 1.5% at k = n/64 and three 0.75%.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import scipy.sparse as sp

from lightinv_core.errors import CancelledError
from lightinv_core.operator.lowrank import LowRank
from lightinv_core.transport.formfactors import default_workers

EXACT_BOUNCES = 3
CHUNKS_PER_WORKER = 16  # row blocks per thread in sparse_dense_product


def sparse_dense_product(
    A: sp.csr_matrix,
    X: np.ndarray,
    workers: int | None = None,
    cancel: Callable[[], bool] | None = None,
) -> np.ndarray:
    """A @ X for sparse A (float32) and dense X, with A's rows split over threads.

    The rows go in ``CHUNKS_PER_WORKER`` blocks per thread (smaller blocks are also
    faster here: 6.3 s instead of 7.6 s for patio's bounces), each polling ``cancel()``
    first, so a large product stops within one block's time (``CancelledError``)."""
    workers = workers or default_workers()
    n = A.shape[0]
    parts = workers * CHUNKS_PER_WORKER
    cuts = np.linspace(0, n, parts + 1).astype(int)
    out = np.empty((n, X.shape[1]), np.float32)
    stop = threading.Event()

    def part(q: int) -> None:
        if stop.is_set() or (cancel is not None and cancel()):
            stop.set()
            return
        out[cuts[q] : cuts[q + 1]] = A[cuts[q] : cuts[q + 1]] @ X

    with ThreadPoolExecutor(max_workers=workers) as pool:
        list(pool.map(part, range(parts)))
    if stop.is_set():
        raise CancelledError("operator build cancelled")
    return out


def exact_bounces(
    F: sp.csr_matrix,
    rho: np.ndarray,
    zone_patches: np.ndarray,
    bounces: int = EXACT_BOUNCES,
    cancel: Callable[[], bool] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """(D1 + ... + D_bounces, D_bounces), each (n, nz) float32: the exact part of Phi
    and the last bounce, whose reflection the low-rank remainder carries on.
    ``cancel()`` is polled during each bounce; True raises ``CancelledError``."""
    F32 = F.astype(np.float32)
    return more_bounces(F32, rho, F32[:, zone_patches].toarray(), bounces, cancel)


def more_bounces(
    F32: sp.csr_matrix,
    rho: np.ndarray,
    first: np.ndarray,
    bounces: int = EXACT_BOUNCES,
    cancel: Callable[[], bool] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """(first + D2 + ... + D_bounces, D_bounces) from the first bounce's illuminance
    ``first`` (n, m) float32, with D(b+1) = F R D(b) on float32 ``F32``."""
    r = rho.astype(np.float32)[:, None]
    bounce = first
    total = bounce.copy()
    for _ in range(bounces - 1):
        bounce = sparse_dense_product(F32, r * bounce, cancel=cancel)
        total += bounce
    return total, bounce


def zone_basis(exact: np.ndarray, last: np.ndarray, lowrank: LowRank) -> np.ndarray:
    """Phi (n, nz) float32 in Fortran order (so a candidate's columns are contiguous):
    the exact bounces plus the low-rank remainder Y V^T R D_last."""
    n, k = lowrank.n, lowrank.k
    labels = lowrank.labels
    VT = sp.csr_matrix(
        (lowrank.area / lowrank.cluster_area[labels], (labels, np.arange(n))), shape=(k, n)
    ).astype(np.float32)
    r = lowrank.rho.astype(np.float32)[:, None]
    Phi = np.asfortranarray(lowrank.Y @ (VT @ (r * last)))
    Phi += exact
    return Phi
