"""Control groups made by clicks at 1366 x 768 (issue #30 item 5, docs/daylight.md
"Control groups in a project"): the integrated office opened by File > Open project...,
Climate > Control groups > Add group... adds a group as proposed, Edit... names it
"window row" and has its sensor read the west third of the work plane, the west
luminaire strip L1 joins it in Properties > Source > Control group (Edit > Undo takes
that back, chosen again), a run, then the energy box lists the two groups with their
energies adding up to the total. The energies themselves are checked in
tests/core/test_control_groups_design.py.

Screenshots go to /tmp/shots-groups/."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from PySide6 import QtCore, QtWidgets

from lightinv_core.design.model import ControlGroup
from tests.app import user as u
from tests.app.conftest import open_by_menu

pytestmark = pytest.mark.slow

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-integrated.json"
SHOTS = Path("/tmp/shots-groups")


def _window_row(dialog: QtWidgets.QWidget) -> None:
    """Answer the control group dialog: "window row", reading x 0-4 m of the plane."""
    name = u.field(dialog, "Name")
    u.click(name)
    u.press(name, QtCore.Qt.Key_A, QtCore.Qt.ControlModifier)
    u.type_text(name, "window row")
    whole = u.field(dialog, "Sensor reads")
    assert whole.isChecked()
    u.click(whole, QtCore.QPoint(8, whole.height() // 2))  # its tick box
    assert not whole.isChecked()
    boxes = u.form_row(dialog, "Region x0 y0 x1 y1 (m)")
    for box, value in zip(boxes, ("0", "0", "4", "8"), strict=True):
        u.type_number(box, value)
    u.ok(dialog)


def test_a_window_row_group_by_clicks(qtbot, window, tmp_path):
    # The integrated demo as shipped, coarser and with a shorter sweep (a test's time).
    data = json.loads(PROJECT.read_text(encoding="utf-8"))
    data["scene"]["resolution"] = 0.7
    data["operator"] = {"rank": 120, "rays": 256}
    data["optimizer"].update(max_evals=1500, epsilon_count=2)
    path = tmp_path / "office.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    open_by_menu(qtbot, window, path)
    window.activateWindow()
    QtWidgets.QApplication.processEvents()
    d = window.doc

    u.tab(window, "Climate")
    box = u.reveal(window.climate_panel.groups)  # below the others: scrolled to
    assert not d.design.control_groups
    assert window.width() <= 1366  # the box widens nothing on a laptop's screen
    u.answer(lambda: u.click(u.button(box, "Add group...")), u.ok)  # as proposed
    assert d.design.control_groups == (ControlGroup("group 1"),)
    # Edit... renames it and gives it a sensor region.
    item = box.list.item(0)
    assert item.text().startswith("group 1: control plane, whole plane; no luminaires")
    u.click(box.list.viewport(), box.list.visualItemRect(item).center())
    u.answer(lambda: u.click(u.button(box, "Edit...")), _window_row)
    (group,) = d.design.control_groups
    assert (group.name, group.sensor, group.workplane) == ("window row", (0, 0, 4, 8), None)
    assert box.list.item(0).text().startswith("window row: control plane, x 0-4, y 0-8 m")

    u.click_tree(window.tree, "L1")
    u.tab(window, "Properties")
    u.tab(window, "Source")
    props = window.findChild(QtWidgets.QDockWidget, "properties")
    combo = u.reveal(u.field(props, "Control group"))
    assert combo.currentText() == "all"
    u.choose(combo, "window row")
    assert d.design.source("L1").control_group == "window row"
    assert d.design.source("L2").control_group == "all"  # its mirror keeps its own
    u.screenshot(window, SHOTS, "source-panel-group")
    # Edit > Undo takes the choice back; chosen again.
    u.menu(window, "Edit", "Undo L1: control group window row")
    QtWidgets.QApplication.processEvents()
    assert d.design.source("L1").control_group == "all" and combo.currentText() == "all"
    u.choose(combo, "window row")
    assert d.design.source("L1").control_group == "window row"

    with qtbot.waitSignal(window.runs.finished, timeout=240_000):
        u.click(u.button(window, "Run"))
    assert window.doc.project.runs  # the run is kept, its best layout shown
    u.reveal(window.tabs.tabBar())  # the panel was scrolled down to the groups
    u.tab(window, "Climate")
    energy = u.reveal(window.climate_panel.energy.text)
    qtbot.waitUntil(lambda: "group window row" in energy.text(), timeout=60_000)
    text = energy.text()
    assert "group all" in text
    total = float(re.search(r"Annual ([\d,.]+) kWh", text)[1].replace(",", ""))
    parts = [float(x.replace(",", "")) for x in re.findall(r"W, ([\d,.]+) kWh", text)]
    assert len(parts) == 2
    standby = d.design.daylight.standby_w * 8760 / 1000
    assert sum(parts) + standby == pytest.approx(total, abs=0.15)
    shot = u.screenshot(window, SHOTS, "energy-two-groups")
    assert shot.exists()
    box.grab().save(str(SHOTS / "control-groups-box.png"))
    window.climate_panel.energy.grab().save(str(SHOTS / "energy-box.png"))
