"""Import a PLY (Stanford polygon) room model as a LightInv scene, through trimesh.

PLY has no unit (``scale`` gives metres per unit) and no up axis (z up by default);
faces are grouped by their colour, which is also the reflectance guess. The rest is
``meshes.import_mesh``. The user guide is docs/obj-import.md.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.importers.faces import clip
from lightinv_core.scene.importers.meshes import Model, Part, import_mesh, short, srgb_to_linear
from lightinv_core.scene.importers.size import ModelCounts, check_counts
from lightinv_core.scene.model import Scene

SUFFIXES = (".ply",)


def load_ply(
    path: str | os.PathLike,
    materials: dict | str | os.PathLike | None = None,
    resolution: float = 0.25,
    scale: float = 1.0,
    up: str = "z",
    skip_degenerate: bool = False,
    name: str | None = None,
) -> Scene:
    """Import the PLY file ``path`` as a Scene (metres, z up).

    Parameters are ``load_gltf``'s (without ``group_by``: faces are grouped by colour).
    Raises ObjImportError for anything wrong with the file, the materials or the options.
    """
    return import_mesh(
        path,
        "PLY",
        SUFFIXES,
        _read,
        "PLY colour",
        materials,
        resolution,
        scale,
        up,
        skip_degenerate,
        name,
    )


def _read(path: Path) -> Model:
    check_counts(ply_counts(path), path.name)
    return read_ply(path)


def ply_counts(path: Path) -> ModelCounts:
    """Vertices and faces a PLY file declares in its header (``element vertex N``,
    ``element face M``); ObjImportError if it has no PLY header."""
    fname = path.name
    with open(path, "rb") as fh:
        head = fh.read(1 << 16)
    if not head.startswith(b"ply"):
        raise ObjImportError(
            f"{fname}: not a PLY file (it does not start with 'ply'); export the model as "
            "Stanford PLY"
        )
    end = head.find(b"end_header")
    if end < 0:
        raise ObjImportError(f"{fname}: the PLY header has no end_header line; export it again")
    counts = {}
    for line in head[:end].decode("latin-1").splitlines():
        words = line.split()
        if len(words) == 3 and words[0] == "element" and words[2].isdigit():
            counts[words[1]] = int(words[2])
    return ModelCounts(counts.get("vertex", 0), counts.get("face", 0), path.stat().st_size)


def read_ply(path: Path) -> Model:
    """Decode a PLY file with trimesh: one Part per face colour (group ``colour #RRGGBB``,
    reflectance guess the colour's linear luminance), or one Part named after the file."""
    import trimesh

    fname = path.name
    try:
        scene = trimesh.load_scene(str(path), file_type="ply", process=False)
    except Exception as exc:  # trimesh raises many kinds on a damaged file
        raise ObjImportError(
            f"{fname}: cannot decode the PLY file ({type(exc).__name__}: {short(exc)}); "
            "export it again"
        ) from None
    geometry = list(scene.geometry.values())
    mesh = geometry[0] if len(geometry) == 1 else None
    faces = getattr(mesh, "faces", None)
    if faces is None or len(faces) == 0:
        raise ObjImportError(
            f"{fname}: no faces found ({len(getattr(mesh, 'vertices', []))} vertices); "
            "export the model as a polygon mesh, not a point cloud"
        )
    v = np.asarray(mesh.vertices, float)
    tri = np.asarray(faces, np.int64)
    _check_vertex_numbers(tri, len(v), path)
    if getattr(mesh.visual, "kind", None) != "face":
        return Model([Part(v, tri, path.stem, None, f"{clip(path.stem)}")], {}, [], "PLY colour")
    rgb = np.asarray(mesh.visual.face_colors)[:, :3]
    colours, which = np.unique(rgb, axis=0, return_inverse=True)
    model = Model([], {}, [], "PLY colour")
    for c, colour in enumerate(colours):
        group = "colour #{:02X}{:02X}{:02X}".format(*colour.tolist())
        model.parts.append(Part(v, tri[which.ravel() == c], group, group, clip(group)))
        lin = srgb_to_linear(colour / 255.0)
        model.colours[group] = float(0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2])
    return model


def _check_vertex_numbers(tri: np.ndarray, nv: int, path: Path) -> None:
    """ObjImportError naming the first face whose vertex numbers are not those of a
    vertex of the file (0 to nv - 1; trimesh passes them through unchecked)."""
    bad = np.flatnonzero(((tri < 0) | (tri >= nv)).any(axis=1))
    if len(bad) == 0:
        return
    k = int(bad[0])
    number = int(tri[k][(tri[k] < 0) | (tri[k] >= nv)][0])
    # trimesh splits polygons into triangles: the triangle is the face when the file
    # declares as many faces as there are triangles.
    declared = ply_counts(path).faces
    where = f"face {k + 1:,}"
    if declared != len(tri):
        where = f"triangle {k + 1:,} (of its faces split)"
    has = f"{nv:,} vertices (numbered 0 to {nv - 1:,})" if nv else "no vertices"
    raise ObjImportError(
        f"{path.name}: {where} names vertex {number:,}, but the file has {has}; the file "
        "is damaged, export it again"
    )
