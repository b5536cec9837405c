"""Benchmark: daylight-linked control groups in a project against the forward study, and
what several groups cost the optimiser. Prints JSON.

    python bench/control_groups.py [--resolution 0.5] [--batch 32] [--repeats 20] [--rounds 5]

``versus_study``: the side-lit room (``sidelit``: 6 x 8 x 3 m, a 4.8 x 1.6 m south
window, glass 0.7) with a luminaire zone over its whole ceiling and two arrays of the
catalogue's 2,000 lm 20 W downlight (maintenance factor 1): a "window row" of 3 over
y 0-2 m read by a sensor over y 0-2.5 m of the work plane, and 9 inner ones in the
default group "all" read over y 2.5-8 m; Greensboro TMY3, weekdays 8-18, dimming to
500 lux from 10%, 3 W standby. The design's year (``layout_daylight(...).energy()``)
against ``study.simulate`` with the same luminaires, groups and sensors (the path of
``lightinv-cli simulate --luminaires ... --sensor GROUP=X0,Y0,X1,Y1``), for the window
as diffusing and as clear glazing. The window's patches are black on both sides (the
study's glazing is black inside; a design's diffusing window otherwise keeps the wall's
reflectance for the luminaires' light: docs/daylight.md).

``optimiser``: the integrated office demo (full resolution) with its west strip L1 in a
"window row" group read over x 0-4 m and its east strip in "all": CPU seconds per batch
of random candidates with the two groups against the demo as shipped (one group), the
same candidates, measured in turn in each round; the ratio's median.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.design.model import (
    ControlGroup,
    Daylight,
    Design,
    Goal,
    LuminaireArray,
    Source,
    Workplane,
)
from lightinv_core.light.arrays import array_luminaires
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.search import random_start
from lightinv_core.project import load_project
from lightinv_core.project.scene import SceneSpec
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import SimulationSpec, prepare, simulate
from lightinv_core.transport.workplane import WorkPlane

PROJECT = (
    Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-integrated.json"
)
PRODUCT = "Downlight 2000 lm 20 W"
SENSORS = {"window row": (0.0, 0.0, 6.0, 2.5), "all": (0.0, 2.5, 6.0, 8.0)}


def sidelit(resolution: float) -> LightModel:
    """The side-lit room with a luminaire zone over its ceiling, the window black."""
    scene = SceneSpec(
        builtin="sidelit",
        resolution=resolution,
        reflectances=(("window", 0.0),),
        zones=(ZoneEdit("lums", "luminaire", "ceiling", (0, 0, 6, 8)),),
    ).load()
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=512)))


def sidelit_design(light: LightModel, glazing: str) -> Design:
    """The two groups' design on ``light``'s room, its window ``glazing``."""
    win = Source("W1", "window", "window", (0, 0, *light.zone_size("window")), glazing=glazing)
    front = LuminaireArray(
        "front", "lums", PRODUCT, (0, 6, 6, 8), columns=3, maintenance_factor=1.0,
        control_group="window row",
    )  # fmt: skip
    back = LuminaireArray(
        "back", "lums", PRODUCT, (0, 0, 6, 6), rows=3, columns=3, maintenance_factor=1.0
    )
    return Design(
        (win,),
        (Goal("min_annual_energy"),),
        daylight=Daylight(transmittance=0.7, standby_w=3.0),
        arrays=(front, back),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        control_groups=tuple(ControlGroup(n, sensor=r) for n, r in SENSORS.items()),
    )


def versus_study(light: LightModel, glazing: str) -> dict:
    """The design's groups and the study's on the side-lit room (see the module)."""
    design = sidelit_design(light, glazing)
    t0 = time.process_time()
    ours = layout_daylight(light, design).energy()
    ours_cpu = time.process_time() - t0
    lums = []
    for a, _, placed in array_luminaires(light.patches, design.arrays):
        lums += [replace(p, control=a.control_group) for p in placed]
    spec = SimulationSpec(
        scene=light.scene,
        luminaires=tuple(lums),
        glazing={"window": 0.7},
        glazing_kinds={"window": glazing},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=design.daylight,
        sensors=SENSORS,
    )
    t0 = time.process_time()
    got = simulate(spec)
    study_cpu = time.process_time() - t0
    study = {g.name: g for g in got.control_groups}
    groups = []
    for g in ours.groups:
        s = study[g.name]
        groups.append(
            {
                "name": g.name,
                "luminaires": g.luminaires,
                "watts": g.watts,
                "sensor_points": [g.sensor_points, s.sensor_points],
                "electric_lux": [g.electric_lux, s.electric_lux],
                "mean_level": [g.mean_level, s.mean_level],
                "energy_kwh": [g.energy_kwh, s.energy_kwh],
                "leni": [g.leni, s.leni],
                "energy_rel_diff": g.energy_kwh / s.energy_kwh - 1.0,
            }
        )
    total = got.control_total["energy_kwh"]
    return {
        "glazing": glazing,
        "groups": groups,
        "total_kwh": [ours.energy_kwh, total],
        "total_rel_diff": ours.energy_kwh / total - 1.0,
        "leni": [ours.leni, got.control_total["leni_kwh_m2"]],
        "design_cpu_s": ours_cpu,
        "study_cpu_s": study_cpu,
    }


def optimiser_cost(batch: int, repeats: int, rounds: int) -> dict:
    """CPU per batch with two control groups against one, on the integrated demo."""
    project = load_project(PROJECT)
    light = prepare(project).light
    one = project.design
    l1 = replace(one.source("L1"), control_group="window row")
    two = replace(
        one,
        sources=tuple(l1 if s.name == "L1" else s for s in one.sources),
        control_groups=(ControlGroup("window row", sensor=(0.0, 0.0, 4.0, 8.0)),),
    )
    problems = [DesignProblem(one, light), DesignProblem(two, light)]
    rng = np.random.default_rng(0)
    X = np.stack([random_start(problems[0], rng) for _ in range(batch)])
    energy = [p.evaluate(X).goals["min_annual_energy"] for p in problems]  # warm
    T = np.zeros((rounds, 2))
    for r in range(rounds):
        for k, p in enumerate(problems):
            t0 = time.process_time()
            for _ in range(repeats):
                p.evaluate(X)
            T[r, k] = (time.process_time() - t0) / repeats
    ratios = T[:, 1] / T[:, 0]
    x0 = problems[1].vars.initial()
    layout = layout_daylight(light, two, problems[1].sources_at(x0)).energy()
    return {
        "patches": light.n,
        "batch": batch,
        "one_group_batch_cpu_s": float(np.median(T[:, 0])),
        "two_groups_batch_cpu_s": float(np.median(T[:, 1])),
        "two_over_one": float(np.median(ratios)),
        "two_over_one_rounds": [float(x) for x in ratios],
        "batch_energy_kwh_median": [float(np.median(e)) for e in energy],
        "start_layout_groups": [g.as_dict() for g in layout.groups],
        "start_layout_total_kwh": layout.energy_kwh,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--resolution", type=float, default=0.5)
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=20)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    light = sidelit(args.resolution)
    rows = [versus_study(light, g) for g in ("diffusing", "clear")]
    out = {
        "date": time.strftime("%Y-%m-%d"),
        "cores": os.cpu_count(),
        "sidelit": {"resolution_m": args.resolution, "patches": light.n, "rooms": rows},
        "optimiser": optimiser_cost(args.batch, args.repeats, args.rounds),
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
