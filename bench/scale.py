"""Benchmark: how the operator's build time, peak memory and evaluation rate grow with n.

Each case (a built-in scene at a resolution) runs in its own process, so its peak
memory (VmHWM, the kernel's high-water mark of the process) is its own: meshing,
the build (form factors, clusters, Y, G) and a typical optimiser batch. Prints one
JSON object and writes it to ``bench/results-scale.json`` (``--out``).

The optimiser batch is what ``DesignProblem.evaluate`` does on every step: ``--batch``
candidate layouts of the scene's first luminaire zones (corners and flux free) and
skylight, judged at every patch of an intention (desks, or the floor) and the
light-power goal. The receivers' rows of the zone basis are made once (timed apart).

    python bench/scale.py                      # every case; the building takes minutes
    python bench/scale.py --cases office_5k,office_10k
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

CASES = {
    # name: (scene, resolution m); office at 0.25 m is 5,424 patches, n ~ 1 / res².
    "office_5k": ("office", 0.25),
    "office_10k": ("office", 0.177),
    "office_20k": ("office", 0.125),
    "office_40k": ("office", 0.0884),
    "patio": ("patio", None),
    "building_14k": ("building", 1.0),
    "building_50k": ("building", 0.5),
    "building": ("building", None),
}
HERE = Path(__file__).resolve().parent


def peak_mb() -> float:
    """This process's own peak resident memory so far, MiB: VmHWM (ru_maxrss would keep
    the parent's high-water mark across fork and exec); ru_maxrss where there is no /proc."""
    try:
        with open("/proc/self/status") as fh:
            return next(int(x.split()[1]) for x in fh if x.startswith("VmHWM:")) / 1024
    except (OSError, StopIteration):
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _design(scene, patches):
    """Up to four luminaires (corners and flux free) in the scene's first luminaire zones
    and one skylight, an intention on the desks (or the floor), the light-power goal."""
    from lightinv_core.design.model import CORNERS, Design, Goal, Intention, Source

    lums = [z for z in scene.zones if z.kind == "luminaire"][:4]
    skies = [z for z in scene.zones if z.kind == "skylight"][:1]
    sources = [
        Source(
            f"L{i}", z.name, "luminaire", (0.2, 0.2, 1.2, 1.2), free=(*CORNERS, "flux"), flux=3000.0
        )
        for i, z in enumerate(lums)
    ]
    sources += [Source("S", z.name, "skylight", (0.1, 0.1, 1.0, 1.0), free=CORNERS) for z in skies]
    group = "desks" if "desks" in patches.group_names else "floor"
    return Design(
        tuple(sources),
        (Goal("min_electric_power"),),
        intentions=(Intention(group, group=group, min=300.0),),
    )


def run_case(name: str, batch: int, rays: int) -> dict:
    """Build and evaluate one case in this process; the measurements as a dict."""
    from lightinv_core.light.model import LightModel
    from lightinv_core.operator.build import estimate_build_bytes
    from lightinv_core.operator.cache import get_operator
    from lightinv_core.operator.settings import OperatorSettings
    from lightinv_core.optimize.problem import DesignProblem
    from lightinv_core.scene.builtin import builtin_scene
    from lightinv_core.scene.patches import mesh_patches

    base = peak_mb()
    scene_name, res = CASES[name]
    scene = builtin_scene(scene_name, res)
    t0 = time.perf_counter()
    patches = mesh_patches(scene)
    t_mesh = time.perf_counter() - t0
    settings = OperatorSettings(rays=rays)
    t0 = time.perf_counter()
    op = get_operator(patches, settings, use_cache=False).operator
    t_build = time.perf_counter() - t0
    build_peak = peak_mb()
    light = LightModel(scene, patches, op)
    problem = DesignProblem(_design(scene, patches), light)
    t0 = time.perf_counter()
    level = problem.level(1)
    t_rows = time.perf_counter() - t0
    rng = np.random.default_rng(5)
    lo, hi = problem.vars.lo, problem.vars.hi
    X = lo + rng.random((batch, problem.vars.n)) * (hi - lo)  # random layouts
    problem.evaluate(X[:2], level)  # warm-up
    calls, t0 = 0, time.perf_counter()
    while calls < 3 or time.perf_counter() - t0 < 2.0:
        problem.evaluate(X, level)
        calls += 1
    rate = calls * batch / (time.perf_counter() - t0)
    info = op.info
    return {
        "case": name,
        "scene": scene_name,
        "resolution": scene.resolution,
        "n": patches.n,
        "k": op.k,
        "nz": op.nz,
        "surfaces": len(scene.surfaces),
        "formfactor_nnz": info["formfactor_nnz"],
        "mesh_seconds": t_mesh,
        "formfactor_seconds": info["formfactor_seconds"],
        "build_seconds": t_build,
        "tries": info["tries"],
        "estimated_rel_error": info["estimated_rel_error"],
        "tol_met": info["tol_met"],
        "memory_limited": info["memory_limited"],
        "lost_fraction": info["lost_fraction"],
        "baseline_peak_mb": base,
        "build_peak_mb": build_peak,
        "estimate_mb": estimate_build_bytes(patches, rays, op.k) / 2**20,
        "operator_mb": op.nbytes() / 2**20,
        "dense_phi_would_be_mb": 4 * patches.n * op.nz / 2**20,
        "receivers": len(level.rows),
        "receiver_rows_seconds": t_rows,
        "batch": batch,
        "candidates_per_s": rate,
        "peak_mb": peak_mb(),
    }


def fit(xs, ys) -> float | None:
    """Slope of log y against log x (the growth exponent), None with under two points."""
    if len(xs) < 2:
        return None
    return float(np.polyfit(np.log(xs), np.log(ys), 1)[0])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--cases", default=",".join(CASES), help="comma-separated, of: " + ", ".join(CASES)
    )
    ap.add_argument("--batch", type=int, default=64)
    ap.add_argument("--rays", type=int, default=1024)
    ap.add_argument("--out", default=str(HERE / "results-scale.json"))
    ap.add_argument("--case", help=argparse.SUPPRESS)  # a child process: run one case
    args = ap.parse_args()
    if args.case:
        print(json.dumps(run_case(args.case, args.batch, args.rays)))
        return
    names = [c for c in args.cases.split(",") if c]
    unknown = [c for c in names if c not in CASES]
    if unknown:
        ap.error(f"unknown cases {unknown}; known: {', '.join(CASES)}")
    load_before = os.getloadavg()
    results = []
    for name in names:
        cmd = [sys.executable, __file__, "--case", name, "--batch", str(args.batch)]
        cmd += ["--rays", str(args.rays)]
        t0 = time.perf_counter()
        done = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if done.returncode != 0:
            results.append({"case": name, "error": done.stderr.strip().splitlines()[-1:]})
            continue
        row = json.loads(done.stdout)
        row["wall_seconds"] = time.perf_counter() - t0
        row["load_after"] = os.getloadavg()
        results.append(row)
        print(f"{name}: n={row['n']:,} {row['build_seconds']:.1f} s", file=sys.stderr)
    ok = [r for r in results if "error" not in r]
    office = [r for r in ok if r["scene"] == "office"]
    growth = {
        "office_build_seconds_vs_n": fit(
            [r["n"] for r in office], [r["build_seconds"] for r in office]
        ),
        "office_peak_mb_vs_n": fit([r["n"] for r in office], [r["build_peak_mb"] for r in office]),
        "office_net_peak_mb_vs_n": fit(
            [r["n"] for r in office], [r["build_peak_mb"] - r["baseline_peak_mb"] for r in office]
        ),
        "all_net_peak_mb_vs_nk": fit(
            [r["n"] * r["k"] for r in ok], [r["build_peak_mb"] - r["baseline_peak_mb"] for r in ok]
        ),
        "all_operator_mb_vs_n": fit([r["n"] for r in ok], [r["operator_mb"] for r in ok]),
    }
    out = {
        "benchmark": "scale",
        "cores": os.cpu_count(),
        "affinity_cores": len(os.sched_getaffinity(0)),
        "memory_gib": os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30,
        "load_before": load_before,
        "load_after": os.getloadavg(),
        "rays": args.rays,
        "batch": args.batch,
        "cases": results,
        "growth_exponents": growth,
    }
    text = json.dumps(out, indent=2)
    print(text)
    Path(args.out).write_text(text + "\n")


if __name__ == "__main__":
    main()
