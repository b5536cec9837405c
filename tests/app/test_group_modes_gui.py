"""A control group's mode, its own target and its sensor drawn in the view, by clicks at
1366 x 768 (issue #30 items 5-6, docs/daylight.md "Control groups: switching, own
targets, sensors drawn; the clear trace in a worker"): the flagship office (two groups,
the window row and the inner rows) opened by File > Open project..., Climate > Control
groups > Edit... on the window row: Control "switching (on/off)", Own target ticked and
300 lux typed, OK; the list and the energy box say so; its sensor, drawn in its colour on
the work plane, follows an edit of its region and Edit > Undo. The energies are checked
by hand in tests/core/test_control_modes.py.

Screenshots go to /tmp/shots-cleargui/."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtCore, QtWidgets

from tests.app import user as u
from tests.app.conftest import open_by_menu

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-flagship.json"
SHOTS = Path("/tmp/shots-cleargui")


def _switching_at_300(dialog: QtWidgets.QWidget) -> None:
    u.choose(u.field(dialog, "Control"), "switching (on/off)")
    tick, target = u.form_row(dialog, "Own target (lux)")
    assert not tick.isChecked() and not target.isEnabled()
    u.click(tick, QtCore.QPoint(8, tick.height() // 2))
    u.type_number(target, "300")
    u.ok(dialog)


def _region_y1(value: str):
    def answer(dialog: QtWidgets.QWidget) -> None:
        u.type_number(u.form_row(dialog, "Region x0 y0 x1 y1 (m)")[3], value)
        u.ok(dialog)

    return answer


def _select(box, name: str) -> None:
    for i in range(box.list.count()):
        item = box.list.item(i)
        if item.text().startswith(name + ":"):
            u.click(box.list.viewport(), box.list.visualItemRect(item).center())
            return
    raise AssertionError(f"no group {name!r} in the list")


def _outline(window, name: str) -> np.ndarray:
    (o,) = [o for o in window.colouring.sensors if o.name == name]
    return o.corners


def test_switching_own_target_and_the_sensor_drawn(qtbot, window, tmp_path):
    data = json.loads(PROJECT.read_text(encoding="utf-8"))
    data["scene"]["resolution"] = 1.0
    data["operator"] = {"rank": 120, "rays": 128}
    path = tmp_path / "flagship.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    open_by_menu(qtbot, window, path)  # the operator, then the clear glazing's trace
    window.activateWindow()
    QtWidgets.QApplication.processEvents()
    d = window.doc
    # The two sensors are drawn on the work plane, each in its colour, labelled.
    assert [o.name for o in window.colouring.sensors] == ["window row", "inner rows"]
    row = _outline(window, "window row")
    assert np.allclose(row[:, :2], [[0, 0], [15, 0], [15, 3], [0, 3]])
    assert np.allclose(row[:, 2], 0.8, atol=0.05)  # the 0.8 m work plane over the floor
    actors = window.viewport.plotter.renderer.actors
    labels = [a for a in actors if a.startswith("sensor-label-")]
    assert "sensors" in actors and len(labels) == 2

    u.tab(window, "Climate")
    box = u.reveal(window.climate_panel.groups)
    _select(box, "window row")
    u.answer(lambda: u.click(u.button(box, "Edit...")), _switching_at_300)
    group = d.design.control_groups[0]
    assert (group.name, group.mode, group.target_lux) == ("window row", "switching", 300.0)
    assert group.sensor == (0.0, 0.0, 15.0, 3.0)  # the rest as it was
    assert "; switching; 300 lux;" in box.list.item(0).text()
    energy = u.reveal(window.climate_panel.energy.text)
    qtbot.waitUntil(
        lambda: "group window row (switching to 300 lux)" in energy.text(), timeout=60_000
    )
    assert "group inner rows (dimming to 500 lux)" in energy.text()
    window.climate_panel.groups.grab().save(str(SHOTS / "groups-box-switching.png"))
    window.climate_panel.energy.grab().save(str(SHOTS / "energy-switching.png"))

    # Its sensor region edited: the outline follows; Edit > Undo brings it back.
    _select(box, "window row")
    u.answer(lambda: u.click(u.button(box, "Edit...")), _region_y1("4.5"))
    assert d.design.control_groups[0].sensor == (0.0, 0.0, 15.0, 4.5)
    assert _outline(window, "window row")[2, 1] == pytest.approx(4.5)
    u.click(u.toolbar_button(window, "Top view"))
    shot = u.screenshot(window, SHOTS, "sensors-edited")
    assert shot.exists()
    u.menu(window, "Edit", "Undo edit control group window row")
    QtWidgets.QApplication.processEvents()
    assert d.design.control_groups[0].sensor == (0.0, 0.0, 15.0, 3.0)
    assert _outline(window, "window row")[2, 1] == pytest.approx(3.0)
    u.menu(window, "Edit", "Undo edit control group window row")
    QtWidgets.QApplication.processEvents()
    assert d.design.control_groups[0].mode == "dimming"
    assert d.design.control_groups[0].target_lux is None
    u.screenshot(window, SHOTS, "sensors-undone")
    # Redrawn, not added: still one outline actor and one label per group.
    labels = [a for a in window.viewport.plotter.renderer.actors if a.startswith("sensor-label-")]
    assert len(labels) == 2
