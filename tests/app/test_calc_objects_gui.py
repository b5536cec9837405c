"""Calculation objects placed by clicks on an imported OBJ room (Design > Add calculation
object...): cylindrical points with a mean Ez at least 100 lux, an L-shaped task area and
a wall surface, each in the design, its points drawn in the 3D view and listed in the
design tree; one edited from the tree (double click), one deleted (Delete key) and
brought back with Edit > Undo, on a 1366 x 768 window."""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6.QtCore import Qt
from PySide6.QtTest import QTest

from tests.app import user as u
from tests.app.test_zones_on_imported_room import import_room

SHOTS = Path("/tmp/shots-calcobj")


def _type_rows(box, rows: str) -> None:
    """Click into the rows box, select all, and type each line with Return between."""
    u.type_text(box, "")
    for k, line in enumerate(rows.split("\n")):
        if k:
            u.press(box, Qt.Key_Return)
        QTest.keyClicks(box, line)


def _fill(name: str, kind: str, rows: str, mean: str | None = None, height: str | None = None):
    def fill(dialog) -> None:
        u.type_text(u.field(dialog, "Name"), name)
        u.choose(u.field(dialog, "Kind"), kind)
        _type_rows(u.field(dialog, "Rows (one per line)"), rows)
        if height is not None:
            u.type_text(u.field(dialog, "Height above the floor (m)"), height)
        if mean is not None:
            tick = u.field(dialog, "Mean at least (lux)")
            u.press(tick, Qt.Key_Space)  # tick it
            assert tick.isChecked()
            box = dialog.average[1]
            u.type_text(box, mean)
        SHOTS.mkdir(exist_ok=True)
        dialog.grab().save(str(SHOTS / f"dialog-{name}.png"))
        u.ok(dialog)

    return fill


@pytest.mark.slow
def test_calculation_objects_are_placed_edited_and_removed_by_clicks(
    qtbot, window, monkeypatch, tmp_path
):
    window.resize(1366, 768)
    import_room(qtbot, window, monkeypatch, tmp_path)  # the 10 x 7 x 3 m classroom
    add = ("Design", "Add calculation object...")
    faces = _fill("faces", "Cylindrical", "2, 2\n5, 3.5\n8, 5", mean="100")
    assert u.answer(lambda: u.menu(window, *add), faces) == ["Calculation object"]
    area = _fill("desks", "Task area", "1, 1\n6, 1\n6, 3\n3, 3\n3, 6\n1, 6")
    u.answer(lambda: u.menu(window, *add), area)
    wall = _fill("board", "Surface", "9.99, 1, 1\n0, 0, 1.2\n0, 5, 0")
    u.answer(lambda: u.menu(window, *add), wall)
    d = window.doc.design
    assert [c.name for c in d.calc_objects] == ["faces", "desks", "board"]
    cyl = d.calc_objects[0]
    assert cyl.kind == "cylindrical" and cyl.positions == ((2, 2), (5, 3.5), (8, 5))
    assert cyl.height == 1.2  # the seated eye, proposed for cylinders
    (it,) = d.intentions
    assert (it.grid, it.average, it.uniformity) == ("faces", 100.0, None)
    assert d.calc_objects[2].kind == "surface"
    # Listed in the design tree and drawn in the view.
    texts = u.tree_texts(window.tree, "Calculation objects")
    assert texts["faces"].startswith("Cylindrical illuminance points (Ez): 3 points")
    assert texts["board"].endswith("facing towards 180°")
    assert u.wait_for(lambda: "calc_objects" in window.viewport.plotter.actors, 20_000)

    # Edit from the tree: a double click opens the dialog filled; the height changes.
    def taller(dialog) -> None:
        assert u.field(dialog, "Rows (one per line)").toPlainText().startswith("2, 2")
        u.type_text(u.field(dialog, "Height above the floor (m)"), "1.6")
        u.ok(dialog)

    item = u.tree_item(window.tree, "faces")
    where = window.tree.visualItemRect(item).center()
    u.answer(lambda: u.double_click(window.tree.viewport(), where), taller)
    assert window.doc.design.calc_objects[0].height == 1.6
    # Delete from the tree (the Delete key), then Edit > Undo by its keys.
    u.click_tree(window.tree, "desks")
    u.press(window.tree, Qt.Key_Delete)
    assert [c.name for c in window.doc.design.calc_objects] == ["faces", "board"]
    u.menu(window, "Edit", "Undo remove calculation object desks")
    QTest.qWait(200)
    assert [c.name for c in window.doc.design.calc_objects] == ["faces", "desks", "board"]
    QTest.qWait(300)
    u.screenshot(window, SHOTS, "calc-objects-window")
