"""The built-in kinds of calculation object, each a ``CalcKind`` registered once.

- ``task_area``: a polygon in plan (convex or not) ``height`` m above a floor group; its
  points follow the EN 12464-1 grid rule of its ``edition`` over the polygon's bounding
  box less the ``border``, kept where they lie inside the polygon and at least
  ``border`` from its edges; horizontal illuminance E (facing up).
- ``surface``: a rectangle ``origin`` + s u + t v in any plane (a wall, a ceiling),
  facing u x v; the edition's grid rule over its two sides; the illuminance on its
  front (vertical on a wall, downward on a ceiling facing down).
- ``cylindrical``: points in plan at ``height``; Ez, the mean vertical illuminance
  around the point (CIE, EN 12464-1), sampled over ``RING`` horizontal directions.
- ``semi_cylindrical``: the same points facing ``facing``; Esc = Ez + (Ev(facing) -
  Ev(behind)) / pi, which is the mean of the vertical illuminance over the half circle
  of directions around ``facing`` (for light of any direction L sin(t) (1 + cos a) / pi
  on both sides; the same ring of samples).
- ``points``: free points with their normals (default: facing up).

Why ``RING`` = 32: the ring's mean of max(0, cos) (a point source: Ez = I sin(t) / (pi
d²)) errs at most 0.32% whatever the source's azimuth; 24 directions erred 0.57%
(``tests/core/test_calc_objects.py`` holds it against the closed form).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from lightinv_core.design.model.calc_object import CalcKind, CalcObject, register_calc_kind
from lightinv_core.errors import DesignError, LightInvError
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.point_sets import PointSet
from lightinv_core.transport.workplane import GRID_RULES

RING = 32
"""Horizontal directions sampled around a cylindrical illuminance point."""
UP = np.array([0.0, 0.0, 1.0])


def floor_height(patches: Patches, group: str, where: str) -> float:
    """World height (m) of floor group ``group``: its patches' area-weighted height."""
    try:
        idx = patches.group_index(group)
    except LightInvError:
        raise DesignError(
            f"{where}: no group {group!r} to stand on; groups: {', '.join(patches.group_names)}"
        ) from None
    a = patches.area[idx]
    return float(patches.centroid[idx, 2] @ a / a.sum())


def inside_polygon(xy: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Whether each point ``xy`` (m, 2) lies inside the polygon ``poly`` (k, 2) (even-odd
    rule, so convex or not)."""
    x, y = xy[:, :1], xy[:, 1:]
    a, b = poly, np.roll(poly, -1, axis=0)
    crosses = (a[:, 1] > y) != (b[:, 1] > y)
    dy = np.where(b[:, 1] == a[:, 1], 1.0, b[:, 1] - a[:, 1])
    at_x = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / dy
    return (crosses & (x < at_x)).sum(axis=1) % 2 == 1


def edge_distance(xy: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Distance (m) from each point ``xy`` (m, 2) to the nearest edge of ``poly``."""
    a, b = poly, np.roll(poly, -1, axis=0)
    ab = b - a
    t = np.einsum("mkc,kc->mk", xy[:, None] - a[None], ab) / np.maximum(
        np.einsum("kc,kc->k", ab, ab), 1e-300
    )
    near = a[None] + np.clip(t, 0.0, 1.0)[..., None] * ab[None]
    return np.linalg.norm(xy[:, None] - near, axis=2).min(axis=1)


def _cells(length_a: float, length_b: float, edition: str) -> tuple[np.ndarray, np.ndarray]:
    """Cell centres (fractions 0-1) along two sides by the edition's grid rule."""
    na, nb, _ = GRID_RULES[edition](length_a, length_b)
    return (np.arange(na) + 0.5) / na, (np.arange(nb) + 0.5) / nb


# -- task areas -----------------------------------------------------------------------------
def _area_needs(obj: CalcObject) -> str | None:
    if obj.corners is None:
        return "give its polygon's corners ([x, y] in plan, m; at least three)"
    poly = np.asarray(obj.corners, float)
    nxt = np.roll(poly, -1, axis=0)
    twice = (poly[:, 0] * nxt[:, 1] - poly[:, 1] * nxt[:, 0]).sum()
    if abs(twice) < 1e-12:
        return "its corners enclose no area"
    return None


def _area_readings(obj: CalcObject, patches: Patches, caster) -> PointSet:
    where = f"task area {obj.name!r}"
    poly = np.asarray(obj.corners, float)
    z = floor_height(patches, obj.group, where) + obj.height
    lo, hi = poly.min(axis=0) + obj.border, poly.max(axis=0) - obj.border
    if np.any(hi - lo <= 0):
        raise DesignError(f"{where}: the border of {obj.border:g} m leaves nothing of it")
    (w, d) = hi - lo
    fx, fy = _cells(float(w), float(d), obj.edition)
    gx, gy = np.meshgrid(lo[0] + fx * w, lo[1] + fy * d, indexing="ij")
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    keep = inside_polygon(xy, poly)
    if obj.border > 0:
        keep &= edge_distance(xy, poly) >= obj.border - 1e-9
    if not keep.any():
        raise DesignError(
            f"{where}: no grid point lies inside it {obj.border:g} m from its edges; "
            "use a smaller border"
        )
    pts = np.column_stack([xy[keep], np.full(int(keep.sum()), z)])
    return PointSet(pts, np.broadcast_to(UP, pts.shape))


# -- surfaces -------------------------------------------------------------------------------
def _surface_needs(obj: CalcObject) -> str | None:
    if obj.origin is None or obj.u is None or obj.v is None:
        return "give its rectangle: origin, u and v ([x, y, z], m)"
    if np.linalg.norm(np.cross(obj.u, obj.v)) < 1e-9:
        return "its edges u and v are parallel or empty: the rectangle has no area"
    return None


def _surface_readings(obj: CalcObject, patches: Patches, caster) -> PointSet:
    o, u, v = (np.asarray(x, float) for x in (obj.origin, obj.u, obj.v))
    fu, fv = _cells(float(np.linalg.norm(u)), float(np.linalg.norm(v)), obj.edition)
    s, t = (a.ravel() for a in np.meshgrid(fu, fv, indexing="ij"))
    pts = o + s[:, None] * u + t[:, None] * v
    n = np.cross(u, v)
    return PointSet(pts, np.broadcast_to(n / np.linalg.norm(n), pts.shape))


# -- cylindrical and semi-cylindrical points --------------------------------------------------
def _ring_needs(obj: CalcObject) -> str | None:
    return None if obj.positions is not None else "give its positions ([x, y] in plan, m)"


def _ring(obj: CalcObject, patches: Patches, semi: bool) -> PointSet:
    """RING samples per position facing around it from ``facing``; each value their mean
    (Ez), plus (Ev(facing) - Ev(behind)) / pi for a semi-cylinder (Esc)."""
    where = f"{obj.kind} points {obj.name!r}"
    z = floor_height(patches, obj.group, where) + obj.height
    xy = np.asarray(obj.positions, float)
    phi = math.radians(obj.facing) + 2 * math.pi * np.arange(RING) / RING
    ring = np.column_stack([np.cos(phi), np.sin(phi), np.zeros(RING)])
    at = np.column_stack([xy, np.full(len(xy), z)])
    pts = np.repeat(at, RING, axis=0)
    nrm = np.tile(ring, (len(xy), 1))
    row = np.full(RING, 1.0 / RING)
    if semi:
        row[0] += 1.0 / math.pi
        row[RING // 2] -= 1.0 / math.pi
    reduce = sp.kron(sp.identity(len(xy)), sp.csr_matrix(row[None]), format="csr")
    return PointSet(pts, nrm, reduce, at)


# -- free points ----------------------------------------------------------------------------
def _points_needs(obj: CalcObject) -> str | None:
    if obj.points is None:
        return "give its points ([x, y, z], m)"
    if obj.normals is not None and len(obj.normals) != len(obj.points):
        return f"{len(obj.normals)} normals for {len(obj.points)} points: give one per point"
    if obj.normals is not None and any(math.hypot(*n) == 0 for n in obj.normals):
        return "a normal [0, 0, 0] has no direction"
    return None


def _points_readings(obj: CalcObject, patches: Patches, caster) -> PointSet:
    pts = np.asarray(obj.points, float)
    nrm = UP if obj.normals is None else np.asarray(obj.normals, float)
    return PointSet(pts, np.broadcast_to(nrm, pts.shape))


def _size(obj: CalcObject) -> str:
    return f"{np.linalg.norm(obj.u):.2f} x {np.linalg.norm(obj.v):.2f} m"


def _facing(obj: CalcObject) -> str:
    n = np.cross(obj.u, obj.v)
    n = n / np.linalg.norm(n)
    if n[2] > 0.99:
        return "up"
    if n[2] < -0.99:
        return "down"
    return f"towards {math.degrees(math.atan2(n[1], n[0])) % 360:.0f}°"


for _spec in (
    CalcKind(
        "task_area",
        "Task area (polygon)",
        "E",
        ("corners", "height", "border", "group", "edition"),
        _area_needs,
        _area_readings,
        lambda o: f"{len(o.corners)} corners, {o.height:g} m high",
    ),
    CalcKind(
        "surface",
        "Surface (wall or ceiling rectangle)",
        "E",
        ("origin", "u", "v", "edition"),
        _surface_needs,
        _surface_readings,
        lambda o: f"{_size(o)}, facing {_facing(o)}",
    ),
    CalcKind(
        "cylindrical",
        "Cylindrical illuminance points",
        "Ez",
        ("positions", "height", "group"),
        _ring_needs,
        lambda o, p, c: _ring(o, p, False),
        lambda o: f"{len(o.positions)} points, {o.height:g} m high",
    ),
    CalcKind(
        "semi_cylindrical",
        "Semi-cylindrical illuminance points",
        "Esc",
        ("positions", "height", "group", "facing"),
        _ring_needs,
        lambda o, p, c: _ring(o, p, True),
        lambda o: f"{len(o.positions)} points, {o.height:g} m high, facing {o.facing:g}°",
    ),
    CalcKind(
        "points",
        "Free points",
        "E",
        ("points", "normals"),
        _points_needs,
        _points_readings,
        lambda o: f"{len(o.points)} points",
    ),
):
    register_calc_kind(_spec)
