"""Benchmark: importing glTF/GLB and IFC models (lightinv_core/scene/importers/gltf.py,
meshes.py, ifc.py). Prints one JSON object:

- ``box``: the tests' 4 x 3 x 2.5 m box as OBJ and as GLB (its quads stored as
  triangles): patches at 0.5 m, and the GLB's patches had its triangles not been joined
  back into rectangles;
- ``glb``: import time of a GLB of k x k separate quads (2 k² triangles), per triangle;
- ``ifc``: import time and patches of a row of n copies of the tests' IFC room
  (slab, four walls, a window, a roof slab with a skylight, a ceiling panel, a space);
- ``ifc_memory``: peak memory of importing the n-room IFC file, measured in a fresh
  process (its peak resident memory, VmHWM, after the import less before it,
  ifcopenshell and shapely already imported): what ``size.check_ifc_size``
  estimates from the file's size;
- ``files``: for IFC files given with ``--ifc``, import time, what was left out, zones,
  patches at 0.5 m and the share of light lost (area-weighted, 128 rays per patch).

python bench/model_import.py
python bench/model_import.py --quads 100 300 --rooms 1 4 16 --ifc AC20-FZK-Haus.ifc
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from lightinv_core.scene.facets import Facets
from lightinv_core.scene.importers import meshes
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.patches import mesh_patches
from tests.core.test_mesh_import import Gltf, box_gltf, to_y_up
from tests.core.test_obj_import import BOX


def box(d: Path) -> dict:
    (d / "room.obj").write_text(BOX)
    glb = box_gltf(d / "room.glb")
    obj_n = mesh_patches(load_scene(str(d / "room.obj"), 0.5)).n
    glb_n = mesh_patches(load_scene(str(glb), 0.5)).n
    real = meshes.join_coplanar

    def no_join(vertices, triangles, keys):
        left = np.arange(len(triangles))
        return Facets(vertices, [], np.zeros(0, int), left, triangles)

    meshes.join_coplanar = no_join
    try:
        unjoined = mesh_patches(load_scene(str(glb), 0.5)).n
    finally:
        meshes.join_coplanar = real
    return {"obj_patches": obj_n, "glb_patches": glb_n, "glb_patches_unjoined": unjoined}


def quads(d: Path, k: int) -> dict:
    i, j = np.meshgrid(np.arange(k), np.arange(k), indexing="ij")
    origin = np.column_stack([i.ravel() * 0.02, j.ravel() * 0.02, np.zeros(k * k)])
    square = np.array([[0, 0, 0], [0.01, 0, 0], [0.01, 0.01, 0], [0, 0.01, 0]])
    q = origin[:, None, :] + square[None]
    tris = np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
    g = Gltf()
    g.node("floor", g.mesh([(to_y_up(tris.reshape(-1, 3)).reshape(-1, 3, 3), None)]))
    path = g.save(d / f"quads{k}.glb")
    t0 = time.perf_counter()
    scene = load_scene(str(path), 1.0)
    seconds = time.perf_counter() - t0
    return {
        "triangles": len(tris),
        "surfaces": len(scene.surfaces),
        "seconds": round(seconds, 3),
        "us_per_triangle": round(1e6 * seconds / len(tris), 1),
    }


def rooms(d: Path, n: int) -> dict:
    import ifcopenshell.api.feature

    from tests.core.test_ifc_import import SKY, WINDOW, H, L, T, W, ifc_room

    dx = L + T  # rooms share no walls: each is the test room moved along x

    def extra(add, f):
        for k in range(1, n):
            x = k * (dx + T)
            add("IfcSlab", f"Floor {k}", x - T, -T, -T, L + 2 * T, W + 2 * T, T, "FLOOR")
            south = add("IfcWall", f"South {k}", x - T, -T, 0, L + 2 * T, T, H)
            add("IfcWall", f"North {k}", x - T, W, 0, L + 2 * T, T, H)
            add("IfcWall", f"West {k}", x - T, 0, 0, T, W, H)
            add("IfcWall", f"East {k}", x + L, 0, 0, T, W, H)
            roof = add("IfcSlab", f"Roof {k}", x - T, -T, H, L + 2 * T, W + 2 * T, T, "ROOF")
            x0, x1, z0, z1 = WINDOW
            hole = add(
                "IfcOpeningElement",
                "o",
                x + x0,
                -T - 0.1,
                z0,
                x1 - x0,
                T + 0.2,
                z1 - z0,
                contained=False,
            )
            ifcopenshell.api.feature.add_feature(f, feature=hole, element=south)
            win = add("IfcWindow", f"W{k}", x + x0, -0.1, z0, x1 - x0, 0.05, z1 - z0)
            ifcopenshell.api.feature.add_filling(f, opening=hole, element=win)
            sx0, sx1, sy0, sy1 = SKY
            hole = add(
                "IfcOpeningElement",
                "o",
                x + sx0,
                sy0,
                H - 0.1,
                sx1 - sx0,
                sy1 - sy0,
                T + 0.2,
                contained=False,
            )
            ifcopenshell.api.feature.add_feature(f, feature=hole, element=roof)
            sky = add("IfcWindow", f"S{k}", x + sx0, sy0, H + 0.1, sx1 - sx0, sy1 - sy0, 0.05)
            ifcopenshell.api.feature.add_filling(f, opening=hole, element=sky)
            add("IfcCovering", f"Panel {k}", x + 4, 0, 2.7, 2, W, 0.02, "CEILING")

    path = ifc_room(d / f"rooms{n}.ifc", extra=extra)
    t0 = time.perf_counter()
    scene = load_scene(str(path), 0.5)
    seconds = time.perf_counter() - t0
    return {
        "rooms": n,
        "elements": scene.info["ifc"]["elements"],
        "zones": len(scene.zones),
        "area_m2": round(scene.area, 3),
        "patches": mesh_patches(scene).n,
        "seconds": round(seconds, 3),
    }


# The child's peak RSS is reset (clear_refs 5) after its imports: a forked child's
# ru_maxrss starts from its parent's.
PEAK = """
import sys
import ifcopenshell, ifcopenshell.geom, shapely
from lightinv_core.scene.loading import load_scene
def hwm():
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1])
open("/proc/self/clear_refs", "w").write("5")
before = hwm()
load_scene(sys.argv[1], 0.5)
print(before, hwm())
"""


def ifc_memory(d: Path, n: int) -> dict:
    """Peak import memory of the n-room file (written by ``rooms``), in a fresh process."""
    import subprocess

    path = d / f"rooms{n}.ifc"
    root = str(Path(__file__).resolve().parents[1])
    got = subprocess.run(
        [sys.executable, "-c", PEAK, str(path)],
        capture_output=True,
        text=True,
        check=True,
        cwd=root,
        env={**os.environ, "PYTHONPATH": root},
    )
    before, after = (int(x) for x in got.stdout.split()[-2:])
    nbytes = path.stat().st_size
    return {
        "rooms": n,
        "file_bytes": nbytes,
        "base_mib": round(before / 1024, 1),
        "import_mib": round((after - before) / 1024, 1),
    }


def ifc_file(path: str) -> dict:
    from lightinv_core.transport.formfactors import form_factor_matrix, lost_fraction

    t0 = time.perf_counter()
    scene = load_scene(path, 0.5)
    seconds = time.perf_counter() - t0
    info = scene.info["ifc"]
    p = mesh_patches(scene)
    kinds = list(info["zones"].values())
    return {
        "file": Path(path).name,
        "seconds": round(seconds, 3),
        "elements": info["elements"],
        "spaces": len(info["spaces"]),
        "contact_m2": round(info["contact_m2"], 1),
        "exterior_m2": round(info["exterior_m2"], 1),
        "area_m2": round(scene.area, 1),
        "zones": {k: kinds.count(k) for k in sorted(set(kinds))},
        "warnings": scene.info["warnings"],
        "patches": p.n,
        "lost_fraction": round(lost_fraction(form_factor_matrix(p, 128, seed=1), p), 4),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quads", type=int, nargs="+", default=[100, 300])
    ap.add_argument("--rooms", type=int, nargs="+", default=[1, 4, 16])
    ap.add_argument("--memory-rooms", type=int, nargs="+", default=[16, 64])
    ap.add_argument("--ifc", nargs="*", default=[], help="IFC files to measure as well")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        out = {"cores": os.cpu_count(), "box": box(d)}
        out["glb"] = [quads(d, k) for k in args.quads]
        out["ifc"] = [rooms(d, n) for n in sorted(set(args.rooms) | set(args.memory_rooms))]
        out["ifc_memory"] = [ifc_memory(d, n) for n in args.memory_rooms]
        out["files"] = [ifc_file(f) for f in args.ifc]
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
