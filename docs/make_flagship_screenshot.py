"""Make the README's first screenshot: the flagship office solved, in the window at a
laptop's 1366 x 768 (run under an X server: ``xvfb-run -a``).

    .venv/bin/lightinv-cli solve resources/projects/office-flagship.json -o /tmp/flagship.json
    xvfb-run -a -s "-screen 0 1366x768x24" \
        .venv/bin/python docs/make_flagship_screenshot.py /tmp/flagship.json

Opens the solved project (its front saved by ``solve -o``), loads the front's
least-energy layout into the view and writes docs/screenshot-flagship.png.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

from PySide6 import QtCore, QtWidgets

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from app.window.main_window import MainWindow  # noqa: E402


def settle(app, win) -> None:
    while win.worker is not None or win.runs.running:
        app.processEvents(QtCore.QEventLoop.AllEvents, 50)
    for _ in range(20):
        app.processEvents()


def main() -> None:
    solved = Path(sys.argv[1])
    os.environ.setdefault("LIGHTINV_AUTOSAVE_DIR", tempfile.mkdtemp())
    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication([])
    settings = QtCore.QSettings(str(Path(tempfile.mkdtemp()) / "s.ini"), QtCore.QSettings.IniFormat)
    win = MainWindow(settings, autosave_seconds=3600)
    win.ask_before_discard = False
    win.resize(1366, 768)
    win.show()
    assert win.open_path(solved)
    settle(app, win)
    front = win.doc.project.pareto.solutions
    best = min(front, key=lambda s: s.objectives["min_annual_energy"])
    panel = win.solutions_panel
    panel.load(panel.index_of(best))
    settle(app, win)
    win.tabs.setCurrentWidget(panel)
    win.viewport.render_now()
    out = ROOT / "docs" / "screenshot-flagship.png"
    win.grab().save(str(out))
    print("wrote", out)
    win.close()


if __name__ == "__main__":
    main()
