"""A clear rooflight's size chosen by the optimiser, by clicks at 1366 x 768 (issue #30,
docs/daylight.md "Clear shapes in the optimiser"): a small project (the built-in toplit
room, its 2 x 2 m rooflight clear, centred and fixed; least glazing area with
sDA300/50% at least 50%) opened by File > Open project..., the rooflight S1 picked in
the design tree, Properties > Source > Optimise "position and size" ticked, Run; the
run's result is a smaller clear rooflight meeting the sDA bound. The light itself is
checked in tests/core/test_clear_shapes.py.

Screenshots go to /tmp/shots-clearshape/."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from PySide6 import QtWidgets

from tests.app import user as u
from tests.app.conftest import open_by_menu

pytestmark = pytest.mark.slow

SHOTS = Path("/tmp/shots-clearshape")

PROJECT = {
    "schema": 1,
    "name": "Clear rooflight, its size chosen",
    "scene": {"builtin": "toplit", "resolution": 0.5},
    "sources": [
        {
            "name": "S1",
            "zone": "rooflight",
            "kind": "skylight",
            "rect": [0, 0, 2, 2],
            "glazing": "clear",
        }
    ],
    "rules": [{"kind": "centred", "sources": ["S1"]}],
    "intentions": [{"name": "sDA", "grid": "wp", "quantity": "sda", "average": 0.5}],
    "goals": [{"kind": "min_glazing_area"}],
    "workplanes": [{"name": "wp", "height": 0.8, "border": 0.5}],
    "daylight": {"transmittance": 0.7},
    "optimizer": {"method": "cmaes", "seed": 0, "max_evals": 120, "divisors": [1]},
    "operator": {"rays": 256},
}


def test_a_clear_rooflights_size_freed_and_chosen_by_clicks(qtbot, window, tmp_path):
    path = tmp_path / "clear-shape.json"
    path.write_text(json.dumps(PROJECT))
    open_by_menu(qtbot, window, path)
    window.activateWindow()
    QtWidgets.QApplication.processEvents()
    d = window.doc
    assert d.design.source("S1").free == ()

    u.click_tree(window.tree, "S1")
    u.tab(window, "Properties")
    u.tab(window, "Source")
    props = window.findChild(QtWidgets.QDockWidget, "properties")
    glazing = u.reveal(u.field(props, "Glazing"))
    assert glazing.currentText().startswith("clear")
    boxes = {b.text(): b for b in props.findChildren(QtWidgets.QCheckBox)}
    place = u.reveal(boxes["position and size"])
    assert place.isEnabled() and not place.isChecked()
    assert not boxes["filter"].isEnabled()  # clear glazing frees its rectangle only
    u.click(place)
    assert place.isChecked()
    assert set(d.design.source("S1").free) == {"u0", "v0", "u1", "v1"}
    u.screenshot(window, SHOTS, "clear-rooflight-free")

    # Run waits for the clear glazing's trace (a worker, the status bar's progress).
    qtbot.waitUntil(lambda: window.worker is None and not d.clear_pending(), timeout=120_000)
    with qtbot.waitSignal(window.runs.finished, timeout=300_000):
        u.click(u.toolbar_button(window, "Run"))
    runs = window.doc.project.runs
    assert runs, "the run is kept"
    assert runs[-1].status == "feasible"
    best = runs[-1].solutions[0]
    s1 = next(s for s in best.sources if s.name == "S1")
    assert s1.glazing == "clear" and s1.area < 4.0  # smaller than the whole rooflight
    assert not best.violations  # sDA300/50% at least 50%, as the optimiser judged it
    shot = u.screenshot(window, SHOTS, "clear-rooflight-chosen")
    assert shot.exists()
