"""Benchmark: EN 17037 daylight provision on the "hours" basis in a project against the
"points" basis, and the cost of its intention in the optimiser. Prints JSON.

    python bench/en17037_hours.py [--batch 32] [--repeats 10] [--rounds 5]

``rooms``: the side-lit room (full resolution) with its window clear (glass 0.7), and
with it diffusing, work plane 0.8 m: every criterion's figure and the level and score on
both bases (``light.en17037_plane.plane_figures``; on the hours basis a figure is the
share of the daylight hours with the plane fraction reaching the illuminance, on the
points basis the share of the plane reaching it in half the hours).

``evaluation``: the integrated office demo (diffusing skylight and luminaires free)
with "EN 17037 at least medium" on its work plane, on each basis: CPU seconds per batch
(median of rounds measured in turn) against the same batch without the intention.
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.design.model import Daylight, Design, Goal, Intention, Source, Workplane
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.en17037_plane import plane_figures
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.search import random_start
from lightinv_core.project import load_project
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import prepare

PROJECT = (
    Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-integrated.json"
)


def rooms() -> list[dict]:
    scene = builtin_scene("sidelit")
    patches = mesh_patches(scene)
    light = LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=512)))
    out = []
    for glazing in ("clear", "diffusing"):
        w = Source("W1", "window", "window", (0.0, 0.0, *light.zone_size("window")),
                   glazing=glazing)  # fmt: skip
        row = {"room": f"sidelit, {glazing} window 0.7"}
        for basis in ("points", "hours"):
            design = Design(
                sources=(w,),
                goals=(Goal("min_electric_power"),),
                workplanes=(Workplane("wp", 0.8, 0.5),),
                daylight=Daylight(transmittance=0.7, en17037_basis=basis),
            )
            t0 = time.process_time()
            lay = layout_daylight(light, design)
            got = plane_figures(lay.points, lay.grids.spans["wp"])
            got["cpu_s"] = time.process_time() - t0
            row[basis] = got
        out.append(row)
    return out


def evaluation(batch: int, repeats: int, rounds: int) -> dict:
    project = load_project(PROJECT)
    light = prepare(project).light
    base = project.design
    en = Intention("EN 17037", grid="wp", quantity="en17037", min=2.0)
    designs = [base]
    for basis in ("points", "hours"):
        daylight = replace(base.daylight, en17037_basis=basis)
        designs.append(replace(base, intentions=(*base.intentions, en), daylight=daylight))
    problems = [DesignProblem(d, light) for d in designs]
    rng = np.random.default_rng(0)
    X = np.stack([random_start(problems[0], rng) for _ in range(batch)])
    for p in problems:
        p.evaluate(X)  # warm: receivers, the weather year, the daylight hours
    T = np.empty((rounds, 3))
    for r in range(rounds):
        for j, p in enumerate(problems):
            t0 = time.process_time()
            for _ in range(repeats):
                p.evaluate(X)
            T[r, j] = (time.process_time() - t0) / repeats
    return {
        "project": "office-integrated (diffusing skylight S1 free, luminaires free)",
        "batch": batch,
        "cpu_per_batch_s": {
            "without": float(np.median(T[:, 0])),
            "points": float(np.median(T[:, 1])),
            "hours": float(np.median(T[:, 2])),
        },
        "ratio_points_median": float(np.median(T[:, 1] / T[:, 0])),
        "ratio_hours_median": float(np.median(T[:, 2] / T[:, 0])),
        "ratio_hours_range": [float((T[:, 2] / T[:, 0]).min()), float((T[:, 2] / T[:, 0]).max())],
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    out = {"rooms": rooms(), "evaluation": evaluation(args.batch, args.repeats, args.rounds)}
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
