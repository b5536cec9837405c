"""Coplanar triangles joined back into the polygons they were cut from.

glTF and PLY files hold triangles only: a rectangular wall arrives as two triangles,
which, subdivided, make about four times the patches of a grid at the same resolution.
Here triangles of one key (lighting group and material) that lie in one plane and share
edges are joined into their outline when that outline is a single simple loop; the
polygon then takes the OBJ importer's path (a rectangle becomes a grid, other polygons
are ear-clipped or cut by the grid). Sets with holes, T-junctions, edges shared by more
than two triangles or triangles facing both ways stay triangles. Units: metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

WELD = 1e-6  # m: vertices closer than this (per coordinate, on a grid) are one vertex
NORMAL_GRID = 1e-5  # unit normals equal to this (per component) share a plane
OFFSET_GRID = 1e-5  # m: plane offsets equal to this share a plane
COLLINEAR = 1e-9  # |sin| of the turn at an outline vertex below which it is dropped
AREA_TOL = 1e-6  # relative: a joined outline must keep the triangles' area


@dataclass(frozen=True)
class Facets:
    """Triangles joined into polygons.

    ``polygons`` are vertex index arrays into the welded ``vertices`` (counter-clockwise
    seen from the front, as the triangles were); ``first[k]`` is the index of polygon k's
    first triangle in the input; ``left`` are the input triangles not joined (indices).
    """

    vertices: np.ndarray
    polygons: list[np.ndarray]
    first: np.ndarray
    left: np.ndarray
    triangles: np.ndarray


def join_coplanar(vertices: np.ndarray, triangles: np.ndarray, keys: np.ndarray) -> Facets:
    """Join edge-connected coplanar triangles of the same key into polygons.

    Parameters
    ----------
    vertices : (n, 3) float, metres.
    triangles : (t, 3) int, counter-clockwise seen from the front.
    keys : (t,) int, triangles of different keys are never joined (group, material).

    Returns the welded vertices, the polygons and the triangles left (``Facets``;
    ``triangles`` are the input triangles re-indexed into the welded vertices).
    """
    q = np.round(vertices / WELD).astype(np.int64)
    inverse = row_ids(q)
    out_v = np.zeros((inverse.max() + 1 if len(inverse) else 0, 3))
    # Keep the file's coordinates (not the grid's) for each welded vertex.
    out_v[inverse] = vertices
    tri = inverse[triangles]
    t = len(tri)
    if t == 0:
        return Facets(out_v, [], np.zeros(0, int), np.zeros(0, int), tri)
    p = out_v[tri]
    cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    twice = np.linalg.norm(cross, axis=1)
    ok = (
        (twice > 0) & (tri[:, 0] != tri[:, 1]) & (tri[:, 1] != tri[:, 2]) & (tri[:, 2] != tri[:, 0])
    )
    unit = cross / np.where(twice > 0, twice, 1.0)[:, None]
    offset = (unit * p[:, 0]).sum(axis=1)
    plane = np.column_stack(
        [keys, np.round(unit / NORMAL_GRID), np.round(offset / OFFSET_GRID)]
    ).astype(np.int64)
    plane[~ok, 0] = -1 - np.arange((~ok).sum())  # degenerate triangles: each on its own
    pid = row_ids(plane)
    comp = _components(tri, pid, t)
    polygons, first, used = _outlines(tri, comp, ok, 0.5 * twice, out_v)
    left = np.flatnonzero(~used)
    return Facets(out_v, polygons, np.array(first, dtype=int), left, tri)


def row_ids(rows: np.ndarray) -> np.ndarray:
    """An id per row of the integer array ``rows`` (n, k), equal for equal rows, from 0
    in sorted order (``np.unique(rows, axis=0, return_inverse=True)``, a lexsort: the
    structured sort np.unique uses was most of the join's time)."""
    if len(rows) == 0:
        return np.zeros(0, np.int64)
    order = np.lexsort(rows.T[::-1])
    s = rows[order]
    new = np.empty(len(rows), bool)
    new[0] = True
    new[1:] = np.any(s[1:] != s[:-1], axis=1)
    ids = np.empty(len(rows), np.int64)
    ids[order] = np.cumsum(new) - 1
    return ids


def _edges(tri: np.ndarray, pid: np.ndarray, t: int):
    """Directed edges (from, to), their triangle, and the undirected key per edge."""
    a = tri.ravel()
    b = np.roll(tri, -1, axis=1).ravel()
    owner = np.repeat(np.arange(t), 3)
    key = np.column_stack([np.repeat(pid, 3), np.minimum(a, b), np.maximum(a, b)])
    return a, b, owner, key


def _components(tri: np.ndarray, pid: np.ndarray, t: int) -> np.ndarray:
    """Component of each triangle: triangles of one plane set sharing an edge that they
    run in opposite directions (consistent winding), the edge used by exactly two."""
    a, b, owner, key = _edges(tri, pid, t)
    inv = row_ids(key)
    counts = np.bincount(inv)
    pair = np.flatnonzero(counts[inv] == 2)
    order = pair[np.argsort(inv[pair], kind="stable")]
    e0, e1 = order[0::2], order[1::2]
    opposite = (a[e0] == b[e1]) & (b[e0] == a[e1])
    e0, e1 = e0[opposite], e1[opposite]
    graph = coo_matrix((np.ones(len(e0)), (owner[e0], owner[e1])), shape=(t, t))
    _, comp = connected_components(graph, directed=False)
    return comp


def _outlines(tri, comp, ok, area, vertices):
    """The outline polygon of each component of two or more triangles with one simple
    boundary loop; returns (polygons, first triangle of each, mask of triangles used)."""
    t = len(tri)
    a = tri.ravel()
    b = np.roll(tri, -1, axis=1).ravel()
    owner = np.repeat(np.arange(t), 3)
    ec = comp[owner]
    # An edge is inside its component when the reverse edge is in the same component.
    fwd = np.column_stack([ec, a, b])
    rev = np.column_stack([ec, b, a])
    allk = np.concatenate([fwd, rev])
    inv = row_ids(allk)
    seen = np.zeros(inv.max() + 1, bool)
    seen[inv[: len(fwd)]] = True
    boundary = ~seen[inv[len(fwd) :]]
    sizes = np.bincount(comp, minlength=comp.max() + 1)
    bad = np.zeros(len(sizes), bool)
    np.logical_or.at(bad, comp, ~ok)
    polygons, first = [], []
    used = np.zeros(t, bool)
    cand = np.flatnonzero((sizes >= 2) & ~bad)
    if len(cand) == 0:
        return polygons, first, used
    be = np.flatnonzero(boundary & np.isin(ec, cand))
    be = be[np.argsort(ec[be], kind="stable")]
    splits = np.flatnonzero(np.diff(ec[be])) + 1
    tri_order = np.argsort(comp, kind="stable")
    tri_starts = np.searchsorted(comp[tri_order], np.arange(len(sizes)))
    comp_area = np.bincount(comp, weights=area, minlength=len(sizes))
    # Plain Python per component: most are a few triangles (a quad is two), and numpy's
    # per-call cost would dominate.
    frm, to, comps = a[be].tolist(), b[be].tolist(), ec[be].tolist()
    pts = vertices.tolist()
    bounds = [0, *splits.tolist(), len(be)]
    for k in range(len(bounds) - 1):
        lo, hi = bounds[k], bounds[k + 1]
        c = comps[lo]
        loop = _loop(frm[lo:hi], to[lo:hi])
        if loop is None:
            continue
        loop = _drop_collinear(loop, pts)
        if len(loop) < 3 or not _keeps_area([pts[i] for i in loop], comp_area[c]):
            continue
        members = tri_order[tri_starts[c] : tri_starts[c] + sizes[c]]
        used[members] = True
        polygons.append(np.array(loop))
        first.append(int(members.min()))
    return polygons, first, used


def _loop(frm: list[int], to: list[int]) -> list[int] | None:
    """The vertices of the single closed loop the directed edges form, or None (a vertex
    left twice, or several loops: holes, touching pieces)."""
    nxt = dict(zip(frm, to, strict=True))
    if len(nxt) != len(frm) or len(set(to)) != len(to):
        return None
    start = frm[0]
    loop, v = [start], nxt[start]
    while v != start:
        loop.append(v)
        v = nxt.get(v)
        if v is None or len(loop) > len(frm):
            return None
    return loop if len(loop) == len(frm) else None


def _sub(p: list[float], q: list[float]) -> tuple[float, float, float]:
    return p[0] - q[0], p[1] - q[1], p[2] - q[2]


def _cross(u, v) -> tuple[float, float, float]:
    return u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]


def _drop_collinear(loop: list[int], pts: list[list[float]]) -> list[int]:
    """``loop`` without vertices where the outline runs straight on (a triangulation
    adds such vertices along a long edge)."""
    changed = True
    while changed and len(loop) > 3:
        changed = False
        keep = []
        n = len(loop)
        for k in range(n):
            prev, here, nxt = pts[loop[k - 1]], pts[loop[k]], pts[loop[(k + 1) % n]]
            e_in, e_out = _sub(here, prev), _sub(nxt, here)
            turn = math.hypot(*_cross(e_in, e_out))
            scale = math.hypot(*e_in) * math.hypot(*e_out)
            ahead = e_in[0] * e_out[0] + e_in[1] * e_out[1] + e_in[2] * e_out[2] > 0
            if turn <= COLLINEAR * scale and ahead and n - (k - len(keep)) > 3:
                changed = True
                continue
            keep.append(loop[k])
        loop = keep
    return loop


def _keeps_area(p: list[list[float]], area: float) -> bool:
    """Whether the polygon ``p`` (Newell's method) has the triangles' total ``area``."""
    sx = sy = sz = 0.0
    n = len(p)
    for k in range(n):
        (x0, y0, z0), (x1, y1, z1) = p[k], p[(k + 1) % n]
        sx += (y0 - y1) * (z0 + z1)
        sy += (z0 - z1) * (x0 + x1)
        sz += (x0 - x1) * (y0 + y1)
    return abs(0.5 * math.sqrt(sx * sx + sy * sy + sz * sz) - area) <= AREA_TOL * area
