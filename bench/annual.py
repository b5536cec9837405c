"""Benchmark: the cost of annual goals against a single-scenario evaluation. Prints JSON.

    python bench/annual.py [--batch 32] [--repeats 100] [--rounds 7]

On the integrated office demo (resources/projects/office-integrated.json, full
resolution), the same random candidates are evaluated by:

- ``single``: one scenario, the paper's: the demo's intention judged in the design
  scenario (luminaires plus skylights at the design exterior lux) and the
  least-electric-power goal: one GEMM of the emitting columns at the receivers;
- ``annual``: the demo's goals, least annual energy and glazing area, with the same
  intention: the luminaires' and the skylight's light apart, and the year's dimming
  energy and sDA by the sorted-hours method (one sky group);
- ``annual_hourly``: the same with the year's statistics counted hour by hour (the
  method used when skylights face several ways), for comparison.

Reported: candidates per second (median of the rounds; the three are measured in turn
within each round), the ratios to ``single`` (median of the rounds' ratios, and each
round's; the target is annual <= 2x single), the occupied hours and the machine's cores; and a
check that the sorted and hourly methods agree on the batch.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.design.model import Goal
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.search import random_start
from lightinv_core.project import load_project
from lightinv_core.study import prepare

PROJECT = (
    Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-integrated.json"
)


def batch_seconds(problem: DesignProblem, X: np.ndarray, repeats: int) -> float:
    """Seconds per candidate over ``repeats`` batches."""
    t0 = time.perf_counter()
    for _ in range(repeats):
        problem.evaluate(X)
    return (time.perf_counter() - t0) / (repeats * len(X))


def interleaved(problems: list, X: np.ndarray, repeats: list, rounds: int) -> np.ndarray:
    """(rounds, len(problems)) seconds per candidate, the problems measured in turn
    within each round, so a slow spell of the machine hits all of them alike."""
    for p in problems:
        p.evaluate(X)  # warm: receivers, the weather year
    return np.array(
        [
            [batch_seconds(p, X, r) for p, r in zip(problems, repeats, strict=True)]
            for _ in range(rounds)
        ]
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=100)
    ap.add_argument("--rounds", type=int, default=7)
    args = ap.parse_args()
    project = load_project(PROJECT)
    prepared = prepare(project)
    light = prepared.light
    design = project.design
    annual = DesignProblem(design, light)
    one = tuple(replace(it, scenario="design") for it in design.intentions)
    single_design = replace(design, goals=(Goal("min_electric_power"),), intentions=one)
    single = DesignProblem(single_design, light)
    hourly = DesignProblem(design, light)
    rng = np.random.default_rng(0)
    X = np.stack([random_start(annual, rng) for _ in range(args.batch)])
    # The hour-by-hour method: the same year without its sorted hours.
    annual.evaluate(X[:1])
    year = annual._year_box[0]
    hourly._year_box[:] = [replace(year, sorted=None, prefix=None)]
    a, h = annual.evaluate(X), hourly.evaluate(X)
    agree = float(
        np.max(np.abs(a.goals["min_annual_energy"] - h.goals["min_annual_energy"]))
        / np.max(a.goals["min_annual_energy"])
    )
    T = interleaved(
        [single, annual, hourly],
        X,
        [args.repeats, args.repeats, max(1, args.repeats // 10)],
        args.rounds,
    )
    t_single, t_annual, t_hourly = np.median(T, axis=0)
    ratios = T[:, 1] / T[:, 0]
    print(
        json.dumps(
            {
                "project": "office-integrated",
                "patches": prepared.patches.n,
                "workplane_points": len(annual.grids.points),
                "occupied_hours": year.hours,
                "batch": args.batch,
                "cores": os.cpu_count(),
                "single_per_s": 1 / t_single,
                "annual_per_s": 1 / t_annual,
                "annual_hourly_per_s": 1 / t_hourly,
                "annual_over_single": float(np.median(ratios)),
                "annual_over_single_rounds": [float(r) for r in ratios],
                "hourly_over_single": float(np.median(T[:, 2] / T[:, 0])),
                "sorted_vs_hourly_energy_rel_diff": agree,
            }
        )
    )


if __name__ == "__main__":
    main()
