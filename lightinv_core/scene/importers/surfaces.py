"""Faces to surfaces: each lighting group's rectangles (grid-meshed), triangles
(ear-clipped in their plane, merged per reflectance) and polygons cut at the resolution
(``polygon_mesh``), and the rectangle of each ``zone:NAME:KIND`` group (an emitter zone).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from lightinv_core.errors import ObjImportError, SceneError
from lightinv_core.scene.importers.faces import Places, clip, zone_spec
from lightinv_core.scene.importers.geometry import (
    MIN_AREA,
    SLIVER,
    FaceGeom,
    ear_clip_3d,
    fan,
    rect_quads,
    triangle_areas,
    zone_rect,
)
from lightinv_core.scene.importers.polygon_mesh import PolygonMesh, mesh_polygon
from lightinv_core.scene.model import EmitterZone, Rect, Surface

FAN_TOL = 0.01  # a polygon further than this times its size from its plane is fanned


@dataclass
class _Group:
    """What one lighting group becomes: zones, rectangles, triangles per reflectance."""

    zones: list[tuple[str, str, Rect, float]] = field(default_factory=list)
    rects: list[tuple[Rect, float]] = field(default_factory=list)
    tris: dict[float, tuple[str | None, list[np.ndarray]]] = field(default_factory=dict)
    # Border triangles of polygons cut by ``mesh_polygon``: one patch each.
    cut: dict[float, tuple[str | None, list[np.ndarray]]] = field(default_factory=dict)


def build_groups(vertices, faces, geom: FaceGeom, keep, rho, places: Places, warnings, res):
    """Lighting group name -> _Group, in order of first appearance in the file."""
    fname = places.fname
    groups: dict[str, _Group] = {}
    zone_faces: dict[str, list[int]] = {}
    odd: dict[str, list[int]] = {"non-planar": [], "self-intersecting": []}
    rects = _rectangles(vertices, faces, keep)
    for i in np.flatnonzero(keep):
        f = faces[i]
        spec = zone_spec(f.group, f"{fname}{places.at(f.line)}")
        if spec is not None:
            groups.setdefault(spec[0], _Group())
            zone_faces.setdefault(f.group, []).append(i)
            continue
        g = groups.setdefault(f.group, _Group())
        r = rho(f.group, f.material)
        piece = rects.get(i) or _piece(vertices[list(f.index)], geom, i, f.line, odd, res)
        if isinstance(piece, Rect):
            g.rects.append((piece, r))
        elif isinstance(piece, PolygonMesh):
            g.rects += [(rect, r) for rect in piece.rects]
            if len(piece.triangles):
                g.cut.setdefault(r, (f.material, []))[1].append(piece.triangles)
        else:
            g.tris.setdefault(r, (f.material, []))[1].append(piece)
    for kind, lines in odd.items():
        if lines:
            warnings.append(
                f"{fname}: {len(lines)} {kind} polygon(s) at {places.many(lines)} were "
                "split into a fan of triangles, which may not follow the intended surface; fix "
                "them in the modeller or triangulate them on export"
            )
    _add_zones(zone_faces, vertices, faces, geom, rho, groups, places, warnings)
    return groups


def _rectangles(vertices, faces, keep) -> dict[int, Rect]:
    """The kept quads that are rectangles, as Rects by face index (tested all at once:
    per face, the test was most of an import's time)."""
    quads = np.array([i for i in np.flatnonzero(keep) if len(faces[i].index) == 4], dtype=int)
    if len(quads) == 0:
        return {}
    pts = vertices[np.array([faces[i].index for i in quads])]
    ok, u, v = rect_quads(pts)
    out = {}
    for k in np.flatnonzero(ok):
        try:
            out[int(quads[k])] = Rect(pts[k, 0], u[k], v[k])
        except SceneError:
            continue
    return out


def _piece(p: np.ndarray, geom: FaceGeom, i: int, line: int, odd: dict[str, list[int]], res: float):
    """Face ``i`` (corners ``p``) as a Rect, as triangles (t, 3, 3) keeping its winding,
    or, when subdividing those would make far more patches than its area needs (slivers
    of a many-sided polygon), as a ``PolygonMesh`` cut at the resolution ``res``."""
    if len(p) == 3:  # the common case, kept free of per-face numpy calls
        a, b, c = p.tolist()
        m = max(1, math.ceil(max(math.dist(a, b), math.dist(b, c), math.dist(c, a)) / res - 1e-9))
        if m * m > SLIVER_EXCESS * geom.area[i] / res**2 + 3:
            return mesh_polygon(p, geom.normal[i], res)
        return p[None]
    size, tris = geom.size[i], None
    if geom.offplane[i] > FAN_TOL * size:
        odd["non-planar"].append(line)
    elif len(p) > MANY_SIDES:
        return mesh_polygon(p, geom.normal[i], res)  # skips a slow ear clip of slivers
    else:
        tris = ear_clip_3d(p, geom.normal[i])
        if tris is None:
            odd["self-intersecting"].append(line)
    if tris is None:  # non-planar or self-intersecting: no mesher can do better
        tris = fan(p)
        return tris[triangle_areas(tris) > max(MIN_AREA, SLIVER * size**2)]
    tris = tris[triangle_areas(tris) > max(MIN_AREA, SLIVER * size**2)]
    if _patches_of(tris, res) > POLYGON_EXCESS * geom.area[i] / res**2 + len(p):
        return mesh_polygon(p, geom.normal[i], res)
    return tris


POLYGON_EXCESS = 2.0
"""The same for a polygon of four or more sides: its ear-clip triangles, subdivided,
would make more than twice the patches of a grid at the resolution (an L-shaped
ceiling made 7 times), so it is cut into rectangles and border triangles."""


MANY_SIDES = 64
"""Polygons with more sides are always cut by ``mesh_polygon``."""


SLIVER_EXCESS = 8.0
"""A face whose triangles would make more than this many times the patches its area
needs (plus one per side) is cut by ``mesh_polygon`` instead. Well-shaped triangles
make 2.3 (equilateral) to 4 (right-angled) times, so only slivers are caught."""


def _patches_of(tris: np.ndarray, res: float) -> int:
    """Patches ``tris`` make when subdivided at ``res`` (as ``mesh_patches`` does)."""
    e = np.stack([tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 1], tris[:, 0] - tris[:, 2]], 1)
    m = np.maximum(1, np.ceil(np.linalg.norm(e, axis=2).max(axis=1) / res - 1e-9))
    return int((m * m).sum())


def _add_zones(zone_faces, vertices, faces, geom, rho, groups, places: Places, warnings) -> None:
    """Fit each zone group's rectangle and add it to its _Group."""
    seen: dict[str, str] = {}
    fname = places.fname
    for label, rows in zone_faces.items():
        line = faces[rows[0]].line
        name, kind = zone_spec(label, f"{fname}{places.at(line)}")
        where = f"{fname}: zone group {clip(label)}{places.within(line)}"
        if name in seen:
            raise ObjImportError(
                f"{where}: zone {clip(name)} is already defined by group {clip(seen[name])}; "
                "give each zone a unique name"
            )
        seen[name] = label
        polys = [vertices[list(faces[i].index)] for i in rows]
        areas = geom.area[rows]
        rect = zone_rect(polys, geom.normal[rows], areas, where)
        rhos = np.array([rho(name, faces[i].material) for i in rows])
        r = float(rhos[0])
        if np.ptp(rhos) > 0:
            r = float(rhos @ areas / areas.sum())
            warnings.append(
                f"{where}: its faces have different reflectances; the zone uses their "
                f"area-weighted mean {r:.3g}"
            )
        groups[name].zones.append((name, kind, rect, r))


def surfaces_of(groups: dict[str, _Group]) -> tuple[list[Surface], list[EmitterZone]]:
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
        alone = len(g.rects) == 1 and not g.tris and not g.cut and not g.zones
        for k, (rect, r) in enumerate(g.rects, 1):
            base = gname if alone else f"{gname}.rect{k}"
            surfaces.append(Surface(unique(base), gname, r, rect=rect))
        for r, (mat, parts) in g.tris.items():
            tri = np.concatenate(parts)
            if len(tri):
                base = gname if len(g.tris) == 1 else f"{gname}.{mat or 'default'}"
                surfaces.append(Surface(unique(base), gname, r, triangles=tri))
        for r, (mat, parts) in g.cut.items():
            base = f"{gname}.border" if len(g.cut) == 1 else f"{gname}.{mat or 'default'}.border"
            tri = np.concatenate(parts)
            surfaces.append(Surface(unique(base), gname, r, triangles=tri, subdivide=False))
    return surfaces, zones
