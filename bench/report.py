"""Time a PDF report of a solved example project; prints JSON.

    .venv/bin/python bench/report.py                       # experiment 3, patio at 0.7 m
    .venv/bin/python bench/report.py --resolution 0.25 --out /tmp/report.pdf --png-dir /tmp/pages

Solves the project briefly (``--max-evals``) with a fixed-rank operator, then writes
the report and times its parts. Also times one view of the full-resolution patio
(~25,000 patches) when ``--full-view`` is given.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.project import OperatorSettings, load_project
from lightinv_core.report import render_view, write_report
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import prepare, solve

PROJECTS = Path(__file__).resolve().parents[1] / "resources" / "projects"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default=str(PROJECTS / "experiment3.json"))
    ap.add_argument("--resolution", type=float, default=0.7)
    ap.add_argument("--rank", type=int, default=250)
    ap.add_argument("--rays", type=int, default=256)
    ap.add_argument("--max-evals", type=int, default=3000)
    ap.add_argument("--out", help="PDF path (default: a temporary file)")
    ap.add_argument("--png-dir", help="also save the pages as PNG here")
    ap.add_argument("--full-view", action="store_true", help="time a full-resolution patio view")
    args = ap.parse_args()

    project = load_project(args.project)
    project = replace(
        project,
        scene=replace(project.scene, resolution=args.resolution),
        operator=OperatorSettings(rank=args.rank, rays=args.rays),
    )
    t0 = time.perf_counter()
    prepared = prepare(project)
    t1 = time.perf_counter()
    result = solve(project, prepared, max_evals=args.max_evals)
    t2 = time.perf_counter()
    if result.best is not None and result.pareto is None:
        project = replace(project, solutions=(result.best,))
    else:
        project = replace(project, pareto=result.pareto)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(args.out) if args.out else Path(tmp) / "report.pdf"
        info = write_report(project, prepared, out, png_dir=args.png_dir)
        t3 = time.perf_counter()
        size = out.stat().st_size
    res = {
        "project": project.name,
        "patches": prepared.patches.n,
        "status": result.status,
        "prepare_seconds": t1 - t0,
        "solve_seconds": t2 - t1,
        "report_seconds": t3 - t2,
        "pages": list(info.pages),
        "pdf_bytes": size,
    }
    if args.full_view:
        patches = mesh_patches(builtin_scene("patio"))
        values = patches.centroid[:, 2] * 10.0 + np.random.default_rng(0).random(patches.n)
        t4 = time.perf_counter()
        fig = render_view(patches, values, "iso")
        with tempfile.TemporaryDirectory() as tmp:
            fig.savefig(Path(tmp) / "view.png", dpi=100)
        res["full_view_patches"] = patches.n
        res["full_view_seconds"] = time.perf_counter() - t4
    print(json.dumps(res, indent=2))


if __name__ == "__main__":
    main()
