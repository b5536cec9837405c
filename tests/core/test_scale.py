"""Whole buildings: the built-in building scene, its operator against the reference
solver, and the memory model (the build's estimate bounds the measured peak; the
operator holds no n x nz array)."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from lightinv_core.errors import SceneError
from lightinv_core.operator.accuracy import sample_emissions
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.building import building
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.solver import solve

COARSE = 1.5  # m: about 7,000 patches


@pytest.fixture(scope="module")
def coarse():
    return mesh_patches(building(COARSE))


def test_the_building_has_its_storeys_rooms_and_zones():
    scene = building(COARSE, floors=3, rooms=2)
    names = {z.name: z.kind for z in scene.zones}
    # A luminaire band in every office and corridor, skylights on the top storey and
    # over both stair voids.
    offices = [f"F{f}.{row}{i}" for f in range(3) for row in "SN" for i in range(2)]
    assert all(names[f"{o}.lum"] == "luminaire" for o in offices)
    assert all(names[f"F{f}.corridor.lum"] == "luminaire" for f in range(3))
    assert {k for k, v in names.items() if v == "skylight"} == {
        "F2.S0.sky",
        "F2.S1.sky",
        "F2.N0.sky",
        "F2.N1.sky",
        "stair_west.sky",
        "stair_east.sky",
    }
    assert {"floor", "walls", "ceiling", "desks", "corridor_floor", "stairs", "roof"} <= set(
        scene.groups
    )
    p = mesh_patches(scene)
    desks = p.group_index("desks")
    storey = np.floor(p.centroid[desks, 2] / 3.3)
    np.testing.assert_allclose(p.centroid[desks, 2] - 3.3 * storey, 0.75)
    assert sorted(np.unique(storey)) == [0, 1, 2]
    with pytest.raises(SceneError, match="1 to 50 storeys"):
        building(COARSE, floors=0)


def test_light_reaches_every_storey_through_the_stairs(coarse):
    """A skylight over a stair void lights every corridor (through the void and the
    openings), while the offices, behind doors, get less: the building is connected."""
    op = build_operator(coarse, OperatorSettings(rank=2500, rays=256))
    E = np.zeros(coarse.n)
    sky = coarse.zone_index("stair_west.sky")
    E[sky] = 10_000.0
    H = op.illuminance(E)
    corridor = coarse.group_index("corridor_floor")
    z = coarse.centroid[corridor, 2]
    for f in range(4):
        on = corridor[np.abs(z - 3.3 * f) < 0.01]
        assert H[on].max() > 0.5, f
    assert op.info["lost_fraction"] < 1e-4


def test_the_building_operator_against_the_reference_solver(coarse):
    op = build_operator(coarse, OperatorSettings(tol=0.01, rays=512, seed=2))
    assert op.info["tol_met"]
    E = sample_emissions(coarse, 4, seed=77)  # not the build's own samples
    for q in range(E.shape[1]):
        ref = solve(op.F.astype(np.float64), coarse.rho, E[:, q])
        C = coarse.rho * op.illuminance(E[:, q])
        assert np.linalg.norm(C - ref.C) / np.linalg.norm(ref.C) < 0.02


PEAK = """
import json, sys
from lightinv_core.operator.build import build_operator, estimate_build_bytes
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches

def hwm():  # this process's own peak (ru_maxrss keeps the parent's across exec)
    with open("/proc/self/status") as fh:
        return next(int(x.split()[1]) * 1024 for x in fh if x.startswith("VmHWM:"))

base, rays = hwm(), int(sys.argv[3])
patches = mesh_patches(builtin_scene(sys.argv[1], float(sys.argv[2])))
op = build_operator(patches, OperatorSettings(rays=rays))
out = {"net": hwm() - base, "estimate": estimate_build_bytes(patches, rays, op.k)}
out.update(operator=op.nbytes(), n=patches.n, k=op.k, nz=op.nz)
print(json.dumps(out))
"""


@pytest.mark.parametrize("scene,res,rays", [("office", 0.25, 1024), ("building", 1.5, 256)])
def test_the_memory_estimate_bounds_the_measured_peak(scene, res, rays):
    """In its own process, a build's peak (ru_maxrss above the interpreter's) stays
    under ``estimate_build_bytes`` at the k it ended with, and the operator holds
    F, Y and G, never an n x nz array."""
    out = subprocess.run(
        [sys.executable, "-c", PEAK, scene, str(res), str(rays)],
        capture_output=True,
        text=True,
        timeout=600,
        check=True,
    )
    got = json.loads(out.stdout)
    assert 0 < got["net"] <= got["estimate"], got
    n, k, nz = got["n"], got["k"], got["nz"]
    held = 2 * 8 * n * rays + 4 * n * k + 4 * k * nz + 16 * (n + 1)  # F, F[:, zone], Y, G
    assert got["operator"] <= held
