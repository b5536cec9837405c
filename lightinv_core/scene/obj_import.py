"""Import a Wavefront OBJ room model as a LightInv ``Scene``.

Units: metres (OBJ coordinates times ``scale``), z up. Faces keep their winding:
counter-clockwise seen from the front is the front face, and LightInv lights front
faces only, so a room's faces must face into the room. A face that is a planar
rectangle becomes a grid-meshed rectangle; other faces are triangulated (ear clipping
in their plane) and merged per group and reflectance. A group named ``zone:NAME:KIND``
becomes the emitter zone NAME. The user guide is docs/obj-import.md.
"""

from __future__ import annotations

import math
import numbers
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError, SceneError
from lightinv_core.scene.model import (
    EmitterZone,
    Rect,
    Scene,
    Surface,
    check_resolution,
)
from lightinv_core.scene.obj_parse import (
    UP_AXES,
    ObjFace,
    Reflectances,
    clip,
    describe_lines,
    load_materials,
    load_mtllibs,
    parse_obj,
    read_text,
    zone_spec,
)

FAN_TOL = 0.01  # a polygon further than this times its size from its plane is fanned
RIGHT_ANGLE_TOL = 1e-6  # |cos| of a rectangle's corner angles, relative
ZONE_PLANE_TOL = 1e-3  # zone vertices' distance from their common plane, times the zone size
ZONE_AREA_TOL = 0.01  # zone faces' area vs. their enclosing rectangle's, relative
# Faces below MIN_AREA m² or SLIVER x size² have zero area for all purposes (and the
# mesher rejects patches of ~1e-14 m²).
MIN_AREA = 1e-12
SLIVER = 1e-9
BIG_MODEL = 1000.0  # m; a model wider than this was probably not drawn in metres


def load_obj(
    path: str | os.PathLike,
    materials: dict | str | os.PathLike | None = None,
    resolution: float = 0.25,
    scale: float = 1.0,
    up: str = "z",
    skip_degenerate: bool = False,
    name: str | None = None,
) -> Scene:
    """Import the OBJ file ``path`` as a Scene (metres, z up).

    Parameters
    ----------
    materials : reflectances by group and material name: a dict or the path of a JSON
        file ``{"default": 0.5, "groups": {...}, "materials": {...}}``.
    resolution : target patch edge length in metres.
    scale : metres per OBJ unit (0.001 for a model drawn in millimetres).
    up : ``"z"`` or ``"y"``, the model's up axis; y-up is turned z-up by (x, y, z) -> (x, -z, y).
    skip_degenerate : drop faces with repeated vertices or zero area (listed in a warning)
        instead of raising.
    name : scene name; default the file name without extension.

    Returns a Scene whose ``info`` holds ``"source"`` (the path) and ``"warnings"`` (list of
    str). Raises ObjImportError for anything wrong with the file, materials or options.
    """
    path, res, scale = _check_options(path, resolution, scale, up)
    mats = load_materials(materials)
    fname = path.name
    data = parse_obj(read_text(path, "OBJ file"), fname, scale, up)
    warnings = data.warnings
    if not data.faces:
        raise ObjImportError(
            f"{fname}: no faces found ({len(data.vertices)} vertices); check that it is a "
            "Wavefront OBJ file and export the model as polygon faces (not lines, points or NURBS)"
        )
    kd = load_mtllibs(data.mtllibs, path.parent, fname, warnings)
    geom = _face_geometry(data.vertices, data.faces)
    keep = _check_degenerate(data.faces, geom, skip_degenerate, fname, warnings)
    rho = Reflectances(mats, kd)
    groups = _build_groups(data.vertices, data.faces, geom, keep, rho, fname, warnings)
    warnings += rho.warnings()
    _scale_warning(data.vertices, scale, fname, warnings)
    info = {"source": str(path), "warnings": warnings}
    try:
        surfaces, zones = _surfaces(groups)
        desc = f"Imported from {fname}: {int(keep.sum())} faces, {len(zones)} emitter zones."
        return Scene(name or path.stem, tuple(surfaces), tuple(zones), res, desc, info)
    except SceneError as exc:
        # A safety net: the checks above should leave nothing the model can reject.
        raise ObjImportError(f"{fname}: {exc}") from None


def _check_options(path, resolution, scale, up) -> tuple[Path, float, float]:
    try:
        path = Path(os.fspath(path))
    except TypeError:
        kind = type(path).__name__
        raise ObjImportError(f"the OBJ path must be a str or PathLike, not {kind}") from None
    try:
        res = check_resolution(resolution)
    except SceneError as exc:
        raise ObjImportError(str(exc)) from None
    try:
        ok = isinstance(scale, numbers.Real) and not isinstance(scale, bool)
        ok = ok and math.isfinite(float(scale)) and float(scale) > 0
    except OverflowError:
        ok = False
    if not ok:
        raise ObjImportError(
            f"scale {scale!r} is not a positive number; give metres per model unit, e.g. 1 "
            "(metres), 0.01 (centimetres), 0.001 (millimetres) or 0.0254 (inches)"
        )
    if not isinstance(up, str) or up not in UP_AXES:
        raise ObjImportError(
            f"up={up!r} is not supported; use up='z' for a z-up model or up='y' for a y-up "
            "model (see docs/obj-import.md)"
        )
    return path, res, float(scale)


@dataclass(frozen=True)
class _FaceGeom:
    """Per face: unit normal (Newell), area (m²), bounding-box diagonal (m), largest vertex
    distance from the best-fit plane (m), and whether it is degenerate."""

    normal: np.ndarray
    area: np.ndarray
    size: np.ndarray
    offplane: np.ndarray
    degenerate: np.ndarray


def _face_geometry(vertices: np.ndarray, faces: list[ObjFace]) -> _FaceGeom:
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
        repeated[rows] = _has_repeats(pts)
    degenerate = repeated | (area <= np.maximum(MIN_AREA, SLIVER * size**2))
    return _FaceGeom(normal, area, size, offplane, degenerate)


def _has_repeats(pts: np.ndarray) -> np.ndarray:
    """Whether each polygon of ``pts`` (m, k, 3) has two vertices at the same position."""
    m, k, _ = pts.shape
    if m * k * k > 4_000_000:
        return np.array([len(np.unique(p, axis=0)) < k for p in pts])
    same = (pts[:, :, None, :] == pts[:, None, :, :]).all(axis=3)
    same[:, np.arange(k), np.arange(k)] = False
    return same.any(axis=(1, 2))


def _check_degenerate(faces, geom: _FaceGeom, skip: bool, fname: str, warnings: list[str]):
    """Mask of the faces to keep; ObjImportError on degenerate faces unless ``skip``."""
    bad = np.flatnonzero(geom.degenerate)
    if len(bad) == 0:
        return np.ones(len(faces), bool)
    where = describe_lines([faces[i].line for i in bad])
    what = f"{len(bad)} degenerate face(s) (repeated vertices or zero area) at {where}"
    if not skip:
        raise ObjImportError(
            f"{fname}: {what}; delete or fix them in the modeller, or pass "
            "skip_degenerate=True to drop them"
        )
    if len(bad) == len(faces):
        raise ObjImportError(
            f"{fname}: all {len(bad)} faces are degenerate (repeated vertices or zero area); "
            "nothing to import, check the model and the scale"
        )
    warnings.append(f"{fname}: dropped {what}")
    return ~geom.degenerate


@dataclass
class _Group:
    """What one lighting group becomes: zones, rectangles, triangles per reflectance."""

    zones: list[tuple[str, str, Rect, float]] = field(default_factory=list)
    rects: list[tuple[Rect, float]] = field(default_factory=list)
    tris: dict[float, tuple[str | None, list[np.ndarray]]] = field(default_factory=dict)


def _build_groups(vertices, faces, geom: _FaceGeom, keep, rho, fname, warnings):
    """Lighting group name -> _Group, in order of first appearance in the file."""
    groups: dict[str, _Group] = {}
    zone_faces: dict[str, list[int]] = {}
    odd: dict[str, list[int]] = {"non-planar": [], "self-intersecting": []}
    for i in np.flatnonzero(keep):
        f = faces[i]
        spec = zone_spec(f.group, f.line, fname)
        if spec is not None:
            groups.setdefault(spec[0], _Group())
            zone_faces.setdefault(f.group, []).append(i)
            continue
        g = groups.setdefault(f.group, _Group())
        r = rho(f.group, f.material)
        piece = _piece(vertices[list(f.index)], geom, i, f.line, odd)
        if isinstance(piece, Rect):
            g.rects.append((piece, r))
        else:
            g.tris.setdefault(r, (f.material, []))[1].append(piece)
    for kind, lines in odd.items():
        if lines:
            warnings.append(
                f"{fname}: {len(lines)} {kind} polygon(s) at {describe_lines(lines)} were "
                "split into a fan of triangles, which may not follow the intended surface; fix "
                "them in the modeller or triangulate them on export"
            )
    _add_zones(zone_faces, vertices, faces, geom, rho, groups, fname, warnings)
    return groups


def _piece(p: np.ndarray, geom: _FaceGeom, i: int, line: int, odd: dict[str, list[int]]):
    """Face ``i`` (corners ``p``) as a Rect, or as triangles (t, 3, 3) keeping its winding."""
    if len(p) == 3:
        return p[None]
    if len(p) == 4 and (rect := _as_rect(p)) is not None:
        return rect
    size, tris = geom.size[i], None
    if geom.offplane[i] > FAN_TOL * size:
        odd["non-planar"].append(line)
    else:
        tris = _ear_clip_3d(p, geom.normal[i])
        if tris is None:
            odd["self-intersecting"].append(line)
    if tris is None:
        tris = np.stack([np.broadcast_to(p[0], (len(p) - 2, 3)), p[1:-1], p[2:]], axis=1)
    area = 0.5 * np.linalg.norm(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]), axis=1)
    return tris[area > max(MIN_AREA, SLIVER * size**2)]


def _as_rect(p: np.ndarray) -> Rect | None:
    """Quad ``p`` (4, 3) as a Rect with the same corners and front side, if it is a rectangle."""
    e = np.roll(p, -1, axis=0) - p
    length = np.linalg.norm(e, axis=1)
    cos = np.abs((e * np.roll(e, -1, axis=0)).sum(axis=1))
    if np.any(cos > RIGHT_ANGLE_TOL * length * np.roll(length, -1)):
        return None
    if np.linalg.norm(e[0] + e[2]) > RIGHT_ANGLE_TOL * length[0]:
        return None
    u, v = e[0], p[3] - p[0]
    # Exactly orthogonal edges: Rect checks orthogonality with the same 1e-6 tolerance.
    v = v - (v @ u) / (u @ u) * u
    try:
        return Rect(p[0], u, v)
    except SceneError:
        return None


def _perpendicular(n: np.ndarray) -> np.ndarray:
    """A unit vector perpendicular to unit vector ``n``."""
    e = np.zeros(3)
    e[np.argmin(np.abs(n))] = 1.0
    a = np.cross(n, e)
    return a / np.linalg.norm(a)


def _ear_clip_3d(p: np.ndarray, normal: np.ndarray) -> np.ndarray | None:
    """Triangles (t, 3, 3) of planar polygon ``p`` (k, 3), or None if it self-intersects."""
    a = _perpendicular(normal)
    b = np.cross(normal, a)
    d = p - p.mean(axis=0)
    # (a, b, normal) is right-handed, so the polygon is counter-clockwise in (a, b).
    ears = _ear_clip(np.column_stack([d @ a, d @ b]))
    return None if ears is None else p[np.array(ears, dtype=int).reshape(-1, 3)]


def _cross2(u: np.ndarray, v: np.ndarray) -> float:
    return float(u[0] * v[1] - u[1] * v[0])


def _ear_clip(q: np.ndarray) -> list[tuple[int, int, int]] | None:
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
        turn = _cross2(q[ib] - q[ia], q[ic] - q[ib])
        # A straight (or back-tracking) vertex adds no area: drop it.
        if abs(turn) <= eps or (turn > 0 and not _any_inside(q, idx, ia, ib, ic, eps)):
            if abs(turn) > eps:
                ears.append((ia, ib, ic))
            del idx[t]
            misses = 0
            continue
        t += 1
        misses += 1
    last = _cross2(q[idx[1]] - q[idx[0]], q[idx[2]] - q[idx[1]])
    if last < -eps:
        return None
    if last > eps:
        ears.append((idx[0], idx[1], idx[2]))
    return ears


def _any_inside(q, idx: list[int], ia: int, ib: int, ic: int, eps: float) -> bool:
    """Whether any other polygon vertex lies inside or on triangle (ia, ib, ic)."""
    rest = q[[i for i in idx if i not in (ia, ib, ic)]]
    if len(rest) == 0:
        return False
    inside = np.ones(len(rest), bool)
    for s, e in ((ia, ib), (ib, ic), (ic, ia)):
        edge, rel = q[e] - q[s], rest - q[s]
        inside &= edge[0] * rel[:, 1] - edge[1] * rel[:, 0] >= -eps
    return bool(inside.any())


def _add_zones(zone_faces, vertices, faces, geom, rho, groups, fname, warnings) -> None:
    """Fit each zone group's rectangle and add it to its _Group."""
    seen: dict[str, str] = {}
    for label, rows in zone_faces.items():
        name, kind = zone_spec(label, faces[rows[0]].line, fname)
        where = f"{fname}: zone group {clip(label)} (line {faces[rows[0]].line})"
        if name in seen:
            raise ObjImportError(
                f"{where}: zone {clip(name)} is already defined by group {clip(seen[name])}; "
                "give each zone a unique name"
            )
        seen[name] = label
        polys = [vertices[list(faces[i].index)] for i in rows]
        areas = geom.area[rows]
        rect = _zone_rect(polys, geom.normal[rows], areas, where)
        rhos = np.array([rho(name, faces[i].material) for i in rows])
        r = float(rhos[0])
        if np.ptp(rhos) > 0:
            r = float(rhos @ areas / areas.sum())
            warnings.append(
                f"{where}: its faces have different reflectances; the zone uses their "
                f"area-weighted mean {r:.3g}"
            )
        groups[name].zones.append((name, kind, rect, r))


def _zone_rect(polys: list[np.ndarray], normals, areas, where: str) -> Rect:
    """The rectangle the coplanar faces ``polys`` tile; ObjImportError (``where``) if none."""
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
    origin, u, v = _min_area_rect(pts - c, n, _candidate_axes(polys, n, size))
    rect = _canonical(origin + c, u, v)
    (su, sv), total = rect.size, float(areas.sum())
    if abs(total - rect.area) > ZONE_AREA_TOL * rect.area:
        raise ObjImportError(
            f"{where} is not a rectangle: its faces cover {total:.4g} m² but their smallest "
            f"enclosing rectangle ({su:.3g} x {sv:.3g} m) has {rect.area:.4g} m²; an emitter "
            "zone must be one rectangle (split other shapes into several zone groups)"
        )
    return rect


def _candidate_axes(polys: list[np.ndarray], n: np.ndarray, size: float) -> np.ndarray:
    """Unit in-plane directions of the polygons' edges, one per direction modulo 90°."""
    e = np.concatenate([np.roll(p, -1, axis=0) - p for p in polys])
    e = e - np.outer(e @ n, n)
    length = np.linalg.norm(e, axis=1)
    e = e[length > 1e-9 * size] / length[length > 1e-9 * size, None]
    a0 = _perpendicular(n)
    b0 = np.cross(n, a0)
    theta = np.unique(np.round(np.mod(np.arctan2(e @ b0, e @ a0), np.pi / 2), 9))
    return np.outer(np.cos(theta), a0) + np.outer(np.sin(theta), b0)


def _min_area_rect(q: np.ndarray, n: np.ndarray, axes: np.ndarray):
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


def _canonical(origin: np.ndarray, u: np.ndarray, v: np.ndarray) -> Rect:
    """The same rectangle and normal with u turned to point most along +x (then +y, +z)."""
    options = [(origin, u, v), (origin + u, v, -u), (origin + u + v, -u, -v), (origin + v, -v, u)]
    w = np.array([1.0, 1e-3, 1e-6])
    o, uu, vv = max(options, key=lambda r: float(r[1] @ w / np.linalg.norm(r[1])))
    return Rect(o, uu, vv)


def _surfaces(groups: dict[str, _Group]) -> tuple[list[Surface], list[EmitterZone]]:
    """Surfaces with unique names (zones keep their own name) and the emitter zones."""
    taken = {z[0] for g in groups.values() for z in g.zones}

    def unique(base: str) -> str:
        name, k = base, 2
        while name in taken:
            name, k = f"{base}.{k}", k + 1
        taken.add(name)
        return name

    surfaces, zones = [], []
    for gname, g in groups.items():
        for zname, kind, rect, r in g.zones:
            surfaces.append(Surface(zname, gname, r, rect=rect))
            zones.append(EmitterZone(zname, kind, zname))
        alone = len(g.rects) == 1 and not g.tris and not g.zones
        for k, (rect, r) in enumerate(g.rects, 1):
            base = gname if alone else f"{gname}.rect{k}"
            surfaces.append(Surface(unique(base), gname, r, rect=rect))
        for r, (mat, parts) in g.tris.items():
            tri = np.concatenate(parts)
            if len(tri):
                base = gname if len(g.tris) == 1 else f"{gname}.{mat or 'default'}"
                surfaces.append(Surface(unique(base), gname, r, triangles=tri))
    return surfaces, zones


def _scale_warning(vertices: np.ndarray, scale: float, fname: str, warnings: list[str]) -> None:
    span = float(np.ptp(vertices, axis=0).max())
    if span > BIG_MODEL:
        warnings.append(
            f"{fname}: the model is {span:,.0f} m across after scaling by {scale:g}; if it was "
            "drawn in millimetres pass scale=0.001 (centimetres: 0.01)"
        )
