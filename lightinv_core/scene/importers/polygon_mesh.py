"""Planar polygons meshed into well-shaped pieces near a target size.

Ear clipping a polygon with many sides (a round floor of 1000 segments) gives long
slivers; subdividing each sliver to the patch size made 78,770 patches where 113
were due. Instead the polygon is cut by a grid of about the patch size, laid along
its smallest enclosing rectangle:

- cells wholly inside become rectangles, one per run of cells in a grid row (each
  meshed later as usual);
- cells on the border keep the part of the polygon inside them, triangulated; these
  triangles are already at most one cell across and are used as patches as they are.

Before the cut, outline vertices that lie within ``SIMPLIFY`` x the patch size of the
outline without them are dropped (Douglas-Peucker): a round floor of 1000 segments
keeps about 50 at 0.5 m, so a border cell holds a few triangles, not dozens. The
area changes by far less than 0.1% (tested); the cut itself is exact. Each cell is
clipped with the Sutherland–Hodgman algorithm, first to its grid row, then to its
column; a concave polygon can leave a zero-width bridge in a cell, and then the cell
falls back to clipping the polygon's ear-clip triangles, which are convex.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.scene.importers.geometry import candidate_axes, ear_clip, min_area_rect
from lightinv_core.scene.model import Rect

AREA_TOL = 1e-9
"""Relative; a cell covered to within this is whole, a piece below it is empty."""
SIMPLIFY = 0.005
"""Outline tolerance, times the patch size (see the module)."""


@dataclass(frozen=True)
class PolygonMesh:
    """A polygon cut at a patch size: rectangles (inner cell runs) and triangles
    (t, 3, 3) along its border, all facing the polygon's way."""

    rects: list[Rect]
    triangles: np.ndarray

    @property
    def area(self) -> float:
        """Total area of the pieces (m²)."""
        tri = self.triangles
        t = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
        return float(sum(r.area for r in self.rects) + t.sum())


def clip_half_plane(p: np.ndarray, axis: int, value: float, keep_above: bool) -> np.ndarray:
    """Polygon ``p`` (m, 2) clipped to ``x[axis] >= value`` (or ``<=``), vertex order kept."""
    if len(p) == 0:
        return p
    d = p[:, axis] - value if keep_above else value - p[:, axis]
    inside = d >= 0
    if inside.all():
        return p
    if not inside.any():
        return p[:0]
    q = np.roll(p, -1, axis=0)
    dq = np.roll(d, -1)
    cross = inside != np.roll(inside, -1)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(cross, d / (d - dq), 0.0)
    hit = p + t[:, None] * (q - p)
    # Per edge i: its start if inside, then the crossing point if the edge crosses.
    both = np.stack([p, hit], axis=1).reshape(-1, 2)
    mask = np.stack([inside, cross], axis=1).reshape(-1)
    return both[mask]


def shoelace(p: np.ndarray) -> float:
    """Signed area of polygon ``p`` (m, 2), positive when counter-clockwise."""
    if len(p) < 3:
        return 0.0
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _cleaned(p: np.ndarray, eps: float) -> np.ndarray:
    """``p`` without repeated points and straight or back-tracking vertices."""
    changed = True
    while changed and len(p) >= 3:
        changed = False
        step = np.roll(p, -1, axis=0) - p
        keep = np.einsum("ij,ij->i", step, step) > eps * eps
        if not keep.all():
            p, changed = p[keep], True
            continue
        a, b = np.roll(step, 1, axis=0), step
        turn = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
        keep = np.abs(turn) > eps * np.sqrt((a * a).sum(1) * (b * b).sum(1)) * 1e-3
        if not keep.all():
            p, changed = p[keep], True
    return p if len(p) >= 3 else p[:0]


def _triangulate(piece: np.ndarray, area: float, eps: float) -> np.ndarray | None:
    """Triangles (t, 3, 2) of a cell's piece, or None if it is not a simple polygon."""
    q = _cleaned(piece, eps)
    if len(q) < 3:
        return None
    ears = ear_clip(q)
    if ears is None:
        return None
    tri = q[np.array(ears, dtype=int).reshape(-1, 3)]
    got = (
        0.5
        * np.abs(
            (tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
            - (tri[:, 1, 1] - tri[:, 0, 1]) * (tri[:, 2, 0] - tri[:, 0, 0])
        ).sum()
    )
    return tri if abs(got - area) <= 1e-6 * max(area, eps * eps) else None


def simplify_outline(q: np.ndarray, tol: float) -> np.ndarray:
    """Closed polygon ``q`` (k, 2) without the vertices within ``tol`` of the outline
    through the others (Douglas-Peucker on the two chains between the vertex farthest
    from the first and the first); order and orientation kept, at least 3 vertices."""
    k = len(q)
    if k <= 4:
        return q
    far = int(np.argmax(((q - q[0]) ** 2).sum(axis=1)))
    keep = np.zeros(k, bool)
    keep[[0, far]] = True
    stack = [(0, far), (far, k)]  # index k stands for vertex 0 closing the loop
    while stack:
        i, j = stack.pop()
        if j - i < 2:
            continue
        a, b = q[i], q[j % k]
        mid = q[i + 1 : j]
        ab = b - a
        length = float(np.hypot(*ab))
        if length > 0:
            dist = np.abs(ab[0] * (mid[:, 1] - a[1]) - ab[1] * (mid[:, 0] - a[0])) / length
        else:
            dist = np.hypot(*(mid - a).T)
        m = int(np.argmax(dist))
        if dist[m] > tol:
            keep[i + 1 + m] = True
            stack += [(i, i + 1 + m), (i + 1 + m, j)]
    out = q[keep]
    return out if len(out) >= 3 else q


def _fan(p: np.ndarray) -> np.ndarray:
    return np.stack([np.broadcast_to(p[0], (len(p) - 2, 2)), p[1:-1], p[2:]], axis=1)


def mesh_polygon(p: np.ndarray, normal: np.ndarray, resolution: float) -> PolygonMesh:
    """Cut planar polygon ``p`` (k, 3), counter-clockwise about unit ``normal``, into
    rectangles and border triangles about ``resolution`` m across (see the module)."""
    size = float(np.linalg.norm(np.ptp(p, axis=0)))
    center = p.mean(axis=0)
    _, u, _ = min_area_rect(p - center, normal, candidate_axes([p], normal, size))
    a = u / np.linalg.norm(u)
    b = np.cross(normal, a)  # (a, b, normal) right-handed: the polygon turns positively
    q = np.column_stack([(p - center) @ a, (p - center) @ b])
    q = simplify_outline(q, SIMPLIFY * resolution)
    lo, hi = q.min(axis=0), q.max(axis=0)
    nu = max(1, round((hi[0] - lo[0]) / resolution))
    nv = max(1, round((hi[1] - lo[1]) / resolution))
    xs = np.linspace(lo[0], hi[0], nu + 1)
    ys = np.linspace(lo[1], hi[1], nv + 1)
    cell = (xs[1] - xs[0]) * (ys[1] - ys[0])
    eps = 1e-9 * size
    rects: list[Rect] = []
    tris: list[np.ndarray] = []
    fallback: list[np.ndarray] | None = None

    def to3d(x: float, y: float) -> np.ndarray:
        return center + x * a + y * b

    for j in range(nv):
        row = clip_half_plane(clip_half_plane(q, 1, ys[j], True), 1, ys[j + 1], False)
        if abs(shoelace(row)) <= AREA_TOL * cell:
            continue
        run_start = None
        for i in range(nu + 1):
            whole = False
            if i < nu:
                piece = clip_half_plane(clip_half_plane(row, 0, xs[i], True), 0, xs[i + 1], False)
                area = shoelace(piece)
                whole = area >= (1 - AREA_TOL) * cell
            if whole:
                run_start = i if run_start is None else run_start
                continue
            if run_start is not None:  # a run of whole cells ends before cell i
                origin = to3d(xs[run_start], ys[j])
                rects.append(Rect(origin, (xs[i] - xs[run_start]) * a, (ys[j + 1] - ys[j]) * b))
                run_start = None
            if i == nu or area <= AREA_TOL * cell:
                continue
            tri = _triangulate(piece, area, eps)
            if tri is None:
                if fallback is None:
                    ears = ear_clip(q)
                    fallback = [] if ears is None else list(q[np.array(ears).reshape(-1, 3)])
                box = (xs[i], xs[i + 1], ys[j], ys[j + 1])
                tri = _clip_triangles(fallback, box)
            if len(tri):
                tris.append(tri)
    flat = np.concatenate(tris) if tris else np.zeros((0, 3, 2))
    t3 = center + flat[..., :1] * a + flat[..., 1:] * b
    return PolygonMesh(rects, t3.reshape(-1, 3, 3))


def _clip_triangles(triangles: list[np.ndarray], box: tuple[float, ...]) -> np.ndarray:
    """The parts of convex ``triangles`` (each (3, 2)) inside ``box`` (x0, x1, y0, y1), fanned."""
    x0, x1, y0, y1 = box
    out = []
    for t in triangles:
        if t[:, 0].max() <= x0 or t[:, 0].min() >= x1 or t[:, 1].max() <= y0 or t[:, 1].min() >= y1:
            continue
        c = clip_half_plane(t, 0, x0, True)
        c = clip_half_plane(c, 0, x1, False)
        c = clip_half_plane(c, 1, y0, True)
        c = clip_half_plane(c, 1, y1, False)
        if len(c) >= 3 and shoelace(c) > 0:
            fan = _fan(c)
            e1, e2 = fan[:, 1] - fan[:, 0], fan[:, 2] - fan[:, 0]
            out.append(fan[e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] > 0])
    return np.concatenate(out) if out else np.zeros((0, 3, 2))
