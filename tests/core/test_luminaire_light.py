"""Photometric luminaires and work planes, checked against closed forms, the flux
budget of a closed room, shadows, symmetry, and the patches' own illuminance."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.errors import LightInvError, PhotometryError
from lightinv_core.luminaires.analytic import batwing_linear, downlight
from lightinv_core.luminaires.photometry import Photometry
from lightinv_core.scene.builders import room_faces
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.model import Rect, Scene, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.sources.luminaire_csv import read_luminaire_csv
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.luminaires import PlacedLuminaire, direct_on_patches
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.scene_light import light_grid, light_scene
from lightinv_core.transport.workplane import (
    WorkPlane,
    en12464_spacing,
    grid_counts,
    grid_statistics,
    work_plane_grid,
)

DOWN = (0.0, 0.0, -1.0)


def isotropic(cd: float) -> Photometry:
    g = np.linspace(0.0, 180.0, 37)
    return Photometry("C", np.array([0.0]), g, np.full((1, len(g)), cd))


def lambertian_down(i0: float) -> Photometry:
    g = np.linspace(0.0, 90.0, 91)
    return Photometry("C", np.array([0.0]), g, i0 * np.cos(np.radians(g))[None])


def square(a: float) -> Scene:
    """One a x a floor patch facing up, centred on the origin."""
    rect = Rect((-a / 2, -a / 2, 0), (a, 0, 0), (0, a, 0))
    return Scene("square", (Surface("floor", "floor", 0.5, rect=rect, grid=(1, 1)),))


def corner_factor(x: float, y: float) -> float:
    """Form factor from a point at unit height to a parallel x-by-y rectangle with a
    corner below it (Howell's catalogue, C-11)."""
    a, b = x, y
    return (
        a / math.sqrt(1 + a * a) * math.atan(b / math.sqrt(1 + a * a))
        + b / math.sqrt(1 + b * b) * math.atan(a / math.sqrt(1 + b * b))
    ) / (2 * math.pi)


@pytest.mark.parametrize("a, h", [(0.5, 2.0), (1.0, 1.0), (2.0, 0.5)])
def test_direct_light_on_a_patch_matches_closed_forms(a, h):
    p = mesh_patches(square(a))
    caster = RayCaster(p)
    # Isotropic 100 cd: the patch receives I times its solid angle.
    solid = 4 * math.asin((a / 2) ** 2 / ((a / 2) ** 2 + h * h))
    iso = PlacedLuminaire("iso", (0, 0, h), isotropic(100.0), DOWN, (1, 0, 0))
    got = direct_on_patches(p, [iso], caster, samples=256)[0]
    assert got == pytest.approx(100.0 * solid / a**2, rel=0.01)
    # Lambertian I0 cos(gamma): I0 * pi * the point-to-square form factor.
    lam = PlacedLuminaire("lam", (0, 0, h), lambertian_down(100.0), DOWN, (1, 0, 0))
    flux = 100.0 * math.pi * 4 * corner_factor(a / 2 / h, a / 2 / h)
    got = direct_on_patches(p, [lam], caster, samples=256)[0]
    assert got == pytest.approx(flux / a**2, rel=0.01)


def test_a_closed_room_receives_all_the_light_and_balances():
    scene = builtin_scene("office", 0.5)
    p = mesh_patches(scene)
    caster = RayCaster(p)
    lums = [
        PlacedLuminaire(f"D{k}", (x, y, 2.95), downlight(2000.0, watts=20.0), DOWN, (1, 0, 0))
        for k, (x, y) in enumerate([(2, 2), (6, 4), (10, 6)])
    ]
    H0 = direct_on_patches(p, lums, caster)
    assert H0 @ p.area == pytest.approx(sum(x.lumens for x in lums), rel=0.01)
    F = form_factor_matrix(p, 256, seed=1, caster=caster)
    light = light_scene(p, F, caster, np.zeros(p.n), lums)
    assert abs(light.imbalance) < 0.01
    assert np.all(light.H >= light.H0) and light.B @ p.area > 0


def test_a_panel_casts_a_shadow():
    faces = room_faces(0, 0, 0, 4, 4, 3)
    surfaces = [Surface(k, k, 0.5, rect=r) for k, r in faces.items()]
    # A 1 m² opaque panel at 2 m, both faces, between the luminaire and the floor centre.
    top = Rect((1.5, 1.5, 2.0), (1, 0, 0), (0, 1, 0))
    bottom = Rect((1.5, 2.5, 2.0), (1, 0, 0), (0, -1, 0))
    surfaces += [Surface("panel.top", "panel", 0.5, rect=top)]
    surfaces += [Surface("panel.bottom", "panel", 0.5, rect=bottom)]
    p = mesh_patches(Scene("shade", surfaces, resolution=0.25))
    lum = PlacedLuminaire("L", (2, 2, 2.9), downlight(2000.0, watts=20.0), DOWN, (1, 0, 0))
    H0 = direct_on_patches(p, [lum], RayCaster(p))
    floor = p.group_index("floor")
    below = floor[np.all(np.abs(p.centroid[floor, :2] - 2.0) < 0.3, axis=1)]
    # The shadow reaches 0.5 x 2.9 / 0.9 = 1.61 m from the centre; beyond, light.
    aside = floor[np.all(np.abs(p.centroid[floor, :2] - [0.125, 2.0]) < 0.2, axis=1)]
    assert len(below) and np.all(H0[below] == 0.0)
    assert np.all(H0[aside] > 0.0)


def test_turning_the_c0_plane_turns_the_light():
    faces = room_faces(0, 0, 0, 6, 6, 3)
    p = mesh_patches(
        Scene("sq", [Surface(k, k, 0.5, rect=r) for k, r in faces.items()], resolution=0.5)
    )
    caster = RayCaster(p)
    wing = batwing_linear(4000.0, watts=32.0)
    along_x = PlacedLuminaire("x", (3, 3, 2.9), wing, DOWN, (1, 0, 0))
    along_y = PlacedLuminaire("y", (3, 3, 2.9), wing, DOWN, (0, 1, 0))
    grid = work_plane_grid(p, caster, WorkPlane(0.8, 0.5))
    ex = along_x.illuminance(grid.points, grid.normals, caster)
    ey = along_y.illuminance(grid.points, grid.normals, caster)
    swapped = grid.points[:, [1, 0, 2]]
    order = [int(np.argmin(np.abs(grid.points - q).sum(axis=1))) for q in swapped]
    np.testing.assert_allclose(ey, ex[order], rtol=1e-9)
    assert not np.allclose(ex, ey)  # a batwing is not round


def test_grid_points_read_what_the_patches_receive():
    """A work plane a millimetre above the floor sees what the floor patches see."""
    scene = builtin_scene("cornell")
    p = mesh_patches(scene)
    caster = RayCaster(p)
    F = form_factor_matrix(p, 1024, seed=2, caster=caster)
    E = np.zeros(p.n)
    E[p.group_index("light")] = 1000.0
    lum = PlacedLuminaire("L", (1.0, 1.0, 1.5), downlight(1500.0, watts=15.0), DOWN, (1, 0, 0))
    light = light_scene(p, F, caster, E, [lum])
    grid = work_plane_grid(p, caster, WorkPlane(0.001, 0.0))
    got = light_grid(grid, light, caster, [lum], rays=1024, seed=3)
    floor = p.group_index("floor")
    near = [
        int(floor[np.argmin(np.linalg.norm(p.centroid[floor] - q, axis=1))]) for q in grid.points
    ]
    assert got.lux.mean() == pytest.approx(light.H[near].mean(), rel=0.03)
    assert np.all(got.indirect > 0)


def test_en12464_spacing_and_counts():
    assert en12464_spacing(1.0) == pytest.approx(0.2)
    assert en12464_spacing(10.0) == pytest.approx(1.0)
    assert en12464_spacing(100.0) == pytest.approx(5.0)
    assert en12464_spacing(1e6) == 10.0
    # 11 x 7 m: d = 11 m, p = 1.07 m, 11 x 7 points.
    assert grid_counts(11.0, 7.0)[:2] == (11, 7)
    # 20 x 4 m (ratio 5): d is the short side, 4 m, p = 0.53 m.
    nx, ny, p = grid_counts(20.0, 4.0)
    assert p == pytest.approx(0.2 * 5 ** math.log10(4.0)) and (nx, ny) == (38, 8)
    stats = grid_statistics(np.array([300.0, 500.0, 700.0]))
    assert stats["Em"] == 500.0 and stats["U0"] == pytest.approx(0.6)


def test_a_round_floor_keeps_only_points_over_it(tmp_path):
    a = 2 * np.pi * np.arange(64) / 64
    ring = " ".join(str(i + 1) for i in range(64))
    lines = [f"v {3 * math.cos(t):.6f} {3 * math.sin(t):.6f} 0" for t in a]
    (tmp_path / "r.obj").write_text("\n".join(lines) + f"\ng floor\nf {ring}\n")
    from lightinv_core.scene.importers.obj import load_obj

    p = mesh_patches(load_obj(tmp_path / "r.obj", resolution=0.5))
    grid = work_plane_grid(p, RayCaster(p), WorkPlane(0.8, 0.5))
    r = np.linalg.norm(grid.points[:, :2], axis=1)
    # At least the border from the edge, checked in 16 directions: 0.98 of it anywhere.
    assert r.max() <= 3.0 - 0.5 * math.cos(math.pi / 16) + 1e-9 and grid.dropped > 0


def test_cli_simulates_luminaires_on_a_work_plane(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    from lightinv_core.luminaires.formats import write_photometry

    write_photometry(downlight(2000.0, watts=20.0), tmp_path / "down.ldt")
    (tmp_path / "lums.csv").write_text(
        "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z\n"
        "D1,3,2,2.95,down.ldt,0,0,-1,1,0,0\nD2,9,6,2.95,down.ldt,0,0,-1,0,1,0\n"
    )
    argv = ["simulate", "office", "--resolution", "0.5", "--luminaires", str(tmp_path / "lums.csv")]
    argv += ["--workplane", "0.8", "--border", "0.5", "--grid-csv", str(tmp_path / "g.csv")]
    argv += ["--edition", "2011"]  # its counts below are the 2011 rule's
    assert cli.main([*argv, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    g = out["grid"]
    assert g["points"] == 77 and g["counts"] == [11, 7] and 0 < g["Emin"] < g["Em"] < g["Emax"]
    assert g["U0"] == pytest.approx(g["Emin"] / g["Em"])
    rows = (tmp_path / "g.csv").read_text().splitlines()
    assert rows[0] == "x,y,z,lux" and len(rows) == 78
    lux = np.array([float(r.split(",")[3]) for r in rows[1:]])
    assert lux.mean() == pytest.approx(g["Em"], rel=1e-5)
    assert abs(out["energy"]["imbalance"]) < 0.01 and len(out["luminaires"]) == 2
    assert cli.main(argv) == 0
    text = capsys.readouterr().out
    assert f"Em {g['Em']:.1f} lux, Emin {g['Emin']:.1f} lux" in text and "U0" in text


@pytest.mark.parametrize(
    "body, message",
    [
        ("name,x,y,z,ies\nD1,0,0,2,down.ldt\n", "line 1: missing column(s) aim_x"),
        ("{h}\nD1,0,zero,2,down.ldt,0,0,-1,1,0,0\n", "line 2: y 'zero' is not a number"),
        ("{h}\nD1,0,0,2,nowhere.ies,0,0,-1,1,0,0\n", "line 2:"),
        ("{h}\nD1,0,0,2,down.ldt,0,0,-1,0,0,1\n", "line 2: luminaire 'D1': c0"),
        ("{h}\nD1,0,0,2,down.ldt,0,0,-1,1,0,0\nD1,1,0,2,down.ldt,0,0,-1,1,0,0\n", "used twice"),
        ("{h}\n", "no luminaires"),
    ],
)
def test_bad_luminaire_schedules_name_the_line(tmp_path, body, message):
    from lightinv_core.luminaires.formats import write_photometry

    write_photometry(downlight(2000.0, watts=20.0), tmp_path / "down.ldt")
    header = "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z"
    (tmp_path / "l.csv").write_text(body.replace("{h}", header))
    with pytest.raises(PhotometryError, match=message.replace("(", r"\(").replace(")", r"\)")):
        read_luminaire_csv(tmp_path / "l.csv")


def test_cli_refuses_lrr_with_luminaires_and_a_border_without_a_plane(tmp_path, capsys):
    assert cli.main(["simulate", "cornell", "--emit", "light=10", "--border", "0.5"]) == 2
    assert "add --workplane" in capsys.readouterr().err
    argv = ["simulate", "cornell", "--workplane", "--method", "lrr"]
    assert cli.main(argv) == 2
    assert "nothing emits" in capsys.readouterr().err
    with pytest.raises(LightInvError, match="parallel to the aim"):
        PlacedLuminaire("L", (0, 0, 1), isotropic(1.0), DOWN, (0, 0, 3))


def test_a_linear_luminaire_is_split_along_its_length():
    """A 1.2 m batwing as 6 point sources, against 120 (converged) and against one."""
    import dataclasses

    wing = batwing_linear(4000.0, watts=32.0)  # opening 0.15 x 1.2 m
    point = dataclasses.replace(wing, opening=(0.0, 0.0, 0.0))
    lum = PlacedLuminaire("W", (0, 0, 0), wing, DOWN, (1, 0, 0))
    assert len(lum.segments) == 6
    fine = [
        PlacedLuminaire(f"s{k}", (x, 0, 0), point, DOWN, (1, 0, 0), dimming=1 / 120)
        for k, x in enumerate((np.arange(120) + 0.5) / 120 * 1.2 - 0.6)
    ]
    one = PlacedLuminaire("P", (0, 0, 0), point, DOWN, (1, 0, 0))
    for depth in (1.0, 2.0):
        pts = np.array([[x, y, -depth] for x in (-0.6, 0.0, 0.9) for y in (0.0, 0.5)])
        up = np.tile([0.0, 0.0, 1.0], (len(pts), 1))
        ref = sum(f.illuminance(pts, up, None) for f in fine)
        np.testing.assert_allclose(lum.illuminance(pts, up, None), ref, rtol=0.01)
    near = np.array([[0.6, 0.0, -0.5]])
    up = np.array([[0.0, 0.0, 1.0]])
    ref = sum(f.illuminance(near, up, None) for f in fine)
    # One point source at the centre is far off near the end of the tube.
    assert abs(one.illuminance(near, up, None)[0] / ref[0] - 1) > 0.1


# ---------------------------------------------------------------------------------------
# Round openings (IES width and length negative): points on the disc, equal areas

ROUND_IES = Path(__file__).resolve().parents[1] / "data" / "photometry" / "rab-round-4.ies"


def disc_lux(ph: Photometry, radius: float, p, n, nr: int = 96, nt: int = 288) -> float:
    """Illuminance (lux) at ``p`` facing ``n`` from a disc of ``radius`` (m) centred on
    the origin, facing down (C0 along x), whose every area element emits ``ph``'s
    intensity over the disc's area: a numerical integral over the disc (Gauss-Legendre in
    the radius, the periodic trapezoid rule in the angle), independent of the split."""
    x, w = np.polynomial.legendre.leggauss(nr)
    r = (x + 1) * radius / 2
    wr = w * radius / 2 * r
    t = (np.arange(nt) + 0.5) * 2 * np.pi / nt
    rr, tt = np.meshgrid(r, t, indexing="ij")
    src = np.stack([rr * np.cos(tt), rr * np.sin(tt), np.zeros_like(rr)], axis=-1)
    v = np.asarray(p, float) - src
    d = np.linalg.norm(v, axis=-1)
    u = v / d[..., None]
    cos_in = np.maximum(-(u @ np.asarray(n, float)), 0.0)
    gamma = np.degrees(np.arccos(np.clip(-u[..., 2], -1.0, 1.0)))
    c = np.degrees(np.arctan2(u[..., 1], u[..., 0])) % 360.0
    f = ph.intensity(c, gamma) * cos_in / d**2
    return float((wr[:, None] * f).sum() * (2 * np.pi / nt)) / (np.pi * radius**2)


def test_a_round_opening_is_split_into_points_on_its_disc():
    import dataclasses

    from lightinv_core.luminaires import read_photometry

    ph = read_photometry(ROUND_IES)  # a real 0.3175 m disc (-1.041667 ft)
    lum = PlacedLuminaire("R", (1.0, 2.0, 3.0), ph, DOWN, (0, 1, 0))
    seg = lum.segments
    assert len(seg) == 7  # was 1: the negative sizes were never split
    np.testing.assert_allclose(seg.mean(axis=0), (1.0, 2.0, 3.0), atol=1e-12)
    assert np.all(np.linalg.norm(seg - (1.0, 2.0, 3.0), axis=1) < 0.3175 / 2)
    assert np.allclose(seg[:, 2], 3.0)  # on the opening's plane, across the aim
    for diameter, count in ((0.2, 1), (0.6, 19), (1.0, 37)):
        disc = dataclasses.replace(ph, opening=(-diameter, -diameter, 0.0))
        assert len(PlacedLuminaire("R", (0, 0, 0), disc, DOWN, (1, 0, 0)).segments) == count
    # An ellipse 0.6 m along C0 and 0.3 m across: the circle's points stretched.
    oval = dataclasses.replace(ph, opening=(-0.3, -0.6, 0.0))
    pts = PlacedLuminaire("E", (0, 0, 0), oval, DOWN, (1, 0, 0)).segments
    assert len(pts) == 19 and np.all((pts[:, 0] / 0.3) ** 2 + (pts[:, 1] / 0.15) ** 2 < 1)


def test_the_split_of_a_round_opening_conserves_the_flux():
    """All the light of the split luminaire crosses a sphere around it: the integral of
    its illuminance over the sphere (inward normals) is the table's flux."""
    import dataclasses

    from lightinv_core.luminaires import read_photometry

    ph = dataclasses.replace(read_photometry(ROUND_IES), opening=(-0.6, -0.6, 0.0))
    lum = PlacedLuminaire("R", (0, 0, 0), ph, DOWN, (1, 0, 0))
    assert len(lum.segments) == 19
    n, radius = 200_000, 1.0
    k = np.arange(n) + 0.5  # a Fibonacci lattice: n points of equal area on the sphere
    z = 1 - 2 * k / n
    phi = np.pi * (1 + 5**0.5) * k
    out = np.column_stack([np.sqrt(1 - z * z) * np.cos(phi), np.sqrt(1 - z * z) * np.sin(phi), z])
    lux = lum.illuminance(radius * out, -out, None)
    assert lux.sum() * 4 * np.pi * radius**2 / n == pytest.approx(ph.flux(), rel=1e-4)


def test_a_big_round_opening_lights_its_near_field_as_its_disc_does():
    """Against the integral over the disc: the split within 3.5% at a distance of one
    diameter, 1.5% from 0.5 m; a single point source is off as the disc predicts
    (brighter straight below, dimmer to the side), at least 4 times as far."""
    import dataclasses

    from lightinv_core.luminaires import read_photometry

    real = read_photometry(ROUND_IES)
    receivers = [
        ((0, 0, -0.3), (0, 0, 1)),
        ((0, 0, -0.6), (0, 0, 1)),
        ((0.3, 0, -0.3), (0, 0, 1)),
        ((0.5, 0.2, -0.5), (0, 0, 1)),
        ((0, 0.3, -0.6), (0, 0, 1)),
        ((0.2, 0.1, -1.0), (0, 0, 1)),
        ((0, 0, -1.2), (0, 0, 1)),
        ((0.6, 0, -0.3), (-1, 0, 0)),  # a wall beside it
    ]
    for diameter in (0.3175, 0.6):
        ph = dataclasses.replace(real, opening=(-diameter, -diameter, 0.0))
        lum = PlacedLuminaire("R", (0, 0, 0), ph, DOWN, (1, 0, 0))
        one = dataclasses.replace(lum, photometry=dataclasses.replace(ph, opening=(0, 0, 0)))
        for p, n in receivers:
            ref = disc_lux(ph, diameter / 2, p, n)
            split = lum.illuminance(np.array([p], float), np.array([n], float), None)[0]
            point = one.illuminance(np.array([p], float), np.array([n], float), None)[0]
            err, point_err = split / ref - 1, point / ref - 1
            assert abs(err) < (0.015 if np.linalg.norm(p) >= 0.5 else 0.035), (diameter, p)
            assert abs(point_err) > 4 * abs(err), (diameter, p)
            if p[:2] == (0, 0):
                assert point_err > 0  # straight below, the disc is dimmer than its centre
        # The integral itself has converged (doubling its nodes moves it < 1e-5).
        p, n = receivers[0]
        assert disc_lux(ph, diameter / 2, p, n, 192, 576) == pytest.approx(
            disc_lux(ph, diameter / 2, p, n), rel=1e-5
        )


def test_a_lambertian_disc_on_its_axis_matches_the_closed_form():
    """A disc of uniform luminance L gives pi L R² / (R² + h²) on its axis: with
    I = I0 cos(gamma) over the disc's area, I0 / (R² + h²); a point source I0 / h²."""
    import dataclasses

    i0, radius = 1000.0, 0.3
    ph = dataclasses.replace(lambertian_down(i0), opening=(-0.6, -0.6, 0.0))
    lum = PlacedLuminaire("L", (0, 0, 0), ph, DOWN, (1, 0, 0))
    for h, tol in ((0.3, 0.03), (0.6, 0.01), (1.2, 0.005)):
        exact = i0 / (radius**2 + h**2)
        got = lum.illuminance(np.array([[0, 0, -h]]), np.array([[0, 0, 1.0]]), None)[0]
        assert got == pytest.approx(exact, rel=tol)
        assert i0 / h**2 > (1 + 5 * tol) * exact  # what one point source would give
        assert disc_lux(ph, radius, (0, 0, -h), (0, 0, 1)) == pytest.approx(exact, rel=1e-4)
