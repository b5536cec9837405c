"""Exact form factors from points to patches (``transport/point_formfactors.py``) against
closed forms: a point to a parallel and to a perpendicular rectangle (Siegel and
Howell; Tregenza and Sharples, Daylight Algorithms 3.14 and 3.15), the same integrated
over a second rectangle (Howell C-11 and C-14 in ``closed_forms``), a rooflight and a
window seen from every work-plane point of the daylight rooms, and a rooflight half
hidden by a plate (the visible part's closed form)."""

from __future__ import annotations

from math import atan, pi, sqrt

import numpy as np
import pytest

from lightinv_core.scene.builders import room_faces
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.model import Rect, Scene, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport import point_formfactors
from lightinv_core.transport.point_formfactors import (
    FINE,
    patch_polygons,
    point_form_factors,
    polygon_factor,
    sub_cells,
)
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors
from lightinv_core.transport.workplane import WorkPlane, work_plane_grid
from tests.core.closed_forms import parallel_rectangles, perpendicular_rectangles

UP = np.array([0.0, 0.0, 1.0])


def parallel_corner(a: float, b: float, c: float) -> float:
    """A point facing a parallel a x b rectangle c away, on the normal through its
    corner (Tregenza and Sharples 3.14); odd in a and in b, so signed corners add."""
    x, y = a / c, b / c
    return (
        x / sqrt(1 + x * x) * atan(y / sqrt(1 + x * x))
        + y / sqrt(1 + y * y) * atan(x / sqrt(1 + y * y))
    ) / (2 * pi)


def perpendicular_corner(width: float, height: float, c: float) -> float:
    """A point facing up to a vertical width x height rectangle rising from its own
    plane, c away, opposite the rectangle's bottom corner (Tregenza and Sharples 3.15)."""
    x, y = height / width, c / width
    r = sqrt(x * x + y * y)
    return (atan(1 / y) - y / r * atan(1 / r)) / (2 * pi)


def parallel_above(p, d: float, x0: float, x1: float, y0: float, y1: float) -> float:
    """Point ``p`` facing up to the rectangle [x0, x1] x [y0, y1] ``d`` m above it."""
    f = [parallel_corner(x - p[0], y - p[1], d) for x in (x0, x1) for y in (y0, y1)]
    return f[3] - f[1] - f[2] + f[0]


def one(point, polygon, normal=UP) -> float:
    return float(polygon_factor(np.array([point], float), np.array([normal], float), polygon)[0])


@pytest.mark.parametrize("a, b, c", [(1.0, 1.0, 1.0), (1.3, 0.7, 0.9), (0.2, 5.0, 0.4)])
def test_a_point_to_a_parallel_and_a_perpendicular_rectangle(a, b, c):
    above = np.array([[[0, 0, c], [a, 0, c], [a, b, c], [0, b, c]]], float)
    assert one((0, 0, 0), above) == pytest.approx(parallel_corner(a, b, c), rel=1e-12)
    # Either winding.
    assert one((0, 0, 0), above[:, ::-1]) == pytest.approx(parallel_corner(a, b, c), rel=1e-12)
    wall = np.array([[[0, c, 0], [a, c, 0], [a, c, b], [0, c, b]]], float)
    assert one((0, 0, 0), wall) == pytest.approx(perpendicular_corner(a, b, c), rel=1e-12)
    # A wall reaching below the point's plane counts its part above only (clipped).
    deep = wall.copy()
    deep[0, :2, 2] = -3.0
    assert one((0, 0, 0), deep) == pytest.approx(perpendicular_corner(a, b, c), rel=1e-12)
    assert one((0, 0, 0), wall - [0, 0, b + 0.1]) == 0.0  # wholly below


def test_a_tilted_point_and_a_straddling_polygon_match_a_dense_quadrature():
    n = np.array([0.3, 0.5, 0.8]) / np.linalg.norm([0.3, 0.5, 0.8])
    poly = np.array([[[-1, 0.9, -1], [1.5, 0.9, -1], [1.5, 1.3, 1.2], [-1, 1.3, 1.2]]], float)
    m = 400  # midpoint rule of cos cos / (pi r^2) over the polygon: an independent sum
    s, t = np.meshgrid((np.arange(m) + 0.5) / m, (np.arange(m) + 0.5) / m)
    o, e1, e2 = poly[0, 0], poly[0, 1] - poly[0, 0], poly[0, 3] - poly[0, 0]
    x = o + s[..., None] * e1 + t[..., None] * e2
    nj = np.cross(e1, e2)
    area = np.linalg.norm(nj)
    r2 = (x * x).sum(axis=-1)
    cos_p = np.maximum(x @ n, 0) / np.sqrt(r2)
    cos_j = np.abs(x @ (nj / area)) / np.sqrt(r2)
    dense = (cos_p * cos_j / (pi * r2)).sum() * area / m**2
    assert one((0, 0, 0), poly, n) == pytest.approx(dense, rel=1e-5)


@pytest.mark.parametrize("a, b, c", [(1.0, 1.0, 1.0), (2.0, 0.5, 1.5), (0.3, 3.0, 0.7)])
def test_integrated_over_a_rectangle_the_point_factor_gives_howells_c11_and_c14(a, b, c):
    x, w = np.polynomial.legendre.leggauss(60)
    x, w = (x + 1) / 2, w / 2
    s, t = (g.ravel() for g in np.meshgrid(x, x, indexing="ij"))
    weight = np.outer(w, w).ravel()

    def mean_factor(polygon, e1, e2) -> float:
        pts = s[:, None] * e1 + t[:, None] * e2
        polys = np.broadcast_to(polygon, (len(pts), *polygon.shape))
        return float(polygon_factor(pts, np.broadcast_to(UP, pts.shape), polys) @ weight)

    opposed = np.array([[0, 0, c], [a, 0, c], [a, b, c], [0, b, c]], float)
    got = mean_factor(opposed, np.array([a, 0, 0.0]), np.array([0, b, 0.0]))
    assert got == pytest.approx(parallel_rectangles(a, b, c), rel=1e-8)
    # C-14: a w x l floor strip (x along the shared edge l = a) to an h x l wall.
    wall = np.array([[0, 0, 0], [a, 0, 0], [a, 0, c], [0, 0, c]], float)
    got = mean_factor(wall, np.array([a, 0, 0.0]), np.array([0, b, 0.0]))
    assert got == pytest.approx(perpendicular_rectangles(a, b, c), rel=1e-5)


def test_sub_cells_tile_rectangles_and_triangles():
    faces = room_faces(0, 0, 0, 2, 2, 2)
    tri = np.array([[[0.5, 0.5, 1.5], [1.5, 0.5, 1.5], [0.5, 1.5, 1.5]]])
    surfaces = [Surface(k, k, 0.5, rect=r) for k, r in faces.items()]
    surfaces.append(Surface("t", "t", 0.5, triangles=tri[:, ::-1], subdivide=False))
    p = mesh_patches(Scene("box", surfaces, resolution=1.0))
    idx = np.arange(p.n)
    point, normal = np.array([0.9, 0.8, 0.3]), np.array([0.2, -0.1, 1.0]) / np.sqrt(1.05)
    whole = polygon_factor(
        np.repeat([point], p.n, axis=0), np.repeat([normal], p.n, axis=0), patch_polygons(p, idx)
    )
    verts, centres = sub_cells(p, idx, 5)
    cells = polygon_factor(
        np.repeat([point], p.n * 25, axis=0),
        np.repeat([normal], p.n * 25, axis=0),
        verts.reshape(-1, 4, 3),
    ).reshape(p.n, 25)
    np.testing.assert_allclose(cells.sum(axis=1), whole, rtol=1e-10, atol=1e-15)
    # Centroids of the cells average to the patch's.
    np.testing.assert_allclose(centres.mean(axis=1), p.centroid, atol=1e-12)


@pytest.mark.parametrize("scene, group", [("toplit", "rooflight"), ("sidelit", "window")])
def test_the_glazing_seen_from_every_work_plane_point_is_its_closed_form(scene, group):
    p = mesh_patches(builtin_scene(scene))
    caster = RayCaster(p)
    grid = work_plane_grid(p, caster, WorkPlane())
    R = point_form_factors(grid.points, grid.normals, p, caster)
    glass = p.group_index(group)
    got = np.asarray(R[:, glass].sum(axis=1)).ravel()
    corners = np.concatenate([p.origin[glass], p.origin[glass] + p.edge1[glass] + p.edge2[glass]])
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    q = grid.points + caster.offset * UP
    if scene == "toplit":
        want = [parallel_above(x, hi[2] - x[2], lo[0], hi[0], lo[1], hi[1]) for x in q]
    else:  # the window in the south wall (y = lo[1]), x from lo[0] to hi[0]
        want = []
        for x in q:
            c = x[1] - lo[1]

            def up_to(z, x=x, c=c):  # the window's part from the point's plane up to z
                d = z - x[2]
                return perpendicular_corner(hi[0] - x[0], d, c) + perpendicular_corner(
                    x[0] - lo[0], d, c
                )

            want.append(up_to(hi[2]) - up_to(lo[2]))
    np.testing.assert_allclose(got, want, rtol=1e-9)
    # Nothing hides anything in these rooms: every view is the room, whole.
    np.testing.assert_allclose(np.asarray(R.sum(axis=1)).ravel(), 1.0, atol=1e-12)


def plate_room(edge: float, rho: float = 0.0, resolution: float = 0.5):
    """Patches of a 6 x 4 x 3 m room of reflectance ``rho`` with a 2 x 4 m rooflight
    (x 2-4 m) and an opaque plate 2 cm thick whose underside is at z = 2 m, from
    x = 1 m to ``edge``, spanning y = 0.5-3.5 m (two faces apart, so rays tell them
    apart)."""
    faces = room_faces(0, 0, 0, 6, 4, 3)
    surfaces = [Surface(k, k, rho, rect=r) for k, r in faces.items() if k != "ceiling"]
    surfaces += [
        Surface("c1", "ceiling", rho, rect=Rect((0, 4, 3), (2, 0, 0), (0, -4, 0))),
        Surface("glass", "rooflight", 0.0, rect=Rect((2, 4, 3), (2, 0, 0), (0, -4, 0))),
        Surface("c2", "ceiling", rho, rect=Rect((4, 4, 3), (2, 0, 0), (0, -4, 0))),
        Surface("top", "plate", rho, rect=Rect((1, 0.5, 2.02), (edge - 1, 0, 0), (0, 3, 0))),
        Surface("under", "plate", rho, rect=Rect((1, 3.5, 2), (edge - 1, 0, 0), (0, -3, 0))),
    ]
    return mesh_patches(Scene("plate", surfaces, resolution=resolution))


@pytest.mark.parametrize("shadow", [3.0, 3.28])
def test_a_rooflight_half_hidden_by_a_plate_is_its_visible_parts_closed_form(shadow):
    point = np.array([3.0, 2.0, 0.8])
    # The plate's edge casts the shadow line x = shadow on the glass, seen from the point.
    edge = point[0] + (2.0 - point[2]) / (3.0 - point[2]) * (shadow - point[0])
    p = plate_room(edge)
    caster = RayCaster(p)
    R = point_form_factors(point[None], UP[None], p, caster)
    glass = p.group_index("rooflight")
    got = R[0, glass].sum()
    lifted = point + caster.offset * UP
    want = parallel_above(lifted, 3.0 - lifted[2], shadow, 4.0, 0.0, 4.0)
    if shadow == 3.0:  # along patch edges: every patch is wholly seen or hidden
        assert got == pytest.approx(want, rel=1e-9)
    else:  # across a column of patches: each is cut in FINE x FINE cells, seen by centre
        cut = glass[np.abs(p.centroid[glass, 0] - 3.25) < 1e-9]
        bound = R[0, cut].sum() / FINE
        assert abs(got - want) <= bound
        assert abs(got - want) > 0  # the quadrature is not the closed form by chance
    # The plate's shadow counts: what the point sees of the room is still all of it.
    assert R.sum() == pytest.approx(1.0, abs=2e-3)


def test_factors_depend_on_no_ray_count_or_seed():
    p = mesh_patches(builtin_scene("office", 0.5))
    caster = RayCaster(p)
    grid = work_plane_grid(p, caster, WorkPlane())
    a = receiver_factors(grid.points, grid.normals, caster, p.n, 16, 0)
    b = receiver_factors(grid.points, grid.normals, caster, p.n, 4096, 9)
    assert (a != b).nnz == 0


def test_a_large_scene_looks_only_at_the_surfaces_its_points_reach(monkeypatch):
    p = mesh_patches(builtin_scene("sidelit"))
    caster = RayCaster(p)
    grid = work_plane_grid(p, caster, WorkPlane())
    whole = point_form_factors(grid.points, grid.normals, p, caster)
    monkeypatch.setattr(point_formfactors, "CULL_PAIRS", 0)  # as for a whole building
    culled = point_form_factors(grid.points, grid.normals, p, caster)
    assert abs(whole - culled).max() == 0.0
