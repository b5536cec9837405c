"""Benchmark: EN 17037 daylight provision in a project against the forward study, and
the cost of its intention in the optimiser. Prints JSON.

    python bench/en17037_design.py [--weather builtin] [--batch 32] [--repeats 20]

``versus_study``: on the daylight rooms ``sidelit`` (a clear south window) and
``toplit`` (a clear rooflight), full resolution, glass 0.7, work plane 0.8 m with a
0.5 m border, the weather of ``--weather``: the plane share of every EN 17037 criterion
(E lux reached in half the daylight hours) and the level, through the design's light
model (``light.en17037_plane.plane_figures``) and through the forward study
(``study.clear_metrics.work_plane_metrics``, checked against Radiance), and both sides'
CPU seconds; and the plane's mean cDA300 on both sides.

``evaluation``: the integrated office demo (diffusing skylight, luminaires free, the
desks' 500 lux at night) evaluated in batches with and without the intention "EN 17037
daylight provision at least medium" on its work plane: CPU seconds per batch of each
(median of rounds measured in turn) and their ratio, and the score of the demo as
written.
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
from lightinv_core.study import SimulationSpec, prepare, simulate
from lightinv_core.study.clear_metrics import work_plane_metrics
from lightinv_core.transport.workplane import WorkPlane

PROJECT = (
    Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-integrated.json"
)
KEYS = ("minimum_300", "minimum_100", "medium_500", "medium_300", "high_750", "high_500")


def versus_study(scene_name: str, weather: str) -> dict:
    """The design's provision figures and the study's on one daylight room."""
    group = {"sidelit": ("window", "window"), "toplit": ("rooflight", "skylight")}[scene_name]
    scene = builtin_scene(scene_name)
    patches = mesh_patches(scene)
    light = LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=512)))
    daylight = Daylight(transmittance=0.7, weather=weather)
    w = Source("G1", group[0], group[1], (0.0, 0.0, *light.zone_size(group[0])), glazing="clear")
    design = Design(
        sources=(w,),
        goals=(Goal("min_electric_power"),),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        daylight=daylight,
    )
    t0 = time.process_time()
    lay = layout_daylight(light, design)
    ours = plane_figures(lay.points, lay.grids.spans["wp"])
    ours_cpu = time.process_time() - t0
    spec = SimulationSpec(
        scene=scene,
        glazing={group[0]: 0.7},
        glazing_kinds={group[0]: "clear"},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=daylight,
    )
    t0 = time.process_time()
    metrics = work_plane_metrics(simulate(spec).clear_year)[0]
    theirs = metrics["en17037_provision"]
    study_cpu = time.process_time() - t0
    keys = [k for k in KEYS if k in theirs]
    return {
        "scene": scene_name,
        "patches": patches.n,
        "points": len(lay.grids.points),
        "horizontal_openings": ours["horizontal_openings"],
        "design": {k: ours[k] for k in keys} | {"level": ours["level"], "score": ours["score"]},
        "study": {k: theirs[k] for k in keys} | {"level": theirs["level"]},
        "largest_difference_points": max(100 * abs(ours[k] - theirs[k]) for k in keys),
        "cda300_mean": {
            "design": float(lay.points.cda(lay.grids.spans["wp"])[:, 0].mean()),
            "study": metrics["cda300_mean"],
        },
        "design_cpu_s": ours_cpu,
        "study_cpu_s": study_cpu,
    }


def evaluation(batch: int, repeats: int, rounds: int) -> dict:
    """CPU per batch of the demo with and without the EN 17037 intention."""
    project = load_project(PROJECT)
    light = prepare(project).light
    base = project.design
    en = Intention("EN 17037", grid="wp", quantity="en17037", min=2.0)
    with_en = replace(base, intentions=(*base.intentions, en))
    problems = [DesignProblem(base, light), DesignProblem(with_en, light)]
    rng = np.random.default_rng(0)
    X = np.stack([random_start(problems[0], rng) for _ in range(batch)])
    for p in problems:
        p.evaluate(X)  # warm: receivers, the weather year, the daylight hours
    T = np.empty((rounds, 2))
    for r in range(rounds):
        for j, p in enumerate(problems):
            t0 = time.process_time()
            for _ in range(repeats):
                p.evaluate(X)
            T[r, j] = (time.process_time() - t0) / repeats
    lay = layout_daylight(light, with_en)
    return {
        "project": "office-integrated (diffusing skylight S1 free, luminaires free)",
        "batch": batch,
        "cpu_per_batch_s": {
            "without": float(np.median(T[:, 0])),
            "with": float(np.median(T[:, 1])),
        },
        "ratio_median": float(np.median(T[:, 1] / T[:, 0])),
        "ratio_range": [float((T[:, 1] / T[:, 0]).min()), float((T[:, 1] / T[:, 0]).max())],
        "demo_as_written": plane_figures(lay.points, lay.grids.spans["wp"]),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--weather", default="builtin")
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=20)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    rooms = [versus_study(name, args.weather) for name in ("sidelit", "toplit")]
    out = {"weather": args.weather, "rooms": rooms}
    out["evaluation"] = evaluation(args.batch, args.repeats, args.rounds)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
