"""EN 17037 daylight provision set by clicks (issue #30): the integrated office opened by
File > Open project... (its path typed into the file dialog); its work plane "wp"
double-clicked in the design tree opens the intention dialog on the plane, where
"EN 17037 daylight provision" offers a level list instead of the bounds: "medium", OK.
View > Colour by then offers the per-point share of the daylight hours with 300 lux or
more, which the view paints as the core computes it. The light itself is checked in
tests/core/test_en17037_design.py."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtWidgets
from PySide6.QtCore import Qt

from tests.app import user as u
from tests.app.conftest import open_by_menu

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-integrated.json"
SHOTS = Path("/tmp/shots-en17037")


def _shown(window) -> np.ndarray:
    """The values the view paints per patch (one triangle of each)."""
    vp = window.viewport
    values = np.zeros(window.doc.patches.n, np.float32)
    values[vp.tri_patch] = vp.mesh.cell_data["value"]
    return values


@pytest.mark.slow
def test_en17037_provision_at_least_medium_by_clicks(qtbot, window, tmp_path):
    path = tmp_path / "office.json"
    shutil.copy(PROJECT, path)
    open_by_menu(qtbot, window, path)
    d = window.doc

    def as_en17037(dialog: QtWidgets.QWidget) -> None:
        u.type_text(u.field(dialog, "Name"), "EN 17037")
        u.choose(u.field(dialog, "Quantity"), "EN 17037 daylight provision")
        # The bounds give way to a level list (its min).
        for label in ("Minimum", "Maximum", "Average at least"):
            with pytest.raises(AssertionError):
                u.field(dialog, label)
        u.choose(u.field(dialog, "Level at least"), "medium")
        u.screenshot(dialog, SHOTS, "intention-dialog-en17037")
        u.ok(dialog)

    u.click_tree(window.tree, "wp")
    item = u.tree_item(window.tree, "wp")
    rect = window.tree.visualItemRect(item)
    u.answer(lambda: u.double_click(window.tree.viewport(), rect.center()), as_en17037)
    (it,) = [i for i in d.design.intentions if i.quantity == "en17037"]
    assert (it.name, it.grid, it.min, it.scenario) == ("EN 17037", "wp", 2.0, "annual")
    assert it.max is None and it.average is None and it.uniformity is None

    # Its value in the Achieved tab: the score with the level's name.
    u.tab(window, "Achieved")
    table = window.achieved_panel.findChild(QtWidgets.QTableWidget)
    levels = ("none", "minimum", "medium", "high")
    assert u.wait_for(lambda: any(
        table.item(r, c) is not None and table.item(r, c).text().endswith(")")
        and table.item(r, c).text().split("(")[-1].rstrip(")") in levels
        for r in range(table.rowCount()) for c in range(4, 5)
    ), 60_000)  # fmt: skip
    assert u.table_cell(table, "2.00 (medium)")  # the level required
    u.screenshot(window, SHOTS, "achieved-en17037")

    # The per-point map of the daylight hours with 300 lux (E_T of the minimum level).
    u.tab(window, "Properties")
    u.tab(window, "Materials and view")
    colour = u.reveal(window.view_options.colour_by)
    u.choose(colour, "EN 17037: share of the daylight hours with 300 lux")
    assert colour.currentData() == "en17037_300"
    ld = d.layout_daylight(shown=True)
    want = 100.0 * ld.patches.en17037_reach(slice(None), 300.0)[:, 0]
    assert u.wait_for(lambda: np.allclose(_shown(window), want, rtol=1e-5, atol=1e-3), 60_000)
    assert 0.0 < want.max() <= 100.0
    assert "daylight hours" in window.viewport.caption
    u.screenshot(window, SHOTS, "map-en17037-300")

    # Climate > Provision basis: the hours reading; the Achieved tab rates it on that
    # basis (the layout's own figure), and Edit > Undo takes it back.
    u.tab(window, "Climate")
    basis = u.reveal(u.field(window.climate_panel, "Provision basis"))
    u.choose(basis, "hours: each hour")
    assert d.design.daylight.en17037_basis == "hours"
    (it,) = [i for i in d.design.intentions if i.quantity == "en17037"]
    score = d.layout_daylight().quantity(it)[0][0]
    u.tab(window, "Achieved")
    level = ("none", "minimum", "medium", "high")[min(int(score), 3)]
    shown = f"{score:.2f} ({level})"
    assert u.wait_for(lambda: any(
        table.item(r, 4) is not None and table.item(r, 4).text() == shown
        for r in range(table.rowCount())
    ), 60_000), shown  # fmt: skip
    # The DGP limit typed beside it (the glare intentions' threshold).
    u.tab(window, "Climate")
    limit = u.reveal(u.field(window.climate_panel, "DGP limit"))
    u.type_text(limit, "0.35")
    u.press(limit, Qt.Key_Return)
    assert d.design.daylight.dgp_limit == pytest.approx(0.35)
    u.screenshot(window, SHOTS, "climate-basis-dgp")
    u.menu(window, "Edit", "Undo climate: dgp_limit")
    u.menu(window, "Edit", "Undo climate: en17037_basis")
    assert d.design.daylight.en17037_basis == "points" and basis.currentData() == "points"
    assert d.design.daylight.dgp_limit == pytest.approx(0.40)


@pytest.mark.slow
def test_en17037_sunlight_at_an_eye_waits_for_the_sites_altitude(qtbot, window, tmp_path):
    """An observer and a sunlight intention at it (Design menu); the Achieved tab says
    the site's least solar altitude is missing until it is typed in the Climate tab,
    then rates the hours of sun; the day and the altitude are saved with the project."""
    path = tmp_path / "office.json"
    shutil.copy(PROJECT, path)
    open_by_menu(qtbot, window, path)

    def eye(dialog: QtWidgets.QWidget) -> None:
        u.type_text(u.field(dialog, "Name"), "desk")
        u.type_text(u.field(dialog, "x (m)"), "4")
        u.type_text(u.field(dialog, "y (m)"), "3")
        tick = u.field(dialog, "UGR at most")
        u.press(tick, Qt.Key_Space)  # no glare limit: only the sun is asked for here
        assert not tick.isChecked()
        u.ok(dialog)

    u.answer(lambda: u.menu(window, "Design", "Add observer (glare, UGR)..."), eye)

    def sun(dialog: QtWidgets.QWidget) -> None:
        u.choose(u.field(dialog, "Quantity"), "EN 17037 sunlight exposure")
        u.type_text(u.field(dialog, "Name"), "sun at desk")
        u.choose(u.field(dialog, "Level at least"), "minimum")
        u.ok(dialog)

    u.answer(lambda: u.menu(window, "Design", "Add UGR limit at the observers..."), sun)
    u.tab(window, "Achieved")
    panel = window.achieved_panel

    def row() -> list[str]:
        try:
            r = u.table_cell(panel.table, "sun at desk").row()
        except AssertionError:
            return []
        return [panel.table.item(r, c).text() for c in range(panel.table.columnCount())]

    listed = u.wait_for(lambda: bool(row()), 60_000)
    u.screenshot(window, SHOTS, "sunlight-achieved")
    assert listed, [i.name for i in window.doc.design.intentions]
    # No altitude yet: nothing is rated, and the window says what is missing.
    assert u.wait_for(lambda: "altitude" in " ".join(row()) + panel_text(panel), 60_000), row()
    u.screenshot(window, SHOTS, "sunlight-no-altitude")

    u.tab(window, "Climate")
    altitude = u.reveal(u.field(window.climate_panel, "Sun counts above"))
    assert altitude.text() == "not set"
    u.type_text(altitude, "12")
    u.press(altitude, Qt.Key_Return)
    u.choose(u.field(window.climate_panel, "Sunlight day"), "1 March")
    u.screenshot(window, SHOTS, "climate-sunlight-fields")
    u.tab(window, "Achieved")
    assert u.wait_for(lambda: any(c.endswith(" h") or "(" in c for c in row()[4:5]), 60_000), row()
    u.screenshot(window, SHOTS, "sunlight-rated")

    u.menu(window, "File", "Save")
    saved = json.loads(path.read_text())["daylight"]
    assert saved["sunlight_min_altitude"] == 12.0 and saved["sunlight_date"] == "03-01"


def panel_text(panel: QtWidgets.QWidget) -> str:
    """Every label's text in ``panel`` (where the Achieved tab writes its messages)."""
    return " ".join(lab.text() for lab in panel.findChildren(QtWidgets.QLabel))
