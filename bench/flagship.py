"""Benchmark: the flagship office (resources/projects/office-flagship.json) solved with
several seeds. Prints JSON.

    python bench/flagship.py [--seeds 10] [--max-evals N] [--resolution R]

Runs the project as shipped (NSGA-II, its budget and population; ``--max-evals`` and
``--resolution`` override them) once per seed on one prepared scene (the operator, the
clear windows' light and the arrays' responses are computed once, before the first
seed, and timed apart). Per seed: the front (kWh a year, installed W), its hypervolume in
the normalised plane (docs/design.md: the least-energy front against the worst point of
every luminaire at full output all year, all luminaires installed), evaluations and
seconds, and whether **every criterion** of every front point passes as the PDF report
judges it (``report.criteria``: the design status table, the work plane's EN 12464-1
rows with Ra, the geometric rules; work-plane values and UGR with the luminaires placed
exactly). Then the share of seeds meeting every criterion (the issue's target: 10 of
10), the median hypervolume and time, and seed 0's least-energy layout's figures.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

from lightinv_core.design.en12464 import ra_warnings
from lightinv_core.optimize.fronts import front_pair
from lightinv_core.optimize.quality import front_quality, front_scales
from lightinv_core.project import load_project
from lightinv_core.report.criteria import status_table, workplane_criteria
from lightinv_core.report.tables import rules_table
from lightinv_core.study import prepare, solve
from lightinv_core.study.solution_light import solution_light

PROJECT = Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-flagship.json"


def failures(project, prepared, sol) -> list[str]:
    """The criteria a solution fails, as the report's tables list them (empty: all pass)."""
    design = project.design
    daylight = solution_light(prepared, design, sol).daylight
    tables = [
        status_table(design, sol, daylight, rules_table(sol, design, prepared.patches)),
        workplane_criteria(design, sol, daylight),
    ]
    out = [
        " / ".join(map(str, row[:-1]))
        for t in tables
        if t is not None
        for row, flag in zip(t.rows, t.flags, strict=True)
        if flag == "fail"
    ]
    return out + ra_warnings(design)


def figures(project, prepared, sol) -> dict:
    """The CLI's daylight and energy summary of one layout, and its night values."""
    from lightinv_core.cli.solve import daylight_summary

    out = daylight_summary(prepared.light, project.design, sol)
    out.pop("monthly_kwh", None)
    out["arrays"] = [
        {"name": a.name, "rows": a.rows, "columns": a.columns, "dimming": round(a.dimming, 3)}
        for a in sol.arrays
    ]
    out["objectives"] = sol.objectives
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--max-evals", type=int, default=None)
    ap.add_argument("--resolution", type=float, default=None)
    args = ap.parse_args()
    project = load_project(PROJECT)
    if args.resolution is not None:
        project = replace(project, scene=replace(project.scene, resolution=args.resolution))
    c0 = time.process_time()
    t0 = time.perf_counter()
    prepared = prepare(project)
    pair = front_pair(project.design)  # (least annual energy, least installed power)
    scales = front_scales(project.design, prepared.light, pair)
    runs, first = [], None
    for seed in range(args.seeds):
        t1, c1 = time.perf_counter(), time.process_time()
        result = solve(
            replace(project, optimizer=replace(project.optimizer, seed=seed)),
            prepared,
            max_evals=args.max_evals,
        )
        seconds, cpu = time.perf_counter() - t1, time.process_time() - c1
        front = result.pareto.solutions if result.pareto is not None else ()
        failed = [f for s in front for f in failures(project, prepared, s)]
        runs.append(
            {
                "seed": seed,
                "status": result.status,
                "front": sorted(
                    [
                        round(s.objectives["min_annual_energy"], 1),
                        round(s.objectives["min_installed_power"], 1),
                    ]
                    for s in front
                ),
                "every_criterion_met": bool(front) and not failed,
                "failures": sorted(set(failed))[:10],
                "hypervolume": front_quality(front, scales, pair).hypervolume if front else 0.0,
                "evaluations": result.evaluations,
                "seconds": seconds,
                "cpu_seconds": cpu,
                "precompute_seconds": result.precompute_seconds,
            }
        )
        if seed == 0 and front:
            first = figures(
                project,
                prepared,
                min(front, key=lambda s: s.objectives["min_annual_energy"]),
            )
        print(json.dumps(runs[-1]), flush=True, file=sys.stderr)
    print(
        json.dumps(
            {
                "project": "office-flagship",
                "patches": prepared.patches.n,
                "cores": os.cpu_count(),
                "seeds": args.seeds,
                "max_evals": args.max_evals or project.optimizer.max_evals,
                "seeds_meeting_every_criterion": sum(r["every_criterion_met"] for r in runs),
                "median_hypervolume": statistics.median(r["hypervolume"] for r in runs),
                "median_seconds": statistics.median(r["seconds"] for r in runs),
                "median_cpu_seconds": statistics.median(r["cpu_seconds"] for r in runs),
                "total_wall_seconds": time.perf_counter() - t0,
                "total_cpu_seconds": time.process_time() - c0,
                "least_energy_seed0": first,
                "runs": runs,
            },
            indent=1,
        )
    )


if __name__ == "__main__":
    main()
