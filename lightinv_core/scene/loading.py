"""One entry point for "a scene the user named": a built-in scene or a model file of
one of the registered import formats (``importers.registry``: OBJ, glTF/GLB, PLY, IFC)."""

from __future__ import annotations

from pathlib import Path

from lightinv_core.errors import SceneError
from lightinv_core.scene.builtin import BUILTIN_SCENES, builtin_scene
from lightinv_core.scene.importers.registry import importer_for, model_suffixes, option_names
from lightinv_core.scene.model import Scene

DEFAULT_OBJ_RESOLUTION = 0.25


def load_scene(
    spec: str,
    resolution: float | None = None,
    materials=None,
    scale: float = 1.0,
    up: str | None = None,
    skip_degenerate: bool = False,
    **options,
) -> Scene:
    """The built-in scene called ``spec``, or the model file at path ``spec``.

    ``resolution`` is the target patch size in metres (None: the scene's default,
    0.25 m for model files); ``materials``, ``scale`` (metres per model unit), ``up``
    ("z" or "y"; None: the format's, ``Importer.up``) and ``skip_degenerate`` are passed
    to the importer of the file's format; ``options`` (``group_by="node"`` or
    ``"material"`` for glTF) to the importers that take them (``Importer.options``), and
    are ignored by the others. IFC files need the optional extra ``lightinv[ifc]``.
    """
    unknown = sorted(set(options) - option_names())
    if unknown:
        raise TypeError(f"load_scene() got an unexpected keyword argument {unknown[0]!r}")
    if spec in BUILTIN_SCENES:
        return builtin_scene(spec, resolution)
    path = Path(spec)
    importer = importer_for(path)
    if importer is None:
        known = ", ".join(BUILTIN_SCENES)
        suffixes = model_suffixes()
        kinds = ", ".join(suffixes[:-1]) + " or " + suffixes[-1] if suffixes[1:] else suffixes[0]
        raise SceneError(
            f"{spec!r} is neither a built-in scene ({known}) nor a model file ({kinds})"
        )
    taken = {k: v for k, v in options.items() if k in importer.options}
    return importer.load(
        path,
        materials=materials,
        resolution=DEFAULT_OBJ_RESOLUTION if resolution is None else resolution,
        scale=scale,
        up=importer.up if up is None else up,
        skip_degenerate=skip_degenerate,
        **taken,
    )
