"""Side windows as daylight zones, by clicks (issue #29, item 8): on an imported OBJ
room, a window (glazing) zone drawn by mouse on the wall seen in Front view, and a whole
wall picked in Select patches mode made a window with the zone panel's button; both
become glazing (the kind whose light is the sky on its own plane: tests/core/
test_wall_glazing.py checks that light). The zone dialog names the surface
for people and gives the zone's size."""

from __future__ import annotations

import pytest
from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from tests.app.conftest import wait_for_operator
from tests.app.test_dialog_buttons import answer, button, click
from tests.app.test_zones_on_imported_room import centre_of, draw_zone, import_room


def test_a_window_drawn_on_a_wall_and_a_wall_picked_become_glazing(
    qtbot, window, monkeypatch, tmp_path
):
    from tests.app.test_main_window import send_mouse, to_qt

    import_room(qtbot, window, monkeypatch, tmp_path)
    d = window.doc
    tools = window.findChild(QtWidgets.QToolBar, "main toolbar")
    QTest.mouseClick(button(tools, "Front view"), QtCore.Qt.LeftButton)
    box = window.zone_kind_box
    assert box.findText("window (glazing) zone") >= 0

    # Front view: the north wall (y = 7 m) seen from inside; a window 3 x 1.2 m on it.
    seen = draw_zone(window, "window (glazing)", (3.0, 7.0, 1.0), (6.0, 7.0, 2.2))
    assert seen["dialog"] == "ZoneDialog" and "left open" not in seen
    assert seen["title"].startswith("New emitter zone on walls, face ")
    assert "~" not in seen["title"] and ".rect" not in seen["title"]
    wait_for_operator(qtbot, window, timeout=120_000)
    (zone,) = d.scene.zones
    assert zone.kind == "window"
    rect = d.scene.surface(zone.surface).rect
    assert rect.normal == pytest.approx((0.0, -1.0, 0.0), abs=1e-9)
    assert centre_of(d, zone.name) == pytest.approx((4.5, 7.0, 1.6), abs=0.15)
    assert sorted(rect.size) == pytest.approx([1.2, 3.0], abs=0.15)
    window.viewport.screenshot("/tmp/lightinv-window-on-north-wall.png")

    # The west wall (x = 0) picked in Select patches mode, made a zone by the panel's
    # button: the dialog offers a window first and gives the wall's size.
    QTest.mouseClick(button(tools, "Select"), QtCore.Qt.LeftButton)
    iw = window.viewport.plotter.interactor
    at = to_qt(window.viewport, (0.0, 3.5, 1.5))
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonPress, at)
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, at)
    picked = d.selection
    assert len(picked) == 1
    assert d.patches.normal[picked[0]] == pytest.approx((1.0, 0.0, 0.0), abs=1e-9)
    panel = window.zone_panel
    shown = {}

    def look_then_ok(dialog):
        shown["kind"] = dialog.kind.currentText()
        shown["size"] = dialog.size.text()
        dialog.grab().save("/tmp/lightinv-zone-dialog-west-wall.png")
        click("OK")(dialog)

    seen = answer(
        lambda: QTest.mouseClick(button(panel, "Make picked face a zone..."), QtCore.Qt.LeftButton),
        look_then_ok,
    )
    assert seen["dialog"] == "ZoneDialog" and "left open" not in seen
    assert shown == {"kind": "Window (glazing)", "size": "7.00 x 3.00 m (21.00 m²)"}
    wait_for_operator(qtbot, window, timeout=120_000)
    kinds = {z.name: z.kind for z in d.scene.zones}
    assert sorted(kinds.values()) == ["window", "window"]
    west = next(z for z in d.scene.zones if z.name != zone.name)
    assert d.scene.surface(west.surface).rect.normal == pytest.approx((1.0, 0.0, 0.0))
    assert d.scene.surface(west.surface).area == pytest.approx(21.0)
    # The panel lists the zones by readable surface names.
    items = [panel.zone.itemText(i) for i in range(panel.zone.count())]
    assert all(", face " in t and "~" not in t for t in items), items
    panel.grab().save("/tmp/lightinv-zone-panel-windows.png")

    window.viewport.screenshot("/tmp/lightinv-two-windows.png")
