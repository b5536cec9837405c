"""Polygons, lighting groups and materials to a Scene, with its import report: the part
every format shares, owned by none (``faces`` is its input, ``surfaces`` its meshing).

``assemble_scene`` checks the faces (degenerate, repeated), meshes each group
(``surfaces.build_groups``), fits the zones, chooses reflectances (``materials``) and
records what became of each group (``report``). ``check_options`` checks the options
every importer takes. The user guide is docs/obj-import.md.
"""

from __future__ import annotations

import math
import numbers
import os
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError, SceneError
from lightinv_core.scene.importers.faces import UP_AXES, Places, Polygons, zone_spec
from lightinv_core.scene.importers.geometry import FaceGeom, face_geometry
from lightinv_core.scene.importers.materials import MaterialMap, Reflectances
from lightinv_core.scene.importers.report import KEY as REPORT_KEY
from lightinv_core.scene.importers.report import ImportItem, ImportReport
from lightinv_core.scene.importers.surfaces import build_groups, surfaces_of
from lightinv_core.scene.model import Scene, check_resolution
from lightinv_core.scene.patches import BIG_SPAN


def assemble_scene(
    data: Polygons,
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
    groups = build_groups(data.vertices, data.faces, geom, keep, rho, places, warnings, res)
    warnings += rho.warnings()
    _scale_warning(data.vertices, scale, fname, warnings)
    report = face_report(data.faces, geom, keep, places, dropped, extra_items)
    report = replace(report, notes=tuple(rho.defaults_used()))
    info = {"source": str(places.path), "warnings": warnings, REPORT_KEY: report.to_dict()}
    try:
        surfaces, zones = surfaces_of(groups)
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


def _scale_warning(vertices: np.ndarray, scale: float, fname: str, warnings: list[str]) -> None:
    span = float(np.ptp(vertices, axis=0).max())
    if span > BIG_SPAN:
        warnings.append(
            f"{fname}: the model is {span:,.0f} m across after scaling by {scale:g}; if it was "
            "drawn in millimetres pass scale=0.001 (centimetres: 0.01)"
        )
