"""An observer placed by clicks (Design > Add observer (glare, UGR)...): its dialog on a
1366 x 768 window, the observer and its UGR limit in the design, its marker and view
arrow in the 3D view, its UGR in the Achieved tab against the limit (CIE 117 at that
eye, the luminaires placed exactly: ``light/glare.layout_glare``)."""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6.QtCore import Qt
from PySide6.QtTest import QTest

from lightinv_core.light.glare import layout_glare
from tests.app import user as u
from tests.app.conftest import open_coarse_office

ROOT = Path(__file__).resolve().parents[2]
SHOTS = Path("/tmp/shots-ugrlimit")


@pytest.mark.slow
def test_an_observer_is_placed_by_clicks_and_its_ugr_shown(qtbot, window):
    open_coarse_office(qtbot, window)

    def fill(dialog) -> None:
        u.type_text(u.field(dialog, "Name"), "desk")
        u.type_text(u.field(dialog, "x (m)"), "6")
        u.type_text(u.field(dialog, "y (m)"), "0.6")
        u.type_text(u.field(dialog, "View azimuth (deg)"), "90")
        assert u.field(dialog, "UGR at most").isChecked()  # 19 offered, ticked
        SHOTS.mkdir(exist_ok=True)
        dialog.grab().save(str(SHOTS / "observer-dialog.png"))
        u.ok(dialog)

    titles = u.answer(lambda: u.menu(window, "Design", "Add observer (glare, UGR)..."), fill)
    assert titles == ["Observer"]
    design = window.doc.design
    (ob,) = design.observers
    assert (ob.name, ob.position, ob.height, ob.azimuth) == ("desk", (6.0, 0.6), 1.2, 90.0)
    glare = next(i for i in design.intentions if i.observers == ("desk",))
    assert glare.quantity == "ugr" and glare.max == 19.0
    # Drawn in the view: a ball at the eye and an arrow along its view.
    assert u.wait_for(lambda: "observers" in window.viewport.plotter.actors, 20_000)
    # The Achieved tab rates it: UGR at the eye against 19.
    u.tab(window, "Achieved")
    panel = window.achieved_panel

    def listed() -> bool:
        try:
            return u.table_cell(panel.table, glare.name) is not None
        except AssertionError:
            return False

    assert u.wait_for(listed, 60_000)
    want = layout_glare(window.doc.light, design, (), design.arrays)["desk"]
    row = u.table_cell(panel.table, glare.name).row()
    cells = [panel.table.item(row, c).text() for c in range(panel.table.columnCount())]
    assert "19" in cells[3] and float(cells[4]) == pytest.approx(want, abs=0.05), cells

    # A second eye, without a limit of its own; then one limit at both, from the
    # intention dialog, which offers UGR (and only UGR) for observers.
    def door(dialog) -> None:
        u.type_text(u.field(dialog, "Name"), "door")
        u.type_text(u.field(dialog, "x (m)"), "0.6")
        u.type_text(u.field(dialog, "y (m)"), "4")
        u.type_text(u.field(dialog, "View azimuth (deg)"), "0")
        tick = u.field(dialog, "UGR at most")
        u.press(tick, Qt.Key_Space)  # untick: no limit at this eye alone
        assert not tick.isChecked()
        u.ok(dialog)

    u.answer(lambda: u.menu(window, "Design", "Add observer (glare, UGR)..."), door)

    def limit(dialog) -> None:
        assert "UGR" in dialog.quantity.currentText() and not dialog.scenario.isEnabled()
        u.type_text(u.field(dialog, "Name"), "glare both")
        assert dialog.fields["max"][0].isChecked() and not dialog.fields["average"][0].isChecked()
        u.type_text(dialog.fields["max"][1], "22")
        dialog.grab().save(str(SHOTS / "ugr-intention-dialog.png"))
        u.ok(dialog)

    u.answer(lambda: u.menu(window, "Design", "Add UGR limit at the observers..."), limit)
    both = window.doc.design.intentions[-1]
    assert (both.name, both.observers, both.max) == ("glare both", ("desk", "door"), 22.0)
    assert [o.name for o in window.doc.design.observers] == ["desk", "door"]
    assert [i.name for i in window.doc.design.intentions] == ["filing", "glare desk", "glare both"]
    assert u.tree_texts(window.tree, "Observers")["door"].startswith("(0.6, 4), eye 1.2 m")
    QTest.qWait(200)
    u.screenshot(window, SHOTS, "observer-window")
