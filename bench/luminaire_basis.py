"""Benchmark: precomputed photometric-luminaire responses on the office scene.

Candidate placements of the shipped 2000 lm downlight on a 0.25 m lattice over both
ceiling luminaire zones, in two orientations; the work plane at 0.8 m (border 0.5 m)
and the desks as receivers. Measures the work-plane grid, the form factors (traced
again with the operator's settings), the responses, and how many random array layouts
per second get their EN 12464-1 values (Em, Emin, U0 on the grid, mean on the desks).
Prints one JSON object.

python bench/luminaire_basis.py [--resolution 0.25] [--lattice 0.25]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

from lightinv_core.cli import peak_rss_mb
from lightinv_core.luminaires import builtin_catalogue
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.luminaire_basis import luminaire_responses
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.luminaires import PlacedLuminaire
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.workplane import WorkPlane, work_plane_grid


def lattice(scene, zone: str, step: float, drop: float) -> np.ndarray:
    """Points (m, 3) on a ``step`` lattice over an emitter zone, ``drop`` m in front."""
    r = scene.zone_rect(zone)
    su, sv = r.size
    nu, nv = max(1, round(su / step)), max(1, round(sv / step))
    s, t = np.meshgrid((np.arange(nu) + 0.5) / nu, (np.arange(nv) + 0.5) / nv, indexing="ij")
    pts = r.origin + s.reshape(-1, 1) * r.u + t.reshape(-1, 1) * r.v
    return pts + drop * r.normal


def accuracy() -> dict:
    """Largest error of the responses against the reference solve on the same form
    factors, office at 0.5 m, four placements (tests/core/test_luminaire_basis.py's)."""
    from lightinv_core.operator.build import build_operator
    from lightinv_core.operator.luminaire_basis import BASIS_SAMPLES
    from lightinv_core.transport.scene_light import light_scene

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the tests' placements
    from tests.core.test_luminaire_basis import SETTINGS, placements

    p = mesh_patches(builtin_scene("office", 0.5))
    op = build_operator(p, SETTINGS)
    F = form_factor_matrix(p, SETTINGS.rays, seed=SETTINGS.seed)
    caster = RayCaster(p)
    names = ("desks", "floor", "walls")
    rows = np.flatnonzero(np.isin(p.group_id, [p.group_names.index(g) for g in names]))
    out = {"n": p.n, "k": op.k}
    for bounces in (3, 1):
        got = luminaire_responses(
            p, F, op.lowrank, placements(), rows, caster=caster, rays=512, seed=7, bounces=bounces
        )
        worst = 0.0
        for j, lum in enumerate(placements()):
            ref = light_scene(p, F, caster, np.zeros(p.n), [lum], samples=BASIS_SAMPLES, seed=7)
            H = ref.H[rows]
            lit = 0.1 * H.max() < H
            worst = max(worst, float((np.abs(got.at_rows[lit, j] - H[lit]) / H[lit]).max()))
        out[f"max_rel_error_lit_patches_{bounces}_bounces"] = worst
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--resolution", type=float, default=None)
    ap.add_argument("--lattice", type=float, default=0.25)
    ap.add_argument("--batch", type=int, default=256)
    args = ap.parse_args()
    scene = builtin_scene("office", args.resolution)
    p = mesh_patches(scene)
    settings = OperatorSettings()
    t0 = time.perf_counter()
    op = get_operator(p, settings).operator
    t_op = time.perf_counter() - t0
    caster = RayCaster(p)
    t0 = time.perf_counter()
    grid = work_plane_grid(p, caster, WorkPlane(0.8, 0.5))
    t_grid = time.perf_counter() - t0
    t0 = time.perf_counter()
    F = form_factor_matrix(p, settings.rays, seed=settings.seed, caster=caster)
    t_ff = time.perf_counter() - t0
    down = next(e for e in builtin_catalogue() if "Downlight" in e.name).photometry()
    placements = []
    for zone in ("lum_west", "lum_east"):
        for k, pos in enumerate(lattice(scene, zone, args.lattice, 0.01)):
            for c0 in ((1, 0, 0), (0, 1, 0)):
                placements.append(PlacedLuminaire(f"{zone}-{k}-{c0[0]}", pos, down, c0=c0))
    rows = p.group_index("desks")
    t0 = time.perf_counter()
    resp = luminaire_responses(p, F, op.lowrank, placements, rows, grid.points, caster=caster)
    t_resp = time.perf_counter() - t0

    # Random array layouts: 2 to 16 luminaires each, dimmed 0.3 to 1.
    rng = np.random.default_rng(0)
    L = len(placements)
    m = args.batch
    W = np.zeros((m, L), np.float32)
    for i in range(m):
        on = rng.choice(L, size=rng.integers(2, 17), replace=False)
        W[i, on] = rng.uniform(0.3, 1.0, len(on))
    t0 = time.perf_counter()
    batches = 0
    while time.perf_counter() - t0 < 3.0:
        at_rows, at_points = resp.evaluate(W)
        em = at_points.mean(axis=0)
        u0 = at_points.min(axis=0) / np.maximum(em, 1e-9)
        desks = rows_mean = p.area[rows] @ at_rows / p.area[rows].sum()
        batches += 1
    rate = batches * m / (time.perf_counter() - t0)
    del desks, rows_mean, u0
    print(
        json.dumps(
            {
                "scene": "office",
                "n": p.n,
                "cores": os.cpu_count(),
                "operator_seconds": t_op,
                "grid_points": len(grid.points),
                "grid_seconds": t_grid,
                "formfactor_seconds": t_ff,
                "placements": L,
                "responses_seconds": t_resp,
                "precompute_seconds": t_grid + t_ff + t_resp,
                "receivers": len(rows) + len(grid.points),
                "batch": m,
                "evaluations_per_second": rate,
                "peak_rss_mb": peak_rss_mb(),
                "accuracy": accuracy(),
            },
            indent=1,
        )
    )


if __name__ == "__main__":
    main()
