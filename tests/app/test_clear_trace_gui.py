"""The clear glazing's light traced off the GUI thread (issue #30, docs/daylight.md
"Control groups: switching, own targets, sensors drawn; the clear trace in a worker"),
by clicks at 1366 x 768 on the flagship office (five clear windows), meshed coarser for
a test's time.

The trace takes seconds here (about 20 s at the flagship's own resolution): to be sure
the clicks land while it runs, the test holds the build at its reflections step until
it has clicked (a ``threading.Event`` around ``clear_build._reflected``); every action
is a click. Checked: File > Open project... shows the rooms at once, the status bar's
progress and the view's veil say the trace is under way, a tab click is processed
meanwhile, the Achieved tab says its figures wait, and once the trace ends the light
grows by the glazing's daylight; Compute > Cancel during a later trace (after a
ground-reflectance edit) leaves the project as it was and says so; a trace that fails
says so in the status bar's warnings, with no traceback and no modal dialog.

Screenshots go to /tmp/shots-cleargui/."""

from __future__ import annotations

import json
import threading
from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtCore, QtWidgets

import lightinv_core.light.clear_build as clear_build
from app.window.workers import ClearLightWorker
from lightinv_core.errors import LightInvError
from tests.app import user as u

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-flagship.json"
SHOTS = Path("/tmp/shots-cleargui")


@pytest.fixture
def held(monkeypatch):
    """An event the clear build waits on at its reflections step (set: it goes on)."""
    gate = threading.Event()
    reflected = clear_build._reflected

    def wait_then_reflect(*args, **kwargs):
        assert gate.wait(120), "the test never let the trace go on"
        return reflected(*args, **kwargs)

    monkeypatch.setattr(clear_build, "_reflected", wait_then_reflect)
    yield gate
    gate.set()  # never leave a worker waiting


def coarse_flagship(tmp_path: Path) -> Path:
    data = json.loads(PROJECT.read_text(encoding="utf-8"))
    data["scene"]["resolution"] = 1.0
    data["operator"] = {"rank": 120, "rays": 128}
    path = tmp_path / "flagship.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


def tracing(win) -> bool:
    return isinstance(win.worker, ClearLightWorker)


def test_the_clear_trace_runs_in_a_worker(qtbot, window, tmp_path, held):
    window.resize(1366, 768)
    u.answer(
        lambda: u.menu(window, "File", "Open project..."), u.file_name(coarse_flagship(tmp_path))
    )
    window.activateWindow()
    QtWidgets.QApplication.processEvents()
    d = window.doc
    qtbot.waitUntil(lambda: tracing(window), timeout=120_000)  # the operator came first
    # Under way: the progress bar and the view's veil say so; the rest of the light shows.
    qtbot.waitUntil(lambda: window.progress.value() > 0, timeout=30_000)
    assert window.progress.isVisible() and window.progress.value() < 1000
    assert window.viewport.busy_text.startswith("Tracing the clear glazing's light...")
    before = d.lighting().copy()
    project = d.project
    # The window answers clicks meanwhile: the tabs change, the Achieved tab says why its
    # figures wait.
    u.tab(window, "Climate")
    assert window.tabs.currentWidget() is window.climate_panel
    u.tab(window, "Achieved")
    assert window.tabs.currentWidget() is window.achieved_panel
    summary = window.achieved_panel.summary.text()
    assert "cannot be judged yet" in summary and "being traced" in summary
    assert tracing(window)  # still held: the clicks were processed during the trace
    u.screenshot(window, SHOTS, "tracing")
    held.set()
    qtbot.waitUntil(lambda: window.worker is None, timeout=120_000)
    assert d.project is project  # the trace changed nothing in the project
    assert "Clear glazing traced in" in window.statusBar().currentMessage()
    after = d.lighting()
    assert np.all(after >= before - 1e-6) and (after - before).max() > 10.0  # lux of daylight
    assert "cannot be judged yet" not in window.achieved_panel.summary.text()
    qtbot.waitUntil(lambda: window.viewport.busy_text is None, timeout=5_000)  # veil lifted
    u.screenshot(window, SHOTS, "traced")

    # A daylight edit needs another trace; Compute > Cancel stops it.
    held.clear()
    u.tab(window, "Climate")
    ground = u.reveal(window.climate_panel.ground)
    u.type_text(ground, "0.3")
    u.press(ground, QtCore.Qt.Key_Tab)
    qtbot.waitUntil(lambda: tracing(window), timeout=30_000)
    assert d.design.daylight.ground_reflectance == pytest.approx(0.3)
    edited = d.project
    u.click(u.toolbar_button(window, "Cancel"))
    held.set()
    qtbot.waitUntil(lambda: window.worker is None, timeout=60_000)
    assert d.project is edited and d.clear_pending()  # as it was; its light left out
    assert "trace was cancelled" in window.statusBar().currentMessage()
    u.tab(window, "Achieved")
    assert "trace was cancelled" in window.achieved_panel.summary.text()
    # Compute > Precompute traces it after all.
    u.menu(window, "Compute", "Precompute")
    qtbot.waitUntil(lambda: window.worker is None and not d.clear_pending(), timeout=120_000)

    # A trace that fails: said in the status bar's warnings, no traceback, no dialog.
    def no_weather(*_a, **_k):
        raise LightInvError("the weather file went missing")

    orig = clear_build._weather
    clear_build._weather = no_weather
    try:
        u.tab(window, "Climate")
        u.type_text(ground, "0.25")
        u.press(ground, QtCore.Qt.Key_Tab)
        qtbot.waitUntil(lambda: window.worker is None and d.clear_pending(), timeout=60_000)
        qtbot.waitUntil(lambda: window.warnings_button.isVisible(), timeout=10_000)
    finally:
        clear_build._weather = orig
    warned = window.warnings_button.toolTip()
    assert "could not be traced: the weather file went missing" in warned
    assert "Traceback" not in warned and QtWidgets.QApplication.activeModalWidget() is None
