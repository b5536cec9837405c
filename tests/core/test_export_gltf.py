"""glTF export of the lit scene (lightinv_core/export/gltf_export.py), read back with
trimesh and with LightInv's own glTF importer."""

from __future__ import annotations

import json
import struct

import numpy as np
import pytest
import trimesh

from lightinv_core.export.gltf_export import lux_colours, write_gltf
from lightinv_core.scene.importers.gltf import load_gltf
from tests.export.office import exported


@pytest.fixture(scope="module")
def glb(tmp_path_factory):
    ex = exported()
    return ex, write_gltf(ex, tmp_path_factory.mktemp("gltf") / "office.glb")


def test_geometry_and_colours_read_back(glb):
    """Per group: the same area as its patches; every vertex coloured by its patch's
    illuminance on inferno from 0 to the brightest patch (the darkest and brightest
    patches get the scale's ends)."""
    ex, out = glb
    scene = trimesh.load(out.path, force="scene")
    patches, lux = ex.patches, ex.illuminance
    assert set(scene.geometry) == set(patches.group_names)
    for g, name in enumerate(patches.group_names):
        mesh = scene.geometry[name]
        idx = patches.group_id == g
        assert mesh.area == pytest.approx(patches.area[idx].sum(), rel=1e-6)
        colours = np.unique(mesh.visual.vertex_colors, axis=0)
        want = np.unique(lux_colours(lux[idx], lux.max()), axis=0)
        np.testing.assert_array_equal(colours, want)
    every = np.concatenate([m.visual.vertex_colors for m in scene.geometry.values()])
    ends = lux_colours(np.array([lux.min(), lux.max()]), lux.max())
    assert (every == ends[1]).all(axis=1).any() and (every == ends[0]).all(axis=1).any()


def test_the_scale_is_in_the_file_and_the_axes_come_back(glb):
    """asset.extras.lightinv holds the unit and scale; LightInv's glTF importer (y up)
    reads the room back in the scene's own axes."""
    ex, out = glb
    data = out.path.read_bytes()
    length = struct.unpack("<I", data[12:16])[0]
    tree = json.loads(data[20 : 20 + length])
    meta = tree["asset"]["extras"]["lightinv"]
    assert meta["unit"] == "lux" and meta["scale"] == [0.0, pytest.approx(ex.illuminance.max())]
    back = load_gltf(out.path, resolution=1.0)
    lo = np.min([s.rect.origin if s.rect is not None else s.triangles.reshape(-1, 3).min(0)
                 for s in back.surfaces], axis=0)  # fmt: skip
    np.testing.assert_allclose(lo, ex.patches.origin.min(axis=0), atol=1e-6)
