"""Triangle meshes read through trimesh (glTF, PLY) to the neutral ``Polygons``.

A reader (``gltf``, ``ply``) decodes its file into a ``Model``: parts of triangles in
model units with their lighting group and material, and the materials' colours as
reflectance guesses. ``import_mesh`` checks the options and the file, turns the parts
into polygons (coplanar triangles joined back, ``facets``) and hands them to
``assembly``, so meshing, size checks, duplicate checks and ``zone:NAME:KIND`` emitter
zones work as for OBJ files.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.facets import join_coplanar
from lightinv_core.scene.importers.assembly import assemble_scene, check_options
from lightinv_core.scene.importers.faces import MAX_COORD, Face, FacePlaces, Polygons
from lightinv_core.scene.importers.files import check_file
from lightinv_core.scene.importers.geometry import z_up
from lightinv_core.scene.importers.materials import load_materials
from lightinv_core.scene.importers.report import ImportItem
from lightinv_core.scene.model import Scene


@dataclass
class Part:
    """Triangles of one glTF node primitive (or a PLY colour): world coordinates in model
    units, the lighting group, the material name (None: no material) and where it came from."""

    vertices: np.ndarray
    triangles: np.ndarray
    group: str
    material: str | None
    label: str  # "node 'Wall'" in messages


@dataclass
class Model:
    """What a reader found: parts, material colours as reflectance guesses, warnings."""

    parts: list[Part]
    colours: dict[str, float] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    colour_source: str = "glTF baseColor"
    left: list[ImportItem] = field(default_factory=list)  # what the reader left out


def import_mesh(
    path: str | os.PathLike,
    fmt: str,
    suffixes: tuple[str, ...],
    read: Callable[[Path], Model],
    item_kind: str,
    materials=None,
    resolution: float = 0.25,
    scale: float = 1.0,
    up: str = "z",
    skip_degenerate: bool = False,
    name: str | None = None,
) -> Scene:
    """The Scene of the mesh file ``path`` of format ``fmt`` ("glTF", "PLY"), whose
    names end in one of ``suffixes``: options checked, ``read(path)`` decodes it (size
    check included), ``item_kind`` names its lighting groups in the import report.
    The other parameters are ``load_gltf``'s. Raises ObjImportError."""
    path, res, scale = check_options(path, resolution, scale, up, fmt)
    if path.suffix.lower() not in suffixes:
        raise ObjImportError(
            f"{path.name}: not a {fmt} file (the name must end in {' or '.join(suffixes)})"
        )
    mats = load_materials(materials)
    check_file(path, f"{fmt} file")
    model = read(path)
    data, places = mesh_polygons(model, path, scale, up)
    places.item_kind = item_kind
    return assemble_scene(
        data, places, mats, model.colours, res, scale, skip_degenerate, name, tuple(model.left)
    )


def srgb_to_linear(c: np.ndarray) -> np.ndarray:
    """sRGB-encoded values in [0, 1] to linear light (IEC 61966-2-1)."""
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def short(exc: Exception, n: int = 80) -> str:
    text = " ".join(str(exc).split()) or "no details"
    return text if len(text) <= n else text[:n] + "..."


def mesh_polygons(model: Model, path: Path, scale: float, up: str) -> tuple[Polygons, FacePlaces]:
    """The parts as polygon faces: coordinates in metres, z up; coplanar
    triangles of one group and material joined into polygons."""
    fname = path.name
    verts, tris, keys, starts, labels = [], [], [], [], []
    offset = count = 0
    kinds: dict[tuple[str, str | None], int] = {}
    for part in model.parts:
        v = z_up(part.vertices * scale, up)
        big = ~(np.abs(v) <= MAX_COORD).all(axis=1)
        if big.any():
            what = "not finite" if not np.all(np.isfinite(v)) else f"larger than {MAX_COORD:g} m"
            raise ObjImportError(
                f"{fname}: {part.label} has a coordinate that is {what} after scaling by "
                f"{scale:g}; check the model's units and the scale"
            )
        verts.append(v)
        tris.append(part.triangles + offset)
        keys.append(
            np.full(len(part.triangles), kinds.setdefault((part.group, part.material), len(kinds)))
        )
        starts.append(count + 1)
        labels.append(part.label)
        offset += len(v)
        count += len(part.triangles)
    tri = np.concatenate(tris)
    key = np.concatenate(keys)
    facets = join_coplanar(np.concatenate(verts), tri, key)
    part_of = np.repeat(np.arange(len(model.parts)), [len(p.triangles) for p in model.parts])
    faces = []
    joined = sorted(
        [
            (int(f), tuple(int(i) for i in poly))
            for f, poly in zip(facets.first, facets.polygons, strict=True)
        ]
        + [(int(f), tuple(int(i) for i in facets.triangles[f])) for f in facets.left]
    )
    for first, index in joined:
        part = model.parts[part_of[first]]
        faces.append(Face(index, first + 1, part.group, part.material))
    data = Polygons(facets.vertices, faces, list(model.warnings))
    return data, FacePlaces(path, starts, labels, model.colour_source)
