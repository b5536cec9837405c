"""Building a ``RadiosityOperator`` to a target accuracy, with progress and cancel.

Steps: trace the form factors F once (sparse, O(n * rays) memory), compute
reference solutions for a few sampled emission vectors and the exact bounces
of the zone basis, then build the low-rank part at k = n/64 clusters and
double k until the measured relative error of C is within ``tol`` (or use the
given ``rank``). Nothing of size n x n is ever formed.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.memory import available_memory_bytes, format_bytes
from lightinv_core.operator.accuracy import reference_reflected, relative_errors, sample_emissions
from lightinv_core.operator.clustering import cluster_patches
from lightinv_core.operator.lowrank import assemble, cluster_form_factors
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.operator.zone_basis import exact_bounces, zone_basis
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.formfactors import (
    form_factor_matrix,
    formfactor_bytes,
    lost_fraction,
)

OPERATOR_VERSION = 2
"""Bump whenever the operator a given (geometry, settings) produces changes, so older
cache files are seen as stale and rebuilt (2: exact-k clustering)."""
ERROR_SAMPLES = 6
START_DIVISOR = 64
MAX_DIVISOR = 4


def estimate_build_bytes(patches: Patches, rays: int, k: int) -> int:
    """Upper estimate of the peak memory of a build (bytes): sparse F, the n x k
    low-rank factors, the n x nz zone basis and its float64 scratch."""
    n = patches.n
    nz = int((patches.zone_id >= 0).sum())
    f_bytes = formfactor_bytes(n, rays)
    lowrank = 3 * 4 * n * k
    zone = (4 + 8 + 8) * n * nz
    return int(f_bytes + lowrank + zone)


def check_memory(patches: Patches, rays: int, k: int) -> None:
    """Refuse a build that would not fit in available memory, naming the numbers."""
    need = estimate_build_bytes(patches, rays, k)
    have = available_memory_bytes()
    if need > 0.8 * have:
        raise LightInvError(
            f"building the operator for {patches.n:,} patches with {rays} rays and rank {k} "
            f"needs about {format_bytes(need)} but {format_bytes(have)} is available "
            "(a build may use at most 80% of it); "
            "use a coarser --resolution, fewer --rays or a lower --rank"
        )


def build_operator(
    patches: Patches,
    settings: OperatorSettings | None = None,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
) -> RadiosityOperator:
    """Trace, factor and measure the radiosity operator of ``patches``.

    ``settings.rank`` fixes k (clusters); otherwise k starts at n/64 and doubles (up to
    n/4) until the mean relative error of C on sampled emissions is <= ``settings.tol``;
    ``settings.rays`` per patch with ray seed ``settings.seed`` (defaults:
    ``OperatorSettings()``). ``progress(fraction)`` is called along the way;
    ``cancel()`` returning True stops the build with ``CancelledError``.
    """
    settings = settings or OperatorSettings()
    rank, tol, rays, seed = settings.rank, settings.tol, settings.rays, settings.seed
    n = patches.n
    if rank is not None and not (1 <= int(rank) <= n):
        raise LightInvError(f"rank must be between 1 and the patch count {n}, got {rank}")
    if rank is None and not (0 < tol < 1):
        raise LightInvError(f"tolerance must be between 0 and 1 (e.g. 0.01 for 1%), got {tol}")
    k = int(rank) if rank is not None else max(1, n // START_DIVISOR)
    k_max = int(rank) if rank is not None else max(k, n // MAX_DIVISOR)
    check_memory(patches, rays, k)
    report = progress or (lambda f: None)

    def check() -> None:
        if cancel is not None and cancel():
            raise CancelledError("operator build cancelled")

    def step(frac: float) -> None:
        check()
        report(frac)

    t0 = time.perf_counter()
    F = form_factor_matrix(
        patches, rays, seed=seed, progress=lambda f: step(0.7 * f), cancel=cancel
    )
    t_ff = time.perf_counter() - t0
    zone_patches = np.flatnonzero(patches.zone_id >= 0)
    E = sample_emissions(patches, ERROR_SAMPLES, seed + 1)
    C_ref = reference_reflected(F, patches.rho, E, cancel=cancel)
    step(0.75)
    exact, last = exact_bounces(F, patches.rho, zone_patches, cancel=cancel)
    step(0.85)
    tries = []
    while True:
        labels, k_actual = cluster_patches(patches, k)
        check()
        lowrank = assemble(
            cluster_form_factors(F, labels, k_actual), labels, patches.area, patches.rho
        )
        check()
        Phi = zone_basis(exact, last, lowrank)
        check()
        op = RadiosityOperator(lowrank, zone_patches, Phi, patches.digest())
        err = relative_errors(patches.rho[:, None] * op.illuminance(E), C_ref)
        tries.append(
            {"k": k_actual, "mean_rel_error": float(err.mean()), "max_rel_error": float(err.max())}
        )
        done = rank is not None or err.mean() <= tol or k >= k_max
        step(0.85 + 0.15 * (1.0 if done else min(0.9, len(tries) / 4)))
        if done:
            break
        k = min(2 * k, k_max)
        check_memory(patches, rays, k)
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
        "tol_met": rank is not None or tries[-1]["mean_rel_error"] <= tol,
        "tries": tries,
        "formfactor_seconds": t_ff,
        "build_seconds": time.perf_counter() - t0,
        "formfactor_nnz": int(F.nnz),
        "lost_fraction": lost_fraction(F, patches),
    }
    return op
