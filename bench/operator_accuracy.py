"""Accuracy of operator variants vs rank: prints one JSON object (the table in docs/operator.md).

Variants: the plain cluster LRR (paper eq. 8, b = 0) and the zone basis with b = 1, 2, 3
exact bounces plus the low-rank remainder. Error: mean and max relative L2 error of
C = B - E against the reference solver (Jacobi on the same traced F) on sampled
emissions (random rectangles in the emitter zones).

    python bench/operator_accuracy.py --scene office --json
"""

from __future__ import annotations

import argparse
import json
import os
import time

import numpy as np

from lightinv_core.operator.accuracy import reference_reflected, relative_errors, sample_emissions
from lightinv_core.operator.clustering import cluster_patches
from lightinv_core.operator.lowrank import assemble, cluster_form_factors
from lightinv_core.operator.zone_basis import exact_bounces, zone_basis
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="office")
    ap.add_argument("--resolution", type=float, default=None)
    ap.add_argument("--samples", type=int, default=8)
    ap.add_argument("--divisors", default="128,64,32,16,8")
    ap.add_argument("--json", action="store_true", help="(default) print JSON")
    args = ap.parse_args()

    p = mesh_patches(builtin_scene(args.scene, args.resolution))
    F = form_factor_matrix(p, 1024, seed=0)
    E = sample_emissions(p, args.samples, seed=1234)
    C_ref = reference_reflected(F, p.rho, E, tol=1e-7)
    zone = np.flatnonzero(p.zone_id >= 0)
    bases = {b: exact_bounces(F, p.rho, zone, b) for b in (1, 2, 3)}
    rows = []
    for div in (int(d) for d in args.divisors.split(",")):
        t0 = time.perf_counter()
        labels, k = cluster_patches(p, p.n // div)
        lr = assemble(cluster_form_factors(F, labels, k), labels, p.area, p.rho)
        row = {"divisor": div, "k": k, "lowrank_seconds": time.perf_counter() - t0}
        nz_idx = np.flatnonzero(np.any(E != 0, axis=1))
        C = p.rho[:, None] * lr.illuminance(lr.project_sparse(nz_idx, E[nz_idx]))
        err = relative_errors(C, C_ref)
        row["plain_lrr"] = {"mean": float(err.mean()), "max": float(err.max())}
        for b, (exact, last) in bases.items():
            Phi = zone_basis(exact, last, lr)
            err = relative_errors(p.rho[:, None] * (Phi @ E[zone]), C_ref)
            row[f"exact_bounces_{b}"] = {"mean": float(err.mean()), "max": float(err.max())}
        rows.append(row)
    print(
        json.dumps(
            {
                "scene": args.scene,
                "n": p.n,
                "nz": len(zone),
                "cores": os.cpu_count(),
                "samples": args.samples,
                "rows": rows,
            },
            indent=2,
        )
    )


if __name__ == "__main__":
    main()
