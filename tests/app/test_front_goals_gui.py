"""The window's front methods on the integrated demo, by clicks: NSGA-II trades the
design's annual energy against its glazing area and the Solutions tab shows those
values; the method list follows the design's goals (NSGA-II greyed out with the reason
for a one-goal design); an epsilon sweep's range run gets its own labelled plot; the
run's reported evaluations are the live counter's; one pin is "1 pinned"; another
project's Solutions plot starts from its own ranges.

Screenshots go to /tmp/nsga_*.png."""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import pytest
from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from lightinv_core.project import OperatorSettings, load_project
from tests.app.conftest import wait_for_operator
from tests.app.test_laptop_screen import click_tab

pytestmark = pytest.mark.slow

DEMO = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-integrated.json"


def _button(win, text: str) -> QtWidgets.QPushButton:
    found = [b for b in win.findChildren(QtWidgets.QPushButton) if b.text() == text]
    assert found, f"no button {text!r}"
    return next((b for b in found if b.isVisible()), found[0])


def _choose(combo: QtWidgets.QComboBox, text: str) -> bool:
    """Open ``combo`` with a click, type the start of item ``text`` and press Enter, as a
    user picks from a list; whether it was taken (a greyed-out item is skipped)."""
    QTest.mouseClick(combo, QtCore.Qt.LeftButton)
    view = combo.view()
    for _ in range(50):  # the list opens (an animation on some styles)
        if view.isVisible():
            break
        QTest.qWait(20)
    QTest.qWait(100)
    assert combo.findText(text) >= 0, f"no item {text!r}"
    QTest.keyClicks(view, text[:4])
    QTest.keyClick(view, QtCore.Qt.Key_Return)
    QTest.qWait(100)
    if view.isVisible():
        QTest.keyClick(view, QtCore.Qt.Key_Escape)
    return combo.currentText() == text


def _type(spin: QtWidgets.QAbstractSpinBox, text: str) -> None:
    QTest.mouseDClick(spin.lineEdit(), QtCore.Qt.LeftButton)
    QTest.keyClick(spin, QtCore.Qt.Key_A, QtCore.Qt.ControlModifier)
    QTest.keyClicks(spin, text)
    QTest.keyClick(spin, QtCore.Qt.Key_Tab)


def _run(qtbot, win, timeout=180_000) -> str:
    with qtbot.waitSignal(win.runs.finished, timeout=timeout) as blocker:
        QTest.mouseClick(_button(win, "Run"), QtCore.Qt.LeftButton)
    return blocker.args[0]


def _numbers(text: str) -> list[int]:
    return [int(n.replace(",", "")) for n in re.findall(r"([\d,]+) evaluations", text)]


@pytest.fixture
def demo(qtbot, window):
    project = load_project(DEMO)
    project = replace(
        project,
        scene=replace(project.scene, resolution=0.7),
        operator=OperatorSettings(rank=120, rays=256),
    )
    assert window.load_project(project)
    wait_for_operator(qtbot, window)
    click_tab(window, "Run")
    return window


def test_the_method_list_follows_the_designs_goals(qtbot, demo):
    win, panel = demo, demo.run_panel
    row = panel.method.findData("nsga2")
    assert panel.method.model().item(row).isEnabled()
    # One goal left (Design > Goals): NSGA-II and the sweeps are greyed out, saying why.
    win.goal_actions["min_glazing_area"].trigger()
    assert [str(g.kind) for g in win.doc.design.goals] == ["min_annual_energy"]
    assert not panel.method.model().item(row).isEnabled()
    tip = panel.method.itemData(row, QtCore.Qt.ToolTipRole)
    assert tip.startswith("NSGA-II trades two of the design's goals")
    assert "one (annual lighting energy)" in tip
    assert not _choose(panel.method, "NSGA-II front")
    assert panel.method.model().item(panel.method.findData("cmaes")).isEnabled()
    panel.grab().save("/tmp/nsga_refused.png")
