"""Daylight factors under the CIE overcast sky: the sky integral against its closed
forms, glazing emission in any orientation, and a black room against the exact
point-to-rectangle form factor."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.climate.sky import overcast_plane_illuminance, overcast_sky_factor
from lightinv_core.scene.builders import room_faces
from lightinv_core.scene.model import Rect, Scene, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.glazing import glazing_emission
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.scene_light import light_grid, light_scene
from lightinv_core.transport.workplane import WorkPlane, work_plane_grid


def test_overcast_sky_factor_against_closed_forms():
    assert overcast_sky_factor(0.0) == pytest.approx(1.0, abs=1e-9)
    # Vertical: L_z (pi/6 + 4/9) over the horizontal 7 pi L_z / 9.
    vertical = (math.pi / 6 + 4 / 9) / (7 * math.pi / 9)
    assert vertical == pytest.approx(0.396, abs=5e-4)
    assert overcast_sky_factor(90.0) == pytest.approx(vertical, abs=1e-5)
    assert overcast_sky_factor(180.0) == pytest.approx(0.0, abs=1e-12)
    tilts = np.linspace(0, 180, 19)
    assert np.all(np.diff([overcast_sky_factor(t) for t in tilts]) < 0)


def test_plane_illuminance_adds_the_ground():
    normals = np.array([[0, 0, 1.0], [1, 0, 0], [0, 0, -1.0], [0, 1, 1.0]])
    got = overcast_plane_illuminance(normals, 10000.0, 0.2)
    assert got[0] == pytest.approx(10000.0)
    assert got[1] == pytest.approx(10000.0 * (overcast_sky_factor(90) + 0.1))
    assert got[2] == pytest.approx(10000.0 * 0.2)  # facing the ground only
    c = math.cos(math.radians(45))
    assert got[3] == pytest.approx(10000.0 * (overcast_sky_factor(45) + 0.2 * (1 - c) / 2))


def corner(a: float, b: float) -> float:
    """Howell C-11: point at unit height to a parallel a x b rectangle at a corner
    (odd in a and in b, so signed corners add up)."""
    return (
        a / math.sqrt(1 + a * a) * math.atan(b / math.sqrt(1 + a * a))
        + b / math.sqrt(1 + b * b) * math.atan(a / math.sqrt(1 + b * b))
    ) / (2 * math.pi)


def parallel_factor(p, d: float, x0: float, x1: float, y0: float, y1: float) -> float:
    """Point ``p`` facing up to the rectangle [x0, x1] x [y0, y1] at ``d`` m above it."""
    f = [corner((x - p[0]) / d, (y - p[1]) / d) for x in (x0, x1) for y in (y0, y1)]
    return f[3] - f[1] - f[2] + f[0]


def black_room_with_a_rooflight() -> Scene:
    faces = room_faces(0, 0, 0, 6, 4, 3)
    surfaces = [Surface(k, k, 0.0, rect=r) for k, r in faces.items() if k != "ceiling"]
    # The ceiling in three strips, the middle one glazed (2 x 4 m), facing down.
    surfaces += [
        Surface("c1", "ceiling", 0.0, rect=Rect((0, 4, 3), (2, 0, 0), (0, -4, 0))),
        Surface("glass", "rooflight", 0.0, rect=Rect((2, 4, 3), (2, 0, 0), (0, -4, 0))),
        Surface("c2", "ceiling", 0.0, rect=Rect((4, 4, 3), (2, 0, 0), (0, -4, 0))),
    ]
    return Scene("black", surfaces, resolution=0.5)


def test_a_black_room_matches_the_exact_form_factor():
    p = mesh_patches(black_room_with_a_rooflight())
    E, lit = glazing_emission(p, {"rooflight": 0.6}, 10000.0, 0.2)
    caster = RayCaster(p)
    F = form_factor_matrix(p, 256, seed=1, caster=caster)
    light = light_scene(lit, F, caster, E, [])
    assert light.emitted_lm == pytest.approx(0.6 * 10000.0 * 8.0)
    grid = work_plane_grid(p, caster, WorkPlane(0.8, 0.5))
    got = light_grid(grid, light, caster, [], rays=4096, seed=2)
    df = 100 * got.lux / 10000.0
    exact = np.array([100 * 0.6 * parallel_factor(q, 2.2, 2, 4, 0, 4) for q in grid.points])
    np.testing.assert_allclose(df, exact, rtol=0.03)
    assert df.mean() == pytest.approx(exact.mean(), rel=0.01)


def test_a_window_lets_in_the_vertical_light():
    faces = room_faces(0, 0, 0, 5, 4, 3)
    surfaces = [Surface(k, k, 0.5, rect=r) for k, r in faces.items() if k != "south"]
    south = faces["south"]  # y = 0: the window fills its middle
    surfaces += [Surface("wall", "walls", 0.5, rect=south.sub(0, 0, 1, 0.3))]
    surfaces += [Surface("window", "window", 0.5, rect=south.sub(0, 0.3, 1, 0.8))]
    surfaces += [Surface("wall2", "walls", 0.5, rect=south.sub(0, 0.8, 1, 1))]
    p = mesh_patches(Scene("room", surfaces, resolution=0.5))
    E, lit = glazing_emission(p, {"window": 0.7}, 10000.0, 0.2)
    win = p.group_index("window")
    assert np.all(lit.rho[win] == 0) and np.all(lit.rho[p.group_index("floor")] == 0.5)
    flux = E[win] @ p.area[win]
    assert flux == pytest.approx(0.7 * 10000.0 * (overcast_sky_factor(90) + 0.1) * 5 * 1.5)


def test_cli_writes_daylight_factors(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    argv = ["simulate", "office", "--resolution", "0.5", "--sky", "cie-overcast"]
    argv += ["--exterior-lux", "10000", "--glazing", "roof=0.7", "--ground-reflectance", "0.2"]
    argv += ["--workplane", "0.8", "--border", "0.5", "--grid-csv", str(tmp_path / "g.csv")]
    argv += ["--patches-csv", str(tmp_path / "p.csv")]
    assert cli.main([*argv, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rows = (tmp_path / "g.csv").read_text().splitlines()
    assert rows[0] == "x,y,z,lux,df"
    values = np.array([[float(v) for v in r.split(",")] for r in rows[1:]])
    np.testing.assert_allclose(values[:, 4], values[:, 3] / 100, rtol=1e-5)
    assert out["grid"]["df"]["mean"] == pytest.approx(values[:, 4].mean(), rel=1e-5)
    assert out["energy"]["emitted_lm"] == pytest.approx(0.7 * 10000 * 8)
    header = (tmp_path / "p.csv").read_text().splitlines()[0].split(",")
    assert header[-1] == "df" and {"group", "area", "lux"} <= set(header)
    for bad, message in (
        (["--sky", "cie-overcast"], "give both --sky cie-overcast (or --weather FILE) and"),
        (["--glazing", "roof=0.5", "--emit", "floor=1"], "give both"),
        (["--sky", "cie-overcast", "--glazing", "roof=1.5"], "transmittance from 0 to 1"),
    ):
        code = None
        try:
            code = cli.main(["simulate", "office", "--resolution", "0.5", *bad])
        except SystemExit as exc:
            code = exc.code
        assert code == 2 and message in capsys.readouterr().err
