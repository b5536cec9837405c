"""The importer registry is a seam: a format registered from this module alone (a toy
'.box' text file, "W D H" in model units, giving a closed box room) is read by
``load_scene``, listed with the model suffixes, checked like every format by the
neutral ``assembly`` and reported in the import report, then unregistered."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from lightinv_core.errors import ObjImportError, SceneError
from lightinv_core.scene.importers.assembly import assemble_scene, check_options
from lightinv_core.scene.importers.faces import Face, Places, Polygons
from lightinv_core.scene.importers.files import read_text
from lightinv_core.scene.importers.materials import load_materials
from lightinv_core.scene.importers.registry import (
    Importer,
    default_up,
    importer_for,
    importers,
    is_model_file,
    model_suffixes,
    register,
    unregister,
)
from lightinv_core.scene.importers.report import report_of
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.patches import mesh_patches

# The box's corners and its six faces, each counter-clockwise seen from inside the room.
CORNERS = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], float)
SIDES = {
    "floor": (0, 1, 3, 2),
    "ceiling": (4, 6, 7, 5),
    "wall": [(0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)],
}


class BoxPlaces(Places):
    what = "box file"
    item_kind = "box side"


def load_box(
    path: str | os.PathLike,
    materials=None,
    resolution: float = 0.25,
    scale: float = 1.0,
    up: str = "z",
    skip_degenerate: bool = False,
    name: str | None = None,
    lit: bool = False,
):
    """A '.box' file: one line "W D H". ``lit``: the ceiling is a luminaire zone."""
    path, res, scale = check_options(path, resolution, scale, up, "box")
    words = read_text(path, "box file").split()
    if len(words) != 3:
        raise ObjImportError(f"{path.name}: expected 'W D H', got {len(words)} numbers")
    size = np.array([float(w) for w in words]) * scale
    faces = []
    for group, rows in SIDES.items():
        for index in rows if isinstance(rows, list) else [rows]:
            if group == "ceiling" and lit:
                group = "zone:ceiling:luminaire"
            faces.append(Face(index, len(faces) + 1, group, None))
    data = Polygons(CORNERS * size, faces)
    mats = load_materials(materials)
    return assemble_scene(data, BoxPlaces(path), mats, {}, res, scale, skip_degenerate, name)


BOX = Importer("box", (".box",), load_box, options=("lit",), label="Toy box")


@pytest.fixture
def box_format():
    register(BOX)
    try:
        yield BOX
    finally:
        unregister("box")


def test_a_format_registered_by_a_test_is_read_by_load_scene(tmp_path, box_format):
    path = tmp_path / "room.box"
    path.write_text("4 3 2.5\n")
    assert importer_for(path) is BOX and importers()[-1] is BOX
    assert ".box" in model_suffixes() and is_model_file("ROOM.BOX")
    assert default_up(path) == "z"
    assert BOX.filter == "Toy box (*.box)"

    scene = load_scene(str(path), resolution=0.5, materials={"groups": {"floor": 0.2}})
    assert scene.area == pytest.approx(2 * (4 * 3 + 4 * 2.5 + 3 * 2.5))
    assert set(scene.groups) == {"floor", "ceiling", "wall"}
    assert not scene.zones
    assert mesh_patches(scene).n > 0
    report = report_of(scene)
    assert report.source == "room.box"
    assert [(i.kind, i.name, i.outcome) for i in report.items] == [
        ("box side", "floor", "group"),
        ("box side", "ceiling", "group"),
        ("box side", "wall", "group"),
    ]
    assert report.items[2].area_m2 == pytest.approx(2 * (4 + 3) * 2.5)
    assert not report.dropped and not report.skipped

    # Its own option reaches it; other formats ignore it.
    lit = load_scene(str(path), resolution=0.5, lit=True, scale=2.0)
    assert [(z.name, z.kind) for z in lit.zones] == [("ceiling", "luminaire")]
    assert [i.outcome for i in report_of(lit).items] == ["group", "zone", "group"]
    assert lit.area == pytest.approx(4 * scene.area)

    # The neutral assembly's checks hold for it as for every format.
    with pytest.raises(ObjImportError, match=r"scale -1 is not a positive number"):
        load_scene(str(path), scale=-1)
    path.write_text("4 0 2.5\n")
    with pytest.raises(ObjImportError, match=r"room\.box: .*degenerate face"):
        load_scene(str(path))


def test_unregistered_the_format_is_gone(tmp_path):
    register(BOX)
    unregister("box")
    path = tmp_path / "room.box"
    path.write_text("4 3 2.5\n")
    assert importer_for(path) is None and ".box" not in model_suffixes()
    with pytest.raises(SceneError, match=r"nor a model file \(\.obj, .* or \.ifc\)"):
        load_scene(str(path))
    with pytest.raises(TypeError, match="'lit'"):
        load_scene(str(path), lit=True)
    assert [i.name for i in importers()] == ["OBJ", "glTF", "PLY", "IFC"]


def test_registration_is_checked(box_format):
    with pytest.raises(ValueError, match="already registered"):
        register(BOX)
    with pytest.raises(ValueError, match=r"\.obj is already read by 'OBJ'"):
        register(Importer("other", (".obj",), load_box))
    with pytest.raises(ValueError, match="suffixes"):
        Importer("bad", ("box",), load_box)
    with pytest.raises(ValueError, match="up must be"):
        Importer("bad", (".bad",), load_box, up="x")
    with pytest.raises(ValueError, match="common option"):
        Importer("bad", (".bad",), load_box, options=("scale",))
    with pytest.raises(ValueError, match="no importer named 'nothing'"):
        unregister("nothing")


def test_builtin_formats_keep_their_conventions():
    assert [(i.name, i.suffixes, i.up, i.options) for i in importers()][:4] == [
        ("OBJ", (".obj",), "z", ()),
        ("glTF", (".gltf", ".glb"), "y", ("group_by",)),
        ("PLY", (".ply",), "z", ()),
        ("IFC", (".ifc",), "z", ()),
    ]
    assert default_up(Path("a.GLB")) == "y" and default_up("a.ifc") == "z"
