"""Benchmark: the paper's five experiments at full resolution. Prints one JSON object.

    python bench/experiments.py --experiment 1 --runs 10 --json

Each run uses seed = its index. ``seconds`` is the optimisation alone (the
operator is built or loaded once, reported as ``precompute_seconds``).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
from pathlib import Path

import numpy as np

from lightinv_core.optimize.pareto import non_dominated
from lightinv_core.project import load_project
from lightinv_core.study import prepare, solve

PROJECTS = Path(__file__).resolve().parent.parent / "resources" / "projects"


def _run(name: str, runs: int, prepared=None) -> tuple[list[dict], object]:
    project = load_project(PROJECTS / f"{name}.json")
    prepared = prepared or prepare(project)
    out = []
    for seed in range(runs):
        r = solve(project, prepared, seed=seed)
        row = {"seed": seed, "status": r.status, "seconds": r.seconds, "evaluations": r.evaluations}
        if r.best is not None:
            row["objectives"] = r.best.objectives
            row["penalty"] = r.best.penalty
            row["violations"] = [
                f"{v.name} {v.constraint} {v.amount:.3f}" for v in r.best.violations
            ]
            row["sources"] = [
                {"name": s.name, "rect": s.rect, "area": s.area, "filter": s.filter}
                for s in r.best.sources
            ]
        if r.pareto is not None:
            F = np.array(
                [
                    [s.objectives["min_electric_power"], -s.objectives["max_light_power"]]
                    for s in r.pareto.solutions
                ]
            ).reshape(-1, 2)
            row["pareto_size"] = len(r.pareto.solutions)
            row["pareto_all_non_dominated"] = bool(non_dominated(F).all()) if len(F) else True
            row["pareto"] = F.tolist()
            row["candidates"] = len(r.pareto.candidates)
        out.append(row)
    return out, prepared


def _median(rows, key):
    return statistics.median(r[key] for r in rows) if rows else None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--experiment", type=int, choices=range(1, 6), required=True)
    ap.add_argument("--runs", type=int, default=10)
    ap.add_argument("--json", action="store_true", help="(default) print JSON")
    args = ap.parse_args()
    result = {"experiment": args.experiment, "runs": args.runs, "cores": os.cpu_count()}
    if args.experiment in (1, 2):
        rows, prep = _run("experiment1", args.runs)
        errors = [r["objectives"]["match"] for r in rows]
        result.update(
            patches=prep.patches.n,
            k=prep.operator.k,
            precompute_seconds=prep.seconds,
            multilevel=rows,
            median_seconds=_median(rows, "seconds"),
            median_evaluations=_median(rows, "evaluations"),
            median_error=statistics.median(errors),
            runs_below_0_03=sum(e < 0.03 for e in errors),
        )
        if args.experiment == 2:
            single, _ = _run("experiment2", args.runs, prep)
            result.update(
                single_level=single,
                single_median_seconds=_median(single, "seconds"),
                single_runs_below_0_03=sum(r["objectives"]["match"] < 0.03 for r in single),
                time_ratio_single_over_multilevel=_median(single, "seconds")
                / _median(rows, "seconds"),
            )
    elif args.experiment == 3:
        rows, prep = _run("experiment3", args.runs)
        bad, _ = _run("experiment3b", args.runs, prep)
        result.update(
            patches=prep.patches.n,
            feasible=rows,
            cmax_over_4=bad,
            median_seconds=_median(rows, "seconds"),
            feasible_runs=sum(r["status"] == "feasible" for r in rows),
            cmax_over_4_infeasible_runs=sum(r["status"] == "infeasible" for r in bad),
        )
    elif args.experiment == 4:
        rows, prep = _run("experiment4", args.runs)
        prod = [
            r["sources"][0]["area"] * r["sources"][0]["filter"]
            for r in rows
            if r["status"] == "feasible"
        ]
        result.update(
            patches=prep.patches.n,
            runs_detail=rows,
            median_seconds=_median(rows, "seconds"),
            feasible_runs=len(prod),
            area_times_filter=prod,
            cv_area_times_filter=float(np.std(prod) / np.mean(prod)) if prod else None,
        )
    else:
        sky, prep = _run("experiment5-skylights", min(args.runs, 3))
        eps, _ = _run("experiment5", 1, prep)
        two, _ = _run("experiment5-twostep", 1, prep)
        result.update(
            patches=prep.patches.n,
            skylights_only=sky,
            skylights_only_infeasible=all(r["status"] == "infeasible" for r in sky),
            epsilon=eps[0],
            two_step=two[0],
        )
    print(json.dumps(result, indent=2, default=float))


if __name__ == "__main__":
    main()
