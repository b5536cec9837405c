"""The low-rank radiosity operator (paper eq. 5-8) and its fast evaluations.

Construction (the original LRR): cluster the patches into k coherent clusters;
W[i, c] = F(i -> cluster c) is the fraction of patch i's rays landing in c, and
V is the area-weighted cluster average, V[j, c] = A_j / A_c for j in c. Then
F ~ W V^T and, with R = diag(rho),

    H = F B ~ W h,   h = V^T B = (I_k - V^T R W)^-1 V^T E,

so the illuminance is ``H = Y z`` with ``Y = W (I_k - V^T R W)^-1`` (n x k) and
``z = V^T E`` (k). The paper's Y_k is ``-R Y``: its reflected radiosity
``C = B - E = -Y_k z = rho * H``. Keeping Y for H (not C) gives illuminance on
black (rho = 0) patches too.

Units: E, B, C in lm/m² (exitance), H in lux, powers in lm.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from lightinv_core.errors import CancelledError, LightInvError

CLUSTER_BLOCK = 1024
"""Rows of F tallied by cluster at once (float64 scratch: rows x k)."""
ASSEMBLE_BLOCK = 2048
"""Rows of W summed per cluster at once (float64 scratch: rows x k)."""
INNER_BLOCK = 256
"""Clusters summed by one float32 product in ``times_inverse``. OpenBLAS sums an inner
dimension longer than its block (``GEMM_Q``: 320 to 448 on x86-64 since Haswell, 352 and
more on ARMv8) in parts cut one way on one thread and another on several, so the last
bits of Y depended on the BLAS threads of whoever computed it (office at k = 587: 278,105
of 1,706,996 entries differed between this process, two threads, and a Dask worker, one).
Kept (the same cut on every machine) now that each block runs on one BLAS thread."""


@dataclass(eq=False)
class LowRank:
    """The cluster low-rank factorisation: ``H ~ Y @ (V^T E)`` for any emission E.

    Attributes
    ----------
    Y : (n, k) float32, lux per unit of cluster-average exitance
    labels : (n,) int32, cluster of each patch
    area, rho : (n,) float64, patch areas (m²) and reflectances
    cluster_area : (k,) float64, m²
    """

    Y: np.ndarray
    labels: np.ndarray
    area: np.ndarray
    rho: np.ndarray
    cluster_area: np.ndarray

    @property
    def n(self) -> int:
        """Number of patches."""
        return self.Y.shape[0]

    @property
    def k(self) -> int:
        """Rank (number of clusters)."""
        return self.Y.shape[1]

    def project_sparse(self, idx: np.ndarray, values: np.ndarray) -> np.ndarray:
        """z = V^T E touching only the emitting patches ``idx`` with exitances ``values``
        ((p,) or (p, m)); cost O(p), not O(n)."""
        idx = np.asarray(idx, dtype=np.int64)
        values = np.asarray(values, dtype=np.float64)
        lab = self.labels[idx]
        w = self.area[idx] / self.cluster_area[lab]
        if values.ndim == 1:
            return np.bincount(lab, weights=w * values, minlength=self.k)
        z = np.zeros((self.k, values.shape[1]))
        np.add.at(z, lab, w[:, None] * values)
        return z

    def illuminance(self, z: np.ndarray) -> np.ndarray:
        """H = Y z, lux: (n,) for z (k,), (n, m) for a batch z (k, m) in one GEMM."""
        return self.Y @ np.asarray(z, dtype=np.float32)


def cluster_form_factors(
    F: sp.csr_matrix, labels: np.ndarray, k: int, block: int | None = None
) -> np.ndarray:
    """W[i, c] = sum_{j in c} F_ij as a dense (n, k) float32 array, built in row blocks
    so the float64 scratch stays at ``block * k`` values."""
    n = F.shape[0]
    block = block or CLUSTER_BLOCK
    W = np.empty((n, k), np.float32)
    for start in range(0, n, block):
        part = F[start : start + block]
        rows = np.repeat(np.arange(part.shape[0]), np.diff(part.indptr))
        flat = rows * k + labels[part.indices]
        W[start : start + part.shape[0]] = np.bincount(
            flat, weights=part.data, minlength=part.shape[0] * k
        ).reshape(-1, k)
    return W


def cluster_weights(
    labels: np.ndarray, area: np.ndarray, rho: np.ndarray, k: int
) -> tuple[np.ndarray, np.ndarray]:
    """(cluster areas (k,) m², each patch's weight A_i rho_i / A_c in V^T R)."""
    cluster_area = np.bincount(labels, weights=area, minlength=k)
    if np.any(cluster_area <= 0):
        raise LightInvError("every cluster needs at least one patch")
    return cluster_area, area / cluster_area[labels] * rho


def cluster_sums(
    W_rows: np.ndarray, labels_rows: np.ndarray, weight_rows: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(cluster ids, float64 sums) of weight * W over a block of rows, per cluster: the
    block's share of V^T R W."""
    order = np.argsort(labels_rows, kind="stable")
    lab = labels_rows[order]
    starts = np.flatnonzero(np.r_[True, lab[1:] != lab[:-1]])
    part = weight_rows[order, None] * W_rows[order].astype(np.float64)
    return lab[starts], np.add.reduceat(part, starts, axis=0)


def _blocks(a: int, b: int, size: int) -> list[tuple[int, int]]:
    return [(s, min(b, s + size)) for s in range(a, b, size)]


def cluster_piece(
    rows: range, F: sp.csr_matrix, labels: np.ndarray, weight: np.ndarray, k: int
) -> tuple[np.ndarray, list[tuple[np.ndarray, np.ndarray]]]:
    """W over ``rows`` (a multiple of ``ASSEMBLE_BLOCK`` from a block start) and the
    cluster sums of each of its ``ASSEMBLE_BLOCK`` row blocks: one piece of a build."""
    a, b = rows.start, rows.stop
    W = cluster_form_factors(F[a:b], labels, k)
    sums = [
        cluster_sums(W[s - a : e - a], labels[s:e], weight[s:e])
        for s, e in _blocks(a, b, ASSEMBLE_BLOCK)
    ]
    return W, sums


def times_inverse(W_rows: np.ndarray, Minv: np.ndarray) -> np.ndarray:
    """W_rows @ Minv (float32) by ``ASSEMBLE_BLOCK`` row blocks: rows of Y. Each block is
    summed over ``INNER_BLOCK`` clusters at a time, the parts added in order, on one
    BLAS thread (the blocks run side by side on as many threads as the BLAS had), so its
    bits do not depend on the BLAS threads nor on where the piece runs: OpenBLAS 0.3.31
    rounds a row differently with the threads it is given and with the rows computed
    beside it (on this machine's Haswell kernels 2-15% of the entries of a product
    changed with the threads, even over 40 clusters), but one block on one thread is
    the same product everywhere."""
    from concurrent.futures import ThreadPoolExecutor

    from threadpoolctl import threadpool_info, threadpool_limits

    k = Minv.shape[0]
    out = np.empty((W_rows.shape[0], Minv.shape[1]), np.float32)

    def block(rows: tuple[int, int]) -> None:
        s, e = rows
        np.matmul(W_rows[s:e, :INNER_BLOCK], Minv[:INNER_BLOCK], out=out[s:e])
        for a, b in _blocks(INNER_BLOCK, k, INNER_BLOCK):
            out[s:e] += W_rows[s:e, a:b] @ Minv[a:b]

    rows = list(_blocks(0, W_rows.shape[0], ASSEMBLE_BLOCK))
    blas = [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]
    threads = max(blas, default=1)
    with threadpool_limits(limits=1, user_api="blas"):
        if threads > 1 and len(rows) > 1:
            with ThreadPoolExecutor(min(threads, len(rows))) as pool:
                list(pool.map(block, rows))  # numpy's products release the GIL
        else:
            for r in rows:
                block(r)
    return out


def factor(
    F: sp.csr_matrix,
    labels: np.ndarray,
    k: int,
    area: np.ndarray,
    rho: np.ndarray,
    run=None,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    blocks_per_piece: int = 1,
) -> LowRank:
    """The low-rank factors on the traced F: W by row pieces (with their cluster sums
    M = I - V^T R W, added in row order), M^-1, then Y = W M^-1 by row pieces written
    over W. ``run`` (``operator.distributed``; default here) runs the pieces; the same
    pieces anywhere give the same Y bit for bit. ``progress`` gets 0-1."""
    from lightinv_core.operator.distributed import LocalRunner, pieces

    run = run or LocalRunner()
    n = F.shape[0]
    cluster_area, weight = cluster_weights(labels, area, rho, k)
    W = np.empty((n, k), np.float32)
    M = np.eye(k)
    row_pieces = pieces(n, ASSEMBLE_BLOCK * blocks_per_piece)

    def put(i: int, got) -> None:
        r = row_pieces[i]
        W[r.start : r.stop] = got[0]
        for ids, sums in got[1]:
            M[ids] -= sums

    shared = [run.share(x) for x in (F, labels, weight)]
    run.map(
        cluster_piece,
        row_pieces,
        *shared,
        k,
        on_result=put,
        progress=None if progress is None else lambda f: progress(0.6 * f),
        cancel=cancel,
    )
    _check(cancel)
    Minv = run.share(la.inv(M).astype(np.float32))

    def put_y(i: int, got: np.ndarray) -> None:
        r = row_pieces[i]
        W[r.start : r.stop] = got

    run.map(
        times_inverse,
        [W[r.start : r.stop] for r in row_pieces],
        Minv,
        on_result=put_y,
        progress=None if progress is None else lambda f: progress(0.6 + 0.4 * f),
        cancel=cancel,
    )
    return LowRank(
        Y=W,
        labels=labels.astype(np.int32),
        area=area.astype(np.float64),
        rho=rho.astype(np.float64),
        cluster_area=cluster_area,
    )


def assemble(
    W: np.ndarray,
    labels: np.ndarray,
    area: np.ndarray,
    rho: np.ndarray,
    cancel: Callable[[], bool] | None = None,
) -> LowRank:
    """Y = W (I_k - V^T R W)^-1 from the cluster form factors W (n, k) float32, by the
    same row blocks as ``factor``; Y is written over W (its buffer is reused), so the
    build holds one (n, k) array, not three. ``cancel()`` is polled between blocks."""
    n, k = W.shape
    cluster_area, weight = cluster_weights(labels, area, rho, k)
    M = np.eye(k)
    for s, e in _blocks(0, n, ASSEMBLE_BLOCK):
        _check(cancel)
        ids, sums = cluster_sums(W[s:e], labels[s:e], weight[s:e])
        M[ids] -= sums
    Minv = la.inv(M).astype(np.float32)
    for s, e in _blocks(0, n, ASSEMBLE_BLOCK):
        _check(cancel)
        W[s:e] = times_inverse(W[s:e], Minv)
    return LowRank(
        Y=W,
        labels=labels.astype(np.int32),
        area=area.astype(np.float64),
        rho=rho.astype(np.float64),
        cluster_area=cluster_area,
    )


def _check(cancel: Callable[[], bool] | None) -> None:
    if cancel is not None and cancel():
        raise CancelledError("operator build cancelled")
