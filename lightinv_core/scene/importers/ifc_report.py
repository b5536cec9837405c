"""The import report of an IFC file (used by ``ifc_import``): what became of each
element, from the areas its faces keep through the import's steps.

Every product of the file is accounted for: the elements ifcopenshell meshed (a lighting
group, an emitter zone, or dropped with the step that removed their last face), the
parts merged into their window, and the products that were never meshed (classes that
are no surfaces, products without a body). Containers whose parts are imported (a roof
of slabs, a stair of flights) are left to their parts.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.scene.importers.faces import LISTED, clip
from lightinv_core.scene.importers.ifc_geometry import MIN_PIECE, Element, Failure, Part
from lightinv_core.scene.importers.report import EXPECTED, ImportItem, ImportReport

SKIPPED_REASONS = {
    "IfcSpace": "not a surface: a space is the room's air",
    "IfcOpeningElement": "not a surface: a void, already cut from its wall or slab",
    "IfcSite": "not a surface of the building: the terrain around it",
    "IfcAnnotation": "not a surface: an annotation",
    "IfcGrid": "not a surface: a grid of axes",
    "IfcVirtualElement": "not a surface: a virtual boundary",
}
"""Classes the import leaves out, and why."""
CONTAINERS = ("IfcSpatialStructureElement", "IfcSpatialElement", "IfcPort")
"""Products that are no building elements (building, storey, ports): not reported."""
NO_FACES = "its body has no faces of measurable area"
TOUCHING = "every face of it lies against or inside other elements"
OUTSIDE = (
    "every face of it looks out of the building (rays from them escape the model or "
    "start inside another element)"
)
NO_BODY = "no geometry: it has no body representation in the file"
NOT_MESHED = "no geometry: ifcopenshell could not make a body of its representation"


class Stages:
    """The area (m²) of each element's faces after each step of the import."""

    def __init__(self, n: int):
        self.n = n
        self.area: dict[str, np.ndarray] = {}

    def record(self, stage: str, planes) -> None:
        """Areas of the planes' outlines now (``"faces"``, ``"cut"``)."""
        a = np.zeros(self.n)
        for p in planes:
            a[p.element] += p.shape.area
        self.area[stage] = a

    def record_pieces(self, planes) -> None:
        """Areas of the pieces kept after the inside/outside test (``"kept"``)."""
        a = np.zeros(self.n)
        for p in planes:
            for poly in p.pieces:
                a[p.element] += poly.area
        self.area["kept"] = a

    def why_dropped(self, k: int) -> str:
        if self.area["faces"][k] < MIN_PIECE:
            return NO_FACES
        return TOUCHING if self.area["cut"][k] < MIN_PIECE else OUTSIDE


def ifc_report(
    fname: str,
    model,
    elements: list[Element],
    names: list[str],
    stages: Stages,
    zones: dict,
    notes: dict[int, str],
    parts: list[Part],
    failed: list[Failure],
    warnings: list[str],
    unplaced: dict[int, str] | None = None,
) -> ImportReport:
    """The report of the import; warnings added for windows and ceilings that were left
    out entirely, windows without a body that could not be placed (``unplaced``: id ->
    why) and cuts shapely could not make."""
    unplaced = unplaced or {}
    items = []
    lost = []
    for k, e in enumerate(elements):
        kept = float(stages.area["kept"][k])
        label = f"{e.name} #{e.id}"
        if kept <= 0:
            items.append(ImportItem(e.ifc_class, label, "dropped", None, stages.why_dropped(k)))
            if e.ifc_class == "IfcWindow" or e.ceiling:
                lost.append(names[k])
        elif names[k] in zones:
            items.append(ImportItem(e.ifc_class, label, "zone", names[k], "", kept))
        else:
            items.append(ImportItem(e.ifc_class, label, "group", names[k], notes.get(k, ""), kept))
    group_of = {e.id: names[k] for k, e in enumerate(elements)}
    for part in parts:
        window = group_of[part.window]
        why = "a part of its window: the window's frames and pane make its surfaces"
        items.append(ImportItem(part.ifc_class, f"{part.name} #{part.id}", "kept", window, why))
    seen = set(group_of) | {part.id for part in parts}
    skipped_windows = []
    for product, item in _not_meshed(model, seen, unplaced):
        items.append(item)
        if product.id() in unplaced:
            skipped_windows.append(f"IfcWindow:{_name(product)}")
        elif item.kind == "IfcWindow" and not item.reason.startswith(EXPECTED):
            lost.append(f"IfcWindow:{_name(product)}")
    if skipped_windows:
        warnings.append(
            f"{fname}: {len(skipped_windows)} window(s) without a body "
            f"({_shown(skipped_windows)}) were skipped: nothing gives where their glass is "
            "(no opening filled, or no OverallWidth and OverallHeight); draw window zones "
            "on their walls instead; see the import report"
        )
    if lost:
        warnings.append(
            f"{fname}: {len(lost)} window(s) or ceiling(s) ({_shown(lost)}) were left out "
            "entirely: every face of them looks out of the building or lies against another "
            "element (a model without floor slabs or roofs leaves its rooms open); see the "
            "import report"
        )
    skipped = _failures(fname, names, failed, warnings)
    return ImportReport(fname, tuple(items), tuple(skipped))


def _failures(fname, names, failed: list[Failure], warnings: list[str]) -> list[str]:
    """One line per pair of elements whose cut was skipped, and a warning."""
    pairs = {}
    for f in failed:
        pairs.setdefault((f.element, f.other), f)
    lines = [
        f"{names[a]}: the cut where {names[b]} meets it was skipped (shapely: "
        f"{f.message}); that part of its faces is kept uncut"
        for (a, b), f in pairs.items()
    ]
    if pairs:
        shown = _shown([names[a] for a, _ in pairs])
        warnings.append(
            f"{fname}: {len(pairs)} cut(s) where elements meet could not be made ({shown}); "
            "those faces are kept uncut, so parts of them may lie inside other elements; "
            "see the import report"
        )
    return lines


def _not_meshed(model, seen: set[int], unplaced: dict) -> list[tuple[object, ImportItem]]:
    """Products that are no element of the import, each with its item: left out by
    class, or without a body (``unplaced``: id -> why, for the windows that could not
    be placed; containers whose parts are imported are left to their parts)."""
    out = []
    for product in model.by_type("IfcProduct"):
        if product.id() in seen:
            continue
        label = f"{_name(product)} #{product.id()}"
        skipped = [why for cls, why in SKIPPED_REASONS.items() if _is_any(product, (cls,))]
        if skipped:
            out.append((product, ImportItem(product.is_a(), label, "dropped", None, skipped[0])))
            continue
        if _is_any(product, CONTAINERS):
            continue
        if _has_parts(product):
            continue
        why = NO_BODY if getattr(product, "Representation", None) is None else NOT_MESHED
        why = unplaced.get(product.id(), why)
        out.append((product, ImportItem(product.is_a(), label, "dropped", None, why)))
    return out


def _is_any(entity, classes) -> bool:
    for cls in classes:
        try:
            if entity.is_a(cls):
                return True
        except (RuntimeError, ValueError):  # a class the file's schema does not have
            continue
    return False


def _has_parts(entity) -> bool:
    return any(
        rel.RelatedObjects
        for attr in ("IsDecomposedBy", "IsNestedBy")
        for rel in getattr(entity, attr, ()) or ()
    )


def _name(entity) -> str:
    name = getattr(entity, "Name", None)
    return (name if isinstance(name, str) and name.strip() else entity.GlobalId).strip()


def _shown(names: list[str]) -> str:
    return ", ".join(clip(n) for n in names[:LISTED]) + (", ..." if len(names) > LISTED else "")
