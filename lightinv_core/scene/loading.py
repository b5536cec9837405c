"""One entry point for "a scene the user named": a built-in scene or a model file
(OBJ, glTF/GLB, PLY or IFC)."""

from __future__ import annotations

from pathlib import Path

from lightinv_core.errors import SceneError
from lightinv_core.scene.builtin import BUILTIN_SCENES, builtin_scene
from lightinv_core.scene.model import Scene

DEFAULT_OBJ_RESOLUTION = 0.25
MODEL_SUFFIXES = (".obj", ".gltf", ".glb", ".ply", ".ifc")
"""The model files a scene can be imported from (docs/obj-import.md)."""


def is_model_file(path: str | Path) -> bool:
    """Whether ``path`` names a model file LightInv imports (by its suffix)."""
    return Path(path).suffix.lower() in MODEL_SUFFIXES


def default_up(path: str | Path) -> str:
    """A model's up axis by its format's convention: "y" for glTF (its specification),
    "z" for OBJ, PLY and IFC."""
    return "y" if Path(path).suffix.lower() in (".gltf", ".glb") else "z"


def load_scene(
    spec: str,
    resolution: float | None = None,
    materials=None,
    scale: float = 1.0,
    up: str | None = None,
    skip_degenerate: bool = False,
    group_by: str = "node",
) -> Scene:
    """The built-in scene called ``spec``, or the model file at path ``spec``.

    ``resolution`` is the target patch size in metres (None: the scene's default,
    0.25 m for model files); ``materials``, ``scale`` (metres per model unit), ``up``
    ("z" or "y"; None: the format's, ``default_up``) and ``skip_degenerate`` are passed
    to the importer of the file's format, ``group_by`` ("node" or "material") to the
    glTF one. IFC files need the optional extra ``lightinv[ifc]``.
    """
    if spec in BUILTIN_SCENES:
        return builtin_scene(spec, resolution)
    path = Path(spec)
    suffix = path.suffix.lower()
    if suffix not in MODEL_SUFFIXES:
        known = ", ".join(BUILTIN_SCENES)
        kinds = ", ".join(MODEL_SUFFIXES[:-1]) + " or " + MODEL_SUFFIXES[-1]
        raise SceneError(
            f"{spec!r} is neither a built-in scene ({known}) nor a model file ({kinds})"
        )
    res = DEFAULT_OBJ_RESOLUTION if resolution is None else resolution
    up = default_up(path) if up is None else up
    options = dict(materials=materials, resolution=res, scale=scale, up=up)
    if suffix == ".obj":
        from lightinv_core.scene.obj_import import load_obj

        return load_obj(path, skip_degenerate=skip_degenerate, **options)
    if suffix == ".ifc":
        from lightinv_core.scene.ifc_import import load_ifc

        return load_ifc(path, skip_degenerate=skip_degenerate, **options)
    from lightinv_core.scene.mesh_import import load_mesh

    return load_mesh(path, skip_degenerate=skip_degenerate, group_by=group_by, **options)
