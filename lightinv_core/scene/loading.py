"""One entry point for "a scene the user named": a built-in scene or an OBJ file."""

from __future__ import annotations

from pathlib import Path

from lightinv_core.errors import SceneError
from lightinv_core.scene.builtin import BUILTIN_SCENES, builtin_scene
from lightinv_core.scene.model import Scene

DEFAULT_OBJ_RESOLUTION = 0.25


def load_scene(
    spec: str,
    resolution: float | None = None,
    materials=None,
    scale: float = 1.0,
    up: str = "z",
    skip_degenerate: bool = False,
) -> Scene:
    """The built-in scene called ``spec``, or the OBJ file at path ``spec``.

    ``resolution`` is the target patch size in metres (None: the scene's default,
    0.25 m for OBJ files); ``materials``, ``scale`` (metres per model unit), ``up``
    ("z" or "y") and ``skip_degenerate`` are passed to the OBJ importer.
    """
    if spec in BUILTIN_SCENES:
        return builtin_scene(spec, resolution)
    path = Path(spec)
    if path.suffix.lower() == ".obj":
        from lightinv_core.scene.obj_import import load_obj

        res = DEFAULT_OBJ_RESOLUTION if resolution is None else resolution
        return load_obj(
            path,
            materials=materials,
            resolution=res,
            scale=scale,
            up=up,
            skip_degenerate=skip_degenerate,
        )
    known = ", ".join(BUILTIN_SCENES)
    raise SceneError(f"{spec!r} is neither a built-in scene ({known}) nor an .obj file")
