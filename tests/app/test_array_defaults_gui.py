"""A new array as the window proposes it (issue #29, item 7): Add array… then OK gives an
array whose rows and columns the optimiser may change, every luminaire at full output
(the "dimming" box unticked, its tooltip saying what ticking it means), and the dialog
says the spacing rule it keeps by default."""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from tests.app.test_dialog_buttons import answer, button, ok_and_cancel


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
