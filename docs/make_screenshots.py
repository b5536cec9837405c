"""Make the window screenshots in docs/ (run under an X server: ``xvfb-run -a``).

    xvfb-run -a -s "-screen 0 1600x1200x24" .venv/bin/python docs/make_screenshots.py

- screenshot-optimisation.png: the office demo after a run, with its convergence plots;
- screenshot-pareto.png: experiment 5's epsilon-constraint front in the Solutions tab,
  a point loaded into the view;
- screenshot-violations.png: the office demo asked for 500-800 lux on the desks with a
  single small luminaire: the violations listed, the offending desk patches in red.
"""

from __future__ import annotations

import os
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

from PySide6 import QtCore, QtWidgets

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from app.window.main_window import MainWindow  # noqa: E402
from lightinv_core.design.model import Intention  # noqa: E402

PROJECTS = ROOT / "resources" / "projects"


def settle(app, win) -> None:
    while win.worker is not None or win.runs.running:
        app.processEvents(QtCore.QEventLoop.AllEvents, 50)
    for _ in range(20):
        app.processEvents()


def run(app, win) -> None:
    loop = QtCore.QEventLoop()
    win.runs.finished.connect(loop.quit)
    assert win.runs.start()
    loop.exec()
    win.runs.finished.disconnect(loop.quit)
    settle(app, win)


def shoot(win, name: str) -> None:
    win.viewport.render_now()
    win.grab().save(str(ROOT / "docs" / name))
    print("wrote", name)


def main() -> None:
    os.environ.setdefault("LIGHTINV_AUTOSAVE_DIR", tempfile.mkdtemp())
    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication([])
    settings = QtCore.QSettings(str(Path(tempfile.mkdtemp()) / "s.ini"), QtCore.QSettings.IniFormat)
    win = MainWindow(settings, autosave_seconds=3600)
    win.ask_before_discard = False
    win.resize(1400, 1000)
    win.show()

    assert win.open_path(PROJECTS / "office-demo.json")
    settle(app, win)
    run(app, win)
    win.tabs.setCurrentWidget(win.run_panel)
    shoot(win, "screenshot-optimisation.png")

    d = win.doc
    d.set_optimizer(max_evals=3000)
    for i in d.design.intentions:
        d.remove_intention(i.name)
        d.add_intention(replace(i, name="desks 500-800 lux", min=500.0, max=800.0, average=None))
    d.remove_source("L2")
    d.remove_source("S1")
    d.update_source("L1", flux_range=(0.0, 6000.0))
    d.add_intention(Intention("floor at most 300 lux", group="floor", max=300.0))
    run(app, win)
    win.viewport.camera("top")
    shoot(win, "screenshot-violations.png")

    assert win.open_path(PROJECTS / "experiment5.json")
    settle(app, win)
    run(app, win)
    panel = win.solutions_panel
    panel.load(panel.index_of(d.project.pareto.solutions[len(d.project.pareto.solutions) // 2]))
    win.viewport.camera("top")
    shoot(win, "screenshot-pareto.png")
    win.close()


if __name__ == "__main__":
    main()
