"""The Run tab on a 1366 x 768 laptop screen (issue #29's leftovers): Run, the method and
the goal are on screen without scrolling; a run clicked there (CMA-ES chosen in the Method
box) draws the running best's luminaire arrays in the view as the search goes; its
counters (elided to the column, the search's penalty named "search P ≈") end on the
evaluation count the core reports, the count the state line and the run history give.

The window runs on its own Xvfb screen of that size (as test_laptop_screen does); the
child writes what it saw as JSON and screenshots under /tmp/lightinv-leftovers."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from tests.app.test_laptop_screen import XVFB, inside, on_screen, whole

ROOT = Path(__file__).resolve().parents[2]
SHOTS = Path("/tmp/lightinv-leftovers")


def _count(text: str) -> int:
    """The first "12,345 evaluations" of ``text``."""
    return int(re.search(r"([\d,]+) evaluations", text).group(1).replace(",", ""))


def report(out: Path) -> None:
    """Open office-arrays.json, set the budget and click Run on the Run tab; record."""
    from PySide6 import QtCore, QtWidgets
    from PySide6.QtTest import QTest

    from lightinv_core.project import OperatorSettings, load_project
    from tests.app.test_laptop_screen import click_tab, open_window

    app, win = open_window()
    project = load_project(ROOT / "resources" / "projects" / "office-arrays.json")
    project = replace(
        project,
        scene=replace(project.scene, resolution=0.7),
        operator=OperatorSettings(rank=200, rays=256),
    )
    assert win.load_project(project)
    deadline = QtCore.QDeadlineTimer(120_000)
    while (win.worker is not None or win.doc.operator is None) and not deadline.hasExpired():
        QTest.qWait(100)
    click_tab(win, "Run")
    panel = win.run_panel
    avail = win.screen().availableGeometry()
    got: dict = {"screen": [avail.left(), avail.top(), avail.right(), avail.bottom()]}
    got["whole"] = {
        name: whole(w)
        for name, w in (
            ("Run", panel.run_button),
            ("Method", panel.method),
            ("Goal", panel.goal),
            ("state", panel.state),
            ("counters", panel.counters),
        )
    }
    got["run"] = on_screen(panel.run_button)
    dock = win.findChild(QtWidgets.QDockWidget, "optimisation")
    got["scrolled"] = dock.findChild(QtWidgets.QScrollArea).verticalScrollBar().value()
    SHOTS.mkdir(exist_ok=True)
    win.grab().save(str(SHOTS / "run-tab.png"))
    # The budget typed into its box, as a user does.
    box = panel.max_evals
    QTest.mouseClick(box, QtCore.Qt.LeftButton)
    box.lineEdit().selectAll()
    QTest.keyClicks(box, "1000")
    QTest.keyClick(box, QtCore.Qt.Key_Tab)
    got["max_evals"] = win.doc.project.optimizer.max_evals
    # CMA-ES chosen in the Method box: on a room this size ``auto`` gives its first
    # thousand evaluations to VNS, whose best layout here changes once, at the start;
    # CMA-ES's population moves the arrays' counts several times, which is what the
    # view must follow.
    from lightinv_core.optimize.registry import get_method
    from tests.app import user as u

    u.choose(panel.method, get_method("cmaes").label)
    got["method"] = win.doc.project.optimizer.method
    design_layout = [(a.rows, a.columns) for a in win.doc.design.arrays]
    live, layouts, glyphs = [], set(), set()
    ended = []
    win.runs.finished.connect(ended.append)
    QTest.mouseClick(panel.run_button, QtCore.Qt.LeftButton)
    shot = 0
    while not ended and not deadline.hasExpired():
        QTest.qWait(100)
        text = panel.counters.full_text()
        if "evaluations" in text:
            live.append(_count(text))
        # A layout: each array's counts and rectangle (a search may move the arrays
        # without changing their counts: VNS, which works first on a room this size).
        drawn = tuple(
            (a.rows, a.columns, *(round(v, 3) for v in a.rect)) for a in win.runs.preview_arrays
        )
        if drawn:
            layouts.add(drawn)
            actor = win.viewport.plotter.actors.get("luminaires")
            if actor is not None:  # the glyphs drawn: how many, and where
                mesh = actor.GetMapper().GetInput()
                box = tuple(round(v, 3) for v in mesh.GetBounds())
                glyphs.add((mesh.GetNumberOfCells(), *box))
            if shot < 2 and len(layouts) > shot:
                win.viewport.screenshot(str(SHOTS / f"running-best-{shot}.png"))
                win.grab().save(str(SHOTS / f"running-window-{shot}.png"))
                shot += 1
    QTest.qWait(300)
    win.grab().save(str(SHOTS / "run-ended.png"))
    run = win.doc.project.runs[-1]
    got.update(
        status=ended,
        design_layout=design_layout,
        layouts=sorted(layouts),
        glyph_cells=sorted(glyphs),
        live=live,
        counters=panel.counters.full_text(),
        counters_shown=panel.counters.text(),
        state=panel.state.text(),
        reported=run.evaluations,
        best_layout=[(a.rows, a.columns) for a in win.doc.design.arrays],
        counters_width=panel.counters.width(),
        column_width=panel.counters.parentWidget().width(),
    )
    out.write_text(json.dumps(got))
    win.close()
    app.processEvents()


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="needs xvfb-run (dev.sh installs it)")
def test_run_on_a_laptop_screen_shows_the_running_best_arrays_and_one_count(tmp_path):
    out = tmp_path / "run.json"
    subprocess.run(
        [*XVFB, sys.executable, "-m", "tests.app.test_leftovers_run", str(out)],
        check=True,
        timeout=600,
        cwd=ROOT,
    )
    got = json.loads(out.read_text())
    assert got["screen"] == [0, 0, 1365, 767]
    # Run, the method and the goal are whole on the screen, the dock not scrolled.
    assert all(got["whole"].values()), got["whole"]
    assert inside(got["run"], got["screen"]) and got["scrolled"] == 0, got
    assert got["max_evals"] == 1000 and got["method"] == "cmaes"
    assert got["status"] in (["feasible"], ["infeasible"]), got["status"]
    # The view drew the running best's arrays, and they changed as the search went.
    assert got["layouts"] and len(got["layouts"]) >= 2, got["layouts"]
    assert len(got["glyph_cells"]) >= 2, got["glyph_cells"]
    # One count: live never above the end's, the end's the core's, in both lines.
    assert got["live"] == sorted(got["live"]) and got["live"][-1] == got["reported"], got
    assert max(got["live"]) <= got["reported"]
    assert _count(got["counters"]) == got["reported"] == _count(got["state"].split(":")[-1])
    seconds = re.search(r"evaluations, ([\d.]+) s", got["counters"]).group(1)
    assert f"evaluations, {seconds} s)" in got["state"]  # the search's time, the core's
    assert "search P ≈" in got["counters"] and "best electric power (W)" in got["counters"]
    assert got["counters_width"] <= got["column_width"]


if __name__ == "__main__":
    report(Path(sys.argv[1]))
