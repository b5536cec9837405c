"""Benchmark: the clear glazing's trace the window runs in a worker, and what the control
groups' modes and own targets do to the flagship office's energy. Prints JSON.

    python bench/clear_trace.py [--project resources/projects/office-flagship.json]

``trace``: the first ``clear_light`` of the project as shipped (its five clear windows,
its work plane, Greensboro TMY3), with the operator loaded first (from the cache, or
built); wall and CPU seconds, and the wall time at which each progress step the window
shows was reported (the longest gap is how long a Cancel may wait); then
``layout_daylight``, the design's light in every scenario the worker makes next.

``modes``: the design as written (its arrays as laid out in the file, not optimised),
its year by ``layout_daylight(...).energy()``: each group's kWh, mean level and the
total with standby, for the groups as shipped (both dimming to the daylight's 500 lux)
and with the window row switching, both switching, and the window row dimming to its
own 300 lux.
"""

from __future__ import annotations

import argparse
import itertools
import json
import time
from dataclasses import replace
from pathlib import Path

from lightinv_core.light.clear_build import clear_light
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.project import load_project
from lightinv_core.study import prepare

PROJECT = Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-flagship.json"


def trace(prepared, design) -> dict:
    steps: list[tuple[float, float]] = []
    t0, c0 = time.perf_counter(), time.process_time()
    clear_light(prepared.light, design, lambda f: steps.append((f, time.perf_counter() - t0)))
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    times = [0.0] + [t for _, t in steps] + [wall]
    return {
        "wall_s": round(wall, 2),
        "cpu_s": round(cpu, 2),
        "steps": [{"fraction": f, "at_s": round(t, 2)} for f, t in steps],
        "longest_gap_s": round(max(b - a for a, b in itertools.pairwise(times)), 2),
    }


def energies(light, design) -> dict:
    e = layout_daylight(light, design).energy()
    return {
        "total_kwh": round(e.energy_kwh, 1),
        "groups": {
            g.name: {
                "mode": g.mode,
                "target_lux": g.target_lux,
                "kwh": round(g.energy_kwh, 1),
                "mean_level": round(g.mean_level, 3),
            }
            for g in e.groups
        },
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default=str(PROJECT))
    args = ap.parse_args()
    project = load_project(args.project)
    t0 = time.perf_counter()
    prepared = prepare(project)
    out = {
        "project": Path(args.project).name,
        "patches": prepared.patches.n,
        "operator_s": round(time.perf_counter() - t0, 1),
        "operator_from_cache": prepared.from_cache,
    }
    design = project.design
    out["trace"] = trace(prepared, design)
    # What the window's worker makes next: the design's light in every scenario.
    t0, c0 = time.perf_counter(), time.process_time()
    layout_daylight(prepared.light, design)
    out["layout_daylight"] = {
        "wall_s": round(time.perf_counter() - t0, 2),
        "cpu_s": round(time.process_time() - c0, 2),
    }
    row, inner = design.control_groups[:2]
    variants = {
        "as shipped (dimming, 500 lux)": design.control_groups,
        "window row switching": (replace(row, mode="switching"), inner),
        "both switching": (replace(row, mode="switching"), replace(inner, mode="switching")),
        "window row dimming to 300 lux": (replace(row, target_lux=300.0), inner),
    }
    out["modes"] = {
        name: energies(prepared.light, replace(design, control_groups=groups))
        for name, groups in variants.items()
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
