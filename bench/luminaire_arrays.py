"""Benchmark: luminaire arrays optimised against an EN 12464-1 work plane, office scene.

The design: the shipped linear batwing (4000 lm, 32 W) in an array in each ceiling
luminaire zone of the built-in office (rows 1-6, columns 1-3, rotation 0/90, dimming
0.1-1 free; SHR at most 1.5, clearance 0.1 m), a work plane at 0.8 m with a 0.5 m border,
EN 12464-1 "filing, copying" on it (Em >= 300 lux, U0 >= 0.4), least electric power.
(Writing and reading, 500 lux with U0 >= 0.6, cannot be met from these two strips along
the side walls: the best of a first try gave U0 = 0.41 with 24 luminaires.) Measures,
on this machine:

- the precompute: the operator (from the cache when there), the grid and its zone basis,
  the arrays' lattice responses (``DesignProblem`` construction, timed in parts);
- evaluations per second of random layouts (batches of 256, the optimiser's size);
- the lattice blend's error against the luminaires placed exactly, at the grid points,
  over 60 random layouts off the lattice nodes (Em, U0, worst point);
- 10 seeds of the ``auto`` method: success rate (the solution judged feasible, with the
  luminaires placed exactly, and its grid values checked again here), evaluations,
  power, luminaires.

Prints one JSON object; ``--out`` also writes it.

python bench/luminaire_arrays.py [--resolution 0.25] [--seeds 10] [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import os
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.cli import peak_rss_mb
from lightinv_core.design.model import Design, Goal, Intention, LuminaireArray, Rule, Workplane
from lightinv_core.design.variables import ArrayLayout
from lightinv_core.light.arrays import arrays_field
from lightinv_core.light.grids import design_grids
from lightinv_core.light.model import LightModel
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.method import RunContext
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.registry import get_method
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.optimize.termination import StopRule
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.workplane import grid_statistics

PRODUCT = "Linear batwing 4000 lm 32 W"
FREE = ("rows", "columns", "rotation", "dimming")
EM, U0 = 300.0, 0.4


def design() -> Design:
    """The benchmark's design (see the module)."""
    arrays = tuple(
        LuminaireArray(
            name,
            zone,
            PRODUCT,
            (0.0, 0.0, 2.0, 6.0),
            rows=3,
            columns=1,
            rotation=90,
            free=FREE,
            rows_range=(1, 6),
            columns_range=(1, 3),
        )
        for name, zone in (("west", "lum_west"), ("east", "lum_east"))
    )
    return Design(
        sources=(),
        goals=(Goal("min_electric_power"),),
        arrays=arrays,
        workplanes=(Workplane("wp", 0.8, 0.5),),
        intentions=(Intention("filing", grid="wp", average=EM, uniformity=U0),),
        rules=(
            Rule("shr", ("west", "east"), max=1.5),
            Rule("clearance", ("west", "east"), min=0.1),
        ),
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--resolution", type=float, default=0.25)
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--max-evals", type=int, default=20000)
    ap.add_argument("--out", type=Path)
    args = ap.parse_args()
    out: dict = {"scene": "office", "resolution": args.resolution, "cores": os.cpu_count()}
    out["load_before"] = os.getloadavg()[0]

    t = time.perf_counter()
    scene = builtin_scene("office", args.resolution)
    patches = mesh_patches(scene)
    got = get_operator(patches, OperatorSettings())
    light = LightModel(scene, patches, got.operator)
    out.update(n=patches.n, operator_seconds=time.perf_counter() - t)
    out["operator_from_cache"] = got.from_cache

    d = design()
    t = time.perf_counter()
    grids = design_grids(light, d.workplanes)
    out["grid_points"] = len(grids.points)
    out["grid_precompute_seconds"] = time.perf_counter() - t
    t = time.perf_counter()
    problem = DesignProblem(d, light)
    out["problem_seconds"] = time.perf_counter() - t  # the grid (remembered) and the rules
    t = time.perf_counter()
    out["lattice_placements"] = problem.arrays.placements  # made on first use
    out["arrays_precompute_seconds"] = time.perf_counter() - t

    rng = np.random.default_rng(0)
    lo, hi = problem.vars.lo, problem.vars.hi
    level = problem.level(1)
    X = lo + rng.random((256, len(lo))) * (hi - lo)
    problem.evaluate(X, level)
    reps, t = 0, time.perf_counter()
    while time.perf_counter() - t < 5.0:
        problem.evaluate(lo + rng.random((256, len(lo))) * (hi - lo), level)
        reps += 1
    out["batch"] = 256
    out["evaluations_per_second"] = reps * 256 / (time.perf_counter() - t)

    # The lattice blend against exact placement: random arrays (any rectangle, 1-5 rows,
    # 1-3 columns, either rotation) off the lattice nodes, at the grid points.
    q = len(problem.grids.points)
    errs = []
    for _ in range(60):
        arrs = []
        for a in problem.design.arrays:
            u0, u1 = sorted(rng.uniform(0, 2, 2))
            v0, v1 = sorted(rng.uniform(0, 6, 2))
            arrs.append(
                replace(
                    a,
                    rect=(u0, v0, u1, v1),
                    rows=int(rng.integers(1, 6)),
                    columns=int(rng.integers(1, 4)),
                    rotation=int(90 * rng.integers(0, 2)),
                    dimming=1.0,
                )
            )
        lay = ArrayLayout(
            np.array([[a.rect for a in arrs]]),
            np.array([[a.rows for a in arrs]]),
            np.array([[a.columns for a in arrs]]),
            np.array([[a.rotation for a in arrs]]),
            np.ones((1, len(arrs))),
        )
        blend = problem.arrays.illuminance(lay, maintained=False)[-q:, 0]
        _, exact = arrays_field(patches, light.op, arrs, problem.grids.points, maintained=False)
        sb, se = grid_statistics(blend), grid_statistics(exact)
        errs.append(
            (
                abs(sb["Em"] / se["Em"] - 1),
                abs(sb["U0"] / se["U0"] - 1),
                float(np.abs(blend - exact).max() / exact.mean()),
            )
        )
    e = np.array(errs)
    out["lattice_blend_error"] = {
        "layouts": len(errs),
        "Em_max": float(e[:, 0].max()),
        "Em_median": float(np.median(e[:, 0])),
        "U0_max": float(e[:, 1].max()),
        "U0_median": float(np.median(e[:, 1])),
        "point_max_over_mean": float(e[:, 2].max()),
    }

    runs = []
    for seed in range(args.seeds):
        t = time.perf_counter()
        context = RunContext(OptimizerSettings(seed=seed), StopRule(args.max_evals), seed=seed)
        res = get_method("auto").run(problem, context)
        seconds = time.perf_counter() - t
        best = (
            res.best
            if res.front is None
            else min(res.front.solutions, key=lambda s: s.objectives["min_electric_power"])
        )
        _, exact = arrays_field(patches, light.op, best.arrays, problem.grids.points)
        stats = grid_statistics(exact)
        # Judged again with the luminaires placed exactly, within the 0.1% tolerance.
        ok = best.feasible and stats["Em"] >= EM * 0.999 and stats["U0"] >= U0 * 0.999
        runs.append(
            {
                "seed": seed,
                "feasible": bool(best.feasible),
                "exact_ok": bool(ok),
                "evaluations": res.evaluations,
                "seconds": seconds,
                "power_W": best.objectives["min_electric_power"],
                "luminaires": int(sum(a.count for a in best.arrays)),
                "front_points": None if res.front is None else len(res.front.solutions),
                "exact_Em": stats["Em"],
                "exact_U0": stats["U0"],
                "layout": [
                    [a.rows, a.columns, a.rotation, round(a.dimming, 3)] for a in best.arrays
                ],
            }
        )
    out["runs"] = runs
    out["success"] = f"{sum(r['exact_ok'] for r in runs)} of {len(runs)}"
    out["median_evaluations"] = float(np.median([r["evaluations"] for r in runs]))
    out["median_power_W"] = float(np.median([r["power_W"] for r in runs]))
    out["peak_rss_mb"] = peak_rss_mb()
    out["load_after"] = os.getloadavg()[0]
    text = json.dumps(out, indent=1)
    print(text)
    if args.out:
        args.out.write_text(text + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
