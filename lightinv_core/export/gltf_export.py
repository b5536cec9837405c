"""glTF binary (.glb) export of the lit scene: every patch coloured by its illuminance
in the design scenario, for a browser or a BIM viewer (docs/export.md).

One mesh per lighting group (its name the node's), every patch its own triangles with
the patch's colour on its vertices (``COLOR_0``), so the colours are the patches'
values, not a blend. The colour scale is matplotlib's ``inferno`` from 0 lux to
``lux_max`` (by default the largest illuminance on a patch), written with the unit in
the file's ``asset.extras.lightinv``. glTF is y-up with metres: LightInv's (x, y, z)
is written as (x, z, -y), a rotation, so faces keep their front side and the file
imports back with LightInv's glTF importer (up "y") in the scene's own axes.
trimesh (a dependency, MIT) writes the file.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.export.design import ExportDesign, ExportedFile, patch_triangles

SUFFIXES = (".glb",)
COLORMAP = "inferno"


def lux_colours(lux: np.ndarray, lux_max: float) -> np.ndarray:
    """(n, 4) uint8 RGBA of illuminances ``lux`` (n,) on the ``COLORMAP`` scale from
    0 to ``lux_max`` lux (values above it get the top colour)."""
    from matplotlib import colormaps

    t = np.clip(np.asarray(lux, float) / max(float(lux_max), 1e-12), 0.0, 1.0)
    return np.round(colormaps[COLORMAP](t) * 255).astype(np.uint8)


def write_gltf(ex: ExportDesign, path: str | Path, *, lux_max: float | None = None) -> ExportedFile:
    """Write the lit scene of ``ex`` as a .glb file ``path`` (see the module)."""
    import trimesh

    path = Path(path)
    patches, lux = ex.patches, ex.illuminance
    top = float(lux.max()) if lux_max is None else float(lux_max)
    if not np.isfinite(top) or top <= 0:
        raise LightInvError("the design lights no patch: nothing to colour in the glTF file")
    colours = lux_colours(lux, top)
    scene = trimesh.Scene()
    turn = np.array([[1.0, 0, 0], [0, 0, 1.0], [0, -1.0, 0]])  # (x, y, z) -> (x, z, -y)
    for g, name in enumerate(patches.group_names):
        idx = np.flatnonzero(patches.group_id == g)
        if not len(idx):
            continue
        v, f, _owner = patch_triangles(patches, idx)
        vc = np.repeat(colours[idx], 4, axis=0)
        mesh = trimesh.Trimesh(v @ turn.T, f, vertex_colors=vc, process=False)
        scene.add_geometry(mesh, node_name=name, geom_name=name)
    extras = {
        "lightinv": {
            "project": ex.name,
            "solution": ex.label,
            "quantity": "illuminance, design scenario",
            "unit": "lux",
            "colormap": COLORMAP,
            "scale": [0.0, top],
            "up": "y (LightInv's z)",
        }
    }

    def add_extras(tree: dict) -> None:
        tree.setdefault("asset", {})["extras"] = extras

    data = trimesh.exchange.gltf.export_glb(
        scene, include_normals=False, tree_postprocessor=add_extras
    )
    from lightinv_core.atomic import atomic_writer

    with atomic_writer(path, "wb") as fh:
        fh.write(data)
    counts = {"patches": int(patches.n), "groups": len(scene.geometry)}
    notes = (f"colours: {COLORMAP} from 0 to {top:.0f} lux",)
    return ExportedFile(path, (path,), counts, notes)
