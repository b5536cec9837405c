"""An imported room before any light (issue #29, item 5): the view showed a black box
under a colour bar of zeros, so zones were drawn blind. Now its surfaces show in the
grey of their reflectance, shaded and outlined, with no colour bar; a hint says what to
do next and follows the design; drawn corners snap to the surface's edges and a 0.1 m
grid. Driven by real mouse clicks in the view and on the panels' buttons."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from app.view.zone_drawing import snap_uv
from tests.app.conftest import wait_for_operator
from tests.app.test_dialog_buttons import answer, button, click
from tests.app.test_laptop_screen import click_tab
from tests.app.test_main_window import send_mouse, to_qt
from tests.app.test_zones_on_imported_room import draw_zone, import_room


def pixel(vp, world) -> np.ndarray:
    """The rendered RGB at a world point."""
    img = vp.screenshot()
    p = to_qt(vp, world)
    return img[int(p.y()), int(p.x())].astype(int)


def zone_corners(doc, zone: str) -> np.ndarray:
    """World corners (k, 3) of a drawn zone: its outline, or its rectangle's corners."""
    rect = doc.scene.zone_rect(zone)
    eu, ev = rect.u / rect.size[0], rect.v / rect.size[1]
    outline = doc.scene.zone(zone).outline
    uv = outline if outline is not None else [(0, 0), (rect.size[0], rect.size[1])]
    return np.array([rect.origin + u * eu + v * ev for u, v in uv])


def test_snap_prefers_a_vertex_then_an_edge_then_the_grid():
    size, tol = (10.0, 7.0), 0.08
    assert snap_uv((0.05, 6.96), size, tol) == (0.0, 7.0)  # the surface's corner
    assert snap_uv((3.31, 2.2), size, tol, vertices=[(3.27, 2.24)]) == (3.27, 2.24)
    assert snap_uv((0.07, 3.33), size, tol) == (0.0, pytest.approx(3.3))  # edge, grid
    assert snap_uv((4.56, 3.33), size, 0.01) == (4.56, pytest.approx(3.33))  # too far: free
    assert snap_uv((4.12, 3.45), size, 0.03) == pytest.approx((4.1, 3.45))  # one axis


def test_an_imported_room_shows_its_materials_and_the_next_step_until_lit(
    qtbot, window, monkeypatch, tmp_path
):
    import_room(qtbot, window, monkeypatch, tmp_path)
    vp, d = window.viewport, window.doc
    tools = window.findChild(QtWidgets.QToolBar, "main toolbar")
    QTest.mouseClick(button(tools, "Iso view"), QtCore.Qt.LeftButton)
    # No light: the materials (the room was black), no colour bar of zeros, and why.
    assert not vp.has_values and "edges" in vp.plotter.actors
    assert not any(bar.GetVisibility() for bar in vp.plotter.scalar_bars.values())
    assert vp.caption.startswith("No light yet")
    assert vp.hint.startswith("Next (step 1 of 5): draw where light may go")
    assert "hint" in vp.plotter.actors
    vp.screenshot("/tmp/lightinv-before-light-iso.png")
    floor = pixel(vp, (5.0, 3.5, 0.0))
    # A mid grey (the floor's 0.5 reflectance, headlit), not the colour map's black.
    assert 90 < floor.mean() < 230 and np.ptp(floor) < 8, floor
    QTest.mouseClick(button(tools, "Top view"), QtCore.Qt.LeftButton)
    vp.screenshot("/tmp/lightinv-before-light-top.png")
    window.grab().save("/tmp/lightinv-before-light-window.png")
    assert 90 < pixel(vp, (5.0, 3.5, 0.0)).mean() < 230

    # A luminaire zone dragged from just off the west wall and off the grid: its
    # corners snap to the wall (x = 0) and to the 0.1 m grid.
    top = vp.plotter.camera_position
    draw_zone(window, "luminaire", (0.09, 2.015, 3.0), (3.985, 4.015, 3.0))
    wait_for_operator(qtbot, window, timeout=120_000)
    # The same room re-meshed keeps the camera (it went back to iso, unlit).
    assert vp.plotter.camera_position == top
    (zone,) = [z.name for z in d.scene.zones]
    lo, hi = zone_corners(d, zone).min(axis=0), zone_corners(d, zone).max(axis=0)
    assert lo[:2] == pytest.approx((0.0, 2.0), abs=1e-9)
    assert hi[:2] == pytest.approx((4.0, 4.0), abs=1e-9)
    assert not vp.has_values and vp.hint.startswith("Next (step 2 of 5): add light")

    # A polygon clicked corner by corner off the grid: every corner on it (0.1 m).
    window.set_mode("polygon")
    iw = vp.plotter.interactor
    for x, y in ((6.015, 2.01), (8.985, 1.99), (8.01, 5.015)):
        p = to_qt(vp, (x, y, 3.0))
        send_mouse(iw, QtCore.QEvent.Type.MouseButtonPress, p)
        send_mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, p)
    seen = answer(lambda: QTest.keyClick(iw, QtCore.Qt.Key_Return), click("OK"))
    assert seen["dialog"] == "ZoneDialog"
    wait_for_operator(qtbot, window, timeout=120_000)
    window.set_mode("navigate")
    vp.screenshot("/tmp/lightinv-zones-before-light.png")
    poly = next(z.name for z in d.scene.zones if z.outline is not None)
    got = zone_corners(d, poly)[:, :2]
    assert sorted(map(tuple, np.round(got, 6))) == [(6.0, 2.0), (8.0, 5.0), (9.0, 2.0)]

    # Light added by a click on the Source page's Add source: the view is coloured by it, with
    # its colour bar and the scenario named; the hint moves on to the work plane.
    props = window.source_panel
    click_tab(window, "Source")
    props.zone.setCurrentIndex(props.zone.findText(f"{zone} (luminaire)"))
    QTest.mouseClick(button(props, "Add source"), QtCore.Qt.LeftButton)
    qtbot.waitUntil(lambda: vp.has_values, timeout=30_000)
    assert any(bar.GetVisibility() for bar in vp.plotter.scalar_bars.values())
    assert "edges" not in vp.plotter.actors
    assert vp.caption.startswith("Illuminance, design scenario: luminaires")
    assert vp.hint.startswith("Next (step 3 of 5): add a work plane")
    vp.screenshot("/tmp/lightinv-first-light.png")
