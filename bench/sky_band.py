"""Benchmark: finer skies in a project's clear glazing, and switching with a dead band.
Prints JSON.

    python bench/sky_band.py [--resolution 0.25] [--mfs 1,2,4] [--batch 256]

``skies``: the side-lit room (its 4.8 x 1.6 m window clear, glass 0.7, work plane 0.8
m) as a project at each Reinhart subdivision (``daylight.sky_subdivision``): the clear
build's CPU and wall seconds, its peak of traced memory (``tracemalloc``: numpy's arrays
included) and the bytes of the light it keeps, its columns; the annual figures (DA300,
UDI 100-3000, sDA300/50%, ASE1000,250, work-plane means) beside the forward study's at
the same subdivision (``simulate --sky-subdivision``).

``dead_band``: the built-in office's diffusing roof light and its two luminaires, the
west one in a switching group on the west half (target 500 lux): for each band the
year's mean level, energy and switchings (on-off changes within a day), and the CPU
seconds of the optimiser's level sum over a batch of candidates (band 0: the sorted
year; a band: hour by hour).
"""

from __future__ import annotations

import argparse
import json
import time
import tracemalloc
from dataclasses import replace

import numpy as np

from lightinv_core.climate.control_modes import control_mode, mode_levels
from lightinv_core.design.model import (
    ControlGroup,
    Daylight,
    Design,
    Goal,
    Intention,
    Source,
    Workplane,
)
from lightinv_core.light import clear_build
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.daylight_year import level_sum
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import SimulationSpec, simulate
from lightinv_core.study.clear_metrics import work_plane_metrics
from lightinv_core.transport.workplane import WorkPlane

TAU = 0.7
KEYS = (("da", "da300_mean"), ("udi", "udi_100_3000"), ("sda", "sda300_50"))


def _model(name: str, resolution: float, rays: int) -> LightModel:
    scene = builtin_scene(name, resolution)
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=rays)))


def _mean(ld, q: str) -> float:
    it = Intention("q", grid="wp", quantity=q, max=1.0)
    return float(ld.points.quantity(it)[:, 0].mean())


def skies(resolution: float, mfs: list[int]) -> dict:
    light = _model("sidelit", resolution, 512)
    window = Source("W1", "window", "window", (0.0, 0.0, *light.zone_size("window")))
    out = {"room": "sidelit", "resolution_m": resolution, "patches": light.n, "runs": []}
    warm = True  # a first build, not timed: the weather read, the sun's positions, imports
    for mf in [mfs[0], *mfs]:
        design = Design(
            sources=(replace(window, glazing="clear"),),
            goals=(Goal("min_electric_power"),),
            workplanes=(Workplane("wp", 0.8, 0.5),),
            daylight=Daylight(transmittance=TAU, sky_subdivision=mf),
        )
        clear_build._CACHE.clear()
        if warm:
            clear_build.clear_light(light, design)
            clear_build._CACHE.clear()
            warm = False
            continue
        tracemalloc.start()
        c0, w0 = time.process_time(), time.perf_counter()
        built = clear_build.clear_light(light, design)
        cpu, wall = time.process_time() - c0, time.perf_counter() - w0
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        cols = built.patches.columns  # shared by the points
        kept = cols.every.nbytes + cols.blinds.nbytes + built.points.direct.nbytes
        kept += built.patches.coefficients.nbytes + built.points.coefficients.nbytes
        ld = layout_daylight(light, design)
        ours = {q: _mean(ld, q) for q in ("da", "udi", "sda", "ase")}
        hourly = ld.points.clear_hours().mean(axis=1)  # each point's mean lux, occupied hours
        spec = SimulationSpec(
            scene=light.scene,
            glazing={"window": TAU},
            glazing_kinds={"window": "clear"},
            workplane=WorkPlane(0.8, 0.5),
            rays=512,
            annual=Daylight(transmittance=TAU),
            sky_mf=mf,
        )
        want, _ = work_plane_metrics(simulate(spec).clear_year)
        study = {q: float(want[k]) for q, k in (*KEYS, ("ase", "ase1000_250"))}
        out["runs"].append(
            {
                "mf": mf,
                "columns": built.patches.columns.count,
                "build_cpu_s": round(cpu, 2),
                "build_wall_s": round(wall, 2),
                "peak_traced_mb": round(peak / 2**20, 1),
                "kept_mb": round(kept / 2**20, 1),
                "project": {k: round(v, 4) for k, v in ours.items()},
                "study": {k: round(v, 4) for k, v in study.items()},
                "max_abs_difference": round(max(abs(ours[k] - study[k]) for k in ours), 4),
                "workplane_mean_lux": round(float(hourly.mean()), 1),
                "_hourly": hourly,
            }
        )
    base, lux = out["runs"][0]["project"], out["runs"][0]["_hourly"]
    for run in out["runs"]:
        run["moved_from_first"] = {k: round(run["project"][k] - base[k], 4) for k in base}
        # Each point's mean lux against the first subdivision's: mean |ratio - 1|.
        ratio = run.pop("_hourly") / lux
        run["point_mean_lux_moved_from_first"] = round(float(np.abs(ratio - 1).mean()), 4)
    return out


def dead_band(bands: list[float], batch: int) -> dict:
    light = _model("office", 0.5, 256)
    sky = Source("S", "skylight", "skylight", (1.0, 0.5, 3.0, 1.5))
    lum = dict(kind="luminaire", rect=(0.5, 1.5, 1.5, 4.5), flux=8000.0, free=("flux",))
    west = Source("L1", "lum_west", control_group="west", **lum)
    sources = (west, Source("L2", "lum_east", **lum), sky)
    out = {"room": "office", "target_lux": 500.0, "bands": []}
    switching = control_mode("switching")
    for band in bands:
        group = ControlGroup("west", sensor=(0, 0, 6, 8), mode="switching", dead_band=band)
        design = Design(
            sources,
            (Goal("min_annual_energy"),),
            daylight=Daylight(transmittance=0.6, standby_w=2.0),
            workplanes=(Workplane("wp"),),
            control_groups=(group, ControlGroup("all")),
        )
        ld = layout_daylight(light, design)
        west = ld.energy().groups[0]
        year = ld.patches.year()
        ids = ld.groups.plan.sensors[0]
        b = ld.points.sky[:, ids, 0].mean(axis=1)
        day = b @ year.exterior
        starts = year.day_starts
        levels = mode_levels(switching, day, 1.0, 500.0, 0.0, band, starts)
        changes = np.abs(np.diff(levels)) * ~starts[1:]
        rng = np.random.default_rng(0)
        B = b[None] * rng.uniform(0.5, 1.5, (batch, 1))
        full = np.full(batch, west.electric_lux)
        t0 = time.process_time()
        for _ in range(5):
            level_sum(switching, year, B, full, 500.0, 0.0, None, band)
        cpu = (time.process_time() - t0) / 5
        out["bands"].append(
            {
                "dead_band": band,
                "mean_level": round(west.mean_level, 4),
                "energy_kwh": round(west.energy_kwh, 1),
                "switchings_a_year": int(changes.sum()),
                "days_switched": len(np.unique(np.cumsum(starts)[1:][changes > 0])),
                "level_sum_cpu_ms": round(1000 * cpu, 2),
            }
        )
    out["batch"] = batch
    out["occupied_hours"] = int(year.hours)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--resolution", type=float, default=0.25)
    ap.add_argument("--mfs", default="1,2,4")
    ap.add_argument("--bands", default="0,0.1,0.15,0.25,0.5")
    ap.add_argument("--batch", type=int, default=256)
    args = ap.parse_args()
    mfs = [int(x) for x in args.mfs.split(",")]
    bands = [float(x) for x in args.bands.split(",") if x]
    result = {}
    if bands:
        result["dead_band"] = dead_band(bands, args.batch)
    result["skies"] = skies(args.resolution, mfs)
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
