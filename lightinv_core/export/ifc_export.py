"""IFC export of a design (ifcopenshell, the optional ``ifc`` extra, imported here
only): the luminaires, the designed glazing and the work planes' results back into the
building model (docs/export.md).

When the project's scene is an imported IFC file, the design is added to a copy of it
(written to the new path; the original is never touched), in the file's own length
unit and spatial structure. Otherwise a new IFC4 file holds the scene: one
``IfcBuildingElementProxy`` per lighting group with its patches as an
``IfcPolygonalFaceSet``, in a site, building and storey.

- every luminaire (of the arrays, where the light model places them, and every
  rectangular luminaire source) is an ``IfcLightFixture`` placed with its local z
  against its aim (gamma 0 along local -z) and C0 along local x, typed by one
  ``IfcLightFixtureType`` per product: its name, ``Pset_LightFixtureTypeCommon``
  (TotalWattage), an ``IfcDocumentReference`` to its IES/LDT file and, for a type C
  table, an ``IfcLightSourceGoniometric`` (rated flux, the table as an
  ``IfcLightIntensityDistribution`` in cd per lm) in its 'Lighting' representation;
  its designed flux, power and dimming are in ``LightInv_Luminaire``;
- every designed skylight or window is an ``IfcOpeningElement`` in its host with an
  ``IfcWindow`` filling it (``LightInv_Glazing``: its transmittance and filter);
- every work plane is an ``IfcAnnotation`` at its height with ``LightInv_WorkPlane``:
  Em, Emin, Emax, U0, the standard and edition, the requirements.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.export.design import ExportDesign, ExportedFile, Fixture, Panel
from lightinv_core.export.ifc_writer import IfcWriter, libraries

SUFFIXES = (".ifc",)
OPENING_DEPTH = 0.3  # m: the opening's solid reaches this far across its surface
PANE = 0.01  # m: the window's pane thickness
SURFACE_THICKNESS = 0.05  # m: a new file's surfaces are solids this thick behind them
COLOUR_TEMPERATURE = 4000.0  # K: the goniometric source's (the tables carry none)
GLAZING_ZONE = re.compile(r"^(Ifc\w+):(.*?)(?: #(\d+))?$")


def _slabs(patches, idx: np.ndarray) -> tuple[np.ndarray, list[list[int]]]:
    """The patches ``idx`` as closed thin solids (``SURFACE_THICKNESS`` m behind each
    patch, away from the room): vertices (v, 3) and faces (1-based, outward)."""
    verts, faces = [], []
    for i in idx:
        o, e1, e2, n = patches.origin[i], patches.edge1[i], patches.edge2[i], patches.normal[i]
        ring = [o, o + e1, o + e2] if patches.is_triangle[i] else [o, o + e1, o + e1 + e2, o + e2]
        if np.dot(np.cross(e1, e2), n) < 0:
            ring = ring[::-1]  # counter-clockwise seen from the room
        k, b = len(verts) + 1, len(ring)
        verts += ring + [p - SURFACE_THICKNESS * n for p in ring]
        faces.append([k + j for j in range(b)])  # the patch, facing the room
        faces.append([k + b + j for j in reversed(range(b))])  # its back
        for j in range(b):  # the sides
            j1 = (j + 1) % b
            faces.append([k + j, k + b + j, k + b + j1, k + j1])
    return np.array(verts), faces


def _group_proxies(w: IfcWriter) -> dict[int, object]:
    """One proxy per lighting group of a new file: its patches as thin closed solids
    (an IFC importer, LightInv's too, reads building elements as solids)."""
    patches, f, out = w.ex.patches, w.f, {}
    for g, name in enumerate(patches.group_names):
        idx = np.flatnonzero(patches.group_id == g)
        if not len(idx):
            continue
        v, faces = _slabs(patches, idx)
        coords = f.createIfcCartesianPointList3D([[float(c) for c in p] for p in v])
        body = f.createIfcPolygonalFaceSet(
            coords, True, [f.createIfcIndexedPolygonalFace(face) for face in faces], None
        )
        rho = float(patches.rho[idx].mean())
        proxy = w.entity(
            "IfcBuildingElementProxy", name, ObjectPlacement=w.placement(),
            Representation=w.shape(w.body, "Body", "Tessellation", [body]),
        )  # fmt: skip
        w.pset(proxy, "LightInv_Surface", {"Reflectance": rho, "Patches": len(idx)})
        out[g] = proxy
    return out


def _distribution(w: IfcWriter, fx: Fixture):
    """The type C table in cd per lm of rated flux, angles in the file's unit."""
    ph, f = fx.photometry, w.f
    per_lm = 1.0 / max(fx.rated_lumens, 1e-12)
    gam = [float(np.radians(g) / w.angle) for g in ph.gamma_angles]
    data = [
        f.createIfcLightDistributionData(
            float(np.radians(c) / w.angle), gam, [float(v * per_lm) for v in ph.candela[i]]
        )
        for i, c in enumerate(ph.c_angles)
    ]
    return f.createIfcLightIntensityDistribution("TYPE_C", data)


def _fixture_type(w: IfcWriter, fx: Fixture | None, name: str, watts: float, lumens: float):
    """An ``IfcLightFixtureType`` with its wattage, photometry file and source."""
    f = w.f
    t = w.ifc.api.root.create_entity(f, "IfcLightFixtureType", name=name)
    t.PredefinedType = "DIRECTIONSOURCE" if fx is not None else "NOTDEFINED"
    w.pset(t, "Pset_LightFixtureTypeCommon", {"TotalWattage": float(watts), "NumberOfSources": 1})
    values = {"RatedLuminousFlux": float(lumens), "Distribution": "Lambertian panel"}
    if fx is not None:
        values["Distribution"] = "photometric table"
        if fx.photometry_file:
            values["PhotometryFile"] = Path(fx.photometry_file).name
            ref = w.document(
                Path(fx.photometry_file).as_uri(),
                Path(fx.photometry_file).name,
                f"photometry of {name}"[:255],
            )
            w.relation("IfcRelAssociatesDocument", "photometry", None, [t], ref)
        if fx.photometry.kind == "C":
            source = f.createIfcLightSourceGoniometric(
                name, f.createIfcColourRgb(None, 1.0, 1.0, 1.0), None, None,
                w.axes([0.0, 0.0, 0.0], None, None), None, COLOUR_TEMPERATURE,
                float(lumens), "NOTDEFINED", _distribution(w, fx),
            )  # fmt: skip
            rep = f.createIfcShapeRepresentation(w.lighting, "Lighting", "LightSource", [source])
            t.RepresentationMaps = [
                f.createIfcRepresentationMap(w.axes([0.0, 0.0, 0.0], None, None), rep)
            ]
    w.pset(t, "LightInv_Product", values)
    return t


def _fixtures(w: IfcWriter) -> int:
    """Every luminaire as an ``IfcLightFixture`` (IFC2X3: ``IfcFlowTerminal``) of its
    product's type."""
    api, ex = w.ifc.api, w.ex
    types: dict[str, object] = {}
    count = 0
    for fx in ex.fixtures:
        if fx.product not in types:
            types[fx.product] = _fixture_type(w, fx, fx.product, fx.rated_watts, fx.rated_lumens)
        e = w.entity(
            w.schema.fixture, fx.name, ObjectPlacement=w.placement(fx.position, -fx.aim, fx.c0)
        )
        api.type.assign_type(w.f, related_objects=[e], relating_type=types[fx.product])
        w.pset(e, "LightInv_Luminaire", {
            "LuminousFlux": fx.lumens, "ElectricPower": fx.watts, "Dimming": fx.dimming,
            "MaintenanceFactor": fx.maintenance, "Array": fx.group, "Product": fx.product,
        })  # fmt: skip
        count += 1
    for p in ex.panels:
        if not p.electric:
            continue
        t = _fixture_type(w, None, f"{p.name} (Lambertian panel)", p.watts, p.lumens)
        edge = p.corners[1] - p.corners[0]
        place = w.placement(p.centre, -p.normal, edge)
        e = w.entity(w.schema.fixture, p.name, ObjectPlacement=place)
        api.type.assign_type(w.f, related_objects=[e], relating_type=t)
        width, length = p.size
        w.pset(e, "LightInv_Luminaire", {
            "LuminousFlux": p.lumens, "ElectricPower": p.watts, "Dimming": 1.0,
            "Product": "Lambertian panel", "Width": width, "Length": length,
        })  # fmt: skip
        count += 1
    return count


def _box(w: IfcWriter, p: Panel, depth: float, offset: float):
    """A solid over panel ``p``'s rectangle, ``depth`` m thick along its normal,
    starting ``offset`` m along it: an extruded rectangle in the panel's frame."""
    f = w.f
    width, length = p.size
    a = (p.corners[1] - p.corners[0]) / max(width, 1e-12)
    corner = p.corners[0] + offset * p.normal
    position = w.axes(w.point(corner), p.normal, a)
    k = 1.0 / (w.unit * w.scale)  # scene metres to file units
    centre = f.createIfcCartesianPoint([width / 2 * k, length / 2 * k])
    profile = f.createIfcRectangleProfileDef(
        "AREA", None, f.createIfcAxis2Placement2D(centre, None), width * k, length * k
    )
    solid = f.createIfcExtrudedAreaSolid(
        profile, position, f.createIfcDirection([0.0, 0.0, 1.0]), depth / w.unit / w.scale
    )
    return w.shape(w.body, "Body", "SweptSolid", [solid])


def _host(w: IfcWriter, p: Panel, proxies: dict[int, object]):
    """The element a glazing panel's opening voids: in a new file the proxy of its
    zone's group; in a copy the wall or roof holding the window its zone was made from;
    else a proxy made for it."""
    patches = w.ex.patches
    zi = patches.zone_names.index(p.zone)
    groups = np.unique(patches.group_id[patches.zone_id == zi])
    if proxies and len(groups):
        return proxies[int(groups[0])]
    m = GLAZING_ZONE.match(p.zone)
    if m is not None:
        cls, label, eid = m.groups()
        found = (
            [w.f.by_id(int(eid))]
            if eid
            else [e for e in w.f.by_type(cls) if (e.Name or e.GlobalId) == label]
        )
        for e in found:
            for fill in getattr(e, "FillsVoids", ()) or ():
                for rel in fill.RelatingOpeningElement.VoidsElements or ():
                    return rel.RelatingBuildingElement
    near = _opening_host(w, p)
    if near is not None:
        return near
    return w.entity(
        "IfcBuildingElementProxy", f"{p.zone} (glazing host)", ObjectPlacement=w.placement()
    )


def _opening_host(w: IfcWriter, p: Panel):
    """The element voided by the model's opening that holds the panel's centre (within
    ``OPENING_DEPTH``), for windows that fill no void of their own (IfcOpenHouse)."""
    import ifcopenshell.geom

    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    centre = np.array(w.point(p.centre)) * w.unit  # metres, world
    pad = OPENING_DEPTH
    for o in w.f.by_type("IfcOpeningElement"):
        voids = o.VoidsElements
        if not voids:
            continue
        try:
            shape = ifcopenshell.geom.create_shape(settings, o)
        except RuntimeError:  # an opening ifcopenshell cannot mesh: not this one
            continue
        v = np.asarray(shape.geometry.verts, float).reshape(-1, 3)
        if (
            len(v)
            and np.all(centre >= v.min(axis=0) - pad)
            and np.all(centre <= v.max(axis=0) + pad)
        ):
            return voids[0].RelatingBuildingElement
    return None


def _glazing(w: IfcWriter, proxies: dict[int, object]) -> int:
    """Every designed skylight or window: an opening in its host filled by a window."""
    count = 0
    for p in w.ex.panels:
        if p.electric:
            continue
        host = _host(w, p, proxies)
        opening = w.entity(
            "IfcOpeningElement", f"{p.name} opening", ObjectPlacement=w.placement(),
            Representation=_box(w, p, OPENING_DEPTH, -OPENING_DEPTH / 2),
            **w.predefined("OPENING"),
        )  # fmt: skip
        w.placed.remove(opening)  # an opening is related through its host, not contained
        w.relation("IfcRelVoidsElement", None, None, host, opening)
        width, length = p.size
        window = w.entity(
            "IfcWindow", p.name, ObjectPlacement=w.placement(),
            Representation=_box(w, p, PANE, -PANE / 2), OverallWidth=width / w.unit / w.scale,
            OverallHeight=length / w.unit / w.scale,
            **w.predefined("SKYLIGHT" if p.kind == "skylight" else "WINDOW"),
        )  # fmt: skip
        w.relation("IfcRelFillsElement", None, None, opening, window)
        w.pset(window, "LightInv_Glazing", {
            "VisibleTransmittance": p.transmittance, "Kind": p.kind, "Diffusing": True,
            "Zone": p.zone,
        })  # fmt: skip
        w.pset(window, "Pset_DoorWindowGlazingType", {"Translucency": p.transmittance})
        count += 1
    return count


def _workplanes(w: IfcWriter) -> int:
    """Every work plane as an annotation at its height with its results."""
    for pl in w.ex.planes:
        centre = pl.points.mean(axis=0)
        a = w.entity(
            "IfcAnnotation", f"work plane {pl.name}", ObjectPlacement=w.placement(centre),
            ObjectType="LightInv work plane",
        )  # fmt: skip
        values = {
            "Height": float(pl.height), "Points": len(pl.points), "Em": pl.em, "Emin": pl.emin,
            "Emax": pl.emax, "U0": pl.u0, "Standard": pl.standard,
            "Scenario": "design", "Maintained": True,
        }  # fmt: skip
        if pl.requirements:
            values["Requirements"] = "; ".join(pl.requirements)
        w.pset(a, "LightInv_WorkPlane", values)
    return len(w.ex.planes)


def write_ifc(ex: ExportDesign, path: str | Path) -> ExportedFile:
    """Write the design ``ex`` as IFC to ``path`` (see the module): into a copy of the
    project's IFC model when it has one, else a new IFC4 file of its scene."""
    ifc = libraries()
    path = Path(path)
    model = ex.model_file if ex.model_file and ex.model_file.suffix.lower() == ".ifc" else None
    if model is not None and path.resolve() == model.resolve():
        raise LightInvError(
            f"{path.name} is the project's own model: export the design to another file "
            "(the original is never overwritten)"
        )
    if model is not None and not model.is_file():
        raise LightInvError(f"the project's model {model} is missing: cannot copy it")
    w = IfcWriter(ifc, ex, model)
    proxies = _group_proxies(w) if model is None else {}
    counts = {"luminaires": _fixtures(w), "glazing": _glazing(w, proxies)}
    counts["workplanes"] = _workplanes(w)
    counts["surfaces"] = len(proxies)
    if w.container is not None and w.placed:
        ifc.api.spatial.assign_container(w.f, products=w.placed, relating_structure=w.container)
    from lightinv_core.atomic import atomic_writer

    with atomic_writer(path, "w", encoding="utf-8") as fh:
        fh.write(w.f.to_string())
    notes = [] if model is None else [f"added to a copy of {model.name}"]
    if not any(fx.photometry_file for fx in ex.fixtures) and ex.fixtures:
        notes.append("the luminaires' photometry is embedded (no file to reference)")
    return ExportedFile(path, (path,), counts, tuple(notes))
