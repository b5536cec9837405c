"""Clear glazing chosen in the window (issue #30, docs/daylight.md "Clear glazing in a
project"), by clicks at 1366 x 768: the integrated office opened by File > Open
project..., its skylight S1 picked in the design tree, Properties > Source > Glazing
set to clear (its rectangle stays free: the optimiser moves clear shapes too, its
filter box greyed), then Edit > Undo by its keys. The light it gives is checked in
tests/core/test_clear_design.py; so the office is meshed coarser here (0.5 m patches,
256 rays: a test's time), as in test_skyband_gui.py."""

from __future__ import annotations

import json
from pathlib import Path

from PySide6 import QtCore, QtWidgets

from tests.app import user as u
from tests.app.conftest import open_by_menu

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-integrated.json"
SHOTS = Path("/tmp/shots-cleardesign")


def test_a_skylight_made_clear_by_clicks(qtbot, window, tmp_path):
    data = json.loads(PROJECT.read_text(encoding="utf-8"))
    data["scene"]["resolution"] = 0.5
    data["operator"] = {"rays": 256}
    path = tmp_path / "office.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    open_by_menu(qtbot, window, path)
    window.activateWindow()
    QtWidgets.QApplication.processEvents()
    d = window.doc
    assert d.design.source("S1").free  # the demo's skylight is free

    u.click_tree(window.tree, "S1")
    u.tab(window, "Properties")
    u.tab(window, "Source")
    props = window.findChild(QtWidgets.QDockWidget, "properties")
    glazing = u.reveal(u.field(props, "Glazing"))
    assert glazing.currentText().startswith("diffusing")
    u.choose(glazing, "clear")
    s = d.design.source("S1")
    assert s.glazing == "clear" and s.free == ("u0", "v0", "u1", "v1")
    boxes = {b.text(): b for b in props.findChildren(QtWidgets.QCheckBox)}
    assert boxes["position and size"].isEnabled() and boxes["position and size"].isChecked()
    assert not boxes["filter"].isEnabled()  # a clear glazing frees its rectangle only
    shot = u.screenshot(window, SHOTS, "source-panel-clear")
    assert shot.exists()

    # A luminaire has no glazing: the row is hidden for it.
    u.click_tree(window.tree, "L1")
    assert not u.shown(glazing)

    # Edit > Undo (its keys): the skylight diffusing and free again.
    u.click_tree(window.tree, "S1")
    u.press(window, QtCore.Qt.Key_Z, QtCore.Qt.ControlModifier)
    QtWidgets.QApplication.processEvents()
    s = d.design.source("S1")
    assert s.glazing == "diffusing" and s.free
    assert glazing.currentText().startswith("diffusing")
