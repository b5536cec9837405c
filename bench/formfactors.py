"""Benchmark: all form-factor rows of a built-in scene. Prints one JSON object.

python bench/formfactors.py --scene patio --rays 1024 --json
"""

from __future__ import annotations

import argparse
import json
import os
import time

from lightinv_core.cli import peak_rss_mb
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import (
    default_workers,
    form_factor_matrix,
    lost_fraction,
    trace_rows,
)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="patio")
    ap.add_argument("--resolution", type=float, default=None)
    ap.add_argument("--rays", type=int, default=1024)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--json", action="store_true", help="(default) print JSON")
    args = ap.parse_args()

    t0 = time.perf_counter()
    patches = mesh_patches(builtin_scene(args.scene, args.resolution))
    t1 = time.perf_counter()
    lost = 0
    for batch in trace_rows(patches, args.rays, seed=args.seed):
        lost += int((batch.hits < 0).sum())
    t2 = time.perf_counter()
    F = form_factor_matrix(patches, args.rays, seed=args.seed)
    t3 = time.perf_counter()
    rays = patches.n * args.rays
    print(
        json.dumps(
            {
                "scene": args.scene,
                "n": patches.n,
                "rays_per_patch": args.rays,
                "cores": os.cpu_count(),
                "workers": default_workers(),
                "mesh_seconds": t1 - t0,
                "trace_seconds": t2 - t1,
                "seconds": t3 - t2,
                "rays_per_second": rays / (t3 - t2),
                "trace_rays_per_second": rays / (t2 - t1),
                "nnz": int(F.nnz),
                "lost_ray_fraction": lost / rays,
                "lost_fraction": lost_fraction(F, patches),
                "peak_rss_mb": peak_rss_mb(),
            },
            indent=2,
        )
    )


if __name__ == "__main__":
    main()
