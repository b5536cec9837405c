"""Building a ``RadiosityOperator`` to a target accuracy, with progress and cancel.

Steps: trace the form factors F once (sparse, O(n * rays) memory, kept in float32),
compute reference solutions for a few sampled emission vectors, then build the
low-rank part at k = n/64 clusters and its transfer G = V^T R D3 of the zone
patches' light (k x nz, from the left: O(nnz(F) k)), and double k until the
measured relative error of C is within ``tol`` (or use the given ``rank``). A scene
without emitter zones keeps the first k: no source the error stands for emits.
Nothing of size n x n or n x nz is ever formed: memory O(nnz(F) + n k + k nz).
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np
import scipy.sparse as sp

from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.memory import available_memory_bytes, format_bytes
from lightinv_core.operator.accuracy import reference_reflected, relative_errors, sample_emissions
from lightinv_core.operator.clustering import cluster_patches
from lightinv_core.operator.distributed import LocalRunner, pieces, runner, trace_piece
from lightinv_core.operator.lowrank import ASSEMBLE_BLOCK, CLUSTER_BLOCK, factor
from lightinv_core.operator.radiosity import RadiosityOperator, zone_part
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.operator.zone_basis import (
    LEFT_BLOCK,
    PRODUCT_PARTS,
    power_weights,
    remainder_transfer,
)
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.formfactors import (
    batch_count,
    form_factor_matrix,
    index_dtype,
    join_rows,
    lost_fraction,
)

OPERATOR_VERSION = 4
"""Bump whenever the operator a given (geometry, settings) produces changes, so older
cache files are seen as stale and rebuilt (2: exact-k clustering; 3: the zone basis
stored as its factors F, Y, G instead of the dense n x nz Phi; 4: Y = W M^-1 summed
256 clusters at a time, the same bits on any number of BLAS threads: above k = 256 the
last bits of Y change)."""
ERROR_SAMPLES = 6
START_DIVISOR = 64
MAX_DIVISOR = 4
USABLE_MEMORY = 0.8
"""Share of the available memory a build may plan to use."""
TRACE_BATCHES_PER_PIECE = 8
"""Ray batches (about 1M rays) per piece of tracing on a cluster."""


def estimate_build_bytes(patches: Patches, rays: int, k: int) -> int:
    """Upper estimate of the peak memory of a build (bytes), taking every traced ray as a
    distinct form-factor entry (nnz <= n * rays): the larger of

    - tracing: each entry's column and value held twice while the batches are joined
      (24 bytes), then the float32 copy beside the float64 F, with a margin (32 bytes
      an entry in all: office at 43,000 patches peaked at 28);
    - building: float32 F and F[:, zone] (8 bytes an entry each), the low-rank factors
      n x k (W, then Y in its place), G (k x nz), the k x k solve in float64 with its
      float64 row blocks, and the dense blocks of the products (2 parts x 3 x 64 rows
      x n) and of the sampled emissions (n x 6, 4 arrays).
    """
    n = patches.n
    nz = int((patches.zone_id >= 0).sum())
    nnz = n * min(rays, n)
    tracing = 32 * nnz
    building = (
        16 * nnz
        + 4 * n * k
        + 4 * k * nz
        + 32 * k * k
        + 8 * k * (2 * ASSEMBLE_BLOCK + CLUSTER_BLOCK)
        + 4 * n * (PRODUCT_PARTS * 3 * LEFT_BLOCK + 4 * ERROR_SAMPLES)
    )
    return int(max(tracing, building))


def _memory_error(patches: Patches, rays: int, k: int, need: int, have: int) -> LightInvError:
    return LightInvError(
        f"building the operator for {patches.n:,} patches with {rays} rays and rank {k} "
        f"needs about {format_bytes(need)} but {format_bytes(have)} is available "
        "(a build may use at most 80% of it); "
        "use a coarser --resolution, fewer --rays or a lower --rank"
    )


def fits_in_memory(patches: Patches, rays: int, k: int) -> bool:
    """Whether a build at rank ``k`` fits in 80% of the available memory."""
    return estimate_build_bytes(patches, rays, k) <= USABLE_MEMORY * available_memory_bytes()


def check_memory(patches: Patches, rays: int, k: int) -> None:
    """Refuse a build that would not fit in available memory, naming the numbers."""
    need = estimate_build_bytes(patches, rays, k)
    have = available_memory_bytes()
    if need > USABLE_MEMORY * have:
        raise _memory_error(patches, rays, k, need, have)


def build_operator(
    patches: Patches,
    settings: OperatorSettings | None = None,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    scheduler: str | None = None,
) -> RadiosityOperator:
    """Trace, factor and measure the radiosity operator of ``patches``.

    ``settings.rank`` fixes k (clusters); otherwise k starts at n/64 and doubles (up to
    n/4, or twice the number of surfaces if more) until the mean relative error of C on
    sampled emissions is <= ``settings.tol``;
    ``settings.rays`` per patch with ray seed ``settings.seed`` (defaults:
    ``OperatorSettings()``). ``progress(fraction)`` is called along the way;
    ``cancel()`` returning True stops the build with ``CancelledError``. ``scheduler``
    (``tcp://host:port``) runs the tracing, the low-rank factors and the zone transfer on
    that Dask cluster (``operator.distributed``): the same operator, bit for bit.
    """
    settings = settings or OperatorSettings()
    rank, tol, rays = settings.rank, settings.tol, settings.rays
    n = patches.n
    if rank is not None and not (1 <= int(rank) <= n):
        raise LightInvError(f"rank must be between 1 and the patch count {n}, got {rank}")
    if rank is None and not (0 < tol < 1):
        raise LightInvError(f"tolerance must be between 0 and 1 (e.g. 0.01 for 1%), got {tol}")
    k = int(rank) if rank is not None else max(1, n // START_DIVISOR)
    # Up to n/4 clusters, or twice the surfaces where a scene has that many (a cluster
    # never spans two surfaces: a coarse mesh of many surfaces starts at one per surface).
    surfaces = len(np.unique(patches.surface_id))
    k_max = int(rank) if rank is not None else min(n, max(k, n // MAX_DIVISOR, 2 * surfaces))
    check_memory(patches, rays, k)
    report = progress or (lambda f: None)

    def check() -> None:
        if cancel is not None and cancel():
            raise CancelledError("operator build cancelled")

    def step(frac: float) -> None:
        check()
        report(frac)

    t0 = time.perf_counter()
    run = runner(scheduler)
    try:
        return _build(patches, settings, k, k_max, run, step, check, cancel, t0)
    finally:
        run.close()


def _trace(patches: Patches, rays: int, seed: int, run, step, cancel) -> sp.csr_matrix:
    """F (float64), traced here on all cores or by pieces of ray batches on a cluster."""
    if isinstance(run, LocalRunner):
        return form_factor_matrix(
            patches, rays, seed=seed, progress=lambda f: step(0.7 * f), cancel=cancel
        )
    n = patches.n
    parts = pieces(batch_count(n, rays), TRACE_BATCHES_PER_PIECE)
    got: list = [None] * len(parts)
    run.map(
        trace_piece,
        parts,
        run.share(patches),
        rays,
        seed,
        on_result=got.__setitem__,
        progress=lambda f: step(0.7 * f),
        cancel=cancel,
    )
    return join_rows([p for part in got for p in part], n, index_dtype(n, rays))


def _build(patches, settings, k, k_max, run, step, check, cancel, t0) -> RadiosityOperator:
    """The steps of ``build_operator`` after its checks, on the runner ``run``."""
    rank, tol, rays, seed = settings.rank, settings.tol, settings.rays, settings.seed
    n = patches.n
    F64 = _trace(patches, rays, seed, run, step, cancel)
    lost = lost_fraction(F64, patches)
    F = F64.astype(np.float32)
    del F64
    t_ff = time.perf_counter() - t0
    zone_patches = np.flatnonzero(patches.zone_id >= 0)
    E = sample_emissions(patches, ERROR_SAMPLES, seed + 1)
    C_ref = reference_reflected(F, patches.rho, E, cancel=cancel)
    Fz = zone_part(F, zone_patches)
    step(0.75)
    tries, memory_limited = [], False
    op = None
    while True:
        t_try = time.perf_counter()
        # Try i spans progress [1 - 0.25 / 2^i, 1 - 0.25 / 2^(i+1)] (0.75-0.875 first).
        lo = 1.0 - 0.25 / 2 ** len(tries)
        span = lo + 0.25 / 2 ** (len(tries) + 1) - lo
        op = None  # the previous try's factors are freed before the next are made
        op = _factor(
            patches,
            F,
            Fz,
            zone_patches,
            k,
            (run, check, cancel),
            lambda f, a=lo, s=span: step(a + s * f),
        )
        err = relative_errors(patches.rho[:, None] * op.illuminance(E), C_ref)
        tries.append(
            {
                "k": op.k,
                "mean_rel_error": float(err.mean()),
                "max_rel_error": float(err.max()),
                "seconds": time.perf_counter() - t_try,
            }
        )
        # Double the clusters actually made: a scene with many small surfaces has more
        # clusters than asked (one per surface at least), and doubling the request would
        # build the same operator again.
        k_next = min(2 * max(k, op.k), k_max)
        # Without emitter zones nothing the error samples stand for emits (the samples
        # are then scattered patches): a higher rank would buy accuracy no source uses,
        # so the first try is kept (the zones drawn later trigger a new build).
        done = rank is not None or not len(zone_patches) or err.mean() <= tol
        done = done or k >= k_max or op.k >= k_max
        if not done and not fits_in_memory(patches, rays, k_next):
            done = memory_limited = True
        if done:
            step(1.0)
            break
        k = k_next
    op.info = {
        "version": OPERATOR_VERSION,
        "n": n,
        "k": op.k,
        "nz": len(zone_patches),
        "rays": rays,
        "seed": seed,
        "rank": rank,
        "tol": tol,
        "estimated_rel_error": tries[-1]["mean_rel_error"],
        "estimated_max_rel_error": tries[-1]["max_rel_error"],
        "tol_met": rank is not None or not len(zone_patches) or tries[-1]["mean_rel_error"] <= tol,
        "memory_limited": memory_limited,
        "tries": tries,
        "formfactor_seconds": t_ff,
        "build_seconds": time.perf_counter() - t0,
        "formfactor_nnz": int(F.nnz),
        "lost_fraction": lost,
        "operator_bytes": op.nbytes(),
        "scheduler": run.address,
    }
    return op


def _factor(
    patches: Patches,
    F: sp.csr_matrix,
    Fz: sp.csr_matrix,
    zone_patches: np.ndarray,
    k: int,
    where: tuple,
    progress: Callable[[float], None],
) -> RadiosityOperator:
    """The operator at (about) k clusters on the traced F: clusters, Y, G, power weights.
    ``where`` is (runner, check, cancel); ``progress`` gets 0-0.3 while Y is made, then
    G's share up to 0.9."""
    run, check, cancel = where
    labels, k_actual = cluster_patches(patches, k)
    check()
    per = run.blocks_per_piece
    lowrank = factor(
        F,
        labels,
        k_actual,
        patches.area,
        patches.rho,
        run,
        lambda f: progress(0.3 * f),
        cancel,
        per,
    )
    G = remainder_transfer(
        F,
        Fz,
        zone_patches,
        lowrank,
        cancel=cancel,
        progress=lambda f: progress(0.3 + 0.6 * f),
        run=run,
        blocks_per_piece=per,
    )
    power = power_weights(F, Fz, zone_patches, lowrank, G)
    progress(0.9)
    return RadiosityOperator(lowrank, zone_patches, F, G, power, patches.digest(), Fz=Fz)
