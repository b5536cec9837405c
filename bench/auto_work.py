"""Benchmark: how well ``auto``'s work model (optimize/work_model.py) predicts the CPU of
its searches' batches, and the least-squares fit its constants come from. Prints JSON.

    python bench/auto_work.py > bench/results-auto-work.json          # ~5 min
    python bench/auto_work.py --problems office experiment4 --evals 3000

Each problem is run by ``auto`` (seeds 0 and 1, ``--evals`` evaluations each); every
batch's CPU (``time.process_time`` around its step) is recorded with what the model
counts: its search, whether it began a CMA-ES run, and the light's multiply-adds and
copied operator entries (``LightTally``). The fit: CPU = BATCH[search] + NEW_RUN x
new run + GEMM x madds + COPY x copies, each batch weighted by the inverse of its
problem's and search's mean (so the cheap office batches count as much as the patio's).
Batches over 0.3 s are left out (a problem's first, which pays its caches). Reported
per problem and search: the mean measured and modelled ms per batch, with the model's
current constants and the fitted ones. One BLAS thread.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent))

import optimizers as bench

from lightinv_core.optimize import portfolio, work_model
from lightinv_core.project import load_project
from lightinv_core.study import prepare, solve

PROBLEMS = ("experiment1", "experiment3", "experiment4", "office", "three-luminaires")


def batches(name: str, evals: int) -> list[dict]:
    """Every batch of ``auto`` on ``name`` (seeds 0 and 1): its search, CPU and counts."""
    rows: list[dict] = []
    step = portfolio._Arm.step

    def timed(arm, before=None):
        t = arm.tally
        m0, c0 = t.madds, t.copies
        es = getattr(arm.run, "es", None) if arm.run is not None else None
        cpu = time.process_time()
        step(arm, before)
        cpu = time.process_time() - cpu
        new = arm.name == "cmaes" and es is not getattr(arm.run, "es", None)
        rows.append(
            {
                "search": arm.name,
                "cpu": cpu,
                "new_run": int(new),
                "madds": t.madds - m0,
                "copies": t.copies - c0,
            }
        )

    if name in bench.BUILT:
        project = bench.built_match(name)
    else:
        project = load_project(bench.PROJECTS / f"{bench.SINGLE[name]}.json")
    prepared = prepare(project)
    solve(bench._with_method(project, "vns:max_evals=64"), prepared, seed=0)  # warm-up
    portfolio._Arm.step = timed
    try:
        for seed in (0, 1):
            solve(bench._with_method(project, f"auto:max_evals={evals}"), prepared, seed=seed)
    finally:
        portfolio._Arm.step = step
    for r in rows:
        r["problem"] = name
    return rows


def features(r: dict) -> list[float]:
    c = r["search"] == "cmaes"
    return [float(c), float(not c), r["new_run"], r["madds"], r["copies"]]


def modelled(r: dict, coef=None) -> float:
    if coef is None:
        light = work_model.GEMM * r["madds"] + work_model.COPY * r["copies"]
        return work_model.batch_seconds(r["search"], light, bool(r["new_run"]))
    return float(np.dot(features(r), coef))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--problems", nargs="+", default=list(PROBLEMS))
    ap.add_argument("--evals", type=int, default=5000)
    args = ap.parse_args()
    import cma

    cma.CMAEvolutionStrategy([0.5, 0.5], 0.3, {"verbose": -9, "verb_log": 0, "verb_disp": 0})
    rows = []
    with threadpool_limits(1):
        for name in args.problems:
            rows += batches(name, args.evals)
            print(f"{name} done", file=sys.stderr, flush=True)
    rows = [r for r in rows if r["cpu"] < 0.3]
    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        groups.setdefault((r["problem"], r["search"]), []).append(r)
    scale = {k: 1.0 / np.mean([r["cpu"] for r in g]) for k, g in groups.items()}
    w = np.array([scale[(r["problem"], r["search"])] for r in rows])
    A = np.array([features(r) for r in rows])
    y = np.array([r["cpu"] for r in rows])
    coef, *_ = np.linalg.lstsq(A * w[:, None], y * w, rcond=None)
    out = {
        "evals_per_run": args.evals,
        "batches": len(rows),
        "fitted": dict(
            zip(
                ("BATCH[cmaes]", "BATCH[vns]", "NEW_RUN", "GEMM", "COPY"),
                map(float, coef),
                strict=True,
            )
        ),
        "model": {
            "BATCH": work_model.BATCH,
            "NEW_RUN": work_model.NEW_RUN,
            "GEMM": work_model.GEMM,
            "COPY": work_model.COPY,
        },
        "per_batch_ms": {},
    }
    for (problem, search), g in sorted(groups.items()):
        out["per_batch_ms"][f"{problem}/{search}"] = {
            "batches": len(g),
            "measured": 1e3 * float(np.mean([r["cpu"] for r in g])),
            "model": 1e3 * float(np.mean([modelled(r) for r in g])),
            "fitted": 1e3 * float(np.mean([modelled(r, coef) for r in g])),
        }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
