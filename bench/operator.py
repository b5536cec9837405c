"""Benchmark: build the radiosity operator of a built-in scene and time its evaluations.

Prints one JSON object. Candidates are what the optimizer evaluates: one random
rectangle (2-20% of a random emitter zone) per candidate at 1,000 lm/m². "full" is the
light on every patch, made from the operator's factors (sparse products over F);
"full_rows" the same through Phi's rows for every patch, made once (what a light model
keeps when they fit, and what an intention on every patch reads); the optimiser reads
"partial" (Phi's rows at p patches, made once).

    python bench/operator.py --scene patio --json
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time

import numpy as np

from lightinv_core.cli import peak_rss_mb
from lightinv_core.operator.accuracy import (
    reference_reflected,
    relative_errors,
    sample_emissions,
)
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.scene.zone_grid import random_zone_emissions


def batch_matrix(op, cands) -> tuple[np.ndarray, np.ndarray]:
    """Union of the candidates' zone patches and their (union, m) exitance matrix."""
    idx = np.unique(np.concatenate([c[0] for c in cands]))
    pos = {int(j): q for q, j in enumerate(idx)}
    V = np.zeros((len(idx), len(cands)), np.float32)
    for m, (ci, cv) in enumerate(cands):
        V[[pos[int(j)] for j in ci], m] = cv
    return idx, V


def rate(fn, per_call: int, repeat: int = 5, min_time: float = 0.2) -> float:
    """Median evaluations per second of ``fn`` (which does ``per_call`` evaluations)."""
    rates = []
    for _ in range(repeat):
        calls, t0 = 0, time.perf_counter()
        while True:
            fn()
            calls += 1
            dt = time.perf_counter() - t0
            if dt >= min_time:
                break
        rates.append(calls * per_call / dt)
    return statistics.median(rates)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="patio")
    ap.add_argument("--resolution", type=float, default=None)
    ap.add_argument("--rank", type=int, default=None)
    ap.add_argument("--tol", type=float, default=0.01)
    ap.add_argument("--batch", type=int, default=256)
    ap.add_argument("--json", action="store_true", help="(default) print JSON")
    args = ap.parse_args()

    patches = mesh_patches(builtin_scene(args.scene, args.resolution))
    t0 = time.perf_counter()
    op = build_operator(patches, OperatorSettings(rank=args.rank, tol=args.tol))
    build = time.perf_counter() - t0
    rss_build = peak_rss_mb()
    n, b = patches.n, args.batch
    cands = random_zone_emissions(patches, 4 * b, seed=11)
    single = iter(range(10**9))

    def one() -> tuple[np.ndarray, np.ndarray]:
        return cands[next(single) % len(cands)]

    idx, V = batch_matrix(op, cands[:b])
    rows = np.sort(np.random.default_rng(3).choice(n, n // 16, replace=False))
    part = op.restrict(rows)
    obj = cands[-1]
    op.total_power(*obj)
    target = op.match_target(*obj)
    target.error(idx, V)
    t1 = time.perf_counter()
    every = op.phi_rows()  # what a light model keeps when it fits (LightModel.field)
    basis_seconds = time.perf_counter() - t1

    def through_rows(i, v):
        cols = op.zone_columns(i)
        return every[:, cols] @ np.asarray(v, np.float32)

    results = {
        "full_single_per_s": rate(lambda: op.zone_illuminance(*one()), 1),
        "full_batched_per_s": rate(lambda: op.zone_illuminance(idx, V), b),
        "full_rows_single_per_s": rate(lambda: through_rows(*one()), 1),
        "full_rows_batched_per_s": rate(lambda: through_rows(idx, V), b),
        "basis_all_rows_seconds": basis_seconds,
        "basis_all_rows_mib": every.nbytes / 2**20,
        "partial_single_per_s": rate(lambda: part.zone_illuminance(*one()), 1),
        "partial_batched_per_s": rate(lambda: part.zone_illuminance(idx, V), b),
        "total_power_per_s": rate(lambda: op.total_power(*one()), 1),
        "total_power_batched_per_s": rate(lambda: op.total_power(idx, V), b),
        "match_error_per_s": rate(lambda: target.error(*one()), 1),
        "match_error_batched_per_s": rate(lambda: target.error(idx, V), b),
    }
    # Accuracy against the reference solver (on the operator's own traced F) on
    # independent sampled emissions.
    F = op.F
    E = sample_emissions(patches, 8, seed=1234)
    err = relative_errors(
        patches.rho[:, None] * op.illuminance(E), reference_reflected(F, patches.rho, E)
    )
    print(
        json.dumps(
            {
                "scene": args.scene,
                "n": n,
                "k": op.k,
                "nz": op.info["nz"],
                "cores": os.cpu_count(),
                "batch": b,
                "union_columns": len(idx),
                "p": len(rows),
                "build_seconds": build,
                "formfactor_seconds": op.info["formfactor_seconds"],
                "peak_rss_mb": rss_build,
                "operator_mb": op.nbytes() / 2**20,
                **results,
                "rel_error_vs_reference": float(err.mean()),
                "max_rel_error_vs_reference": float(err.max()),
                "build_estimated_rel_error": op.info["estimated_rel_error"],
            },
            indent=2,
        )
    )


if __name__ == "__main__":
    main()
