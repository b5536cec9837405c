"""The window on a 1366 x 768 laptop screen (issue #29, major 3 and the docks' minor
item): it opened at 1400 x 900, so Run and the status bar were off the screen, and the
Luminaires dock was wider than its column (the arrays' Remove button cut off).

The window is started on its own Xvfb screen of that size (the test session's is
smaller), finds its size from the screen's available area, and reports where things
are on the screen; the panels are reached by clicking their tabs."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

SHOTS = Path("/tmp/lightinv-laptop")
XVFB = ("xvfb-run", "-a", "-s", "-screen 0 1366x768x24")


def on_screen(widget) -> list[int]:
    """(left, top, right, bottom) of ``widget`` in screen pixels."""
    r = widget.rect()
    tl, br = widget.mapToGlobal(r.topLeft()), widget.mapToGlobal(r.bottomRight())
    return [tl.x(), tl.y(), br.x(), br.y()]


def whole(widget) -> bool:
    """Whether all of ``widget`` is drawn (not clipped by a scroll area or the window)."""
    return widget.isVisible() and widget.visibleRegion().boundingRect().size() == widget.size()


def click_tab(window, text: str) -> None:
    """Click the tab showing ``text`` (a dock's tab or the Optimisation tabs)."""
    from PySide6 import QtCore, QtWidgets
    from PySide6.QtTest import QTest

    for bar in window.findChildren(QtWidgets.QTabBar):
        for i in range(bar.count()):
            if bar.tabText(i) == text and bar.isVisible():
                QTest.mouseClick(bar, QtCore.Qt.LeftButton, pos=bar.tabRect(i).center())
                QTest.qWait(200)
                return
    raise AssertionError(f"no tab {text!r}")


def open_window():
    """(the application, a main window shown with settings of its own) in a process
    started on its own screen (``XVFB``)."""
    from PySide6 import QtCore, QtWidgets

    from app.window.main_window import MainWindow

    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication(sys.argv[:1])
    folder = Path(tempfile.mkdtemp())
    settings = QtCore.QSettings(str(folder / "settings.ini"), QtCore.QSettings.IniFormat)
    win = MainWindow(settings)
    win.ask_before_discard = False
    win.show()
    return app, win


def report(out: Path) -> None:
    """Open the window on the office, click through its panels, write what is where."""
    from PySide6 import QtWidgets
    from PySide6.QtTest import QTest

    app, win = open_window()
    assert win.new_project("office", 0.5)
    QTest.qWait(500)
    avail, frame = win.screen().availableGeometry(), win.frameGeometry()
    got = {
        "screen": [avail.left(), avail.top(), avail.right(), avail.bottom()],
        "window": [frame.left(), frame.top(), frame.right(), frame.bottom()],
        "run": on_screen(win.run_panel.run_button),
        "status bar": on_screen(win.statusBar()),
    }
    SHOTS.mkdir(exist_ok=True)
    click_tab(win, "Luminaires")
    panel = win.luminaires_panel
    got["luminaires buttons whole"] = {
        b.text(): whole(b)
        for b in (
            panel.add_array_button,
            panel.edit_array_button,
            panel.remove_array_button,
            panel.add_plane_button,
            panel.remove_plane_button,
        )
    }
    win.grab().save(str(SHOTS / "luminaires.png"))
    click_tab(win, "Properties")
    got["properties wider than its dock"] = [
        a.horizontalScrollBar().isVisible()
        for a in win.findChild(QtWidgets.QDockWidget, "properties").findChildren(
            QtWidgets.QScrollArea
        )
    ]
    win.grab().save(str(SHOTS / "properties.png"))
    optimisation = win.findChild(QtWidgets.QDockWidget, "optimisation")
    got["tabs wider than their dock"] = {}
    for tab in ("Run", "Solutions", "Climate"):
        click_tab(win, tab)
        scroll = optimisation.findChild(QtWidgets.QScrollArea).horizontalScrollBar()
        got["tabs wider than their dock"][tab] = scroll.isVisible()
        win.grab().save(str(SHOTS / f"{tab.lower()}.png"))
    out.write_text(json.dumps(got))
    win.close()
    app.processEvents()


def inside(box: list[int], screen: list[int]) -> bool:
    return (
        screen[0] <= box[0] and screen[1] <= box[1] and box[2] <= screen[2] and box[3] <= screen[3]
    )


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="needs xvfb-run (dev.sh installs it)")
def test_the_window_fits_a_1366_x_768_screen(tmp_path):
    out = tmp_path / "laptop.json"
    subprocess.run(
        [*XVFB, sys.executable, "-m", "tests.app.test_laptop_screen", str(out)],
        check=True,
        timeout=600,
        cwd=Path(__file__).resolve().parents[2],
    )
    got = json.loads(out.read_text())
    assert got["screen"] == [0, 0, 1365, 767]
    assert inside(got["window"], got["screen"]), got
    assert inside(got["run"], got["screen"]) and inside(got["status bar"], got["screen"]), got
    assert all(got["luminaires buttons whole"].values()), got
    assert not any(got["properties wider than its dock"]), got
    assert not any(got["tabs wider than their dock"].values()), got


if __name__ == "__main__":
    report(Path(sys.argv[1]))
