"""Import a Wavefront OBJ room model as a LightInv ``Scene``.

Units: metres (OBJ coordinates times ``scale``), z up. Faces keep their winding:
counter-clockwise seen from the front is the front face, and LightInv lights front
faces only, so a room's faces must face into the room. A face that is a planar
rectangle becomes a grid-meshed rectangle; other faces are triangulated (ear clipping
in their plane) and merged per group and reflectance. A group named ``zone:NAME:KIND``
becomes the emitter zone NAME. The user guide is docs/obj-import.md.

This module reads the file and its MTL libraries; text parsing is in ``obj_parse``, the
size guard in ``obj_size``, and the scene is made by the neutral ``assembly``.
"""

from __future__ import annotations

import os
from pathlib import Path

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.importers.assembly import assemble_scene, check_options
from lightinv_core.scene.importers.faces import Places
from lightinv_core.scene.importers.files import read_text
from lightinv_core.scene.importers.materials import load_materials
from lightinv_core.scene.importers.obj_parse import parse_mtl, parse_obj
from lightinv_core.scene.importers.obj_size import check_obj_size
from lightinv_core.scene.model import Scene

SUFFIXES = (".obj",)


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
    return assemble_scene(data, ObjPlaces(path), mats, kd, res, scale, skip_degenerate, name)


class ObjPlaces(Places):
    """Places in an OBJ file: ``Face.line`` is a line of the file."""

    what = "OBJ file"  # "... do not occur in the OBJ file"
    colour = "MTL Kd"  # where a material's colour comes from
    item_kind = "OBJ group"  # what a lighting group is in the import report
    white = "Kd 1 1 1"
    colour_file = "an MTL file"


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
