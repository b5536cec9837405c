"""Benchmark: simplified DGP at observers in a project against Radiance and the forward
study, and the cost of its intention in the optimiser. Prints JSON.

    python bench/dgp_observers.py [--batch 32] [--repeats 10] [--rounds 5]

``versus_rtrace``: eye illuminance (lux) on planes facing each observer's view, three
eyes 1.2 m up (by the window looking at it, mid-room looking along the window wall, at
the back looking at the window):

- ``clear_hour``: the side-lit room (0.5 m patches) with its clear south window (glass
  0.7), blinds open, at the occupied hour of the builtin weather year whose sun lights
  the near eye most, against ``rtrace -I -ab 5 -ad 16384`` under gendaylit's Perez sky
  and sun of that hour's direct normal and diffuse horizontal illuminance;
- ``diffusing_overcast``: the Radiance bench office (4 x 6 x 3 m, a 3 x 1.5 m window of
  reflectance 0) with the window diffusing (``trans``, 0.7) under the CIE overcast sky of
  10,000 lux, against ``rtrace -ab 8 -ad 32768``.

``versus_study``: the side-lit room at its full resolution, the same eyes: the shares of
the occupied hours above DGPs 0.35 / 0.40 / 0.45, the brightest hour's Ev and the EN
17037 glare protection level through the project (``light.dgp_observers``) and through
``lightinv-cli simulate --view`` (``study.clear_metrics.view_metrics``), with the CPU
seconds of each.

``evaluation``: the integrated office demo (diffusing skylight S1 free, luminaires free)
with two observers, evaluated in batches with and without the intention "DGPs above
0.40 in at most 5% of the hours" at both: CPU seconds per batch (median of rounds
measured in turn), their ratio, the one-off build of the eyes' light, and the spread of
the intention's value over the batch.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # tests.radiance: the Radiance harness

from lightinv_core.design.model import (  # noqa: E402
    Daylight,
    Design,
    Goal,
    Intention,
    Observer,
    Source,
    Workplane,
)
from lightinv_core.light.daylight_year import sky_groups, weather_path  # noqa: E402
from lightinv_core.light.dgp_observers import eye_daylight, observer_dgp  # noqa: E402
from lightinv_core.light.model import LightModel  # noqa: E402
from lightinv_core.operator.build import build_operator  # noqa: E402
from lightinv_core.operator.settings import OperatorSettings  # noqa: E402
from lightinv_core.optimize.problem import DesignProblem  # noqa: E402
from lightinv_core.optimize.search import random_start  # noqa: E402
from lightinv_core.project import load_project  # noqa: E402
from lightinv_core.scene.builtin import builtin_scene  # noqa: E402
from lightinv_core.scene.patches import mesh_patches  # noqa: E402
from lightinv_core.sources.emission import source_stack  # noqa: E402
from lightinv_core.study import SimulationSpec, prepare, simulate  # noqa: E402
from lightinv_core.transport.workplane import WorkPlane  # noqa: E402

TAU = 0.7
PROJECT = ROOT / "resources" / "projects" / "office-integrated.json"


def _light(scene) -> LightModel:
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=512)))


def _design(light, eyes: dict, glazing: str) -> Design:
    w = Source("W1", "window", "window", (0.0, 0.0, *light.zone_size("window")), glazing=glazing)
    return Design(
        sources=(w,),
        goals=(Goal("min_electric_power"),),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        daylight=Daylight(transmittance=TAU),
        observers=tuple(Observer(n, (x, y), azimuth=a) for n, (x, y, a) in eyes.items()),
    )


SIDELIT_EYES = {"near": (3.0, 1.5, -90.0), "side": (1.0, 4.0, 0.0), "back": (3.0, 7.0, -90.0)}
OFFICE_EYES = {"near": (2.0, 1.5, -90.0), "side": (1.0, 3.0, 0.0), "back": (2.0, 5.0, -90.0)}


def _errors(ours, theirs) -> dict:
    err = np.abs(np.asarray(ours) / np.asarray(theirs) - 1)
    return {
        "ours_lux": [float(x) for x in ours],
        "rtrace_lux": [float(x) for x in theirs],
        "error": [float(x) for x in err],
        "mean_error": float(err.mean()),
    }


def clear_hour() -> dict:
    from lightinv_core.climate.transposition import sun_and_sky
    from lightinv_core.climate.weather import load_weather
    from lightinv_core.export.radiance_sky import gensky_azimuth
    from tests.radiance.run import POINT_PARAMS, point_lux
    from tests.radiance.scene import SKY_GLOW, _gen

    light = _light(builtin_scene("sidelit", 0.5))
    design = _design(light, SIDELIT_EYES, "clear")
    eyes = eye_daylight(light, design)
    d = design.daylight
    w = load_weather(weather_path(d))
    occ = np.asarray(w.occupied(*d.occupancy, weekdays=d.weekdays))
    dn, dh = np.asarray(w.dn_lux, float), np.asarray(w.dh_lux, float)
    beam = eyes.clear_light.direct.sum(axis=0)
    hours = np.flatnonzero(occ & (dn > 20000))
    h = int(hours[np.argmax(beam[0, hours])])
    mask = np.zeros(len(dn), bool)
    mask[h] = True
    ours = eyes.clear_light.open_hours(slice(None), mask)[:, 0]
    sky = sun_and_sky(w)
    alt, az = 90.0 - sky.zenith[h], sky.azimuth[h]
    args = ["gendaylit", "-ang", f"{alt:.6f}", f"{gensky_azimuth(az):.6f}"]
    args += ["-L", f"{dn[h]:g}", f"{dh[h]:g}", "-g", f"{d.ground_reflectance:g}"]
    t0 = time.time()
    theirs = point_lux(
        light.patches, {"window": TAU}, _gen(args) + SKY_GLOW, eyes.eyes.points,
        eyes.eyes.views, ab=5, params=POINT_PARAMS,
    )  # fmt: skip
    return {
        "hour": str(w.midpoints[h]),
        "sun_altitude_deg": float(alt),
        "sun_azimuth_deg": float(az),
        "direct_normal_lux": float(dn[h]),
        "diffuse_horizontal_lux": float(dh[h]),
        "rtrace": "-ab 5 -ad 16384 (tests/radiance/run.py POINT_PARAMS)",
        "rtrace_wall_s": time.time() - t0,
        **_errors(ours, theirs),
    }


def diffusing_overcast() -> dict:
    from tests.radiance.rooms import box_room
    from tests.radiance.run import point_lux
    from tests.radiance.scene import sky_cie_overcast

    light = _light(box_room((4.0, 6.0, 3.0), window=(0.5, 0.9, 3.5, 2.4), resolution=0.5))
    design = _design(light, OFFICE_EYES, "diffusing")
    eyes = eye_daylight(light, design)
    unit = replace(design.daylight, exterior_lux=1.0)
    V = light.zone_emission(design.sources, *source_stack(design.sources), unit)[:, :1]
    vertical = sky_groups(light, design).overcast[0] * 10000.0
    ours = eyes.sky_at_eyes(V)[0, :, 0] * vertical
    theirs = point_lux(
        light.patches, {"window": TAU}, sky_cie_overcast(10000.0, 0.2), eyes.eyes.points,
        eyes.eyes.views, diffusing={"window"}, ab=8, params="-aa 0 -ad 32768 -lw 1e-6",
    )  # fmt: skip
    return {"rtrace": "-ab 8 -ad 32768 -lw 1e-6", **_errors(ours, theirs)}


def versus_study() -> dict:
    scene = builtin_scene("sidelit")
    light = _light(scene)
    design = _design(light, SIDELIT_EYES, "clear")
    t0 = time.process_time()
    ours = observer_dgp(light, design)
    ours_cpu = time.process_time() - t0
    views = []
    for x, y, a in SIDELIT_EYES.values():
        r = np.radians(a)
        views.append((x, y, 1.2, round(np.cos(r), 12), round(np.sin(r), 12), 0.0))
    spec = SimulationSpec(
        scene=scene,
        glazing={"window": TAU},
        glazing_kinds={"window": "clear"},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=Daylight(transmittance=TAU),
        views=tuple(views),
    )
    t0 = time.process_time()
    theirs = simulate(spec).clear_annual["views"]
    study_cpu = time.process_time() - t0
    keys = ("dgp_over_0.35", "dgp_over_0.40", "dgp_over_0.45", "ev_max_lux", "en17037_glare")
    eyes = {}
    for name, row in zip(SIDELIT_EYES, theirs, strict=True):
        mine = {k: ours[name][k] for k in keys}
        eyes[name] = {"project": mine, "study": {k: row[k] for k in keys}}
    shares = [
        abs(ours[n][k] - row[k])
        for n, row in zip(SIDELIT_EYES, theirs, strict=True)
        for k in keys[:3]
    ]
    return {
        "patches": light.n,
        "eyes": eyes,
        "largest_share_difference_points": 100 * max(shares),
        "project_cpu_s": ours_cpu,
        "study_cpu_s": study_cpu,
    }


def evaluation(batch: int, repeats: int, rounds: int) -> dict:
    project = load_project(PROJECT)
    light = prepare(project).light
    observers = (
        Observer("desk west", (3.0, 4.0), azimuth=0.0),
        Observer("desk east", (9.0, 4.0), azimuth=180.0),
    )
    base = replace(project.design, observers=observers)
    it = Intention("glare", observers=("desk west", "desk east"), quantity="dgp", max=0.05)
    with_dgp = replace(base, intentions=(*base.intentions, it))
    problems = [DesignProblem(base, light), DesignProblem(with_dgp, light)]
    rng = np.random.default_rng(0)
    X = np.stack([random_start(problems[0], rng) for _ in range(batch)])
    problems[0].evaluate(X)  # warm: receivers, the weather year
    t0 = time.process_time()
    eyes = eye_daylight(light, with_dgp)
    build = time.process_time() - t0
    problems[1].evaluate(X)
    T = np.empty((rounds, 2))
    for r in range(rounds):
        for j, p in enumerate(problems):
            t0 = time.process_time()
            for _ in range(repeats):
                p.evaluate(X)
            T[r, j] = (time.process_time() - t0) / repeats
    lit = problems[1].lighting.of(*problems[1].vars.decode(X), problems[1].level(1), None)
    values = eyes.values(it, lit)
    return {
        "project": "office-integrated (diffusing skylight S1 free, luminaires free) + 2 eyes",
        "batch": batch,
        "occupied_hours": int(eyes.clear.shape[1]),
        "eye_build_cpu_s": build,
        "cpu_per_batch_s": {
            "without": float(np.median(T[:, 0])),
            "with": float(np.median(T[:, 1])),
        },
        "cpu_per_candidate_added_ms": 1e3 * float(np.median(T[:, 1] - T[:, 0])) / batch,
        "ratio_median": float(np.median(T[:, 1] / T[:, 0])),
        "ratio_range": [float((T[:, 1] / T[:, 0]).min()), float((T[:, 1] / T[:, 0]).max())],
        "value_over_batch": {
            name: [float(values[i].min()), float(values[i].max())]
            for i, name in enumerate(it.observers)
        },
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    out = {
        "versus_rtrace": {"clear_hour": clear_hour(), "diffusing_overcast": diffusing_overcast()},
        "versus_study": versus_study(),
        "evaluation": evaluation(args.batch, args.repeats, args.rounds),
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
