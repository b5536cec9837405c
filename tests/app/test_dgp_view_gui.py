"""Simplified DGP shown on the observers in the 3D view, by clicks at 1366 x 768 (issue #30
item 6, docs/daylight.md "DGP in the view; dragging sensors"): the side-lit room with a
clear south window and two observers (one by the window looking at it, one at the back)
opened by File > Open project...; View > Colour by "glare at the observers: simplified
DGP (% of occupied hours above the limit)" colours each observer's glyph by its share of
the occupied hours above DGPs 0.40, with a colour bar of its own and a label per eye,
without any DGP intention; "EN 17037 glare protection (level)" colours them by level.
The values are the core's (``light.dgp_observers.observer_dgp``, itself checked against
Radiance in tests/core/test_dgp_observers.py). ASE and EN 17037's provision maps are in
the same list on this clear-glazed room and colour the patches.

Screenshots go to /tmp/shots-dgpview/."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtWidgets
from PySide6.QtTest import QTest

from app.view import observer_overlay
from app.view.observer_maps import LEVEL_COLOURS, LEVELS
from lightinv_core.light.dgp_observers import observer_dgp
from tests.app import user as u
from tests.app.conftest import open_by_menu
from tests.app.test_dgp_gui import sidelit_project

SHOTS = Path("/tmp/shots-dgpview")


def _glyph_values(window) -> dict[float, int]:
    """{value: points} the observers' glyphs carry (each glyph its observer's value)."""
    mapper = window.viewport.plotter.actors[observer_overlay.NAME].mapper
    mapper.Update()  # its input is a pipeline's output, brought up to date by a render
    mesh = mapper.dataset
    values, counts = np.unique(np.asarray(mesh.point_data["value"]), return_counts=True)
    return dict(zip(values.tolist(), counts.tolist(), strict=True))


def _choose(box: QtWidgets.QComboBox, text: str) -> None:
    """Colour by ``text``, chosen from the list by clicks; a while after the last choice
    (a click on the box just after its list closed does not open it again)."""
    QTest.qWait(QtWidgets.QApplication.doubleClickInterval() + 200)
    u.choose(box, text)
    assert box.currentText() == text


def _rgb(lut, value: float) -> np.ndarray:
    out = [0.0, 0.0, 0.0]
    lut.GetColor(value, out)
    return np.array(out)


def _label_texts(window) -> list[str]:
    actor = window.viewport.plotter.actors[f"{observer_overlay.LABELS}-labels"]
    hierarchy = actor.GetMapper().GetInputAlgorithm()  # the labels' points and texts
    points = hierarchy.GetInputDataObject(0, 0)
    labels = points.GetPointData().GetAbstractArray(hierarchy.GetLabelArrayName())
    return [labels.GetValue(i) for i in range(labels.GetNumberOfValues())]


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_dgp_coloured_on_the_observers_by_clicks(qtbot, window, tmp_path):
    path = tmp_path / "sidelit.json"
    sidelit_project(path)
    open_by_menu(qtbot, window, path)
    d = window.doc
    assert not d.design.intentions  # no DGP intention: the map needs none
    want = observer_dgp(d.light, d.design)
    near, back = want["by the window"], want["at the back"]
    assert near["exceedance"] > 0.05 and back["exceedance"] == 0.0  # a contrast to see

    u.tab(window, "Properties")  # the dock's tab (Luminaires shares its column)
    u.tab(window, "Materials and view")
    box = window.view_options.colour_by
    u.reveal(box)
    entries = [box.itemText(i) for i in range(box.count())]
    _choose(box, "glare at the observers: simplified DGP (% of occupied hours above the limit)")
    vp = window.viewport
    assert u.wait_for(lambda: observer_overlay.BAR in vp.plotter.actors, 60_000)
    # Each glyph in its observer's colour: its share of the hours, in %.
    got = _glyph_values(window)
    assert sorted(got) == pytest.approx(sorted([100 * near["exceedance"], 0.0]))
    texts = _label_texts(window)
    assert f"by the window: {100 * near['exceedance']:.1f}% > 0.40, none" in texts
    assert "at the back: 0.0% > 0.40, high" in texts
    assert "DGPs above 0.40" in vp.caption and f"{near['hours']:,} occupied hours" in vp.caption
    assert not vp.has_values  # the surfaces in their materials, the observers coloured
    bar = vp.plotter.actors[observer_overlay.BAR]
    assert bar.GetVisibility() and bar.GetTitle().startswith("DGPs > 0.40")
    # The glyph by the window is drawn red-ish (above 5%), the one at the back green.
    lut = bar.GetLookupTable()
    red = _rgb(lut, 100 * near["exceedance"])
    green = _rgb(lut, 0.0)
    assert red[0] > red[1] and green[1] > green[0]
    u.menu(window, "View", "Top view")
    QTest.qWait(300)
    u.screenshot(window, SHOTS, "dgp-share-on-observers")

    # The EN 17037 glare protection level: one colour per level, named on the bar.
    _choose(box, "glare at the observers: EN 17037 glare protection (level)")
    assert u.wait_for(lambda: "EN 17037" in (vp.caption or ""), 30_000)
    got = _glyph_values(window)
    assert sorted(got) == [LEVELS.index("none"), LEVELS.index("high")]
    lut = vp.plotter.actors[observer_overlay.BAR].GetLookupTable()
    assert lut.GetNumberOfAnnotatedValues() == 4
    rgb = [int(LEVEL_COLOURS[3][i : i + 2], 16) / 255 for i in (1, 3, 5)]
    assert np.allclose(_rgb(lut, 3.0), rgb, atol=0.01)  # "high" in green
    u.screenshot(window, SHOTS, "dgp-level-on-observers")

    # ASE and EN 17037's provision are in the list on this clear-glazed room and colour
    # the patches (ASE1000,250 reaches 100% by the window: the sun falls there).
    ase = next(t for t in entries if "ASE1000,250" in t)
    assert ase.endswith("(100 % where a point counts)")
    assert any(t.startswith("EN 17037: share of the daylight hours with 300 lux") for t in entries)
    _choose(box, ase)
    assert u.wait_for(lambda: vp.has_values and "ASE1000,250" in (vp.caption or ""), 60_000)
    assert observer_overlay.BAR not in vp.plotter.actors  # plain observers again
    assert float(vp.mesh.cell_data["value"].max()) == pytest.approx(100.0)
    _choose(box, next(t for t in entries if "300 lux or more" in t))
    assert u.wait_for(lambda: "EN 17037" in (vp.caption or ""), 60_000)
    assert vp.has_values and float(vp.mesh.cell_data["value"].max()) > 50.0
    u.screenshot(window, SHOTS, "en17037-300-map")

    # Back to the level map: a pick keeps the colours (the one picked in a green cage).
    _choose(box, "glare at the observers: EN 17037 glare protection (level)")
    assert u.wait_for(lambda: observer_overlay.BAR in vp.plotter.actors, 30_000)
    u.click(u.toolbar_button(window, "Move"))
    eye = np.array([3.0, 7.0, 1.2])
    u.view_click(vp, eye)
    assert u.wait_for(lambda: observer_overlay.CURRENT in vp.plotter.actors, 5_000)
    assert observer_overlay.BAR in vp.plotter.actors and sorted(_glyph_values(window)) == [0, 3]
