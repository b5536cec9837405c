"""Benchmark: an annual evaluation with a fixed clear rooflight against the same design
with the rooflight diffusing. Prints JSON.

    python bench/clear_design.py [--batch 32] [--repeats 30] [--rounds 5]

On the integrated office demo (resources/projects/office-integrated.json, full
resolution) with its skylight S1 fixed as drawn (2 x 1 m) and the two luminaire
strips free, goal least annual energy, intentions: the desks' 500 lux at night, sDA
and ASE on the work plane (checks). The same random candidates are evaluated by:

- ``diffusing``: S1 diffusing (one sky group: the year's statistics by sorted hours);
- ``clear``: S1 clear: its light (145 sky patches, the ground, the sun on an MF:2
  basis, the work plane's direct sun hour by hour) computed once, the same for every
  candidate, and added to each candidate's light.

Reported: CPU seconds of the clear glazing's light (its first build, rays and
inter-reflections), candidates per second of each (median of the rounds, measured in
turn within each round), the ratio clear / diffusing of the time per batch (median of
the rounds' ratios; the issue's target is within 3x), and the two layouts' figures.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.design.model import Goal, Intention
from lightinv_core.light.clear_glazing import clear_light
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.search import random_start
from lightinv_core.project import load_project
from lightinv_core.study import prepare

PROJECT = (
    Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-integrated.json"
)


def batch_cpu(problem: DesignProblem, X: np.ndarray, repeats: int) -> float:
    """CPU seconds per batch over ``repeats`` batches."""
    t0 = time.process_time()
    for _ in range(repeats):
        problem.evaluate(X)
    return (time.process_time() - t0) / repeats


def designs(design):
    """(diffusing, clear) versions of the demo with S1 fixed."""
    sources = tuple(replace(s, free=()) if s.kind == "skylight" else s for s in design.sources)
    checks = (
        Intention("sDA", grid="wp", quantity="sda", average=0.0, max=1.0),
        Intention("ASE", grid="wp", quantity="ase", max=1.0),
    )
    base = replace(
        design,
        sources=sources,
        goals=(Goal("min_annual_energy"),),
        intentions=design.intentions + checks,
    )
    clear = tuple(replace(s, glazing="clear") if s.kind == "skylight" else s for s in sources)
    return base, replace(base, sources=clear)


def figures(light, design) -> dict:
    got = layout_daylight(light, design)
    out = {}
    for q in ("da", "udi", "sda", "ase"):
        it = Intention(q, grid="wp", quantity=q, max=1.0)
        out[q] = float(got.points.quantity(it)[:, 0].mean())
    out["df_mean_pct"] = float(100 * got.points.overcast_daylight().mean())
    out["energy_kwh"] = got.energy().energy_kwh
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=30)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    project = load_project(PROJECT)
    prepared = prepare(project)
    light = prepared.light
    diffusing, clear = designs(project.design)
    t0 = time.process_time()
    built = clear_light(light, clear)
    build_cpu = time.process_time() - t0
    problems = [DesignProblem(diffusing, light), DesignProblem(clear, light)]
    rng = np.random.default_rng(0)
    X = np.stack([random_start(problems[0], rng) for _ in range(args.batch)])
    for p in problems:
        p.evaluate(X)  # warm: receivers, the weather year, the clear light's hours
    T = np.array([[batch_cpu(p, X, args.repeats) for p in problems] for _ in range(args.rounds)])
    ratios = T[:, 1] / T[:, 0]
    t_d, t_c = np.median(T, axis=0)
    print(
        json.dumps(
            {
                "project": "office-integrated, S1 fixed (2 x 1 m), luminaires free",
                "patches": prepared.patches.n,
                "workplane_points": len(problems[0].grids.points),
                "batch": args.batch,
                "cores": os.cpu_count(),
                "clear_build_cpu_s": build_cpu,
                "clear_columns": int(built.patches.columns.count),
                "diffusing_batch_cpu_s": float(t_d),
                "clear_batch_cpu_s": float(t_c),
                "diffusing_per_s": args.batch / float(t_d),
                "clear_per_s": args.batch / float(t_c),
                "clear_over_diffusing": float(np.median(ratios)),
                "clear_over_diffusing_rounds": [float(r) for r in ratios],
                "diffusing_layout": figures(light, diffusing),
                "clear_layout": figures(light, clear),
            }
        )
    )


if __name__ == "__main__":
    main()
