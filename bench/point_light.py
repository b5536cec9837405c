"""Daylight at work-plane points: the traced estimate against the exact point form factors.

For each room, diffusing glazing under the CIE overcast sky (10,000 lux outside, ground
0.2, transmittance 0.7) is solved once (reference radiosity on the traced F, default
1,024 rays); the work plane's illuminance F_p B is then read three ways:

- ``traced``: the points' form factors from 1,024 cosine-weighted rays each (the code
  before the exact factors, ``traced_receiver_factors``);
- ``exact``: the exact point form factors (``point_formfactors``, the default now);
- the reference: traced with 65,536 rays per point, averaged over ``--seeds`` seeds
  (unbiased, independent of the exact factors; its own standard error is printed).

Per-point relative errors against the reference (rms and max), the grid's Emin and U0
three ways, and the seconds each took, as one JSON object:

    python bench/point_light.py --scenes sidelit toplit office --seeds 4
"""

from __future__ import annotations

import argparse
import json
import os
import time

import numpy as np

from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import DEFAULT_RAYS, MAX_RAYS, form_factor_matrix
from lightinv_core.transport.glazing import glazing_emission
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors, traced_receiver_factors
from lightinv_core.transport.solver import solve
from lightinv_core.transport.workplane import WorkPlane, grid_statistics, work_plane_grid

GLAZING = {"sidelit": "window", "toplit": "rooflight", "office": "roof", "patio": "roof"}


def errors(lux: np.ndarray, ref: np.ndarray) -> dict[str, float]:
    """rms and max of the per-point relative error (%)."""
    e = lux / ref - 1.0
    return {"rms_pct": 100 * float(np.sqrt(np.mean(e * e))), "max_pct": 100 * float(abs(e).max())}


def room(scene: str, seeds: int) -> dict:
    p = mesh_patches(builtin_scene(scene))
    caster = RayCaster(p)
    F = form_factor_matrix(p, DEFAULT_RAYS, seed=0, caster=caster)
    E, lit = glazing_emission(p, {GLAZING[scene]: 0.7}, 10000.0, 0.2)
    B = solve(F, lit.rho, E).B
    grid = work_plane_grid(p, caster, WorkPlane())
    pts, nrm = grid.points, grid.normals
    t0 = time.perf_counter()
    traced = traced_receiver_factors(pts, nrm, caster, p.n, DEFAULT_RAYS, 0) @ B
    t1 = time.perf_counter()
    exact = receiver_factors(pts, nrm, caster, p.n) @ B
    t2 = time.perf_counter()
    fine = [traced_receiver_factors(pts, nrm, caster, p.n, MAX_RAYS, 100 + s) for s in range(seeds)]
    runs = np.array([R @ B for R in fine])
    ref = runs.mean(axis=0)
    stderr = runs.std(axis=0, ddof=1) / np.sqrt(seeds) / ref if seeds > 1 else np.nan * ref
    stats = {k: grid_statistics(v) for k, v in (("traced", traced), ("exact", exact), ("ref", ref))}
    return {
        "scene": scene,
        "patches": p.n,
        "points": len(pts),
        "reference_rays_per_point": MAX_RAYS * seeds,
        "reference_stderr_rms_pct": 100 * float(np.sqrt(np.mean(stderr**2))),
        "traced_1024": errors(traced, ref),
        "exact": errors(exact, ref),
        "Emin": {k: s["Emin"] for k, s in stats.items()},
        "U0": {k: s["U0"] for k, s in stats.items()},
        "seconds": {"traced_1024": t1 - t0, "exact": t2 - t1},
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", nargs="+", default=["sidelit", "toplit", "office"])
    ap.add_argument("--seeds", type=int, default=4)
    args = ap.parse_args()
    rows = [room(s, args.seeds) for s in args.scenes]
    print(json.dumps({"cores": os.cpu_count(), "rooms": rows}, indent=2))


if __name__ == "__main__":
    main()
