"""Observers by clicks after they are placed, and an EN 12464-1 preset's UGR_L as a glare
limit (issue #31, items 1-2 leftovers), on a 1366 x 768 window:

- Add work plane… with the 2021 "Technical drawing" preset: its ticked "Add UGR limit
  from preset (UGR_L 16)" adds two seated observers at the plane's edges, looking across,
  and UGR at most 16 at both; a new observer is then offered 16;
- an observer edited in its dialog (a double-click on its row), dragged in the view
  (Move mode, its ball), edited from the view (a double-click on its ball), deleted from
  the tree (Delete); Edit > Undo takes each back in one step."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from lightinv_core.design.en12464 import EDITION_2021
from tests.app import user as u
from tests.app.conftest import open_coarse_office

ROOT = Path(__file__).resolve().parents[2]
SHOTS = Path("/tmp/shots-observer")
pytestmark = pytest.mark.slow


def _preset_combo(dialog: QtWidgets.QWidget) -> QtWidgets.QComboBox:
    edition = u.field(dialog, "EN 12464-1")
    combos = [c for c in dialog.findChildren(QtWidgets.QComboBox) if c is not edition]
    return next(c for c in combos if c.itemText(0) == "no preset")


def _glare_box(dialog: QtWidgets.QWidget) -> QtWidgets.QCheckBox:
    return next(
        b for b in dialog.findChildren(QtWidgets.QCheckBox) if b.text().startswith("Add UGR")
    )


def _observer(window, name: str):
    return next(o for o in window.doc.design.observers if o.name == name)


def test_preset_glare_limit_and_observers_edited_by_clicks(qtbot, window):
    project = open_coarse_office(qtbot, window)
    SHOTS.mkdir(exist_ok=True)
    window.findChild(QtWidgets.QDockWidget, "luminaires").raise_()
    seen = {}

    def plane(dialog) -> None:
        u.type_text(u.field(dialog, "Name"), "desks")
        u.choose(u.field(dialog, "EN 12464-1"), EDITION_2021)
        box = _glare_box(dialog)
        seen["no preset"] = (box.text(), box.isEnabled())
        u.choose(_preset_combo(dialog), "Technical drawing")
        seen["drawing"] = (box.text(), box.isEnabled(), box.isChecked(), u.shown(box))
        dialog.grab().save(str(SHOTS / "workplane-dialog-ugr.png"))
        u.ok(dialog)

    u.answer(lambda: u.click(u.button(window.luminaires_panel, "Add work plane…")), plane)
    assert seen["no preset"] == ("Add UGR limit from preset", False)
    assert seen["drawing"] == ("Add UGR limit from preset (UGR_L 16)", True, True, True)
    d = window.doc.design
    # No observer before: two seated ones at the middle of the plane's y- and x- edges
    # (the office floor is 12 x 8 m, the plane's border 0.5 m), looking across it.
    eyes = {o.name: (o.position, o.height, o.azimuth) for o in d.observers}
    assert eyes == {
        "desks along y": ((6.0, 0.5), 1.2, 90.0),
        "desks along x": ((0.5, 4.0), 1.2, 0.0),
    }
    glare = d.intentions[-1]
    assert (glare.name, glare.quantity, glare.max) == ("desks UGR_L", "ugr", 16.0)
    assert glare.observers == ("desks along y", "desks along x")
    assert u.wait_for(lambda: "observers" in window.viewport.plotter.actors, 20_000)
    assert set(u.tree_texts(window.tree, "Observers")) == set(eyes)

    # A new observer is offered the design's strictest UGR_L (16, the drawing preset's).
    def offered(dialog) -> None:
        seen["offered"] = (dialog.limit[0].isChecked(), dialog.limit[1].value())
        u.click(u.button(dialog, "Cancel"))

    u.answer(lambda: u.menu(window, "Design", "Add observer (glare, UGR)..."), offered)
    assert seen["offered"] == (True, 16.0)

    # Edited in its dialog: a double-click on its row under Observers.
    def edit(dialog) -> None:
        assert dialog.windowTitle() == "Edit observer desks along y"
        assert not u.shown(dialog.limit[0])  # its limits are intentions of their own
        u.type_text(u.field(dialog, "x (m)"), "5")
        u.type_text(u.field(dialog, "Eye height (m)"), "1.7")
        u.type_text(u.field(dialog, "View azimuth (deg)"), "60")
        dialog.grab().save(str(SHOTS / "observer-edit-dialog.png"))
        u.ok(dialog)

    item = u.tree_item(window.tree, "desks along y")
    window.tree.scrollToItem(item)
    at = window.tree.visualItemRect(item).center()
    u.answer(lambda: u.double_click(window.tree.viewport(), at), edit)
    ob = _observer(window, "desks along y")
    assert (ob.position, ob.height, ob.azimuth) == ((5.0, 0.5), 1.7, 60.0)
    u.menu(window, "Edit", "Undo edit observer desks along y")
    ob = _observer(window, "desks along y")
    assert (ob.position, ob.height, ob.azimuth) == ((6.0, 0.5), 1.2, 90.0)

    # Dragged in the view: Move mode, a press on its ball, the ball follows the cursor
    # over the plane at the eye's height.
    u.menu(window, "View", "Top view")
    u.click(u.toolbar_button(window, "Move"))
    QTest.qWait(200)
    eye = np.array([6.0, 0.5, 1.2])
    u.view_drag(window.viewport, eye, eye + np.array([1.5, 1.0, 0.0]), steps=6)
    x, y = _observer(window, "desks along y").position
    assert (x, y) == pytest.approx((7.5, 1.5), abs=0.05)
    # The one picked is drawn green (its own actor), the other pink as before.
    actors = window.viewport.plotter.actors
    green = actors["observer-current"].GetBounds()
    assert (green[0] + green[1]) / 2 == pytest.approx(x, abs=0.3) and "observers" in actors
    assert window.doc.design.sources == project.design.sources  # no source moved
    QTest.qWait(200)
    u.screenshot(window, SHOTS, "observer-dragged")
    u.menu(window, "Edit", "Undo move observer desks along y")  # the whole drag, one step
    assert _observer(window, "desks along y").position == (6.0, 0.5)

    # A double-click on its ball in the view opens the same dialog.
    def cancel(dialog) -> None:
        seen["from view"] = dialog.windowTitle()
        u.click(u.button(dialog, "Cancel"))

    u.answer(lambda: u.view_click(window.viewport, eye, double=True), cancel)
    assert seen["from view"] == "Edit observer desks along y"

    # Deleted from the tree (Delete on its row): the limit keeps the other eye.
    u.click_tree(window.tree, "desks along x")  # picked: its ball turns green
    green = window.viewport.plotter.actors["observer-current"].GetBounds()
    assert (green[2] + green[3]) / 2 == pytest.approx(4.0, abs=0.3)  # at y 4, looking +x
    u.press(window.tree, QtCore.Qt.Key_Delete)
    design = window.doc.design
    assert [o.name for o in design.observers] == ["desks along y"]
    assert design.intentions[-1].observers == ("desks along y",)
    u.menu(window, "Edit", "Undo remove observer desks along x")
    design = window.doc.design
    assert [o.name for o in design.observers] == ["desks along y", "desks along x"]
    assert design.intentions[-1].observers == ("desks along y", "desks along x")
    QTest.qWait(200)
    u.screenshot(window, SHOTS, "observer-window")
