"""Polygon geometry for the OBJ importer: face measures, rectangles, triangulation, zones.

Points are numpy arrays in metres. Polygons keep their vertex order: counter-clockwise
seen from the front, so a polygon's normal (Newell's method) points to its front side.
Nothing here reads files; the only error raised is ``ObjImportError`` by ``zone_rect``,
whose message starts with the caller's ``where``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.model import Rect

RIGHT_ANGLE_TOL = 1e-6  # |cos| of a rectangle's corner angles, relative
ZONE_PLANE_TOL = 1e-3  # zone vertices' distance from their common plane, times the zone size
ZONE_AREA_TOL = 0.01  # zone faces' area vs. their enclosing rectangle's, relative
# Faces below MIN_AREA m² or SLIVER x size² have zero area for all purposes (and the
# mesher rejects patches of ~1e-14 m²).
MIN_AREA = 1e-12
SLIVER = 1e-9


def z_up(v: np.ndarray, up: str) -> np.ndarray:
    """Points ``v`` (n, 3) of a model with up axis ``up`` ("z" or "y"), turned z-up.

    A y-up model is turned by (x, y, z) -> (x, -z, y), a proper rotation, so faces keep
    their front side.
    """
    return np.column_stack([v[:, 0], -v[:, 2], v[:, 1]]) if up == "y" else v


@dataclass(frozen=True)
class FaceGeom:
    """Per face: unit normal (Newell), area (m²), bounding-box diagonal (m), largest vertex
    distance from the best-fit plane (m), and whether it is degenerate."""

    normal: np.ndarray
    area: np.ndarray
    size: np.ndarray
    offplane: np.ndarray
    degenerate: np.ndarray


def face_geometry(vertices: np.ndarray, faces) -> FaceGeom:
    """FaceGeom of the polygons ``faces`` (each with ``.index`` into ``vertices`` (n, 3)).

    A face is degenerate if two of its vertices coincide or its area is at most
    ``max(MIN_AREA, SLIVER * size²)``.
    """
    n = len(faces)
    normal, area = np.zeros((n, 3)), np.zeros(n)
    size, offplane, repeated = np.zeros(n), np.zeros(n), np.zeros(n, bool)
    by_len: dict[int, list[int]] = {}
    for i, f in enumerate(faces):
        by_len.setdefault(len(f.index), []).append(i)
    # Faces with the same vertex count are handled together, as (m, k, 3) arrays.
    for rows in by_len.values():
        pts = vertices[np.array([faces[i].index for i in rows])]
        d = pts - pts.mean(axis=1, keepdims=True)
        vec = np.cross(d, np.roll(d, -1, axis=1)).sum(axis=1)
        twice = np.linalg.norm(vec, axis=1)
        unit = vec / np.where(twice > 0, twice, 1.0)[:, None]
        normal[rows], area[rows] = unit, 0.5 * twice
        size[rows] = np.linalg.norm(np.ptp(pts, axis=1), axis=1)
        offplane[rows] = np.abs((d * unit[:, None, :]).sum(axis=2)).max(axis=1)
        repeated[rows] = has_repeats(pts)
    degenerate = repeated | (area <= np.maximum(MIN_AREA, SLIVER * size**2))
    return FaceGeom(normal, area, size, offplane, degenerate)


def has_repeats(pts: np.ndarray) -> np.ndarray:
    """Whether each polygon of ``pts`` (m, k, 3) has two vertices at the same position."""
    m, k, _ = pts.shape
    if k * k > 4_000_000:  # one huge polygon: sort its vertices instead
        return np.array([len(np.unique(p, axis=0)) < k for p in pts])
    # Pairwise comparison in blocks of about 4 million pairs (bounded memory, linear time).
    step = max(1, 4_000_000 // (k * k))
    out = np.empty(m, bool)
    for a in range(0, m, step):
        block = pts[a : a + step]
        same = (block[:, :, None, :] == block[:, None, :, :]).all(axis=3)
        same[:, np.arange(k), np.arange(k)] = False
        out[a : a + step] = same.any(axis=(1, 2))
    return out


def triangle_areas(tris: np.ndarray) -> np.ndarray:
    """Areas of triangles ``tris`` (t, 3, 3)."""
    return 0.5 * np.linalg.norm(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]), axis=1)


def fan(p: np.ndarray) -> np.ndarray:
    """Triangles (k - 2, 3, 3) fanning polygon ``p`` (k, 3) from its first vertex."""
    return np.stack([np.broadcast_to(p[0], (len(p) - 2, 3)), p[1:-1], p[2:]], axis=1)


def rect_quads(p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Which quads ``p`` (m, 4, 3) are rectangles, all at once: (mask, u, v), where a
    rectangle is ``p[0] + s*u + t*v`` with the same corners and front side (v made
    exactly orthogonal to u: Rect checks orthogonality with the same 1e-6 tolerance)."""
    e = np.roll(p, -1, axis=1) - p
    length = np.linalg.norm(e, axis=2)
    cos = np.abs((e * np.roll(e, -1, axis=1)).sum(axis=2))
    ok = (cos <= RIGHT_ANGLE_TOL * length * np.roll(length, -1, axis=1)).all(axis=1)
    ok &= np.linalg.norm(e[:, 0] + e[:, 2], axis=1) <= RIGHT_ANGLE_TOL * length[:, 0]
    u, v = e[:, 0], p[:, 3] - p[:, 0]
    uu = np.einsum("ij,ij->i", u, u)
    with np.errstate(divide="ignore", invalid="ignore"):
        v = v - (np.einsum("ij,ij->i", v, u) / uu)[:, None] * u
    return ok & (uu > 0), u, v


def perpendicular(n: np.ndarray) -> np.ndarray:
    """A unit vector perpendicular to unit vector ``n``."""
    e = np.zeros(3)
    e[np.argmin(np.abs(n))] = 1.0
    a = np.cross(n, e)
    return a / np.linalg.norm(a)


def ear_clip_3d(p: np.ndarray, normal: np.ndarray) -> np.ndarray | None:
    """Triangles (t, 3, 3) of planar polygon ``p`` (k, 3), or None if it self-intersects.

    The triangles keep the polygon's winding; ``normal`` is its unit normal.
    """
    a = perpendicular(normal)
    b = np.cross(normal, a)
    d = p - p.mean(axis=0)
    # (a, b, normal) is right-handed, so the polygon is counter-clockwise in (a, b).
    ears = ear_clip(np.column_stack([d @ a, d @ b]))
    return None if ears is None else p[np.array(ears, dtype=int).reshape(-1, 3)]


def cross2(u: np.ndarray, v: np.ndarray) -> float:
    """The z component of the cross product of 2D vectors ``u`` and ``v``."""
    return float(u[0] * v[1] - u[1] * v[0])


def ear_clip(q: np.ndarray) -> list[tuple[int, int, int]] | None:
    """Ears (index triples, counter-clockwise) of simple counter-clockwise polygon ``q`` (k, 2).

    Returns None when no ear can be found, i.e. the polygon is not simple.
    """
    idx = list(range(len(q)))
    eps = 1e-12 * float(np.ptp(q, axis=0).max()) ** 2
    ears: list[tuple[int, int, int]] = []
    t = misses = 0
    while len(idx) > 3:
        n = len(idx)
        if misses >= n:
            return None
        t %= n
        ia, ib, ic = idx[t - 1], idx[t], idx[(t + 1) % n]
        turn = cross2(q[ib] - q[ia], q[ic] - q[ib])
        # A straight (or back-tracking) vertex adds no area: drop it.
        if abs(turn) <= eps or (turn > 0 and not any_inside(q, idx, ia, ib, ic, eps)):
            if abs(turn) > eps:
                ears.append((ia, ib, ic))
            del idx[t]
            misses = 0
            continue
        t += 1
        misses += 1
    last = cross2(q[idx[1]] - q[idx[0]], q[idx[2]] - q[idx[1]])
    if last < -eps:
        return None
    if last > eps:
        ears.append((idx[0], idx[1], idx[2]))
    return ears


def any_inside(q: np.ndarray, idx: list[int], ia: int, ib: int, ic: int, eps: float) -> bool:
    """Whether any vertex ``q[idx]`` other than ia, ib, ic lies inside or on that triangle."""
    rest = q[[i for i in idx if i not in (ia, ib, ic)]]
    if len(rest) == 0:
        return False
    inside = np.ones(len(rest), bool)
    for s, e in ((ia, ib), (ib, ic), (ic, ia)):
        edge, rel = q[e] - q[s], rest - q[s]
        inside &= edge[0] * rel[:, 1] - edge[1] * rel[:, 0] >= -eps
    return bool(inside.any())


def zone_rect(polys: list[np.ndarray], normals, areas, where: str) -> Rect:
    """The rectangle the coplanar faces ``polys`` tile; ObjImportError (``where``) if none.

    ``normals`` (m, 3) and ``areas`` (m,) are the faces' unit normals and areas. The
    rectangle faces their area-weighted mean normal, in ``canonical_rect`` orientation.
    """
    if np.any(normals @ normals[np.argmax(areas)] < 0):
        raise ObjImportError(
            f"{where}: its faces do not all face the same way; flip the reversed faces so "
            "that all face into the room"
        )
    n = (normals * areas[:, None]).sum(axis=0)
    n /= np.linalg.norm(n)
    pts = np.concatenate(polys)
    c = pts.mean(axis=0)
    size = float(np.linalg.norm(np.ptp(pts, axis=0)))
    off = float(np.abs((pts - c) @ n).max())
    if off > ZONE_PLANE_TOL * size:
        raise ObjImportError(
            f"{where} is not planar: its vertices are up to {off:.3g} m from their common "
            "plane; an emitter zone must be one flat rectangle"
        )
    origin, u, v = min_area_rect(pts - c, n, candidate_axes(polys, n, size))
    rect = canonical_rect(origin + c, u, v)
    (su, sv), total = rect.size, float(areas.sum())
    if abs(total - rect.area) > ZONE_AREA_TOL * rect.area:
        raise ObjImportError(
            f"{where} is not a rectangle: its faces cover {total:.4g} m² but their smallest "
            f"enclosing rectangle ({su:.3g} x {sv:.3g} m) has {rect.area:.4g} m²; an emitter "
            "zone must be one rectangle (split other shapes into several zone groups)"
        )
    return rect


def candidate_axes(polys: list[np.ndarray], n: np.ndarray, size: float) -> np.ndarray:
    """Unit in-plane directions of the polygons' edges, one per direction modulo 90°."""
    e = np.concatenate([np.roll(p, -1, axis=0) - p for p in polys])
    e = e - np.outer(e @ n, n)
    length = np.linalg.norm(e, axis=1)
    e = e[length > 1e-9 * size] / length[length > 1e-9 * size, None]
    a0 = perpendicular(n)
    b0 = np.cross(n, a0)
    theta = np.unique(np.round(np.mod(np.arctan2(e @ b0, e @ a0), np.pi / 2), 9))
    return np.outer(np.cos(theta), a0) + np.outer(np.sin(theta), b0)


def min_area_rect(q: np.ndarray, n: np.ndarray, axes: np.ndarray):
    """(origin, u, v) of the smallest rectangle around points ``q`` with u along one of ``axes``."""
    best = None
    for start in range(0, len(axes), 512):
        a = axes[start : start + 512]
        b = np.cross(n, a)
        pa, pb = q @ a.T, q @ b.T
        lo_a, hi_a, lo_b, hi_b = pa.min(0), pa.max(0), pb.min(0), pb.max(0)
        area = (hi_a - lo_a) * (hi_b - lo_b)
        k = int(np.argmin(area))
        if best is None or area[k] < best[0]:
            best = (area[k], a[k], b[k], lo_a[k], hi_a[k], lo_b[k], hi_b[k])
    _, a, b, lo_a, hi_a, lo_b, hi_b = best
    return lo_a * a + lo_b * b, (hi_a - lo_a) * a, (hi_b - lo_b) * b


def canonical_rect(origin: np.ndarray, u: np.ndarray, v: np.ndarray) -> Rect:
    """The same rectangle and normal with u turned to point most along +x (then +y, +z)."""
    options = [(origin, u, v), (origin + u, v, -u), (origin + u + v, -u, -v), (origin + v, -v, u)]
    w = np.array([1.0, 1e-3, 1e-6])
    o, uu, vv = max(options, key=lambda r: float(r[1] @ w / np.linalg.norm(r[1])))
    return Rect(o, uu, vv)
