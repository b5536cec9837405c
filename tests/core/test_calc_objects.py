"""Calculation objects (``design/model/calc_kinds.py``): task areas of any polygon,
wall and ceiling rectangles, cylindrical and semi-cylindrical points, free point sets.

Checked against closed forms:
- a point source (isotropic I cd) at a cylindrical point: Ez = I sin(t) / (pi d²),
  semi-cylindrical Esc = I sin(t) (1 + cos a) / (pi d²) (t from the vertical, a the
  azimuth of the source from the facing direction): within 0.5% at every azimuth;
- a Lambertian rectangle (the window of a black side-lit room) seen from points of a
  wall rectangle facing it: M x the point-to-parallel-rectangle form factor (Howell's
  catalogue C-11 by superposition), through the whole design path (the zone basis of
  the points, the window source's exitance);
- the 2021 grid rule: a task area drawn over a whole floor gives the work plane's grid.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.design.model import CalcObject, Daylight, DesignError, Source, Workplane
from lightinv_core.errors import LightInvError
from lightinv_core.light.grids import design_grids, edition_grid, grid_light
from lightinv_core.light.model import LightModel
from lightinv_core.luminaires.photometry import Photometry
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.luminaires import PlacedLuminaire
from lightinv_core.transport.point_sets import parse_points_csv
from lightinv_core.transport.raycast import RayCaster


def isotropic(cd: float) -> Photometry:
    g = np.linspace(0.0, 180.0, 37)
    return Photometry("C", np.array([0.0]), g, np.full((1, len(g)), cd))


def corner_factor(x: float, y: float) -> float:
    """Point at unit distance to a parallel x-by-y rectangle with a corner opposite it
    (Howell C-11's differential form)."""
    return (
        x / math.sqrt(1 + x * x) * math.atan(y / math.sqrt(1 + x * x))
        + y / math.sqrt(1 + y * y) * math.atan(x / math.sqrt(1 + y * y))
    ) / (2 * math.pi)


def rect_factor(px, pz, x0, x1, z0, z1, c) -> float:
    """A point (px, pz) at distance c from a parallel rectangle [x0, x1] x [z0, z1]: the
    signed sum of four corner rectangles."""

    def f(a, b):
        return math.copysign(1, a) * math.copysign(1, b) * corner_factor(abs(a) / c, abs(b) / c)

    return f(x1 - px, z1 - pz) - f(x0 - px, z1 - pz) - f(x1 - px, z0 - pz) + f(x0 - px, z0 - pz)


@pytest.fixture(scope="module")
def black_sidelit():
    """The side-lit room (window x 0.6-5.4, z 0.9-2.5 in the wall y = 0) with every
    surface black: the points read the window's direct light alone."""
    scene = builtin_scene("sidelit", 0.5)
    black = Scene(
        scene.name,
        tuple(replace(s, reflectance=0.0) for s in scene.surfaces),
        scene.zones,
        scene.resolution,
    )
    patches = mesh_patches(black)
    return LightModel(black, patches, build_operator(patches, OperatorSettings(rays=64)))


def test_cylindrical_and_semi_cylindrical_points_meet_the_point_source_forms(black_sidelit):
    patches = black_sidelit.patches
    rng = np.random.default_rng(3)
    source = np.array([3.0, 4.0, 2.6])
    lum = PlacedLuminaire("iso", source, isotropic(1000.0))
    r = rng.uniform(0.5, 2.5, 40)
    az = rng.uniform(0, 2 * math.pi, 40)
    xy = source[:2] + np.column_stack([r * np.cos(az), r * np.sin(az)])
    for facing in (0.0, 37.0, 200.0):
        for kind in ("cylindrical", "semi_cylindrical"):
            face = {"facing": facing} if kind == "semi_cylindrical" else {}
            obj = CalcObject("c", kind, height=1.2, positions=tuple(map(tuple, xy)), **face)
            ps = obj.spec.readings(obj, patches, None)
            assert ps.points.shape == (40 * 32, 3) and ps.size == 40
            got = ps.values(lum.illuminance(ps.points, ps.normals, None))
            d = np.linalg.norm(ps.at - source, axis=1)
            sin_t = r / d
            ez = 1000.0 * sin_t / (math.pi * d**2)
            if kind == "cylindrical":
                np.testing.assert_allclose(got, ez, rtol=0.005)
                continue
            # the source's azimuth from the facing direction
            a = np.arctan2(*(source - ps.at)[:, 1::-1].T) - math.radians(facing)
            esc = ez * (1 + np.cos(a))
            assert np.all(np.abs(got - esc) <= 0.005 * ez)
            front = np.cos(a) >= 0
            np.testing.assert_allclose(got[front], esc[front], rtol=0.005)
    # Fewer directions would not do: 24 err 0.57% somewhere (the module's reason for 32).
    phi0 = np.linspace(0, 2 * math.pi / 24, 201)
    k = np.arange(24) * 2 * math.pi / 24
    worst = np.abs(np.maximum(0, np.cos(k[None] - phi0[:, None])).mean(axis=1) * math.pi - 1)
    assert worst.max() > 0.005


def test_a_wall_rectangle_reads_the_window_by_the_parallel_rectangle_form(black_sidelit):
    light = black_sidelit
    # On the north wall (y = 8) facing the window (u x v = -y), 1-5 m along, 0.5-2.5 m up.
    wall = CalcObject("north", "surface", origin=(1.0, 8.0, 0.5), u=(4.0, 0, 0), v=(0, 0, 2.0))
    # Points facing the window from 2 m, 3 m, 6 m into the room, and a ceiling rectangle
    # facing down (reads nothing of a window in a wall below its plane... but some).
    pts = CalcObject(
        "free",
        "points",
        points=((3.0, 2.0, 1.7), (1.0, 3.0, 1.0), (5.0, 6.0, 2.0)),
        normals=((0, -1, 0), (0, -1, 0), (0, -1, 0)),
    )
    grids = design_grids(light, (), (wall, pts))
    window = Source("w", "window", "window", (0, 0, *light.zone_size("window")), filter=1.0)
    day = Daylight()
    lux = grid_light(light, grids, (window,), (), day)
    exitance = 1.0 * day.transmittance * day.exterior_lux
    span = grids.calc_spans["north"]
    p = grids.points[span]
    assert len(p) >= 6 and np.allclose(grids.samples.normals[span], [0, -1, 0])
    expect = [exitance * rect_factor(x, z, 0.6, 5.4, 0.9, 2.5, y) for x, y, z in p]
    np.testing.assert_allclose(lux[span], expect, rtol=1e-4)
    span = grids.calc_spans["free"]
    expect = [exitance * rect_factor(x, z, 0.6, 5.4, 0.9, 2.5, y) for x, y, z in pts.points]
    np.testing.assert_allclose(lux[span], expect, rtol=1e-4)


def test_a_task_area_over_the_floor_is_the_work_plane_grid(black_sidelit):
    patches = black_sidelit.patches
    caster = RayCaster(patches)
    floor = ((0.0, 0.0), (6.0, 0.0), (6.0, 8.0), (0.0, 8.0))
    for edition in ("EN 12464-1:2011", "EN 12464-1:2021"):
        area = CalcObject("a", "task_area", corners=floor, border=0.5, edition=edition)
        got = area.spec.readings(area, patches, caster).points
        plane = edition_grid(patches, caster, Workplane("wp", 0.8, 0.5, edition=edition))
        np.testing.assert_allclose(got, plane.points, atol=1e-9)
    # 2021 on 5 x 7 m: p = 0.2 x 5^log10(7) = 0.781 m; 6 x 9 points (2011: 7 x 9).
    assert len(got) == 54


def test_a_non_convex_task_area_keeps_its_points_and_its_border():
    patches = mesh_patches(builtin_scene("sidelit", 1.0))
    ell = ((0.0, 0.0), (4.0, 0.0), (4.0, 1.0), (1.0, 1.0), (1.0, 3.0), (0.0, 3.0))
    area = CalcObject("L", "task_area", corners=ell, height=0.75)
    pts = area.spec.readings(area, patches, None).points
    # The 2021 rule over the 4 x 3 m box: p = 0.2 x 5^log10(4) = 0.525, 8 x 6 cells;
    # the points in the missing 3 x 2 m corner are dropped.
    x, y = pts[:, 0], pts[:, 1]
    assert len(pts) == 48 - 6 * 4
    assert not np.any((x > 1) & (y > 1))
    assert np.allclose(pts[:, 2], 0.75)
    # With a 0.3 m border every point lies at least 0.3 m inside the L.
    bordered = replace(area, border=0.3)
    pb = bordered.spec.readings(bordered, patches, None).points
    assert 0 < len(pb) < len(pts)
    inner = (pb[:, 0] >= 0.3) & (pb[:, 1] >= 0.3) & ((pb[:, 0] <= 0.7) | (pb[:, 1] <= 0.7))
    assert inner.all()
    with pytest.raises(DesignError, match="corners enclose no area"):
        CalcObject("flat", "task_area", corners=((0, 0), (1, 1), (2, 2)))
    with pytest.raises(DesignError, match="leaves nothing"):
        big = replace(area, border=2.0)
        big.spec.readings(big, patches, None)


def test_each_kind_says_what_it_lacks_and_what_it_does_not_take():
    with pytest.raises(DesignError, match="give its rectangle"):
        CalcObject("s", "surface", origin=(0, 0, 0), u=(1, 0, 0))
    with pytest.raises(DesignError, match="no area"):
        CalcObject("s", "surface", origin=(0, 0, 0), u=(1, 0, 0), v=(2, 0, 0))
    with pytest.raises(DesignError, match="do not take 'corners'"):
        CalcObject("c", "cylindrical", positions=((1, 1),), corners=((0, 0), (1, 0), (0, 1)))
    with pytest.raises(DesignError, match="2 normals for 1 points"):
        CalcObject("p", "points", points=((1, 1, 1),), normals=((0, 0, 1), (0, 1, 0)))
    with pytest.raises(DesignError, match="kind must be one of 'task_area', 'surface'"):
        CalcObject("x", "sphere")


def test_points_csv_with_and_without_header_and_normals():
    pts, nrm = parse_points_csv("x,y,z\n1,2,0.8\n\n3,4,0.8\n")
    assert pts.tolist() == [[1, 2, 0.8], [3, 4, 0.8]] and nrm is None
    pts, nrm = parse_points_csv("1;2;1.5;0;-2;0\n2;2;1.5;1;0;0\n")
    assert nrm.tolist() == [[0, -1, 0], [1, 0, 0]]
    with pytest.raises(LightInvError, match=r"pts\.csv, line 3: expected numbers"):
        parse_points_csv("x,y,z\n1,2,3\n1,two,3\n", "pts.csv")
    with pytest.raises(LightInvError, match=r"line 2: expected 3 values .* got 4"):
        parse_points_csv("1,2,3\n1,2,3,4\n", "pts.csv")
    with pytest.raises(LightInvError, match=r"line 1: the normal \(0, 0, 0\)"):
        parse_points_csv("1,2,3,0,0,0\n", "pts.csv")
    with pytest.raises(LightInvError, match="some rows give a normal"):
        parse_points_csv("1,2,3\n1,2,3,0,0,1\n", "pts.csv")
    with pytest.raises(LightInvError, match="no point"):
        parse_points_csv("x,y,z\n", "pts.csv")
