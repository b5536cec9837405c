"""Optimisation from the window under Xvfb: runs with live plots, cancel keeping the best,
the Pareto browser (loading, pinning, comparing), infeasibility feedback, several seeds,
worker errors — asserted on the project, the panels and the viewport's pixels."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtWidgets

from app.window.workers import RunWorker
from lightinv_core.design.model import CORNERS, Intention
from lightinv_core.project import OperatorSettings, load_project
from tests.app.conftest import wait_for_operator

PROJECTS = Path(__file__).resolve().parents[2] / "resources" / "projects"


def image(win) -> np.ndarray:
    return win.viewport.screenshot().astype(float)


def run_and_wait(qtbot, win, timeout=90_000) -> str:
    with qtbot.waitSignal(win.runs.finished, timeout=timeout) as blocker:
        assert win.runs.start()
    return blocker.args[0]


@pytest.fixture
def cornell_design(qtbot, window):
    """Cornell box with one luminaire (corners and flux free) and 'floor >= 20 lux'."""
    win = window
    assert win.new_project("cornell", 0.25)
    wait_for_operator(qtbot, win)
    src = win.doc.add_source("light")
    win.doc.update_source(src.name, rect=(0.1, 0.1, 0.3, 0.3), free=(*CORNERS, "flux"))
    win.doc.add_intention(Intention("floor", group="floor", min=20.0))
    win.doc.set_optimizer(method="vns", max_evals=1500)
    return win


def test_a_run_plots_its_convergence_and_loads_the_best(qtbot, cornell_design):
    win = cornell_design
    status = run_and_wait(qtbot, win)
    assert status == "feasible"
    plot = win.run_panel.plot
    assert plot.point_count >= 3 and plot.redraws >= 1
    curve = plot.curve(0)
    assert np.all(np.diff(curve[:, 1]) <= 1e-9)  # best power never rises...
    assert curve[-1, 2] == 0.0  # ...and the run ends feasible
    (best,) = win.doc.project.runs[-1].solutions
    assert best.feasible and best.info.evaluations >= 1500
    assert win.doc.shown is best
    assert win.doc.design.sources[0].rect == best.sources[0].rect
    assert "evaluations" in win.run_panel.counters.text()
    assert win.run_panel.run_button.isEnabled() and not win.run_panel.cancel_button.isEnabled()


def test_cancel_keeps_the_best_solution_in_the_project(qtbot, cornell_design):
    win = cornell_design
    win.doc.set_optimizer(max_evals=None)  # runs until cancelled
    with qtbot.waitSignal(win.runs.finished, timeout=60_000) as blocker:
        assert win.runs.start()
        qtbot.waitUntil(lambda: win.run_panel.plot.point_count >= 3, timeout=30_000)
        win.run_panel.cancel_button.click()
    assert blocker.args == ["cancelled"]
    (best,) = win.doc.project.runs[-1].solutions
    assert best.info.status == "cancelled" and best.info.evaluations > 0
    assert win.doc.design.sources[0].rect == best.sources[0].rect
    assert "Cancelled" in win.run_panel.state.text()


def test_infeasible_runs_list_violations_and_highlight_patches(qtbot, cornell_design):
    win = cornell_design
    win.doc.add_intention(Intention("blinding", group="floor", min=1e6))
    assert run_and_wait(qtbot, win) == "infeasible"
    panel = win.violations_panel
    assert win.tabs.currentWidget() is panel
    names = {panel.table.item(r, 0).text() for r in range(panel.table.rowCount())}
    assert "blinding" in names
    assert "Not feasible" in panel.summary.text()
    floor = win.doc.patches.group_index("floor")
    lit = panel.highlighted()
    assert len(lit) and set(lit) <= set(floor)
    assert "offending" in win.viewport.plotter.actors
    before = image(win)
    panel.highlight.setChecked(False)
    assert "offending" not in win.viewport.plotter.actors
    assert np.abs(image(win) - before).mean() > 0.5  # the red patches are gone


def test_several_seeds_show_each_run(qtbot, cornell_design):
    win = cornell_design
    win.doc.set_optimizer(max_evals=600)
    win.run_panel.runs.setValue(3)
    assert run_and_wait(qtbot, win) == "feasible"
    sols = win.doc.project.runs[-1].solutions
    assert [s.info.seed for s in sols] == [0, 1, 2]
    assert {0, 1, 2} <= set(win.run_panel.plot._data)  # one curve per run
    panel = win.solutions_panel
    assert panel.table.rowCount() == 3 and win.tabs.currentWidget() is panel
    # The paper's experiment 4 view: area against strength of each run's layout.
    panel.x_axis.setCurrentIndex(panel.x_axis.findData("area:luminaire"))
    panel.y_axis.setCurrentIndex(panel.y_axis.findData("strength:luminaire"))
    assert np.isfinite(panel.scatter.xy).all() and len(panel.scatter.xy) == 3


def test_worker_errors_are_shown_not_swallowed(qtbot, cornell_design, monkeypatch):
    shown = []
    monkeypatch.setattr(
        QtWidgets.QMessageBox, "critical", lambda *a: shown.append(a[2]) or QtWidgets.QMessageBox.Ok
    )

    def broken(self):
        raise RuntimeError("disk on fire")

    monkeypatch.setattr(RunWorker, "work", broken)
    before = cornell_design.doc.project
    assert run_and_wait(qtbot, cornell_design) == "failed"
    assert "disk on fire" in shown[0] and "Traceback" in shown[0]
    assert cornell_design.doc.project is before


@pytest.fixture
def experiment5(qtbot, window):
    project = load_project(PROJECTS / "experiment5.json")
    project = replace(
        project,
        scene=replace(project.scene, resolution=0.7),
        operator=OperatorSettings(rank=200, rays=256),
        # 9,000 in all: the sweep shares it (1,500 for each of its 6 sub-runs, as before).
        optimizer=replace(
            project.optimizer, epsilon_count=4, max_evals=9000, stall=None, divisors=(1,)
        ),
    )
    assert window.load_project(project)
    wait_for_operator(qtbot, window)
    return window


def test_pareto_browser_loads_pins_and_compares_solutions(qtbot, experiment5, tmp_path):
    win = experiment5
    assert win.doc.project.optimizer.method == "epsilon"
    assert run_and_wait(qtbot, win, timeout=180_000) == "feasible"
    panel = win.solutions_panel
    front = win.doc.project.runs[-1].pareto.solutions
    assert len(front) >= 2 and win.tabs.currentWidget() is panel
    rows = [panel.index_of(s) for s in (front[0], front[-1])]
    assert None not in rows
    # Loading a point (table row or scatter point) sets the design and relights the view.
    win.viewport.camera("top")
    assert panel.load(rows[0])
    first = image(win)
    assert win.doc.design.sources[0].rect == front[0].sources[0].rect
    panel.scatter.clicked.emit(rows[1])
    second = image(win)
    assert win.doc.shown.x == front[-1].x
    changed = np.abs(first - second).max(axis=2) > 10
    assert changed.mean() > 0.005, changed.mean()  # the lit patches change colour
    assert panel.scatter.chosen.data["x"][0] == pytest.approx(
        front[-1].objectives["min_electric_power"]
    )
    # Pin the first, compare: the view shows the difference, centred on zero.
    panel.table.selectRow(rows[0])
    panel.toggle_pin()
    assert [s.x for s in win.doc.pinned()] == [front[0].x]
    panel.load(panel.index_of(front[-1]))
    panel.difference.setChecked(True)
    lo, hi = win.viewport.plotter.actors["scene"].mapper.scalar_range
    assert lo == pytest.approx(-hi) and hi > 0
    assert win.viewport.cmap == "coolwarm"
    panel.difference.setChecked(False)
    assert win.viewport.cmap == win.view_options.cmap.currentText()
    # Pinned results and the front are saved with the project.
    path = tmp_path / "exp5.json"
    assert win.save_to(path)
    again = load_project(path)
    assert [s.x for s in again.runs[-1].pareto.solutions if s.info.pinned] == [front[0].x]
    assert len(again.runs[-1].pareto.solutions) == len(front)


def test_the_run_panel_offers_every_method_and_runs_an_nsga2_front(qtbot, experiment5, tmp_path):
    win = experiment5
    panel = win.run_panel
    names = [panel.method.itemData(i) for i in range(panel.method.count())]
    assert names == ["auto", "vns", "multilevel", "cmaes", "epsilon", "two_step", "nsga2"]
    # Choosing NSGA-II in the combo box writes it to the project; its count is the population.
    panel.method.setCurrentIndex(names.index("nsga2"))
    assert win.doc.project.optimizer.method == "nsga2"
    assert panel.runs_label.text() == "Population"
    panel.runs.setValue(24)
    assert win.doc.project.optimizer.population == 24
    assert not panel.goal.isEnabled()
    assert run_and_wait(qtbot, win, timeout=180_000) == "feasible"
    assert panel.plot.goal_plot.getPlotItem().titleLabel.text.startswith("best front hypervolume")
    curve = panel.plot.curve(0)
    assert len(curve) >= 2 and np.all(np.diff(curve[:, 1]) >= 0)  # hypervolume only rises
    front = win.doc.project.runs[-1].pareto.solutions
    assert 2 <= len(front) <= 24 and all(s.feasible for s in front)
    summary = win.solutions_panel.summary.text()
    q = win.doc.front_quality()
    assert f"front hypervolume {q.hypervolume:.4f}" in summary
    assert "on the NSGA-II front" in summary  # the method's label, not its id
    assert "(NSGA-II front: " in panel.state.text() and "nsga2" not in panel.state.text()
    win.grab().save(str(tmp_path / "nsga2-window.png"))
    win.tabs.setCurrentWidget(panel)
    panel.grab().save(str(tmp_path / "nsga2-run-panel.png"))
    # Auto on this two-goal design finds a front too (NSGA-II), and says so.
    panel.method.setCurrentIndex(names.index("auto"))
    assert panel.runs_label.text() == "Population" and not panel.goal.isEnabled()
