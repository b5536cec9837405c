"""Polygon outlines of emitter zones, and how much of a rectangle lies inside one.

A zone may be any simple planar polygon drawn on a surface: an L-shaped roof light
zone, a ceiling zone that keeps clear of a column. The zone's patches are those of the
polygon's bounding rectangle (meshed as a grid, like every zone); its ``outline`` is
the polygon in the zone's own (u, v) metres, and a source must lie inside it. The
geometric rules reject a candidate with any source partly outside (``design/geometry``).

``inside_area`` is exact and vectorised over many rectangles: by Green's theorem the
area of polygon ∩ rectangle is the integral of x dy around its boundary, which is made
of the polygon's edges clipped to the rectangle (Liang-Barsky) and the parts of the
rectangle's two vertical sides inside the polygon. The inside length of a vertical
segment x = c, y in [a, b] is the integral of the polygon's winding number along it,
sum_k s_k (b - clip(y_k, a, b)) over the edges crossing x = c at y_k with direction
s_k (+1 rising, -1 falling), for a counter-clockwise outline.
"""

from __future__ import annotations

import math

import numpy as np

from lightinv_core.errors import SceneError

MIN_SIDE = 1e-3  # m: outline corners closer than this are one corner
OUTLINE_TOL = 1e-9
"""Relative: a source with no more than this share of its area outside the outline is
inside (rounding at an edge it touches)."""


def signed_area(points: np.ndarray) -> float:
    """Shoelace area (m²) of a closed polygon (k, 2); positive counter-clockwise."""
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _segments_cross(p, q, r, s) -> bool:
    """Whether closed segments pq and rs share a point (collinear overlaps count)."""

    def orient(a, b, c) -> float:
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])

    def on(a, b, c) -> bool:
        return (
            min(a[0], b[0]) - 1e-12 <= c[0] <= max(a[0], b[0]) + 1e-12
            and min(a[1], b[1]) - 1e-12 <= c[1] <= max(a[1], b[1]) + 1e-12
        )

    d1, d2, d3, d4 = orient(r, s, p), orient(r, s, q), orient(p, q, r), orient(p, q, s)
    scale = 1e-12 * max(1.0, *(abs(float(c)) for pt in (p, q, r, s) for c in pt))
    if ((d1 > scale and d2 < -scale) or (d1 < -scale and d2 > scale)) and (
        (d3 > scale and d4 < -scale) or (d3 < -scale and d4 > scale)
    ):
        return True
    return (
        (abs(d1) <= scale and on(r, s, p))
        or (abs(d2) <= scale and on(r, s, q))
        or (abs(d3) <= scale and on(p, q, r))
        or (abs(d4) <= scale and on(p, q, s))
    )


def check_outline(value, where: str) -> np.ndarray:
    """``value`` as a counter-clockwise simple polygon (k, 2) in metres, else SceneError.

    Takes at least three (u, v) corners; a last corner equal to the first is dropped,
    as are repeated corners (closer than 1 mm). The polygon must not cross itself and
    must enclose some area.
    """
    try:
        pts = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        pts = np.zeros((0, 0))
    if pts.ndim != 2 or pts.shape[1] != 2 or not np.all(np.isfinite(pts)):
        raise SceneError(
            f"{where}: an outline is a list of [u, v] corners in metres, got {value!r}"
        )
    keep = [pts[0]] if len(pts) else []
    for p in pts[1:]:
        if math.dist(p, keep[-1]) > MIN_SIDE:
            keep.append(p)
    while len(keep) > 1 and math.dist(keep[0], keep[-1]) <= MIN_SIDE:
        keep.pop()
    if len(keep) < 3:
        raise SceneError(f"{where}: an outline needs at least 3 distinct corners")
    pts = np.array(keep)
    k = len(pts)
    for i in range(k):
        for j in range(i + 1, k):
            if j == i + 1 or (i == 0 and j == k - 1):
                continue  # neighbours share a corner
            if _segments_cross(pts[i], pts[(i + 1) % k], pts[j], pts[(j + 1) % k]):
                raise SceneError(
                    f"{where}: the outline crosses itself (edges {i + 1} and {j + 1}); "
                    "draw the corners in order around the zone"
                )
    area = signed_area(pts)
    if abs(area) < MIN_SIDE**2:
        raise SceneError(f"{where}: the outline encloses no area")
    return pts if area > 0 else pts[::-1].copy()


def _clipped_x_dy(p: np.ndarray, q: np.ndarray, lo: tuple, hi: tuple) -> np.ndarray:
    """Integral of x dy along each polygon edge p -> q (k, 2) clipped to each rectangle
    [lo_u, hi_u] x [lo_v, hi_v] (arrays (...)); returns (...) summed over the edges."""
    d = q - p  # (k, 2)
    t0 = np.zeros(np.broadcast(lo[0], p[:, 0]).shape)
    t1 = np.ones_like(t0)
    for axis in (0, 1):
        pa = p[:, axis]
        da = d[:, axis]
        moving = np.abs(da) > 1e-15
        safe = np.where(moving, da, 1.0)
        ta, tb = (lo[axis] - pa) / safe, (hi[axis] - pa) / safe
        enter, leave = np.minimum(ta, tb), np.maximum(ta, tb)
        if axis == 0:
            # Half-open in x, as the vertical sides' winding count: a polygon edge lying
            # on the rectangle's left side belongs to that side's term, not here.
            inside = (pa > lo[axis]) & (pa <= hi[axis])
        else:
            inside = (pa >= lo[axis]) & (pa <= hi[axis])
        t0 = np.where(moving, np.maximum(t0, enter), np.where(inside, t0, 1.0))
        t1 = np.where(moving, np.minimum(t1, leave), np.where(inside, t1, 0.0))
    dt = np.maximum(t1 - t0, 0.0)
    t1 = t0 + dt
    part = d[:, 1] * (p[:, 0] * dt + 0.5 * d[:, 0] * (t1 * t1 - t0 * t0))
    return part.sum(axis=-1)


def _inside_length(p: np.ndarray, q: np.ndarray, c, a, b) -> np.ndarray:
    """Length of the vertical segment x = c, y in [a, b] inside the counter-clockwise
    polygon with edges p -> q (arrays c, a, b of one shape (...))."""
    x0, x1 = p[:, 0], q[:, 0]
    cc = np.asarray(c)[..., None]
    # Half-open in x so a crossing at a shared corner counts once.
    up = (x0 <= cc) & (x1 > cc)
    down = (x1 <= cc) & (x0 > cc)
    sign = np.where(up, 1.0, np.where(down, -1.0, 0.0))
    dx = np.where(x1 != x0, x1 - x0, 1.0)
    y = p[:, 1] + (cc - x0) / dx * (q[:, 1] - p[:, 1])
    aa, bb = np.asarray(a)[..., None], np.asarray(b)[..., None]
    # Counter-clockwise, an edge running right has the inside above it: going up past it
    # the winding number rises by one; an edge running left, falls by one.
    return (sign * (bb - np.clip(y, aa, bb))).sum(axis=-1)


def inside_area(outline: np.ndarray, rect: np.ndarray) -> np.ndarray:
    """Area (m²) of each rectangle (..., 4) = (u0, v0, u1, v1) inside ``outline``
    (a counter-clockwise simple polygon (k, 2), ``check_outline``)."""
    rect = np.asarray(rect, dtype=float)
    lo_u = np.minimum(rect[..., 0], rect[..., 2])
    hi_u = np.maximum(rect[..., 0], rect[..., 2])
    lo_v = np.minimum(rect[..., 1], rect[..., 3])
    hi_v = np.maximum(rect[..., 1], rect[..., 3])
    p = np.asarray(outline, dtype=float)
    q = np.roll(p, -1, axis=0)
    ex = (lo_u[..., None], lo_v[..., None])
    ey = (hi_u[..., None], hi_v[..., None])
    edges = _clipped_x_dy(p, q, ex, ey)
    right = hi_u * _inside_length(p, q, hi_u, lo_v, hi_v)
    left = lo_u * _inside_length(p, q, lo_u, lo_v, hi_v)
    area = edges + right - left
    full = (hi_u - lo_u) * (hi_v - lo_v)
    return np.clip(area, 0.0, full)


def outside_area(outline: np.ndarray | None, rect: np.ndarray) -> np.ndarray:
    """Area (m²) of each rectangle (..., 4) outside ``outline`` (0 where none)."""
    rect = np.asarray(rect, dtype=float)
    if outline is None:
        return np.zeros(rect.shape[:-1])
    full = np.abs(rect[..., 2] - rect[..., 0]) * np.abs(rect[..., 3] - rect[..., 1])
    return np.maximum(full - inside_area(outline, rect), 0.0)


def outside_share(outline: np.ndarray, rect: np.ndarray) -> np.ndarray:
    """The share (0 to 1) of each rectangle (..., 4) outside ``outline``, less the
    rounding tolerance ``OUTLINE_TOL`` (0 for a rectangle inside): the rules' amount."""
    rect = np.asarray(rect, dtype=float)
    full = np.abs(rect[..., 2] - rect[..., 0]) * np.abs(rect[..., 3] - rect[..., 1])
    share = outside_area(outline, rect) / np.maximum(full, 1e-12)
    return np.maximum(0.0, share - OUTLINE_TOL)


def points_inside(outline: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Whether each point (..., 2) lies inside or on ``outline`` (even-odd rule)."""
    pts = np.asarray(points, dtype=float)
    p = np.asarray(outline, dtype=float)
    q = np.roll(p, -1, axis=0)
    x, y = pts[..., 0:1], pts[..., 1:2]
    straddle = (p[:, 1] > y) != (q[:, 1] > y)
    dy = np.where(q[:, 1] != p[:, 1], q[:, 1] - p[:, 1], 1.0)
    xc = p[:, 0] + (y - p[:, 1]) / dy * (q[:, 0] - p[:, 0])
    odd = (straddle & (x < xc)).sum(axis=-1) % 2 == 1
    # On an edge counts as inside.
    d = q - p
    t = ((x - p[:, 0]) * d[:, 0] + (y - p[:, 1]) * d[:, 1]) / np.maximum((d * d).sum(1), 1e-30)
    t = np.clip(t, 0.0, 1.0)
    near = np.hypot(p[:, 0] + t * d[:, 0] - x, p[:, 1] + t * d[:, 1] - y).min(axis=-1)
    return odd | (near <= 1e-9)


def bounds(outline: np.ndarray) -> tuple[float, float, float, float]:
    """(u0, v0, u1, v1): the outline's bounding rectangle."""
    lo, hi = outline.min(axis=0), outline.max(axis=0)
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def is_inside(outline: np.ndarray | None, rect) -> bool:
    """Whether the rectangle (u0, v0, u1, v1) lies inside ``outline`` (None: any)."""
    return outline is None or float(outside_share(outline, rect)) == 0.0


def kept_inside(outline: np.ndarray | None, start, end) -> tuple[float, ...]:
    """``end``, or the rectangle furthest along the straight move from ``start`` to
    ``end`` that stays inside ``outline`` (a drag stops at the zone's edge). A ``start``
    already outside moves freely, so a misplaced source can be dragged back in."""
    start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    if outline is None or is_inside(outline, end) or not is_inside(outline, start):
        return tuple(map(float, end))
    lo, hi = 0.0, 1.0
    for _ in range(40):  # to 1e-12 of the move
        mid = 0.5 * (lo + hi)
        if is_inside(outline, start + mid * (end - start)):
            lo = mid
        else:
            hi = mid
    return tuple(map(float, start + lo * (end - start)))


def inner_square(outline: np.ndarray, side: float) -> tuple[float, float, float, float]:
    """A square (u0, v0, u1, v1) inside ``outline``: of ``side`` m if one fits (else
    the largest of halving sizes that does), centred as near the outline's centroid as
    a 41 x 41 grid of centres over its bounds allows."""
    u0, v0, u1, v1 = bounds(outline)
    x, y = outline[:, 0], outline[:, 1]
    cross = x * np.roll(y, -1) - np.roll(x, -1) * y
    a6 = 3.0 * cross.sum()
    centroid = np.array(
        [((x + np.roll(x, -1)) * cross).sum() / a6, ((y + np.roll(y, -1)) * cross).sum() / a6]
    )
    gu, gv = np.meshgrid(np.linspace(u0, u1, 41), np.linspace(v0, v1, 41), indexing="ij")
    centres = np.column_stack([gu.ravel(), gv.ravel()])
    order = np.argsort(np.hypot(*(centres - centroid).T), kind="stable")
    centres = centres[order]
    s = min(side, u1 - u0, v1 - v0)
    while s > MIN_SIDE:
        h = 0.5 * s
        rects = np.column_stack([centres - h, centres + h])
        ok = np.flatnonzero(outside_share(outline, rects) == 0.0)
        if len(ok):
            return tuple(map(float, rects[ok[0]]))
        s *= 0.5
    raise SceneError("the zone's outline is too thin to hold a source")
