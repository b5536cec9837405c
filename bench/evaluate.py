"""Benchmark: DesignProblem.evaluate throughput on the shipped projects. Prints JSON.

    python bench/evaluate.py --project office-demo --batch 32 --repeats 200

Candidates are random layouts meeting the geometric rules (so every one needs light);
reported: candidates per second (median of ``--rounds`` rounds) at full resolution and,
for multilevel projects, at the coarsest level. ``--cpu`` times by the process's CPU
seconds instead of the wall clock: on a busy machine that compares two versions of the
code fairly (run with OMP_NUM_THREADS=1 so one core's work is counted).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from pathlib import Path

import numpy as np

from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.search import random_start
from lightinv_core.project import load_project
from lightinv_core.study import prepare

PROJECTS = Path(__file__).resolve().parent.parent / "resources" / "projects"


def rate(
    problem: DesignProblem, X: np.ndarray, level, repeats: int, rounds: int, clock=time.perf_counter
) -> float:
    """Median candidates per second (by ``clock``) over ``rounds`` rounds of ``repeats``
    batches."""
    out = []
    for _ in range(rounds):
        t0 = clock()
        for _ in range(repeats):
            problem.evaluate(X, level)
        out.append(repeats * len(X) / (clock() - t0))
    return statistics.median(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default="office-demo")
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=200)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--cpu", action="store_true", help="time by CPU seconds, not wall")
    args = ap.parse_args()
    clock = time.process_time if args.cpu else time.perf_counter
    project = load_project(PROJECTS / f"{args.project}.json")
    prepared = prepare(project)
    problem = DesignProblem(project.design, prepared.light)
    rng = np.random.default_rng(0)
    X = np.stack([random_start(problem, rng) for _ in range(args.batch)])
    out = {
        "project": args.project,
        "patches": prepared.patches.n,
        "k": prepared.operator.k,
        "batch": args.batch,
        "cores": os.cpu_count(),
        "clock": "cpu" if args.cpu else "wall",
        "full_per_s": rate(problem, X, problem.level(1), args.repeats, args.rounds, clock),
    }
    if project.optimizer.method == "multilevel":
        d = max(project.optimizer.divisors)
        out[f"level_{d}_per_s"] = rate(
            problem, X, problem.level(d), args.repeats, args.rounds, clock
        )
    print(json.dumps(out))


if __name__ == "__main__":
    main()
