"""EN 12464-1's two grid rules on the issue's room (issue #31 item 3): an 8 x 6 x 3 m
room (walls 0.5, ceiling 0.7, floor 0.2), six 600 x 600 LEDVANCE panels (a real
EULUMDAT file) in two rows of three at 2.9 m, a work plane 0.8 m up with a 0.5 m
border. The same light (direct from the photometry, inter-reflected by the reference
radiosity solver) read at the 2011 grid (points per side rounded up) and at the 2021
grid (cell from the longer side, points rounded): the points, Em, Emin and U0 of each.
Prints one JSON object.

    .venv/bin/python bench/en12464_editions.py
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from lightinv_core.design.en12464 import EDITIONS  # noqa: E402
from lightinv_core.design.model import Workplane  # noqa: E402
from lightinv_core.light.grids import edition_grid  # noqa: E402
from lightinv_core.luminaires import read_photometry  # noqa: E402
from lightinv_core.scene.builders import room_faces  # noqa: E402
from lightinv_core.scene.model import Scene, Surface  # noqa: E402
from lightinv_core.scene.patches import mesh_patches  # noqa: E402
from lightinv_core.transport.formfactors import form_factor_matrix  # noqa: E402
from lightinv_core.transport.luminaires import PlacedLuminaire  # noqa: E402
from lightinv_core.transport.raycast import RayCaster  # noqa: E402
from lightinv_core.transport.scene_light import light_grid, light_scene  # noqa: E402
from lightinv_core.transport.workplane import grid_statistics  # noqa: E402

RHO = {"floor": 0.2, "ceiling": 0.7}
PANEL = ROOT / "tests" / "data" / "photometry" / "ledvance-panel-600.ldt"


def main() -> dict:
    t0 = time.process_time()
    faces = room_faces(0, 0, 0, 8, 6, 3)
    scene = Scene(
        "issue-room",
        [Surface(k, k, RHO.get(k, 0.5), rect=r) for k, r in faces.items()],
        resolution=0.25,
    )
    p = mesh_patches(scene)
    caster = RayCaster(p)
    F = form_factor_matrix(p, 1024, seed=1, caster=caster)
    ph = read_photometry(PANEL)
    lums = [
        PlacedLuminaire(f"L{i}{j}", (x, y, 2.9), ph)
        for i, x in enumerate((4 / 3, 4.0, 20 / 3))
        for j, y in enumerate((1.5, 4.5))
    ]
    light = light_scene(p, F, caster, np.zeros(p.n), lums)
    out = {"room": "8 x 6 x 3 m, border 0.5 m, 6 LEDVANCE 600 panels at 2.9 m", "editions": {}}
    for edition in EDITIONS:
        grid = edition_grid(p, caster, Workplane("wp", 0.8, 0.5, edition=edition))
        lux = light_grid(grid, light, caster, lums, rays=4096, seed=3).lux
        st = grid_statistics(lux)
        out["editions"][str(edition)] = {
            "counts": list(grid.counts),
            "p_m": round(grid.rule_spacing, 4),
            "points": st["points"],
            "Em": round(st["Em"], 1),
            "Emin": round(st["Emin"], 1),
            "U0": round(st["U0"], 3),
        }
    out["cpu_s"] = round(time.process_time() - t0, 1)
    return out


if __name__ == "__main__":
    print(json.dumps(main(), indent=2))
