"""The Luminaires tab's leftovers of issue #29, clicked as a user does: a second array
added with the defaults goes in a free zone (a third, with none left, is said to overlap),
the arrays table names the product (name and catalogue number; an IES file's description
in the tooltip), and each desk figure says what light it is: the work-plane values the
design scenario, an EN 12464-1 preset and the Achieved tab the night it is judged in."""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from tests.app.conftest import wait_for_operator
from tests.app.test_dialog_buttons import answer, button
from tests.app.test_laptop_screen import click_tab

IES = Path(__file__).resolve().parents[1] / "data" / "photometry" / "rab-square-1.ies"
SHOTS = Path("/tmp/lightinv-leftovers")


def add_array(window, respond) -> dict:
    """Click Add array… and answer its dialog with ``respond(dialog)``."""
    add = button(window.luminaires_panel, "Add array…")
    return answer(lambda: QTest.mouseClick(add, QtCore.Qt.LeftButton), respond)


def look_then_ok(seen: list):
    def respond(dialog):
        seen.append((dialog.zone.currentText(), dialog.summary.text()))
        QTest.mouseClick(button(dialog, "OK"), QtCore.Qt.LeftButton)

    return respond


def pick(combo: QtWidgets.QComboBox, text_start: str) -> None:
    """Open ``combo``'s list by a click and click the entry starting with ``text_start``."""
    QTest.mouseClick(combo, QtCore.Qt.LeftButton)
    view = combo.view()
    QTest.qWait(200)
    assert view.isVisible(), "the list did not open"
    row = next(i for i in range(combo.count()) if combo.itemText(i).startswith(text_start))
    index = combo.model().index(row, 0)
    # Down to the entry with the arrow keys, then Enter, as on a keyboard.
    for _ in range(row - view.currentIndex().row()):
        QTest.keyClick(view, QtCore.Qt.Key_Down)
    assert view.currentIndex() == index
    QTest.keyClick(view, QtCore.Qt.Key_Return)
    QTest.qWait(200)


def test_arrays_go_in_free_zones_name_their_product_and_figures_their_scenario(
    qtbot, window, monkeypatch
):
    assert window.new_project("office", 0.5)
    wait_for_operator(qtbot, window)
    d, panel = window.doc, window.luminaires_panel
    click_tab(window, "Luminaires")
    seen: list = []
    add_array(window, look_then_ok(seen))
    add_array(window, look_then_ok(seen))
    # The second array, with the defaults, went in the zone the first left free.
    assert [a.zone for a in d.design.arrays] == ["lum_west", "lum_east"]
    assert not any("overlaps" in summary for _, summary in seen)
    # A third, with every zone taken: the dialog says it overlaps (OK still adds it). Its
    # product is an IES file chosen with File… (the file chooser answered here).
    monkeypatch.setattr("app.dialogs.ask.open_file", lambda *a, **k: str(IES))

    def ies_then_ok(dialog):
        QTest.mouseClick(button(dialog, "File…"), QtCore.Qt.LeftButton)
        seen.append((dialog.zone.currentText(), dialog.summary.text()))
        dialog.grab().save(str(SHOTS / "overlap-dialog.png"))
        QTest.mouseClick(button(dialog, "OK"), QtCore.Qt.LeftButton)

    SHOTS.mkdir(exist_ok=True)
    add_array(window, ies_then_ok)
    zone, summary = seen[-1]
    assert zone == "lum_west" and "overlaps array A1 in zone lum_west" in summary
    # The table: the catalogue product's name with its number, the file's maker and
    # number; the IES file's description is the tooltip, not the cell.
    column = [panel.arrays.horizontalHeaderItem(c).text() for c in range(8)].index("product")
    cells = [panel.arrays.item(r, column) for r in range(3)]
    first = d.design.arrays[0].product
    assert cells[0].text() == f"{first} (LI-DL-2000)" == "Downlight 2000 lm 20 W (LI-DL-2000)"
    assert cells[2].text() == "RAB LIGHTING INC. PRT70/480, PRT70/480/D10"
    assert "FROSTED TRANSLUCENT" in cells[2].toolTip() and "rab-square-1.ies" in cells[2].toolTip()
    assert "FROSTED" not in cells[2].text()
    # A work plane (its dialog's OK) and a preset from the list, clicked.
    plane = button(panel, "Add work plane…")
    answer(
        lambda: QTest.mouseClick(plane, QtCore.Qt.LeftButton),
        lambda dialog: QTest.mouseClick(button(dialog, "OK"), QtCore.Qt.LeftButton),
    )
    assert [w.name for w in d.design.workplanes] == ["wp"]
    placeholder = panel.preset.itemText(0)
    # A new work plane follows EN 12464-1:2021: the list is that edition's.
    assert placeholder == "EN 12464-1:2021 intention (night: luminaires only)…"
    pick(panel.preset, "Filing")
    (preset,) = [i for i in d.design.intentions if i.grid == "wp"]
    assert str(preset.scenario) == "night"
    # The work-plane values say their scenario: the design one, with its daylight.
    em = d.grid_stats()["wp"]["Em"]
    assert panel.planes.item(0, 3).text() == f"{em:.0f}"
    note = panel.status.full_text()
    assert note.startswith("Em, Emin, Emax, U0 in the design scenario: luminaires plus daylight")
    assert "3 luminaires in 3 arrays." in note or "luminaires in 3 arrays" in note
    window.grab().save(str(SHOTS / "luminaires-window.png"))
    panel.grab().save(str(SHOTS / "luminaires-panel.png"))
    # The Achieved tab: the preset's Em judged at night, so named; the note says why it
    # differs from the table's Em.
    click_tab(window, "Achieved")
    achieved = window.achieved_panel
    headers = [achieved.table.horizontalHeaderItem(c).text() for c in range(7)]
    assert "achieved (in night)" in headers
    row = next(r for r in achieved.rows() if r.intention == preset.name and "average" in r.bound)
    # The office has no skylight yet: night and design light agree here, to the digit.
    assert row.scenario == "night" and float(row.achieved.replace(",", "")) == round(em, 1)
    text = achieved.summary.text()
    assert "night: luminaires only" in text and "show the design scenario" in text
    window.grab().save(str(SHOTS / "achieved-window.png"))
