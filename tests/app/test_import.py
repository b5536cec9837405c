"""File > Import model: glTF/GLB, PLY and IFC through the real window and its dialog."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6 import QtWidgets

from app.dialogs import ask
from app.dialogs.import_dialog import ImportDialog, model_filter
from tests.app.conftest import wait_for_operator
from tests.core.test_mesh_import import Gltf, box_polygons


def down(x0, x1, y0, y1, z=2.5):
    """A rectangle at height z facing down (counter-clockwise seen from below)."""
    return np.array([[x0, y0, z], [x0, y1, z], [x1, y1, z], [x1, y0, z]], float)


def sky_room_glb(path):
    """The 4 x 3 x 2.5 m box in metres (y up, as glTF is) with a 2 x 1 m skylight zone
    in its ceiling (the ceiling is the four rectangles around it)."""
    g = Gltf()
    greys = {"floor": 0.2, "ceiling": 0.8, "walls": 0.5}
    polys = box_polygons()
    polys["ceiling"] = [down(0, 1, 0, 3), down(3, 4, 0, 3), down(1, 3, 0, 1), down(1, 3, 2, 3)]
    for name, faces in polys.items():
        grey = greys[name]
        g.part(name, faces, g.material(name + "-paint", [grey, grey, grey, 1.0]))
    g.part("zone:sky:skylight", [down(1, 3, 1, 2)])
    return g.save(path)


def test_the_file_menu_imports_every_model_format(qtbot, window, monkeypatch):
    assert window.act_import.text() == "&Import model..."
    asked = []
    monkeypatch.setattr(ask, "open_file", lambda parent, title, filt: asked.append(filt) or "")
    window.act_import.trigger()
    assert asked == [model_filter()]
    for pattern in ("*.obj", "*.gltf", "*.glb", "*.ply", "*.ifc"):
        assert pattern in asked[0].split(";;")[0]


def test_importing_a_glb_through_the_window(qtbot, window, tmp_path):
    path = sky_room_glb(tmp_path / "room.glb")
    dialog = ImportDialog(path, window)
    assert dialog.up.currentData() == "y"  # glTF is y-up by its specification
    assert dialog.units.currentText() == "metres"
    assert dialog.size.text() == "4.00 m across"
    # 10 quads as 20 triangles; the test writer gives each triangle its own vertices.
    assert dialog.summary.text() == "60 vertices, 20 triangles"
    assert not dialog.group_by.isHidden()
    dialog.resolution.setValue(0.5)
    dialog.grab().save("/tmp/import-glb-dialog.png")
    dialog.setResult(QtWidgets.QDialog.Accepted)
    assert window.files.import_obj_dialog(dialog)
    wait_for_operator(qtbot, window)
    spec = window.doc.project.scene
    assert (spec.up, spec.group_by, spec.resolution) == ("y", "node", 0.5)
    scene = window.doc.scene
    assert scene.groups == ("floor", "ceiling", "walls", "sky")
    assert [(z.name, z.kind) for z in scene.zones] == [("sky", "skylight")]
    assert window.doc.patches.n == 236  # the box's grid cells, 8 of them the zone's
    assert window.warnings() == []
    window.doc.add_source("sky")
    lux = window.doc.lighting()
    assert lux is not None and lux.max() > 0
    window.grab().save("/tmp/import-glb-window.png")


def test_importing_an_ifc_through_the_window(qtbot, window, tmp_path):
    pytest.importorskip("ifcopenshell")
    from tests.core.test_ifc_import import ifc_room

    path = ifc_room(tmp_path / "office.ifc")
    dialog = ImportDialog(path, window)
    assert not dialog.units.isEnabled()  # IFC files carry their unit
    assert dialog.size.text() == "read from the file"
    assert dialog.up.currentData() == "z"
    assert dialog.group_by.isHidden()
    dialog.resolution.setValue(0.5)
    dialog.grab().save("/tmp/import-ifc-dialog.png")
    dialog.setResult(QtWidgets.QDialog.Accepted)
    assert window.files.import_obj_dialog(dialog)
    wait_for_operator(qtbot, window)
    scene = window.doc.scene
    assert {z.name: z.kind for z in scene.zones} == {
        "IfcWindow:W1": "window",
        "IfcWindow:S1": "skylight",
        "IfcCovering:Panel": "luminaire",
    }
    assert "IfcSlab:Floor" in scene.groups and "IfcWall:South" in scene.groups
    # A closed room: nothing escapes, so no warning reaches the status bar.
    assert window.warnings() == []
    window.doc.add_source("IfcCovering:Panel")
    lux = window.doc.lighting()
    floor = window.doc.patches.group_index("IfcSlab:Floor")
    assert lux is not None and lux[floor].min() > 0
    window.grab().save("/tmp/import-ifc-window.png")


def test_a_ply_preview_counts_its_faces(qtbot, window, tmp_path):
    from tests.core.test_mesh_import import box_ply

    dialog = ImportDialog(box_ply(tmp_path / "room.ply", colours=True), window)
    assert dialog.summary.text() == "24 vertices, 12 triangles"
    assert dialog.up.currentData() == "z" and dialog.size.text() == "4.00 m across"
