"""Opening a project lays out its light off the GUI thread, and Compute > Cancel stops
the clear trace inside its reflections (issue #30, docs/daylight.md "Opening and
cancelling without freezing (issue #30)"), by clicks at 1366 x 768 on the flagship office
(five clear windows, two luminaire arrays, a work plane), meshed coarser for a test's
time.

To be sure the clicks land while the work runs, the test holds it: the layout at its
work-plane grids (in the worker's thread only) and the clear trace at its second block
of reflected columns, each on a ``threading.Event`` the test sets once it has clicked.
Checked: File > Open project... returns with the model in the view and the layout
still held; a menu opens meanwhile and Compute > Run optimisation is refused in the
status bar and the run panel, without a dialog; neither the grids nor the arrays' light
is made on the GUI thread; once the layout is let go the operator and the light arrive;
Compute > Cancel during the trace's reflections stops it after the block under way (not
at the end of the step), leaving the project as it was.

Screenshots go to /tmp/shots-openasync/."""

from __future__ import annotations

import json
import threading
from pathlib import Path

import pytest
from PySide6 import QtWidgets

import lightinv_core.editing.lighting as lighting
import lightinv_core.light.clear_build as clear_build
import lightinv_core.light.grids as grids
from app.window.workers import ClearLightWorker, PrecomputeWorker
from tests.app import user as u

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-flagship.json"
SHOTS = Path("/tmp/shots-openasync")


def coarse_flagship(tmp_path: Path) -> Path:
    data = json.loads(PROJECT.read_text(encoding="utf-8"))
    data["scene"]["resolution"] = 1.0
    data["operator"] = {"rank": 120, "rays": 128}
    path = tmp_path / "flagship.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


class Held:
    """The gates and what ran on which thread."""

    def __init__(self) -> None:
        self.layout = threading.Event()  # set: the layout's grids go on
        self.trace = threading.Event()  # set: the trace's second reflections block goes on
        self.reflected = 0  # reflection blocks started
        self.on_gui_thread: list[str] = []  # heavy work found on the GUI thread


@pytest.fixture
def held(monkeypatch):
    h = Held()
    gui = threading.main_thread()
    receivers, reflected = grids.design_receivers, clear_build._reflected
    made, placed = grids._design_grids, lighting.arrays_field

    def held_receivers(light, design):
        if threading.current_thread() is not gui:
            assert h.layout.wait(120), "the test never let the layout go on"
        return receivers(light, design)

    def held_reflected(*args, **kwargs):
        h.reflected += 1
        if h.reflected == 2:
            assert h.trace.wait(120), "the test never let the trace go on"
        return reflected(*args, **kwargs)

    def noted(name, f):
        def run(*args, **kwargs):
            if threading.current_thread() is gui:
                h.on_gui_thread.append(name)
            return f(*args, **kwargs)

        return run

    monkeypatch.setattr(grids, "design_receivers", held_receivers)
    monkeypatch.setattr(grids, "_design_grids", noted("grids", made))
    monkeypatch.setattr(lighting, "arrays_field", noted("arrays", placed))
    monkeypatch.setattr(clear_build, "_reflected", held_reflected)
    # Four blocks of reflected columns on this coarse mesh (two at the default's size).
    monkeypatch.setattr(clear_build, "REFLECT_WORK", 8e7)
    yield h
    h.layout.set()  # never leave a worker waiting
    h.trace.set()


def laying_out(win) -> bool:
    w = win.worker
    return isinstance(w, PrecomputeWorker) and w.phase == "layout"


def test_open_lays_out_in_a_worker_and_cancel_stops_the_reflections(qtbot, window, tmp_path, held):
    window.resize(1366, 768)
    d = window.doc
    # File > Open returns while the layout is still held: it is not on this thread.
    u.answer(
        lambda: u.menu(window, "File", "Open project..."), u.file_name(coarse_flagship(tmp_path))
    )
    window.activateWindow()
    assert d.project is not None and d.project.design.arrays
    qtbot.waitUntil(lambda: laying_out(window), timeout=60_000)  # the operator came first
    assert d.operator is None and not held.layout.is_set()
    assert window.viewport.mesh is not None and window.viewport.mesh.n_cells > 0
    qtbot.waitUntil(
        lambda: (window.viewport.busy_text or "").startswith("Laying out the light"),
        timeout=10_000,
    )
    assert "Laying out the light" in window.statusBar().currentMessage()
    # A menu opens meanwhile; Run is refused with words, not a dialog (``answer`` with no
    # responses fails on any dialog shown).
    u.answer(lambda: u.menu(window, "Compute", "Run optimisation"))
    said = window.statusBar().currentMessage()
    assert said.startswith("Wait for the light being laid out"), said
    assert "laid out" in window.run_panel.state.text()
    assert QtWidgets.QApplication.activeModalWidget() is None
    assert laying_out(window) and d.operator is None  # still held: all that happened meanwhile
    u.screenshot(window, SHOTS, "laying-out")

    held.layout.set()
    qtbot.waitUntil(lambda: d.operator is not None, timeout=60_000)
    assert d.field is not None and d.grid_stats()  # lit, its work plane's figures there
    assert held.on_gui_thread == [], held.on_gui_thread  # grids and arrays made in the worker

    # The clear trace follows; Compute > Cancel while its reflections run.
    qtbot.waitUntil(lambda: held.reflected >= 2, timeout=120_000)
    assert isinstance(window.worker, ClearLightWorker)
    assert "laid out" not in window.run_panel.state.text()  # the refusal's words went
    project = d.project
    u.screenshot(window, SHOTS, "tracing")
    u.menu(window, "Compute", "Cancel")
    held.trace.set()
    qtbot.waitUntil(lambda: window.worker is None, timeout=60_000)
    # Stopped at the next block, not after the step's four: the cancel was checked inside.
    assert held.reflected == 2
    assert d.project is project and d.clear_pending()  # as it was; its light left out
    assert "trace was cancelled" in window.statusBar().currentMessage()
    assert QtWidgets.QApplication.activeModalWidget() is None
    u.screenshot(window, SHOTS, "cancelled")


def test_the_light_laid_out_in_a_worker_is_the_light_the_document_makes(tmp_path):
    """``lay_out`` (the worker's) handed to ``set_operator`` gives the light the document
    makes itself, and its light in every scenario is kept; a layout made on another
    operator is not taken. The flagship's arrays and intentions without its clear
    windows (so the light in every scenario is made on opening)."""
    import copy

    import numpy as np

    from app.window.workers import lay_out
    from lightinv_core.editing import DocumentModel
    from lightinv_core.operator.build import build_operator
    from lightinv_core.operator.settings import OperatorSettings

    data = json.loads(coarse_flagship(tmp_path).read_text(encoding="utf-8"))
    data["sources"] = []
    path = tmp_path / "arrays-only.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    docs = []
    for _ in range(2):
        doc = DocumentModel()
        doc.clear_elsewhere = True  # as the window
        doc.open(path)
        docs.append(doc)
    laid, itself = docs
    op = build_operator(laid.patches, OperatorSettings(rank=120, rays=128, seed=0))
    steps: list[float] = []
    shown, daylight = lay_out(laid.scene, laid.patches, op, laid.design, steps.append)
    assert daylight is not None and steps == sorted(steps) and steps[-1] == 1.0
    laid.set_operator(op, shown=shown, daylight=daylight)
    assert laid.light is shown.model and laid.layout_daylight() is daylight
    itself.set_operator(op)
    assert itself.light is not shown.model
    np.testing.assert_allclose(laid.lighting(), itself.lighting(), rtol=1e-12, atol=1e-9)
    for name, stats in itself.grid_stats().items():
        assert laid.grid_stats()[name] == pytest.approx(stats, rel=1e-12)
    assert laid.grid_stats()["work plane"]["Em"] > 100.0
    # Made on another operator (another object, the same matrices): not taken.
    other = copy.copy(op)
    itself.set_operator(other, shown=shown, daylight=daylight)
    assert itself.light is not shown.model and itself.light.op is other


def test_a_layout_that_fails_is_said_in_the_status_bar(qtbot, window, tmp_path, monkeypatch):
    """A layout that fails in the worker (here its grids, in the worker's thread only)
    is said in the status bar, not in a dialog, and the window lights the design itself.
    The flagship without its clear windows (no trace follows)."""
    from lightinv_core.errors import LightInvError

    data = json.loads(coarse_flagship(tmp_path).read_text(encoding="utf-8"))
    data["sources"] = []
    path = tmp_path / "arrays-only.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    gui, receivers = threading.main_thread(), grids.design_receivers

    def failing(light, design):
        if threading.current_thread() is not gui:
            raise LightInvError("the test's failure")
        return receivers(light, design)

    monkeypatch.setattr(grids, "design_receivers", failing)
    window.resize(1366, 768)
    u.answer(lambda: u.menu(window, "File", "Open project..."), u.file_name(path))
    qtbot.waitUntil(
        lambda: window.worker is None and window.doc.operator is not None, timeout=120_000
    )
    said = window.statusBar().currentMessage()
    assert "could not be laid out in the background: the test's failure" in said, said
    assert QtWidgets.QApplication.activeModalWidget() is None
    assert window.doc.field is not None and window.doc.grid_stats()["work plane"]["Em"] > 100.0
