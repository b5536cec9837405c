"""Found in the first-day walkthrough (docs/walkthrough-first-day.md) on an IFC house:
Add work plane… proposed the model's first group as the floor, a spiral stair
(``IfcStair:Wendeltreppe``), so OK gave a work plane over the stair. It now proposes the
lowest of the groups with the most upward-facing area (IfcOpenHouse has no floor slab:
its footing's top is the floor, and its first slab is a roof); a built-in scene keeps
its "floor"."""

from __future__ import annotations

import gzip
from pathlib import Path

from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from app.dialogs import ask
from app.dialogs.workplane_dialog import floor_default
from app.widgets.design_tree import DesignTree
from tests.app.conftest import wait_for_operator
from tests.app.test_dialog_buttons import answer, button, menu_action, ok_and_cancel
from tests.app.test_zones_on_imported_room import half_metre_patches

HOUSE = Path(__file__).resolve().parents[1] / "data" / "ifc" / "IfcOpenHouse_IFC4.ifc.gz"


def import_house(qtbot, window, monkeypatch, tmp_path) -> None:
    """File > Import model..., IfcOpenHouse chosen, patch size 0.5 m typed, OK clicked."""
    path = tmp_path / "IfcOpenHouse_IFC4.ifc"
    path.write_bytes(gzip.decompress(HOUSE.read_bytes()))
    monkeypatch.setattr(ask, "open_file", lambda *a, **k: str(path))

    answer(menu_action(window, "File/Import model...").trigger, half_metre_patches)
    wait_for_operator(qtbot, window, timeout=180_000)


def test_add_work_plane_proposes_the_ifc_floor_not_the_first_group(
    qtbot, window, monkeypatch, tmp_path
):
    import_house(qtbot, window, monkeypatch, tmp_path)
    d = window.doc
    groups = list(d.patches.group_names)
    assert groups[0] == "IfcWallStandardCase:South wall"  # the old default
    window.findChild(QtWidgets.QDockWidget, "luminaires").raise_()
    shown = {}

    def look_then_ok(dialog):
        shown["group"] = dialog.group.currentText()
        QTest.mouseClick(button(dialog, "OK"), QtCore.Qt.LeftButton)

    warned = []  # a refused work plane says why in a message box: kept, not shown
    monkeypatch.setattr(ask, "warn", lambda parent, message: warned.append(message))
    add = button(window.luminaires_panel, "Add work plane…")
    ok_and_cancel(answer(lambda: QTest.mouseClick(add, QtCore.Qt.LeftButton), look_then_ok))
    assert warned == [] and shown["group"] == "IfcFooting:Footing", warned
    (wp,) = d.design.workplanes
    assert wp.group == "IfcFooting:Footing"
    # Its grid has points: the Luminaires panel's work-plane table counts them.
    table = window.luminaires_panel.findChildren(QtWidgets.QTableWidget)
    counts = [
        t.item(0, 2).text()
        for t in table
        if t.rowCount()
        and t.horizontalHeaderItem(2)
        and t.horizontalHeaderItem(2).text() == "points"
    ]
    assert counts and int(counts[0]) > 0, counts
    tree = window.findChild(DesignTree)
    assert tree.textElideMode() == QtCore.Qt.ElideMiddle  # "IfcWallS...South wall"


def test_the_default_floor_without_patches_goes_by_name():
    assert floor_default(["ceiling", "floor", "walls"]) == "floor"
    assert floor_default(["Walls", "Ground_Floor", "Roof"]) == "Ground_Floor"
    assert floor_default(["a", "b"]) == "a"
