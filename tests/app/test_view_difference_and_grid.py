"""The view of a loaded result against a pinned one, and of a broken work-plane
intention (issue #29, minor items): the difference view's colour-bar title was cut
and its work plane grey with absolute labels; "highlight the patches that break…"
marked nothing for a grid intention. A project with a run is opened by File > Open
project..., results are loaded, pinned and compared by clicks on the Solutions tab."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from app.dialogs import ask
from lightinv_core.design.model import Intention, Workplane
from lightinv_core.design.solution import SolutionInfo
from lightinv_core.editing import DocumentModel, blank_project
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.settings import OptimizerSettings
from tests.app.conftest import wait_for_operator
from tests.app.test_dialog_buttons import button, menu_action


def office_with_a_run(path) -> None:
    """An office project with two luminaires, a work plane asking for a uniformity its
    light cannot give, and a run of two results (different fluxes), saved at ``path``."""
    doc = DocumentModel()
    doc.set_project(blank_project("office", 0.7))
    doc.set_operator(build_operator(doc.patches, OperatorSettings(rank=100, rays=128)))
    doc.add_source("lum_west")
    doc.add_source("lum_east")
    doc.set_workplanes((Workplane("desks"),))
    doc.add_intention(Intention("even", grid="desks", uniformity=0.99))
    problem = doc.problem()
    x0 = problem.vars.initial()
    sols = [problem.solution(x0 - 0.1 * i, SolutionInfo(method="vns")) for i in range(2)]
    assert not any(s.feasible for s in sols)
    doc.add_run(tuple(sols), None, settings=OptimizerSettings())
    doc.save(path)


def click_row(table: QtWidgets.QTableWidget, row: int) -> None:
    rect = table.visualRect(table.model().index(row, 0))
    QTest.mouseClick(table.viewport(), QtCore.Qt.LeftButton, pos=rect.center())


def tick(box: QtWidgets.QCheckBox) -> None:
    """A click on a check box's tick (its middle may be past its text)."""
    QTest.mouseClick(box, QtCore.Qt.LeftButton, pos=QtCore.QPoint(8, box.height() // 2))


def test_difference_view_and_broken_grid_points(qtbot, window, monkeypatch, tmp_path):
    path = tmp_path / "office.json"
    office_with_a_run(path)
    monkeypatch.setattr(ask, "open_file", lambda *a, **k: str(path))
    menu_action(window, "File/Open project...").trigger()
    wait_for_operator(qtbot, window, timeout=120_000)
    vp, d = window.viewport, window.doc
    assert vp.caption.startswith("Illuminance, design scenario")
    assert vp.hint is None and "hint" not in vp.plotter.actors  # a run's results: done
    tabs = window.tabs
    tabs.setCurrentIndex([tabs.tabText(i) for i in range(tabs.count())].index("Solutions"))
    panel = window.solutions_panel
    assert panel.table.rowCount() == 2

    # The second result loaded, its grid intention broken: the Violations tab marks the
    # floor under the points below U0 x Em (it marked nothing).
    click_row(panel.table, 1)
    assert d.shown is not None and not d.shown.feasible
    tabs.setCurrentIndex([tabs.tabText(i) for i in range(tabs.count())].index("Violations"))
    violations = window.violations_panel
    assert "patches out of bounds" in violations.summary.text()
    marked = violations.highlighted()
    floor = set(d.patches.group_index("floor"))
    assert len(marked) and set(marked) <= floor
    assert "offending" in vp.plotter.actors

    # The points themselves in red: those below U0 x Em (the design's light, night).
    dots = vp.plotter.actors["grid-marks"].mapper.dataset.points
    ((_, _, _, broken),) = d.offending_points()
    grids, _ = d.shown_grids()
    assert len(dots) == len(broken) < len(grids.points)
    np.testing.assert_allclose(dots[:, :2], grids.points[broken, :2])
    vp.camera("top")
    vp.screenshot("/tmp/lightinv-grid-broken.png")
    tick(violations.highlight)  # unticked: no marks
    assert not violations.highlight.isChecked() and "grid-marks" not in vp.plotter.actors
    tick(violations.highlight)
    assert "grid-marks" in vp.plotter.actors

    # Pin the first, load the second, show the difference.
    tabs.setCurrentIndex([tabs.tabText(i) for i in range(tabs.count())].index("Solutions"))
    click_row(panel.table, 0)
    QTest.mouseClick(button(panel, "Pin / unpin"), QtCore.Qt.LeftButton)
    click_row(panel.table, 1)
    tick(panel.difference)
    assert panel.difference.isChecked() and panel.compared() is not None
    (bar,) = vp.plotter.scalar_bars.values()
    assert bar.GetTitle() == "Δ lux" and bar.GetLabelFormat() == "%+.0f"
    assert vp.caption.startswith("Difference: the loaded layout minus the pinned one")
    # The work plane in the same signed colours, its iso-lines with signed labels.
    plane = vp.plotter.actors["workplane"].mapper
    lo, hi = plane.scalar_range
    assert lo == -hi and hi > 0
    assert plane.lookup_table.GetTableValue(0)[2] > 0.5  # coolwarm: blue at the low end
    values = plane.dataset.point_data["lux"]
    assert values.min() < 0 or values.max() > 0
    labels = vp.plotter.actors.get("isolux-labels")
    if labels is not None:  # iso-lines where the difference varies over the plane
        texts = labels.GetMapper().GetInput().GetPointData().GetAbstractArray(0)
        assert all(texts.GetValue(i)[0] in "+-" for i in range(texts.GetNumberOfValues()))
    window.grab().save("/tmp/lightinv-difference-window.png")
    vp.screenshot("/tmp/lightinv-difference.png")
    assert np.isfinite(values).all()
