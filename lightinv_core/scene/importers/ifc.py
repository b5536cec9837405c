"""Import an IFC (BIM) model as a LightInv scene, through ifcopenshell (optional extra).

ifcopenshell turns every building element into triangles in world coordinates (metres,
z up), with the voids of its openings cut. BIM elements are solids, while LightInv
needs the room surfaces: so the faces of each element are merged per plane, the parts
where two elements touch (a wall standing on a slab, a window in its opening) or run
into each other are cut away, and faces that look out of the building (most rays from
their front escape the model or start inside another element) are left out
(``ifc_geometry``). Windows become glazing zones
(skylight kind), ceiling coverings luminaire zones; what remains goes through the
neutral ``assembly.assemble_scene``. The user guide is docs/obj-import.md.

ifcopenshell and shapely (which it installs) are imported only here and only when an
IFC file is read: the core works without them.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.facets import row_ids
from lightinv_core.scene.importers.assembly import assemble_scene, check_options
from lightinv_core.scene.importers.faces import LISTED, MAX_COORD, Face, FacePlaces, Polygons, clip
from lightinv_core.scene.importers.geometry import z_up
from lightinv_core.scene.importers.ifc_fixtures import light_fixtures
from lightinv_core.scene.importers.ifc_geometry import (
    GRID,
    Element,
    Part,
    Plane,
    centre_of,
    cull_outside,
    cut_contacts,
    cut_sections,
    planes_of,
    rectangles,
)
from lightinv_core.scene.importers.ifc_openings import bodiless_windows
from lightinv_core.scene.importers.ifc_report import SKIPPED_REASONS, Stages, ifc_report
from lightinv_core.scene.importers.materials import load_materials
from lightinv_core.scene.importers.report import KEY as REPORT_KEY
from lightinv_core.scene.importers.report import report_of
from lightinv_core.scene.importers.size import check_ifc_size
from lightinv_core.scene.model import Scene

MISSING = "IFC import needs the optional extra: pip install 'lightinv[ifc]'"
SUFFIXES = (".ifc",)
SKIPPED = tuple(SKIPPED_REASONS)
"""Classes not meshed (spaces, openings, the site, ...; why: ``SKIPPED_REASONS``)."""
ROLE_REFLECTANCE = {"floor": 0.2, "wall": 0.5, "ceiling": 0.7, "furniture": 0.2, "glazing": 0.1}
"""Default reflectance by role: the lower end of the ranges EN 12464-1:2011 (4.2.2)
recommends (ceiling 0.7-0.9, walls 0.5-0.8, floor 0.2-0.4, major objects such as
furniture 0.2-0.7), so finishes lighter than specified never flatter a design; clear
glazing 0.1 (each glass surface reflects about 4 % at normal incidence, more at grazing
angles). The materials mapping's ``"materials"`` keys are these roles."""
FURNITURE = ("IfcFurnishingElement", "IfcFurniture", "IfcSystemFurnitureElement")
UPWARD = 0.7  # a face whose normal has a z component above this faces up (a floor)
RECTANGLE = 0.99  # a zone's face must fill this share of its smallest enclosing rectangle


def _libraries():
    """ifcopenshell, its geometry module and shapely, or ObjImportError naming the extra."""
    try:
        import ifcopenshell
        import ifcopenshell.geom
        import shapely
        import shapely.affinity
    except ImportError:
        raise ObjImportError(MISSING) from None
    return ifcopenshell, shapely


def load_ifc(
    path: str | os.PathLike,
    materials: dict | str | os.PathLike | None = None,
    resolution: float = 0.25,
    scale: float = 1.0,
    up: str = "z",
    skip_degenerate: bool = False,
    name: str | None = None,
) -> Scene:
    """Import the IFC file ``path`` as a Scene (metres, z up).

    ifcopenshell converts the file's length unit to metres; ``scale`` multiplies on top
    (leave it 1). Lighting groups are ``CLASS:NAME`` of each element (``IfcWall:North``);
    reflectances come from the materials mapping, else from ``ROLE_REFLECTANCE`` by
    role (floor, wall, ceiling by the face's direction; furniture; glazing). Each
    window's largest room-side rectangle becomes a skylight-kind emitter zone named
    after it, each ceiling covering's largest downward rectangle a luminaire zone.
    ``info["ifc"]`` records the elements, spaces, zones, the area left out and the
    light fixtures (``ifc_fixtures.light_fixtures``).

    Raises ObjImportError for a missing extra, a file ifcopenshell cannot read, no
    building elements, bad options, or a file too large for the memory available
    (``check_ifc_size``).
    """
    path, res, scale = check_options(path, resolution, scale, up, "IFC")
    if path.is_file():  # a missing file is _open's error
        check_ifc_size(path, path.name)
    ifcopenshell, shapely = _libraries()
    mats = load_materials(materials)
    fname = path.name
    model = _open(ifcopenshell, path)
    elements, spaces, parts, unplaced = _elements(ifcopenshell, model, fname)
    planes = planes_of(elements, _role, shapely)
    stages = Stages(len(elements))
    stages.record("faces", planes)
    failed: list = []
    contact = cut_contacts(planes, shapely, failed)
    contact += cut_sections(planes, elements, shapely, failed)
    stages.record("cut", planes)
    centre = centre_of(elements)

    def underside(p: Plane) -> bool:
        # A ceiling covering's underside faces a room whatever the rays find: in a model
        # without floor slabs they escape, and its zone was lost.
        return elements[p.element].ceiling and p.normal[2] < -UPWARD

    exterior = cull_outside(planes, elements, centre, shapely, keep=underside)
    stages.record_pieces(planes)
    warnings: list[str] = []
    zones, notes = _zones(planes, elements, shapely, warnings, fname)
    names = _group_names(elements)
    report = ifc_report(
        fname, model, elements, names, stages, zones, notes, parts, failed, warnings, unplaced
    )
    data, places, counts = _faces(planes, elements, zones, scale, up, path)
    data.warnings.extend(warnings)
    scene = assemble_scene(
        data, places, mats, dict(ROLE_REFLECTANCE), res, scale, skip_degenerate, name
    )
    wall = sum(1 for z in zones.values() if z[1] == "wall window")
    info = {
        "elements": len(elements),
        "spaces": spaces,
        "zones": {z: kind for z, (_, kind) in zones.items()},
        "contact_m2": contact,
        "exterior_m2": exterior,
        "light_fixtures": light_fixtures(model, scale, up),
    }
    scene.info["ifc"] = info
    faces = report_of(scene)  # the faces assemble_scene dropped, if any
    skipped = report.skipped + (faces.skipped if faces is not None else ())
    scene.info[REPORT_KEY] = replace(report, skipped=skipped).to_dict()
    desc = (
        f"Imported from {fname}: {len(elements)} elements ({counts} faces), "
        f"{len(scene.zones)} emitter zones ({wall} wall windows); {contact:.1f} m² where "
        f"elements touch and {exterior:.1f} m² facing outside left out."
    )
    return Scene(scene.name, scene.surfaces, scene.zones, scene.resolution, desc, scene.info)


def _open(ifcopenshell, path: Path):
    fname = path.name
    if not path.exists():
        raise ObjImportError(f"IFC file '{path}' does not exist; check the path")
    if not path.is_file():
        raise ObjImportError(
            f"IFC file '{path}' is not a file (a folder or device); give the path of the file"
        )
    _check_complete(path)
    log = getattr(ifcopenshell, "get_log", lambda: "")
    log()  # the parser's log is read and cleared: start from an empty one
    try:
        model = ifcopenshell.open(str(path))
    except Exception as exc:  # ifcopenshell raises its own and plain errors on bad files
        text = " ".join(str(exc).split())[:80] or type(exc).__name__
        raise ObjImportError(
            f"{fname}: cannot read it as IFC ({text}); export the model as IFC2X3 or IFC4 "
            "(STEP, .ifc)"
        ) from None
    _check_references(log(), fname)
    return model


STEP_START = b"ISO-10303-21;"
STEP_END = b"END-ISO-10303-21;"
TAIL_BYTES = 4096


def _check_complete(path: Path) -> None:
    """ObjImportError if a STEP file does not end with ``END-ISO-10303-21;``: a file cut
    short (a copy or download that stopped) reads without an error in ifcopenshell and
    would import as a partial building. Files that do not start as STEP files are left
    to ifcopenshell's own error."""
    size = path.stat().st_size
    with open(path, "rb") as fh:
        head = fh.read(64).lstrip(b"\xef\xbb\xbf \t\r\n")
        fh.seek(max(0, size - TAIL_BYTES))
        tail = fh.read()
    if not head.upper().startswith(STEP_START) or STEP_END in tail.upper():
        return
    last = tail.rstrip().rsplit(b"\n", 1)[-1].decode("latin-1").strip()
    raise ObjImportError(
        f"{path.name}: the file is cut short (it ends after {size:,} bytes with "
        f"{clip(last[:40])}, not with END-ISO-10303-21; as every IFC file does), so it holds "
        "only part of the model; copy or export it again"
    )


def _check_references(log: str, fname: str) -> None:
    """ObjImportError if the parser found references to entities missing from the file
    (``#12 used by #40 ... not found``): a damaged file that would import with elements
    or parts of them silently missing."""
    missing = re.findall(r"Instance reference (#\d+) used by instance (#\d+)", log)
    if not missing:
        return
    shown = ", ".join(f"{a} (used by {b})" for a, b in missing[:LISTED])
    more = ", ..." if len(missing) > LISTED else ""
    raise ObjImportError(
        f"{fname}: {len(missing)} reference(s) to entities that are not in the file "
        f"({shown}{more}); the file is damaged or incomplete, export it again"
    )


def _elements(ifcopenshell, model, fname: str):
    """The building elements with geometry, ordered by their id in the file (windows
    without a body that fill an opening as panes, ``ifc_openings``); the names of the
    spaces; the parts merged into windows (``Part``s); and id -> why of the windows
    without a body that could not be placed."""
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    # Elements are meshed in parallel, leaving a core for the window (on this 2-core
    # machine, two threads took twice as long as one while other work ran).
    threads = max(1, min((os.cpu_count() or 2) - 1, 8))
    it = ifcopenshell.geom.iterator(settings, model, threads, exclude=list(SKIPPED))
    out = []
    for shape in _shapes(it):
        entity = model.by_id(shape.id)
        v = np.asarray(shape.geometry.verts, float).reshape(-1, 3)
        t = np.asarray(shape.geometry.faces, np.int64).reshape(-1, 3)
        if len(t) == 0:
            continue
        # One vertex per position (sections walk shared edges from face to face).
        ids = row_ids(np.round(v / GRID).astype(np.int64))
        welded = np.zeros((ids.max() + 1, 3))
        welded[ids] = v
        v, t = welded, ids[t]
        cls = entity.is_a()
        out.append(
            Element(
                shape.id,
                cls,
                _label(entity),
                v,
                t,
                ceiling=cls == "IfcCovering" and _predefined(entity) == "CEILING",
                roof_host=cls == "IfcWindow" and _in_roof(entity),
            )
        )
    out, parts = _windows_of_parts(model, out)
    seen = {e.id for e in out} | {p.id for p in parts}
    panes, unplaced = bodiless_windows(model, seen, _label, _in_roof)
    out += panes
    if not out:
        raise ObjImportError(
            f"{fname}: no building elements with geometry (walls, slabs, roofs, ...); "
            "export the model with its 3D body representations"
        )
    out.sort(key=lambda e: e.id)
    spaces = sorted((s.Name or s.LongName or s.GlobalId) for s in model.by_type("IfcSpace"))
    return out, spaces, parts, unplaced


def _label(entity) -> str:
    """An entity's Name, else its GlobalId."""
    name = getattr(entity, "Name", None)
    return (name if isinstance(name, str) and name.strip() else entity.GlobalId).strip()


def _windows_of_parts(model, elements: list[Element]) -> tuple[list[Element], list[Part]]:
    """Windows without a body of their own that aggregate parts (IfcMember frames, an
    IfcPlate pane: how IfcOpenShell and many IFC4 exporters write them) as one element
    each, of their parts' triangles; the parts, which are no elements of their own then."""
    by_id = {e.id: e for e in elements}
    parts: list[Part] = []
    merged: list[Element] = []
    for window in model.by_type("IfcWindow"):
        if window.id() in by_id:
            continue
        mine = [
            by_id.pop(p.id())
            for p in _decomposition(window)
            if p.id() in by_id and by_id[p.id()].ifc_class != "IfcWindow"
        ]
        if not mine:
            continue
        offsets = np.cumsum([0] + [len(e.vertices) for e in mine])
        v = np.concatenate([e.vertices for e in mine])
        t = np.concatenate([e.triangles + o for e, o in zip(mine, offsets, strict=False)])
        ids = row_ids(np.round(v / GRID).astype(np.int64))
        welded = np.zeros((ids.max() + 1, 3))
        welded[ids] = v
        name = _label(window)
        merged.append(
            Element(window.id(), "IfcWindow", name, welded, ids[t], roof_host=_in_roof(window))
        )
        parts += [Part(e.id, e.ifc_class, e.name, window.id()) for e in mine]
    return list(by_id.values()) + merged, parts


def _decomposition(entity) -> list:
    """The parts an entity aggregates or nests (IfcRelAggregates; IFC2x3's
    IfcRelDecomposes; IfcRelNests)."""
    out = []
    for attr in ("IsDecomposedBy", "IsNestedBy"):
        for rel in getattr(entity, attr, ()) or ():
            out += list(rel.RelatedObjects)
    return out


def _shapes(it) -> Iterator:
    if not it.initialize():
        return
    while True:
        yield it.get()
        if not it.next():
            break


def _predefined(entity) -> str | None:
    """An element's PredefinedType, or its type object's when it says USERDEFINED or
    NOTDEFINED."""
    own = getattr(entity, "PredefinedType", None)
    if own not in (None, "NOTDEFINED", "USERDEFINED"):
        return own
    for rel in getattr(entity, "IsTypedBy", ()) or ():
        kind = getattr(rel.RelatingType, "PredefinedType", None)
        if kind not in (None, "NOTDEFINED", "USERDEFINED"):
            return kind
    return own


def _in_roof(window) -> bool:
    """Whether a window fills an opening of an IfcRoof or of a slab of type ROOF (or a
    slab that is part of a roof)."""
    for fill in getattr(window, "FillsVoids", ()) or ():
        voids = getattr(fill.RelatingOpeningElement, "VoidsElements", ()) or ()
        for rel in voids:
            host = rel.RelatingBuildingElement
            if host.is_a("IfcRoof") or (host.is_a("IfcSlab") and _predefined(host) == "ROOF"):
                return True
            for agg in getattr(host, "Decomposes", ()) or ():
                if agg.RelatingObject.is_a("IfcRoof"):
                    return True
    return False


# --- zones and faces ----------------------------------------------------------------------


def _zones(planes, elements, shapely, warnings, fname):
    """Zone name -> (the rectangle piece, "roof window" / "wall window" / "ceiling"), its
    piece replaced in its plane by the rectangle; and element index -> why a window or
    ceiling covering with faces left is no zone. Those whose largest face is not a
    rectangle, or whose face towards the room was left out, get a warning."""
    names = _group_names(elements)
    by_element: dict[int, list[tuple[Plane, object]]] = {}
    for p in planes:
        for poly in p.pieces:
            by_element.setdefault(p.element, []).append((p, poly))
    out: dict[str, tuple[object, str]] = {}
    notes: dict[int, str] = {}
    odd, lost = [], []
    for k, e in enumerate(elements):
        if e.ifc_class != "IfcWindow" and not e.ceiling:
            continue
        found = [
            (p, poly) for p, poly in by_element.get(k, []) if not e.ceiling or p.normal[2] < -UPWARD
        ]
        if not found:
            if by_element.get(k):  # faces left, but none that makes the zone
                lost.append(names[k])
                notes[k] = NO_ROOM_FACE
            continue
        plane, poly = max(found, key=lambda f: f[1].area)
        rect = poly.minimum_rotated_rectangle
        if poly.area < RECTANGLE * rect.area:
            odd.append(names[k])
            notes[k] = NOT_RECTANGLE
            continue
        plane.pieces = [q for q in plane.pieces if q is not poly] + [rect]
        if e.ceiling:
            kind = "ceiling"
        elif e.roof_host or abs(plane.normal[2]) > UPWARD:
            kind = "roof window"
        else:
            kind = "wall window"
        out[names[k]] = (rect, kind)
    if odd:
        warnings.append(
            f"{fname}: {len(odd)} window(s) or ceiling(s) ({_shown(odd)}) have no rectangular "
            "face towards the room, so they are plain surfaces and not emitter zones; draw "
            "zones on them in the window or split them in the model"
        )
    if lost:
        warnings.append(
            f"{fname}: {len(lost)} window(s) or ceiling(s) ({_shown(lost)}) are no emitter "
            "zones: their face towards the room was left out (it looks out of the building "
            "or lies against another element), so only their other faces are kept; see the "
            "import report"
        )
    return out, notes


NOT_RECTANGLE = "not a zone: no rectangular face towards the room"
NO_ROOM_FACE = (
    "not a zone: its face towards the room was left out (it looks out of the building or "
    "lies against another element); only its other faces are kept"
)


def _shown(names: list[str]) -> str:
    return ", ".join(clip(n) for n in names[:LISTED]) + (", ..." if len(names) > LISTED else "")


def _group_names(elements: list[Element]) -> list[str]:
    """``CLASS:NAME`` per element; windows and ceilings (which become zones) sharing one
    get their file id appended (``IfcWindow:W #212``)."""
    base = [f"{e.ifc_class}:{e.name}" for e in elements]
    zoned = [e.ifc_class == "IfcWindow" or e.ceiling for e in elements]
    seen: dict[str, int] = {}
    for b, z in zip(base, zoned, strict=True):
        if z:
            seen[b] = seen.get(b, 0) + 1
    return [
        f"{b} #{e.id}" if z and seen[b] > 1 else b
        for b, z, e in zip(base, zoned, elements, strict=True)
    ]


def _faces(planes, elements, zones, scale, up, path: Path):
    """The kept pieces as polygon faces (holes cut into strips)."""
    import shapely

    fname = path.name
    names = _group_names(elements)
    zone_of = {id(rect): name for name, (rect, _) in zones.items()}
    # A window in a wall is a window (glazing) zone; one in a roof a skylight zone.
    kinds = {"ceiling": "luminaire", "wall window": "window"}
    vertices, faces, starts, labels = [], [], [], []
    count = nv = 0
    for p in planes:
        e = elements[p.element]
        group = names[p.element]
        for poly in p.pieces:
            zname = zone_of.get(id(poly))
            if zname is not None:
                label = f"zone:{zname}:{kinds.get(zones[zname][1], 'skylight')}"
                parts = [poly]
            else:
                label = group
                parts = rectangles(poly, shapely)
            for part in parts:
                ring = np.array(shapely.orient_polygons(part).exterior.coords)[:-1]
                xyz = p.offset * p.normal + ring[:, :1] * p.u + ring[:, 1:2] * p.v
                vertices.append(xyz)
                count += 1
                starts.append(count)
                labels.append(f"{e.ifc_class} {clip(e.name)}")
                faces.append(Face(tuple(range(nv, nv + len(xyz))), count, label, p.role))
                nv += len(xyz)
    if not faces:
        raise ObjImportError(
            f"{fname}: no faces look into the building (all face outside or lie where "
            "elements touch); check that the model has closed rooms"
        )
    v = z_up(np.concatenate(vertices) * scale, up)
    if not np.all(np.abs(v) <= MAX_COORD):
        raise ObjImportError(
            f"{fname}: a coordinate is larger than {MAX_COORD:g} m after scaling by "
            f"{scale:g}; check the scale"
        )
    places = FacePlaces(path, starts, labels, "IFC role", noun="face")
    return Polygons(v, faces), places, count


def _role(e: Element, n: np.ndarray) -> str:
    if e.ifc_class == "IfcWindow":
        return "glazing"
    if e.ifc_class in FURNITURE:
        return "furniture"
    return "floor" if n[2] > UPWARD else "ceiling" if n[2] < -UPWARD else "wall"
