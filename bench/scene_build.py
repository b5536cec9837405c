"""Benchmark: building scenes from big OBJ files, which must grow linearly with the faces.

Each size runs in a fresh process (so peak memory is its own): the streaming size
check, the import (parse, faces to surfaces) and the meshing into patches, for a
grid of rectangular faces (the worst case: every face becomes a surface) and for a
soup of separate triangles; then round floors of 1000 and 10,000 segments. Prints
one JSON object with a linear fit of seconds against faces.

python bench/scene_build.py                 # 10k, 40k, 160k, 1M faces
python bench/scene_build.py --faces 10000 40000
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def write_quads(path: Path, faces: int) -> None:
    """A k x k grid of 1 cm quads sharing vertices (about ``faces`` faces)."""
    k = round(math.sqrt(faces))
    i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
    v = np.column_stack([i.ravel() * 0.01, j.ravel() * 0.01, np.zeros(i.size)])
    a = (np.arange(k)[:, None] * (k + 1) + np.arange(k)[None, :] + 1).ravel()
    f = np.column_stack([a, a + k + 1, a + k + 2, a + 1])
    with open(path, "w") as fh:
        fh.write("g floor\n")
        np.savetxt(fh, v, fmt="v %.4f %.4f %.1f")
        np.savetxt(fh, f, fmt="f %d %d %d %d")


def write_triangles(path: Path, faces: int) -> None:
    """``faces`` separate small triangles (an exporter's triangle soup)."""
    rng = np.random.default_rng(0)
    base = rng.random((faces, 2)) * 20
    v = np.concatenate(
        [np.column_stack([base + off, np.zeros(faces)]) for off in ([0, 0], [0.05, 0], [0, 0.05])],
        axis=1,
    ).reshape(-1, 3)
    f = np.arange(1, 3 * faces + 1).reshape(-1, 3)
    with open(path, "w") as fh:
        fh.write("g floor\n")
        np.savetxt(fh, v, fmt="v %.5f %.5f %.1f")
        np.savetxt(fh, f, fmt="f %d %d %d")


def write_round(path: Path, sides: int, radius: float = 3.0) -> None:
    t = 2 * np.pi * np.arange(sides) / sides
    with open(path, "w") as fh:
        for x, y in zip(radius * np.cos(t), radius * np.sin(t), strict=True):
            fh.write(f"v {x:.9f} {y:.9f} 0\n")
        fh.write("g floor\nf " + " ".join(str(i + 1) for i in range(sides)) + "\n")


CHILD = """
import json, sys, time
from lightinv_core.cli import peak_rss_mb
from lightinv_core.scene.importers.obj import load_obj
from lightinv_core.scene.importers.obj_size import count_obj_lines
from lightinv_core.scene.patches import mesh_patches
path, res = sys.argv[1], float(sys.argv[2])
t0 = time.perf_counter(); counts = count_obj_lines(path)
t1 = time.perf_counter(); scene = load_obj(path, resolution=res)
t2 = time.perf_counter(); p = mesh_patches(scene)
t3 = time.perf_counter()
print(json.dumps({"faces": counts.faces, "file_mb": counts.nbytes / 2**20,
    "scan_seconds": t1 - t0, "import_seconds": t2 - t1, "mesh_seconds": t3 - t2,
    "seconds": t3 - t0, "surfaces": len(scene.surfaces), "patches": p.n,
    "area_m2": float(p.area.sum()), "estimated_import_mb": counts.import_bytes / 2**20,
    "peak_rss_mb": peak_rss_mb()}))
"""


def run(path: Path, resolution: float) -> dict:
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(path), str(resolution)],
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout)


def fit(rows: list[dict]) -> dict:
    """seconds = a + b * faces by least squares, and the largest relative residual."""
    x = np.array([r["faces"] for r in rows], float)
    y = np.array([r["seconds"] for r in rows])
    b, a = np.polyfit(x, y, 1)
    return {
        "seconds_per_million_faces": 1e6 * b,
        "intercept_seconds": a,
        "max_relative_residual": float(np.max(np.abs(a + b * x - y) / y)),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--faces", type=int, nargs="+", default=[10_000, 40_000, 160_000, 1_000_000])
    args = ap.parse_args()
    result: dict = {"cores": os.cpu_count(), "python": sys.version.split()[0]}
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for kind, writer, res in (("quads", write_quads, 1.0), ("triangles", write_triangles, 1.0)):
            rows = []
            for n in args.faces:
                path = folder / f"{kind}-{n}.obj"
                writer(path, n)
                rows.append(run(path, res))
                path.unlink()
                print(f"{kind} {n}: {rows[-1]['seconds']:.1f} s", file=sys.stderr)
            result[kind] = {"rows": rows, "fit": fit(rows) if len(rows) > 1 else None}
        rounds = []
        for sides in (1000, 10_000):
            path = folder / f"round-{sides}.obj"
            write_round(path, sides)
            t0 = time.perf_counter()
            row = run(path, 0.5)
            row.update(sides=sides, wall_seconds=time.perf_counter() - t0)
            row["area_error"] = (
                row["area_m2"] / (0.5 * sides * 9 * math.sin(2 * math.pi / sides)) - 1
            )
            rounds.append(row)
        result["round_floors_at_0.5_m"] = rounds
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
