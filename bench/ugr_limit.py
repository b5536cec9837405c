"""Benchmark: inverse design for a glare limit on the office demo's luminaire arrays.

The design: ``resources/projects/office-arrays.json`` as shipped (linear batwings in the
two ceiling strips, rows, columns, rotation and dimming free; EN 12464-1 filing on the
work plane, Em >= 300 lux, U0 >= 0.4), solved by ``auto`` with and without a UGR bound
(UGR_L 19, EN 12464-1's limit for offices) at two seated observers: "south" at the
middle of the south wall looking north across the room, "west" at the middle of the
west wall looking east along it. For each goal (the project's least electric power, and
least installed power) and seed: the layout's UGR at each observer (luminaires placed
exactly, ``light/glare.layout_glare``), installed and electric power, luminaires, Em and
U0 on the work plane (placed exactly), evaluations and seconds; and the evaluation rate
of random batches (256) with and without the UGR intention.

Prints one JSON object; ``--out`` also writes it.

python bench/ugr_limit.py [--seeds 3] [--max-evals 20000] [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import os
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.design.model import Goal, Intention, Observer
from lightinv_core.light.arrays import arrays_field
from lightinv_core.light.glare import layout_glare
from lightinv_core.light.model import LightModel
from lightinv_core.operator.cache import get_operator
from lightinv_core.optimize.method import RunContext
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.registry import get_method
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.optimize.termination import StopRule
from lightinv_core.project import load_project
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.workplane import grid_statistics

ROOT = Path(__file__).resolve().parents[1]
PROJECT = ROOT / "resources" / "projects" / "office-arrays.json"
UGR_L = 19.0
OBSERVERS = (
    Observer("south", (6.0, 0.6), azimuth=90.0),
    Observer("west", (0.6, 4.0), azimuth=0.0),
)


def rate(problem: DesignProblem, seconds: float = 3.0) -> float:
    """Evaluations per second of random batches of 256 at every receiver."""
    rng = np.random.default_rng(0)
    lo, hi = problem.vars.lo, problem.vars.hi
    level = problem.level(1)
    problem.evaluate(lo + rng.random((256, len(lo))) * (hi - lo), level)
    reps, t = 0, time.process_time()
    while time.process_time() - t < seconds:
        problem.evaluate(lo + rng.random((256, len(lo))) * (hi - lo), level)
        reps += 1
    return reps * 256 / (time.process_time() - t)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--max-evals", type=int, default=20000)
    ap.add_argument("--out", type=Path)
    args = ap.parse_args()
    project = load_project(PROJECT)
    out: dict = {"project": PROJECT.name, "ugr_limit": UGR_L, "cores": os.cpu_count()}
    out["observers"] = [
        {"name": o.name, "position": o.position, "height": o.height, "azimuth": o.azimuth}
        for o in OBSERVERS
    ]
    out["load_before"] = os.getloadavg()[0]
    scene = builtin_scene("office", project.scene.resolution)
    patches = mesh_patches(scene)
    light = LightModel(scene, patches, get_operator(patches, project.operator).operator)
    base = replace(project.design, observers=OBSERVERS)
    bound = Intention("glare", observers=("south", "west"), quantity="ugr", max=UGR_L)
    runs, precompute, rates = [], {}, {}
    for goal in ("min_electric_power", "min_installed_power"):
        for limited in (False, True):
            its = base.intentions + ((bound,) if limited else ())
            design = replace(base, intentions=its, goals=(Goal(goal),))
            t = time.perf_counter()
            problem = DesignProblem(design, light)
            _ = problem.arrays  # the lattice responses, made on first use
            key = "with_ugr" if limited else "without_ugr"
            precompute.setdefault(key, time.perf_counter() - t)
            if key not in rates:
                rates[key] = rate(problem)
            for seed in range(args.seeds):
                t = time.perf_counter()
                ctx = RunContext(OptimizerSettings(seed=seed), StopRule(args.max_evals), seed=seed)
                res = get_method("auto").run(problem, ctx)
                seconds = time.perf_counter() - t
                best = res.best
                _, lux = arrays_field(patches, light.op, best.arrays, problem.grids.points)
                stats = grid_statistics(lux)
                ugr = layout_glare(light, design, (), best.arrays)
                lay = problem.layout_of(np.asarray(best.x)[None])
                runs.append(
                    {
                        "goal": goal,
                        "ugr_bound": UGR_L if limited else None,
                        "seed": seed,
                        "feasible": bool(best.feasible),
                        "ugr": {k: round(v, 2) for k, v in ugr.items()},
                        "installed_W": float(problem.arrays.installed_power(lay)[0]),
                        "electric_W": round(float(problem.arrays.electric_power(lay)[0]), 1),
                        "luminaires": int(sum(a.count for a in best.arrays)),
                        "arrays": [
                            (a.rows, a.columns, a.rotation, round(a.dimming, 3))
                            for a in best.arrays
                        ],
                        "Em": round(stats["Em"], 1),
                        "U0": round(stats["U0"], 3),
                        "evaluations": res.evaluations,
                        "seconds": round(seconds, 1),
                    }
                )
                print(json.dumps(runs[-1]), flush=True)
    out.update(precompute_seconds=precompute, evaluations_per_cpu_second=rates, runs=runs)
    out["load_after"] = os.getloadavg()[0]
    text = json.dumps(out, indent=1)
    print(text)
    if args.out:
        args.out.write_text(text + "\n")


if __name__ == "__main__":
    main()
