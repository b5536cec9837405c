"""A control group's sensor region dragged in the 3D view, by real mouse events at
1366 x 768 (issue #30 item 6, docs/daylight.md "DGP in the view; dragging sensors"): the
flagship office (two groups, the window row and the inner rows) opened by File > Open
project..., Top view, Move; the window row's corner handle dragged from (0, 0) to
(3, 1) m resizes its region, then its edge dragged 1 m west moves it; each drag is one
Edit > Undo step; the Climate tab's energy box follows (the group's kWh equal to the
core's ``layout_daylight`` of the edited design, made afresh) and comes back with the
undo. The energies themselves are checked by hand in tests/core/test_control_modes.py.

Screenshots go to /tmp/shots-dgpview/."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtWidgets
from PySide6.QtTest import QTest

from app.view import sensor_overlay
from lightinv_core.light.daylight import layout_daylight
from tests.app import user as u
from tests.app.conftest import open_by_menu

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-flagship.json"
SHOTS = Path("/tmp/shots-dgpview")


def _sensor(window, name: str) -> tuple[float, ...]:
    return next(c.sensor for c in window.doc.design.control_groups if c.name == name)


def _group_line(window, name: str) -> str:
    text = window.climate_panel.energy.text.text()
    lines = [line for line in text.splitlines() if line.startswith(f"group {name} (")]
    return lines[0] if lines else ""


def _kwh(window, name: str) -> str:
    """The group's kWh as the core computes it for the design on screen, afresh."""
    d = window.doc
    group = next(g for g in layout_daylight(d.light, d.design).energy().groups if g.name == name)
    return f"{group.energy_kwh:,.1f} kWh"


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_a_sensor_region_dragged_in_the_view(qtbot, window, tmp_path):
    data = json.loads(PROJECT.read_text(encoding="utf-8"))
    data["scene"]["resolution"] = 1.0
    data["operator"] = {"rank": 120, "rays": 128}
    path = tmp_path / "flagship.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    open_by_menu(qtbot, window, path)  # the operator, then the clear glazing's trace
    window.activateWindow()
    QtWidgets.QApplication.processEvents()
    u.tab(window, "Climate")
    assert u.wait_for(lambda: _group_line(window, "window row"), 120_000)
    before = _group_line(window, "window row")
    assert _sensor(window, "window row") == (0.0, 0.0, 15.0, 3.0)
    vp = window.viewport
    # Both declared groups have a handle at each corner (8 balls over the 15 x 9 m plan).
    handles = vp.plotter.actors[sensor_overlay.HANDLES]
    handles.mapper.Update()
    assert handles.mapper.dataset.n_points == 8
    assert np.allclose(handles.GetBounds()[:4], (0.0, 15.0, 0.0, 9.0))
    u.menu(window, "View", "Top view")
    u.click(u.toolbar_button(window, "Move"))
    QTest.qWait(200)
    (row,) = [o for o in window.colouring.sensors if o.name == "window row"]
    z = float(row.corners[0, 2]) + sensor_overlay.LIFT
    steps = window.undo_stack.count()

    # The south-west corner's handle dragged to (3, 1): the region is resized from it.
    u.view_drag(vp, np.array([0.0, 0.0, z]), np.array([3.0, 1.0, z]), steps=6)
    x0, y0, x1, y1 = _sensor(window, "window row")
    assert (x0, y0) == pytest.approx((3.0, 1.0), abs=0.06) and (x1, y1) == (15.0, 3.0)
    assert _sensor(window, "inner rows") == (0.0, 3.0, 15.0, 9.0)  # the other one stays
    assert window.undo_stack.count() == steps + 1  # one edit for the whole drag
    assert "Sensor of window row: x 3" in window.statusBar().currentMessage()
    # The outline follows, and the energy box: the group's kWh as the core has it now.
    (row,) = [o for o in window.colouring.sensors if o.name == "window row"]
    assert np.allclose(row.corners[0, :2], (x0, y0))
    assert u.wait_for(lambda: _group_line(window, "window row") != before, 60_000)
    want = _kwh(window, "window row")
    assert want in _group_line(window, "window row"), (want, _group_line(window, "window row"))
    resized = _group_line(window, "window row")
    QTest.qWait(200)
    u.screenshot(window, SHOTS, "sensor-resized")

    # Its west edge dragged 1 m west: the whole region moves, its size kept.
    edge = np.array([x0, (y0 + y1) / 2, z])
    u.view_drag(vp, edge, edge - np.array([1.0, 0.0, 0.0]), steps=5)
    moved = _sensor(window, "window row")
    assert moved[0] == pytest.approx(x0 - 1.0, abs=0.06)
    assert moved[2] == pytest.approx(14.0, abs=0.06) and moved[1::2] == (y0, y1)
    assert window.undo_stack.count() == steps + 2
    assert u.wait_for(lambda: _group_line(window, "window row") != resized, 60_000)
    u.screenshot(window, SHOTS, "sensor-moved")

    # Edit > Undo takes each drag back in one step; the energy box comes back with it.
    u.menu(window, "Edit", "Undo edit control group window row")
    assert _sensor(window, "window row") == (x0, y0, x1, y1)
    u.menu(window, "Edit", "Undo edit control group window row")
    assert _sensor(window, "window row") == (0.0, 0.0, 15.0, 3.0)
    assert u.wait_for(lambda: _group_line(window, "window row") == before, 60_000)
    assert window.doc.design.arrays == window.doc.project.design.arrays  # nothing else moved
