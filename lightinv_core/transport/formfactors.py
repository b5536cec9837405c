"""Form factors F_ij by cosine-weighted stratified ray casting.

F_ij is the fraction of the light leaving patch i (uniform, Lambertian) that
arrives at patch j. Row i is estimated from ``rays_per_patch`` rays leaving
patch i: F_ij ~ (rays hitting j) / rays_per_patch. Rows are traced in batches
on a thread pool (Embree releases the GIL), each batch with its own random
stream derived from (seed, batch index), so the result is bit-for-bit the same
for a given seed whatever the thread scheduling.
"""

from __future__ import annotations

import os
from collections import deque
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.memory import available_memory_bytes, format_bytes
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.raycast import RayCaster, sample_rays

RAYS_PER_BATCH = 1 << 17
DEFAULT_RAYS = 1024
MAX_RAYS = 65_536
"""Rays per patch; 64 times the default, beyond any accuracy a design needs (the
error falls as 1/sqrt(rays)), and far from the sizes that overflow memory."""

ProgressFn = Callable[[float], None]
CancelFn = Callable[[], bool]


def default_workers() -> int:
    """Worker threads for ray casting: one per core available to this process."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - non-Linux
        return max(1, os.cpu_count() or 1)


@dataclass(frozen=True)
class RowHits:
    """The rays of one batch of rows: ``hits[r, q]`` is the patch hit by ray q of
    row ``rows[r]``, or -1 (lost)."""

    rows: np.ndarray
    hits: np.ndarray


def _check_rays(rays_per_patch: int) -> int:
    r = int(rays_per_patch)
    if not 1 <= r <= MAX_RAYS or r != rays_per_patch:
        raise LightInvError(
            f"rays per patch must be a whole number from 1 to {MAX_RAYS:,}, got {rays_per_patch!r}"
        )
    return r


def rows_per_batch(rays_per_patch: int) -> int:
    """Rows traced in one batch (about ``RAYS_PER_BATCH`` rays): batch b holds rows
    ``b * rows_per_batch`` onwards and draws its rays from (seed, b)."""
    return max(1, RAYS_PER_BATCH // _check_rays(rays_per_patch))


def trace_batch(
    patches: Patches, caster: RayCaster, rows: np.ndarray, count: int, seed: int, batch: int
) -> RowHits:
    """The rays of batch number ``batch`` (rows ``rows``, ``count`` rays each) from the
    random stream (seed, batch): the same hits on any machine, thread or process."""
    rng = np.random.default_rng([seed, batch])
    o, d = sample_rays(patches, rows, count, rng, caster.offset)
    return RowHits(rows, caster.hit_patches(o, d).reshape(len(rows), count))


def batch_entries(batch: RowHits, n: int, index: type = np.int32) -> FormFactorRows:
    """The CSR entries of a batch's rows: (entries per row, columns, values)."""
    local = np.repeat(np.arange(len(batch.rows)), batch.hits.shape[1])
    flat = batch.hits.ravel()
    ok = flat >= 0
    keys = local[ok].astype(np.int64) * n + flat[ok]
    uniq, counts = np.unique(keys, return_counts=True)
    r, c = np.divmod(uniq, n)
    return FormFactorRows(
        np.bincount(r, minlength=len(batch.rows)), c.astype(index), counts / batch.hits.shape[1]
    )


@dataclass(frozen=True)
class FormFactorRows:
    """Consecutive rows of F in CSR pieces: entries per row, their columns and values."""

    counts: np.ndarray
    cols: np.ndarray
    vals: np.ndarray


def index_dtype(n: int, rays_per_patch: int) -> type:
    """Index type of F's CSR arrays: int32 while n * rays fits."""
    return np.int32 if n * _check_rays(rays_per_patch) < 2**31 - 1 else np.int64


def join_rows(pieces: list[FormFactorRows], n: int, index: type) -> sp.csr_matrix:
    """F (n x n, float64 CSR) from its row pieces in row order."""
    # Pieces come in row order and each is sorted by (row, column), so the CSR arrays are
    # just the pieces concatenated: no sort of all of F at the end (seconds on large
    # scenes, during which a cancel would go unheard).
    indptr = np.zeros(n + 1, np.int64)
    if pieces:
        np.cumsum(np.concatenate([p.counts for p in pieces]), out=indptr[1:])
    cols = np.concatenate([p.cols for p in pieces]) if pieces else np.zeros(0, index)
    vals = np.concatenate([p.vals for p in pieces]) if pieces else np.zeros(0)
    return sp.csr_matrix((vals, cols, indptr.astype(index)), shape=(n, n))


def trace_rows(
    patches: Patches,
    rays_per_patch: int = DEFAULT_RAYS,
    seed: int = 0,
    rows: np.ndarray | None = None,
    workers: int | None = None,
    progress: ProgressFn | None = None,
    cancel: CancelFn | None = None,
    caster: RayCaster | None = None,
) -> Iterator[RowHits]:
    """Trace ``rays_per_patch`` rays from each patch in ``rows`` (default all), in order.

    Yields one ``RowHits`` per batch of about ``RAYS_PER_BATCH`` rays. ``progress``
    gets the fraction of rows done; if ``cancel()`` turns True the pool is shut
    down and ``CancelledError`` raised. At most ``2 * workers`` batches are held
    in memory at once.
    """
    count = _check_rays(rays_per_patch)
    rows = np.arange(patches.n) if rows is None else np.asarray(rows, dtype=np.int64)
    caster = caster or RayCaster(patches)
    per_batch = rows_per_batch(count)
    starts = range(0, len(rows), per_batch)
    workers = workers or default_workers()

    def run(k: int, start: int) -> RowHits:
        return trace_batch(patches, caster, rows[start : start + per_batch], count, seed, k)

    done = 0
    with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="lightinv-rays") as pool:
        pending: deque = deque()
        jobs = iter(enumerate(starts))
        try:
            for k, start in jobs:
                pending.append(pool.submit(run, k, start))
                if len(pending) >= 2 * workers:
                    break
            while pending:
                if cancel is not None and cancel():
                    raise CancelledError("form-factor computation cancelled")
                result = pending.popleft().result()
                nxt = next(jobs, None)
                if nxt is not None:
                    pending.append(pool.submit(run, *nxt))
                done += len(result.rows)
                if progress is not None:
                    progress(done / max(1, len(rows)))
                yield result
        finally:
            for f in pending:
                f.cancel()


def form_factor_matrix(
    patches: Patches,
    rays_per_patch: int = DEFAULT_RAYS,
    seed: int = 0,
    workers: int | None = None,
    progress: ProgressFn | None = None,
    cancel: CancelFn | None = None,
    caster: RayCaster | None = None,
) -> sp.csr_matrix:
    """The sparse form-factor matrix F (n x n, float64, row i = patch i's view);
    ``caster`` reuses a RayCaster of the same patches.

    Memory grows with the number of distinct (i, j) pairs hit, at most
    n * rays_per_patch; use the low-rank operator for large scenes instead of F.
    """
    n = patches.n
    index = index_dtype(n, rays_per_patch)
    pieces = [
        batch_entries(batch, n, index)
        for batch in trace_rows(
            patches,
            rays_per_patch,
            seed,
            workers=workers,
            progress=progress,
            cancel=cancel,
            caster=caster,
        )
    ]
    if cancel is not None and cancel():
        raise CancelledError("form-factor computation cancelled")
    return join_rows(pieces, n, index)


def batch_count(n: int, rays_per_patch: int) -> int:
    """Number of ray batches over all n rows."""
    return -(-n // rows_per_batch(rays_per_patch))


def trace_pieces(
    patches: Patches,
    rays_per_patch: int,
    seed: int,
    batches: range,
    caster: RayCaster | None = None,
) -> list[FormFactorRows]:
    """The rows of F of batch numbers ``batches`` (over all rows, as ``trace_rows``
    numbers them): a share of the tracing for another process or machine, giving the
    same entries as the local trace."""
    count = _check_rays(rays_per_patch)
    caster = caster or RayCaster(patches)
    per_batch, n = rows_per_batch(count), patches.n
    index = index_dtype(n, count)
    out = []
    for b in batches:
        rows = np.arange(b * per_batch, min(n, (b + 1) * per_batch))
        out.append(batch_entries(trace_batch(patches, caster, rows, count, seed, b), n, index))
    return out


def formfactor_bytes(n: int, rays: int) -> int:
    """Upper estimate of the peak memory of ``form_factor_matrix`` (bytes): every ray
    of every row a distinct entry, each a column index and a value, held twice while
    the CSR arrays are joined."""
    return 16 * n * min(rays, n)


def check_formfactor_memory(patches: Patches, rays: int) -> None:
    """Refuse form factors that would not fit in 80% of the memory available."""
    need, have = formfactor_bytes(patches.n, rays), available_memory_bytes()
    if need > 0.8 * have:
        raise LightInvError(
            f"the form factors of {patches.n:,} patches with {rays:,} rays per patch need up "
            f"to {format_bytes(need)} but {format_bytes(have)} is available (at most 80% "
            "may be used); use the low-rank method (--method lrr), a coarser --resolution "
            "or fewer --rays"
        )


OPEN_MODEL = 0.01
"""Lost fraction above which the light escaping the model is worth a warning."""


def escape_warning(lost: float) -> str | None:
    """A warning when more than 1% of the light leaving the surfaces escapes the model
    (an open room, or faces turned the wrong way), else None."""
    if not lost > OPEN_MODEL:
        return None
    return (
        f"{100 * lost:.1f}% of the light leaving the surfaces escapes the model: the room "
        "is open or some faces face away from it (lighting will be too dark there)"
    )


def lost_fraction(F: sp.spmatrix, patches: Patches) -> float:
    """Fraction of the light leaving the surfaces that hits nothing (or a back face):
    0 for a closed room, the escaping share for an open model.

    Each patch's lost share (1 - its row sum) is weighed by the light it can receive:
    the flux reaching it when every patch leaves 1 lm/m² (``F^T A``, by reciprocity).
    A face no light reaches, such as the floor under a closed desk box or the box's
    bottom lying on it, lights nothing and is not an opening, though its rays meet
    the back of the box or leave through the floor. When no light reaches any face
    (every face looks away), the patches weigh by their area: all of it escapes."""
    area = patches.area
    lost = 1.0 - np.asarray(F.sum(axis=1)).ravel()
    received = np.asarray(F.T @ area).ravel()
    if received.sum() <= 1e-9 * area.sum():
        return float(np.dot(area, lost) / area.sum())
    return float(np.dot(received, lost) / received.sum())


def reciprocal_column(F: sp.spmatrix, patches: Patches, j: int) -> np.ndarray:
    """Column j of F from row j by reciprocity: F_ij = A_j F_ji / A_i."""
    row = np.asarray(F.getrow(j).todense()).ravel()
    return patches.area[j] * row / patches.area
