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

``--versus-study`` instead compares, on the daylight rooms ``sidelit`` and ``toplit``
(glass 0.7, work plane 0.8 m, the weather of ``--weather``), a design with the room's
glazing as one fixed clear source (``layout_daylight``) with the forward study of the
same scene (``study.simulate``, checked against Radiance: docs/daylight.md): DA300,
UDI 100-3000, sDA300/50% (LM-83 blinds), ASE1000,250 and the dimming energy of
luminaires giving 300 lux at full output (100 W), both sides' CPU seconds, and the
range over the points of the annual mean lux design / study and, for the study's own
noise, study (seed 1) / study (seed 0).
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
from lightinv_core.light.clear_build import clear_light
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


def versus_study(scene_name: str, weather: str) -> dict:
    """The design's figures and the study's on one daylight room (see the docstring)."""
    from lightinv_core.design.model import Daylight, Design, Source, Workplane
    from lightinv_core.light.model import LightModel
    from lightinv_core.operator.build import build_operator
    from lightinv_core.operator.settings import OperatorSettings
    from lightinv_core.scene.builtin import builtin_scene
    from lightinv_core.scene.patches import mesh_patches
    from lightinv_core.study import SimulationSpec, simulate
    from lightinv_core.study.clear_light import clear_dimming
    from lightinv_core.study.clear_metrics import blinds, work_plane_metrics
    from lightinv_core.transport.workplane import WorkPlane

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
    got = layout_daylight(light, design)
    ours_cpu = time.process_time() - t0
    ours = {}
    for q in ("da", "udi", "sda", "ase"):
        it = Intention(q, grid="wp", quantity=q, max=1.0)
        ours[q] = float(got.points.quantity(it)[:, 0].mean())
    lit = replace(got, installed_w=100.0)
    object.__setattr__(lit.points, "electric", np.full_like(lit.points.electric, 300.0))
    ours["energy_kwh"] = lit.energy().energy_kwh
    spec = SimulationSpec(
        scene=scene,
        glazing={group[0]: 0.7},
        glazing_kinds={group[0]: "clear"},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=daylight,
    )
    t0 = time.process_time()
    year = simulate(spec).clear_year
    study_cpu = time.process_time() - t0
    m, _ = work_plane_metrics(year)
    q = len(got.grids.points)
    # The study's own noise: its points' annual means under a second seed.
    other = simulate(replace(spec, seed=1)).clear_year
    occ = year.occupied
    mine = got.points.clear_hours().mean(axis=1)
    first = year.total(blinds(year))[:, occ].mean(axis=1)
    second = other.total(blinds(other))[:, occ].mean(axis=1)
    energy = clear_dimming(year, np.full(q, 300.0), 100.0, lit.floor_m2, daylight).energy_kwh
    study = {
        "da": m["da300_mean"],
        "udi": m["udi_100_3000"],
        "sda": m["sda300_50"],
        "ase": m["ase1000_250"],
        "energy_kwh": energy,
    }
    return {
        "scene": scene_name,
        "patches": patches.n,
        "points": q,
        "design": ours,
        "study": study,
        "point_mean_design_over_study": [float(x) for x in (min(mine / first), max(mine / first))],
        "point_mean_study_seed1_over_seed0": [
            float(x) for x in (min(second / first), max(second / first))
        ],
        "design_cpu_s": ours_cpu,
        "study_cpu_s": study_cpu,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=30)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--versus-study", action="store_true")
    ap.add_argument("--weather", default="builtin")
    args = ap.parse_args()
    if args.versus_study:
        rows = [versus_study(name, args.weather) for name in ("sidelit", "toplit")]
        print(json.dumps({"weather": args.weather, "rooms": rows}))
        return
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
