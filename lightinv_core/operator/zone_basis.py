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
        out[cuts[q] : cuts[q + 1]] = _row_view(A, cuts[q], cuts[q + 1]) @ X

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


# -- the factored basis: Phi is never formed whole --------------------------------------------
#
# Phi = S + Y G with S = D1 + D2 + D3 (exact bounces) and G = V^T R D3 (k x nz). A row block
# of S (or of G, whose rows are the cluster averages V^T R) is computed from the left:
# X = L F, then X <- (X R) F, and the last step (X R) F[:, zone]; a column block (or a batch
# of emissions) from the right by ``more_bounces``. From the left costs O(nnz(F)) per row,
# from the right O(nnz(F)) per zone patch, so p rows are read from the side that is smaller.

BLOCK_BYTES = 128 << 20
"""Bytes of one dense float32 block (rows x patches) of the blocked products."""
PRODUCT_PARTS = 2
"""Fixed split of a dense-by-sparse product (threads add their parts in a fixed order, so
the result does not depend on the number of cores)."""
RUN_GAP = 512
"""Rows of F: reached columns closer than this are read as one run (``dense_sparse_product``)."""


LEFT_BLOCK = 64
"""Rows of a block read from the left: each product then takes about 0.2 s on patio (a
cancel is heard within that), and the dense scratch stays at 64 x n values."""


def block_rows(n: int, arrays: int = 3) -> int:
    """Rows (or columns) per dense block so ``arrays`` blocks of n float32 fit ``BLOCK_BYTES``."""
    return max(8, BLOCK_BYTES // max(1, 4 * n * arrays))


def _row_view(A: sp.csr_matrix, a: int, b: int) -> sp.csr_matrix:
    """Rows a:b of CSR ``A`` sharing its data and indices (scipy's slicing copies them)."""
    lo, hi = int(A.indptr[a]), int(A.indptr[b])
    return sp.csr_matrix(
        (A.data[lo:hi], A.indices[lo:hi], A.indptr[a : b + 1] - lo), shape=(b - a, A.shape[1])
    )


def dense_sparse_product(X: np.ndarray, A: sp.csr_matrix, workers: int | None = None) -> np.ndarray:
    """X @ A for dense X (b, n) and CSR A (n, N): only the rows of A under X's nonzero
    columns are read, as runs of neighbouring rows (light leaving one room of a building
    reaches few of its patches), in ``PRODUCT_PARTS`` fixed parts added in order."""
    reach = np.flatnonzero(np.any(X != 0, axis=0))
    out_shape = (X.shape[0], A.shape[1])
    if len(reach) == 0:
        return np.zeros(out_shape, np.result_type(X.dtype, A.dtype))
    breaks = np.flatnonzero(np.diff(reach) > RUN_GAP) + 1
    runs = [(int(r[0]), int(r[-1]) + 1) for r in np.split(reach, breaks)]
    # Split the runs into parts of about equal row counts (fixed for a given X).
    sizes = np.cumsum([b - a for a, b in runs])
    part_of = np.minimum(PRODUCT_PARTS - 1, (PRODUCT_PARTS * (sizes - 1)) // sizes[-1])

    def part(q: int) -> np.ndarray | None:
        acc = None
        for (a, b), p in zip(runs, part_of, strict=True):
            if p != q:
                continue
            term = np.asarray(X[:, a:b] @ _row_view(A, a, b))
            acc = term if acc is None else acc + term
        return acc

    threads = min(PRODUCT_PARTS, workers or default_workers())
    if threads > 1:
        with ThreadPoolExecutor(max_workers=threads) as pool:
            parts = list(pool.map(part, range(PRODUCT_PARTS)))
    else:
        parts = [part(q) for q in range(PRODUCT_PARTS)]
    out = None
    for p in parts:
        if p is not None:
            out = p if out is None else out + p
    return out.reshape(out_shape)


def left_bounces(
    XF: np.ndarray,
    F: sp.csr_matrix,
    Fz: sp.csr_matrix,
    zone_patches: np.ndarray,
    rho: np.ndarray,
    bounces: int = EXACT_BOUNCES,
    workers: int | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """(sum_b L D_b, L D_bounces) for left vectors L given as ``XF`` = L F (b, n): the rows
    of the exact bounces seen through L (L = patch selectors gives rows of D1 + D2 + D3,
    L = V^T R the low-rank transfer, L = (A rho)^T the power weights). ``Fz`` is
    F[:, zone_patches] (CSR) and ``rho`` (n,) the reflectances in XF's dtype."""
    X = XF
    last = X[:, zone_patches]
    total = last.copy()
    for b in range(2, bounces + 1):
        X = X * rho
        if b == bounces:
            last = dense_sparse_product(X, Fz, workers)
        else:
            X = dense_sparse_product(X, F, workers)
            last = X[:, zone_patches]
        total += last
    return total, last


def cluster_rows(lowrank: LowRank) -> sp.csr_matrix:
    """V^T R (k, n) float32 CSR: each cluster's area-weighted average of reflected light."""
    n, labels = lowrank.n, lowrank.labels
    w = lowrank.area / lowrank.cluster_area[labels] * lowrank.rho
    return sp.csr_matrix((w.astype(np.float32), (labels, np.arange(n))), shape=(lowrank.k, n))


def transfer_block(n: int) -> int:
    """Clusters per block of G (fixed for a scene: the same blocks wherever they run)."""
    return min(LEFT_BLOCK, block_rows(n))


def transfer_piece(
    clusters: range,
    F: sp.csr_matrix,
    Fz: sp.csr_matrix,
    zone_patches: np.ndarray,
    VTR: sp.csr_matrix,
    rho: np.ndarray,
    bounces: int = EXACT_BOUNCES,
) -> np.ndarray:
    """Rows ``clusters`` of G (a range starting on a block), block by block of
    ``transfer_block(n)`` clusters: one piece of a build. ``VTR`` is V^T R (k, n) and
    ``rho`` the reflectances in float32."""
    step = transfer_block(F.shape[0])
    out = np.empty((len(clusters), len(zone_patches)), np.float32)
    for a in range(clusters.start, clusters.stop, step):
        b = min(clusters.stop, a + step)
        XF = (VTR[a:b] @ F).toarray()
        rows = slice(a - clusters.start, b - clusters.start)
        out[rows] = left_bounces(XF, F, Fz, zone_patches, rho, bounces)[1]
    return out


def remainder_transfer(
    F: sp.csr_matrix,
    Fz: sp.csr_matrix,
    zone_patches: np.ndarray,
    lowrank: LowRank,
    bounces: int = EXACT_BOUNCES,
    cancel: Callable[[], bool] | None = None,
    progress: Callable[[float], None] | None = None,
    run=None,
    blocks_per_piece: int = 1,
) -> np.ndarray:
    """G = V^T R D_bounces (k, nz) float32: the light of each zone patch after the exact
    bounces, averaged per cluster, which the low-rank part carries on (Phi = S + Y G).
    Computed from the left in blocks of clusters, so no (n, nz) array is ever formed;
    ``run`` (``operator.distributed``; default here) runs the pieces of
    ``blocks_per_piece`` blocks. ``cancel()`` is polled and ``progress(fraction)`` called
    between pieces."""
    from lightinv_core.operator.distributed import LocalRunner, pieces

    run = run or LocalRunner()
    k, nz = lowrank.k, len(zone_patches)
    parts = pieces(k, transfer_block(F.shape[0]) * blocks_per_piece)
    G = np.empty((k, nz), np.float32)

    def put(i: int, rows: np.ndarray) -> None:
        G[parts[i].start : parts[i].stop] = rows

    rho = lowrank.rho.astype(np.float32)
    shared = [run.share(x) for x in (F, Fz, zone_patches, cluster_rows(lowrank), rho)]
    run.map(
        transfer_piece,
        parts,
        *shared,
        bounces,
        on_result=put,
        progress=progress,
        cancel=cancel,
    )
    return G


def power_weights(
    F: sp.csr_matrix,
    Fz: sp.csr_matrix,
    zone_patches: np.ndarray,
    lowrank: LowRank,
    G: np.ndarray,
    bounces: int = EXACT_BOUNCES,
) -> np.ndarray:
    """(A rho)^T Phi (nz,) float64: reflected light power (lm) per unit exitance (lm/m²)
    of each zone patch, from the left (one row) and the low-rank part's (A rho)^T Y."""
    w = lowrank.area * lowrank.rho
    # float32 products: each entry sums one column of F (hundreds of terms), not n.
    XF = dense_sparse_product(w[None].astype(np.float32), F)
    rho = lowrank.rho.astype(np.float32)
    exact = left_bounces(XF, F, Fz, zone_patches, rho, bounces)[0][0].astype(np.float64)
    wY = sum(w[a:b] @ lowrank.Y[a:b].astype(np.float64) for a, b in _blocks(lowrank.n, 1 << 14))
    return exact + wY @ G.astype(np.float64)


def _blocks(n: int, size: int) -> list[tuple[int, int]]:
    return [(a, min(n, a + size)) for a in range(0, n, size)]
