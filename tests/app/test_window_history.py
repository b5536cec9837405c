"""The run history in the window: each optimisation run is kept (a new run used to replace
every earlier result), browsed one run or all at a time, deleted (and undone), saved and
reopened."""

from __future__ import annotations

import pytest

from lightinv_core.design.model import CORNERS, Intention
from lightinv_core.editing.results import ALL
from lightinv_core.project import load_project
from tests.app.conftest import wait_for_operator

pytestmark = pytest.mark.slow


def run_and_wait(qtbot, win, timeout=90_000) -> str:
    with qtbot.waitSignal(win.runs.finished, timeout=timeout) as blocker:
        assert win.runs.start()
    return blocker.args[0]


@pytest.fixture
def cornell_design(qtbot, window):
    """Cornell box with one luminaire (corners and flux free) and 'floor >= 20 lux'."""
    assert window.new_project("cornell", 0.25)
    wait_for_operator(qtbot, window)
    src = window.doc.add_source("light")
    window.doc.update_source(src.name, rect=(0.1, 0.1, 0.3, 0.3), free=(*CORNERS, "flux"))
    window.doc.add_intention(Intention("floor", group="floor", min=20.0))
    window.doc.set_optimizer(method="vns", max_evals=600, seed=0)
    return window


def rows(panel) -> list[str]:
    return [panel.table.item(r, 0).text() for r in range(panel.table.rowCount())]


def test_each_run_is_kept_browsed_deleted_and_saved(qtbot, cornell_design, tmp_path):
    win = cornell_design
    d, panel = win.doc, win.solutions_panel
    assert run_and_wait(qtbot, win) == "feasible"
    d.set_optimizer(seed=5, max_evals=900)
    assert run_and_wait(qtbot, win) == "feasible"
    assert "(run 2)" in win.run_panel.state.text()
    # Both runs are kept; the newest is browsed.
    assert [r.number for r in d.runs] == [1, 2]
    assert [r.settings.seed for r in d.runs] == [0, 5]
    assert [r.settings.max_evals for r in d.runs] == [600, 900]
    choices = [panel.run_choice.itemText(i) for i in range(panel.run_choice.count())]
    assert choices[0] == "all runs (2)"
    assert choices[1].startswith("run 2: VNS, ") and choices[2].startswith("run 1: VNS, ")
    assert panel.run_choice.currentText() == choices[1]
    assert rows(panel) == ["seed 5"] and panel.delete_run_button.isEnabled()
    assert "seed 5, at most 900 evaluations" in panel.run_info.text()
    assert "feasible" in panel.run_info.text()
    # Every run's results at once, each run's front its own line.
    assert panel.choose_run(ALL)
    assert rows(panel) == ["run 1: seed 0", "run 2: seed 5"]
    assert not panel.delete_run_button.isEnabled() and len(panel.scatter.xy) == 2
    win.tabs.setCurrentWidget(panel)
    panel.choose_run(1)
    win.grab().save("/tmp/h3-history.png")
    panel.grab().save("/tmp/h3-history-panel.png")
    assert rows(panel) == ["seed 0"] and "seed 0, at most 600 evaluations" in panel.run_info.text()
    # Loading a result of the older run puts its layout in the design.
    assert panel.load(0)
    assert d.design.sources[0].rect == d.runs[0].solutions[0].sources[0].rect
    # Delete run 1: gone, a status message, Edit > Undo brings it back.
    panel.delete_run_button.click()
    assert [r.number for r in d.runs] == [2]
    assert "Deleted run 1" in win.statusBar().currentMessage()
    assert win.act_undo.text() == "&Undo delete run 1"
    win.act_undo.trigger()
    assert [r.number for r in d.runs] == [1, 2]
    assert panel.run_choice.findData(1) >= 0
    # Saved with the project and reopened.
    path = tmp_path / "history.json"
    assert win.save_to(path)
    assert [r.number for r in load_project(path).runs] == [1, 2]
    assert win.open_path(path)
    wait_for_operator(qtbot, win)
    assert [r.seeds or (r.settings.seed,) for r in win.doc.runs] == [(0,), (5,)]
    assert panel.run_choice.count() == 3 and rows(panel) == ["run 1: seed 0", "run 2: seed 5"]


def test_undoing_an_edit_made_before_a_run_keeps_the_run(qtbot, cornell_design):
    """Undo put the whole project back: undoing an edit made before a run threw the run's
    results away."""
    win = cornell_design
    d = win.doc
    d.add_intention(Intention("walls", group="back_wall", min=1.0))
    assert run_and_wait(qtbot, win) == "feasible"
    assert len(d.runs) == 1
    win.act_undo.trigger()  # the load of the best result
    win.act_undo.trigger()  # the intention
    assert [i.name for i in d.design.intentions] == ["floor"]
    assert len(d.runs) == 1 and win.solutions_panel.table.rowCount() == 1
