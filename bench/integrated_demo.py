"""Benchmark: the integrated office demo's front of glazing area against annual energy,
over seeds. Prints JSON.

    python bench/integrated_demo.py [--seeds 10] [--weather FILE]

Runs the demo as shipped (resources/projects/office-integrated.json: the epsilon
method, its evaluation budget and bound count) once per seed and reports, per seed, the
front's points (glazing m², kWh a year), its hypervolume in the normalised plane
(docs/design.md), evaluations and seconds; then the seeds whose sweep ended feasible at
every bound, and the median over seeds of the least energy and of the energy at the
smallest glazing. Also the least-energy layout's daylight (seed 0): DF, DA300, sDA,
UDI, kWh, full-output kWh and LENI, as ``lightinv-cli solve`` prints them.
"""

from __future__ import annotations

import argparse
import gzip
import json
import os
import statistics
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from lightinv_core.optimize.quality import front_quality, front_scales
from lightinv_core.project import load_project
from lightinv_core.study import prepare, solve

PROJECT = (
    Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-integrated.json"
)


def _plain(path: str) -> str:
    """The weather file's path; a gzipped one (tests/data/weather) decompressed first."""
    if not path.endswith(".gz"):
        return str(Path(path).resolve())
    out = Path(tempfile.mkdtemp()) / Path(path).name[:-3]
    out.write_bytes(gzip.decompress(Path(path).read_bytes()))
    return str(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument(
        "--weather", default=None, help="another weather file (EPW, TMY3, TMY2) for the demo"
    )
    args = ap.parse_args()
    from lightinv_core.cli.solve import daylight_summary

    project = load_project(PROJECT)
    if args.weather:
        daylight = replace(project.design.daylight, weather=_plain(args.weather))
        project = replace(project, design=replace(project.design, daylight=daylight))
    prepared = prepare(project)
    scales = front_scales(project.design, prepared.light)
    runs = []
    for seed in range(args.seeds):
        t0 = time.perf_counter()
        result = solve(replace(project, optimizer=replace(project.optimizer, seed=seed)), prepared)
        seconds = time.perf_counter() - t0
        front = result.pareto
        points = sorted(
            (s.objectives["min_glazing_area"], s.objectives["min_annual_energy"])
            for s in front.solutions
        )
        runs.append(
            {
                "seed": seed,
                "front": [[round(a, 3), round(e, 1)] for a, e in points],
                "all_feasible": all(s.feasible for s in front.candidates),
                "candidates": len(front.candidates),
                "hypervolume": front_quality(front.solutions, scales).hypervolume,
                "evaluations": result.evaluations,
                "seconds": seconds,
            }
        )
        if seed == 0:
            best = min(front.solutions, key=lambda s: s.objectives["min_annual_energy"])
            daylight = daylight_summary(prepared.light, project.design, best)
            daylight.pop("monthly_kwh")
    least = [min(e for _, e in r["front"]) for r in runs if r["front"]]
    smallest = [r["front"][0][1] for r in runs if r["front"]]
    print(
        json.dumps(
            {
                "project": "office-integrated",
                "weather": args.weather or project.design.daylight.weather,
                "patches": prepared.patches.n,
                "cores": os.cpu_count(),
                "seeds": args.seeds,
                "all_feasible_seeds": sum(r["all_feasible"] for r in runs),
                "median_least_kwh": statistics.median(least) if least else None,
                "median_kwh_at_smallest_glazing": statistics.median(smallest) if smallest else None,
                "median_hypervolume": statistics.median(r["hypervolume"] for r in runs),
                "median_seconds": statistics.median(r["seconds"] for r in runs),
                "least_energy_daylight_seed0": daylight,
                "runs": runs,
            }
        )
    )


if __name__ == "__main__":
    main()
