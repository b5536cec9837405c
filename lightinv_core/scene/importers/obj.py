"""Import a Wavefront OBJ room model as a LightInv ``Scene``.

Units: metres (OBJ coordinates times ``scale``), z up. Faces keep their winding:
counter-clockwise seen from the front is the front face, and LightInv lights front
faces only, so a room's faces must face into the room. A face that is a planar
rectangle becomes a grid-meshed rectangle; other faces are triangulated (ear clipping
in their plane) and merged per group and reflectance. A group named ``zone:NAME:KIND``
becomes the emitter zone NAME. The user guide is docs/obj-import.md.

This module assembles the scene: options, MTL libraries, reflectances, groups, zones and
surfaces. Text parsing is in ``obj_parse`` and polygon geometry in ``obj_geometry``.
``assemble_scene`` is the part every importer shares: the glTF/PLY and IFC readers
(``mesh_import``, ``ifc_import``) hand it the same polygons, groups and materials.
"""

from __future__ import annotations

import math
import numbers
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError, SceneError
from lightinv_core.scene.import_report import KEY as REPORT_KEY
from lightinv_core.scene.import_report import ImportItem, ImportReport
from lightinv_core.scene.model import (
    EmitterZone,
    Rect,
    Scene,
    Surface,
    check_resolution,
)
from lightinv_core.scene.obj_geometry import (
    MIN_AREA,
    SLIVER,
    FaceGeom,
    ear_clip_3d,
    face_geometry,
    fan,
    rect_quads,
    triangle_areas,
    zone_rect,
)
from lightinv_core.scene.obj_parse import (
    KD_CAP,
    LISTED,
    UP_AXES,
    MaterialMap,
    ObjData,
    clip,
    describe_lines,
    load_materials,
    parse_mtl,
    parse_obj,
    read_text,
    zone_spec,
)
from lightinv_core.scene.obj_size import check_obj_size
from lightinv_core.scene.patches import BIG_SPAN
from lightinv_core.scene.polygon_mesh import PolygonMesh, mesh_polygon

FAN_TOL = 0.01  # a polygon further than this times its size from its plane is fanned


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
    path, res, scale = check_options(path, resolution, scale, up, "OBJ")
    mats = load_materials(materials)
    fname = path.name
    text = read_text(path, "OBJ file", guard=check_obj_size)
    data = parse_obj(text, fname, scale, up)
    if not data.faces:
        raise ObjImportError(
            f"{fname}: no faces found ({len(data.vertices)} vertices); check that it is a "
            "Wavefront OBJ file and export the model as polygon faces (not lines, points or NURBS)"
        )
    kd = load_mtllibs(data.mtllibs, path.parent, fname, data.warnings)
    return assemble_scene(data, Places(path), mats, kd, res, scale, skip_degenerate, name)


class Places:
    """How messages name the model file and places in it: OBJ line numbers.

    ``ObjFace.line`` is a line of the file here; other readers number their faces
    instead and say where a face is in their own terms (``mesh_import.FacePlaces``).
    """

    what = "OBJ file"  # "... do not occur in the OBJ file"
    colour = "MTL Kd"  # where a material's colour comes from
    item_kind = "OBJ group"  # what a lighting group is in the import report

    def __init__(self, path: Path):
        self.path = path
        self.fname = path.name

    def at(self, line: int) -> str:
        """Where face ``line`` is, after the file name: ``" line 12"``."""
        return f" line {line}"

    def within(self, line: int) -> str:
        """The same in brackets, after a group name: ``" (line 12)"``."""
        return f" (line {line})"

    def many(self, lines: list[int]) -> str:
        """Where several faces are: ``"lines 7, 9"``."""
        return describe_lines(lines)


def assemble_scene(
    data: ObjData,
    places: Places,
    mats: MaterialMap,
    kd: dict[str, float],
    res: float,
    scale: float,
    skip_degenerate: bool,
    name: str | None,
    extra_items: tuple[ImportItem, ...] = (),
) -> Scene:
    """The Scene of parsed polygons ``data`` (metres, z up): degenerate and repeated
    faces, rectangles, triangulation, zones and reflectances, as for an OBJ file.

    ``kd`` is each material's colour as a reflectance guess (MTL Kd, glTF baseColor);
    ``places`` names the file and its faces in messages; ``extra_items`` are what the
    reader left out, for the import report (``info["import_report"]``, with one item
    per group). Raises ObjImportError.
    """
    fname = places.fname
    warnings = data.warnings
    geom = face_geometry(data.vertices, data.faces)
    before = len(warnings)
    keep = _check_degenerate(data.faces, geom, skip_degenerate, places, warnings)
    keep = _drop_duplicates(data.vertices, data.faces, keep, places, warnings)
    dropped = [w for w in warnings[before:] if w.startswith(f"{fname}: dropped ")]
    rho = Reflectances(mats, kd, places)
    groups = _build_groups(data.vertices, data.faces, geom, keep, rho, places, warnings, res)
    warnings += rho.warnings()
    _scale_warning(data.vertices, scale, fname, warnings)
    report = face_report(data.faces, geom, keep, places, dropped, extra_items)
    info = {"source": str(places.path), "warnings": warnings, REPORT_KEY: report.to_dict()}
    try:
        surfaces, zones = _surfaces(groups)
        desc = f"Imported from {fname}: {int(keep.sum())} faces, {len(zones)} emitter zones."
        return Scene(name or places.path.stem, tuple(surfaces), tuple(zones), res, desc, info)
    except SceneError as exc:
        # A safety net: the checks above should leave nothing the model can reject.
        raise ObjImportError(f"{fname}: {exc}") from None


def face_report(faces, geom: FaceGeom, keep, places: Places, dropped, extra=()) -> ImportReport:
    """One item per group, in order of first appearance: the emitter zone of a
    ``zone:NAME:KIND`` group, a lighting group, or dropped when none of its faces is
    kept; the faces dropped (``dropped``: the warnings saying so) as skipped lines."""
    count: dict[str, list] = {}
    for i, f in enumerate(faces):
        row = count.setdefault(f.group, [0, 0, 0.0])
        row[0] += 1
        if keep[i]:
            row[1] += 1
            row[2] += float(geom.area[i])
    items = []
    for group, (n, kept, area) in count.items():
        spec = zone_spec(group, places.fname)
        becomes = spec[0] if spec else group
        if not kept:
            why = f"all its {n} face(s) were dropped (degenerate or repeated)"
            items.append(ImportItem(places.item_kind, group, "dropped", None, why))
        else:
            outcome = "zone" if spec else "group"
            items.append(ImportItem(places.item_kind, group, outcome, becomes, "", area))
    return ImportReport(places.fname, (*items, *extra), tuple(dropped))


def check_options(path, resolution, scale, up, fmt: str) -> tuple[Path, float, float]:
    """The path, resolution (m) and scale of an import of format ``fmt`` ("OBJ", "glTF",
    ...), checked; ObjImportError saying what to give instead."""
    try:
        path = Path(os.fspath(path))
    except TypeError:
        kind = type(path).__name__
        raise ObjImportError(f"the {fmt} path must be a str or PathLike, not {kind}") from None
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


def _check_degenerate(faces, geom: FaceGeom, skip: bool, places: Places, warnings: list[str]):
    """Mask of the faces to keep; ObjImportError on degenerate faces unless ``skip``."""
    bad = np.flatnonzero(geom.degenerate)
    if len(bad) == 0:
        return np.ones(len(faces), bool)
    fname = places.fname
    where = places.many([faces[i].line for i in bad])
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


def _drop_duplicates(vertices, faces, keep, places: Places, warnings: list[str]) -> np.ndarray:
    """``keep`` without faces that repeat an earlier face of the same group: the same
    corners (to the micrometre) in the same turning order, which would count the area
    twice and split the light between the copies. A repeat in another group is kept
    with a warning (which one is meant is the modeller's call); the same corners in
    reverse order (the two sides of a thin wall) are not a repeat."""
    fname = places.fname
    q = np.round(vertices * 1e6).astype(np.int64)
    first: dict[tuple, int] = {}
    same: list[int] = []
    other: list[int] = []
    for i in np.flatnonzero(keep):
        rows = [tuple(r) for r in q[list(faces[i].index)].tolist()]
        m = rows.index(min(rows))
        j = first.setdefault(tuple(rows[m:] + rows[:m]), i)
        if j != i:
            (same if faces[j].group == faces[i].group else other).append(i)
    if other:
        warnings.append(
            f"{fname}: {len(other)} face(s) at {places.many([faces[i].line for i in other])}"
            " repeat a face of another group; both are kept, so that area counts twice "
            "(delete the one not meant)"
        )
    if not same:
        return keep
    warnings.append(
        f"{fname}: dropped {len(same)} duplicated face(s) at "
        f"{places.many([faces[i].line for i in same])} (the same polygon facing the same "
        "way as an earlier face of its group would count its area twice)"
    )
    out = keep.copy()
    out[same] = False
    return out


@dataclass
class _Group:
    """What one lighting group becomes: zones, rectangles, triangles per reflectance."""

    zones: list[tuple[str, str, Rect, float]] = field(default_factory=list)
    rects: list[tuple[Rect, float]] = field(default_factory=list)
    tris: dict[float, tuple[str | None, list[np.ndarray]]] = field(default_factory=dict)
    # Border triangles of polygons cut by ``mesh_polygon``: one patch each.
    cut: dict[float, tuple[str | None, list[np.ndarray]]] = field(default_factory=dict)


def _build_groups(vertices, faces, geom: FaceGeom, keep, rho, places: Places, warnings, res):
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


def load_mtllibs(refs: list[tuple[str, int]], folder: Path, fname: str, warnings: list[str]):
    """Kd luminance (0.2126 R + 0.7152 G + 0.0722 B) per material from the ``mtllib`` files.

    File names are resolved relative to ``folder``; a missing or unreadable file is a
    warning. A later definition of a material replaces an earlier one.
    """
    lum: dict[str, float] = {}
    for rest, no in refs:
        # A name with spaces is one file if it exists as such, else a list of files.
        names = [rest] if os.path.isfile(folder / rest) else rest.split()
        for name in names:
            try:
                text = read_text(folder / name, "material library")
            except ObjImportError as exc:
                warnings.append(
                    f"{fname} line {no}: {exc}; its materials get the default reflectance"
                )
                continue
            lum.update(parse_mtl(text, Path(name).name, warnings))
    return lum


class Reflectances:
    """Reflectance of a (group, material): mapping by group, by material, the material's
    colour (MTL Kd, glTF baseColor), default."""

    def __init__(self, mats: MaterialMap, kd: dict[str, float], places: Places):
        self.mats, self.kd, self.places = mats, kd, places
        self.capped: dict[str, float] = {}
        self.defaulted: set[str] = set()
        self.groups: set[str] = set()
        self.materials: set[str | None] = set()

    def __call__(self, group: str, material: str | None) -> float:
        self.groups.add(group)
        self.materials.add(material)
        if group in self.mats.groups:
            return self.mats.groups[group]
        if material in self.mats.materials:
            return self.mats.materials[material]
        if material in self.kd:
            lum = self.kd[material]
            if lum > KD_CAP:
                self.capped[material] = lum
            return min(lum, KD_CAP)
        if material is not None:
            self.defaulted.add(material)
        return self.mats.default

    def warnings(self) -> list[str]:
        """One warning per capped material, defaulted materials and unused mapping names."""
        colour = self.places.colour
        out = [
            f"material {clip(m)}: {colour} luminance {lum:.3g} capped at {KD_CAP} (exporters "
            f"write {WHITE.get(colour, colour + ' 1 1 1')} for white, and a reflectance of 1 "
            "makes radiosity diverge); give its reflectance in the materials mapping to "
            "silence this"
            for m, lum in self.capped.items()
        ]
        if self.defaulted:
            where = "an MTL file" if colour == "MTL Kd" else f"its {colour}"
            out.append(
                f"no reflectance for material(s) {_names(self.defaulted)} (not in the materials "
                f"mapping or {where}); they use the default {self.mats.default:g}"
            )
        for key, seen in (("groups", self.groups), ("materials", self.materials)):
            unused = set(getattr(self.mats, key)) - seen
            if unused:
                out.append(
                    f"{self.mats.source}: {key} {_names(unused)} do not occur in the "
                    f"{self.places.what} and are ignored; check the spelling"
                )
        return out


WHITE = {"MTL Kd": "Kd 1 1 1"}
"""How white is written in each colour source, for the capping warning."""


def _names(names) -> str:
    shown = sorted(names)
    return ", ".join(clip(n) for n in shown[:LISTED]) + (", ..." if len(shown) > LISTED else "")


def _scale_warning(vertices: np.ndarray, scale: float, fname: str, warnings: list[str]) -> None:
    span = float(np.ptp(vertices, axis=0).max())
    if span > BIG_SPAN:
        warnings.append(
            f"{fname}: the model is {span:,.0f} m across after scaling by {scale:g}; if it was "
            "drawn in millimetres pass scale=0.001 (centimetres: 0.01)"
        )
