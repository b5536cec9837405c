"""A new array as the window proposes it (issue #29, item 7): Add array… then OK gives an
array whose rows and columns the optimiser may change, every luminaire at full output
(the "dimming" box unticked, its tooltip saying what ticking it means), and the dialog
says the spacing rule it keeps by default. An infeasible result's penalty is one number:
the Violations tab's and the Solutions table's, from the violations listed."""

from __future__ import annotations

import pytest
from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from lightinv_core.design.model import Intention
from tests.app.test_dialog_buttons import answer, button, ok_and_cancel
from tests.app.test_optimisation import cornell_design, run_and_wait  # noqa: F401 (a fixture)


def test_add_array_proposes_full_output_and_the_default_spacing_rule(qtbot, window):
    assert window.new_project("office", 0.5)
    d = window.doc
    window.findChild(QtWidgets.QDockWidget, "luminaires").raise_()
    add_array = button(window.luminaires_panel, "Add array…")
    shown: dict = {}

    def look_then_ok(dialog):
        boxes = {b.text(): b for b in dialog.findChildren(QtWidgets.QCheckBox)}
        shown["ticked"] = {t for t, b in boxes.items() if b.isChecked()}
        shown["dimming tip"] = boxes["dimming"].toolTip()
        shown["summary"] = dialog.summary.text()
        dialog.grab().save("/tmp/lightinv-array-defaults.png")
        QTest.mouseClick(button(dialog, "OK"), QtCore.Qt.LeftButton)

    ok_and_cancel(answer(lambda: QTest.mouseClick(add_array, QtCore.Qt.LeftButton), look_then_ok))
    assert shown["ticked"] == {"rows", "columns"}
    assert "dimming controls" in shown["dimming tip"]
    assert "within 1.5 x the mounting height" in shown["summary"]
    (array,) = d.design.arrays
    assert array.free == ("rows", "columns") and array.dimming == 1.0


def test_an_infeasible_result_shows_one_penalty(qtbot, cornell_design):  # noqa: F811 (fixture)
    win = cornell_design
    win.doc.add_intention(Intention("blinding", group="floor", min=1e6))
    assert run_and_wait(qtbot, win) == "infeasible"
    best = win.doc.shown
    # The Violations tab and the Solutions table show the solution's own penalty, and it
    # is the sum of weight x amount^power over the violations the tab lists.
    weights = {it.name: it.weight for it in win.doc.design.intentions}
    power = win.doc.design.penalty_power
    total = sum(weights[v.name] * v.amount**power for v in best.violations)
    assert best.penalty == pytest.approx(total)
    assert f"penalty P = {best.penalty:.3g}" in win.violations_panel.summary.text()
    table = win.solutions_panel.table
    column = [table.horizontalHeaderItem(c).text() for c in range(table.columnCount())]
    shown = {table.item(r, column.index("penalty")).text() for r in range(table.rowCount())}
    assert f"{best.penalty:.3g}" in shown
