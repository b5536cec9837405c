"""EN 12464-1 editions in the window: Add work plane… offers the edition beside the
preset list (2021 for a new plane; the list follows the edition); choosing 2021 and the
office preset gives the plane 2021's grid (9 x 6 style rounding) and the 500 lux / U0
0.60 intention, and the panel shows the edition, the preset's values and the products'
Ra check. Everything by clicks on visible widgets."""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6 import QtWidgets

from lightinv_core.design.en12464 import EDITION_2011, EDITION_2021
from lightinv_core.design.model import LuminaireArray
from tests.app.conftest import wait_for_operator
from tests.app.user import answer, button, choose, click, field, ok, screenshot, tree_texts

SHOTS = Path("/tmp/shots-en12464")
pytestmark = pytest.mark.slow  # an office operator built, a dialog walked


def _preset_combo(dialog: QtWidgets.QWidget) -> QtWidgets.QComboBox:
    """The combo beside the edition: the one listing activities."""
    edition = field(dialog, "EN 12464-1")
    combos = [c for c in dialog.findChildren(QtWidgets.QComboBox) if c is not edition]
    return next(c for c in combos if c.itemText(0) == "no preset")


def test_the_work_plane_dialog_names_the_edition_and_its_presets(qtbot, window):
    assert window.new_project("office", 0.5)
    wait_for_operator(qtbot, window, timeout=120_000)
    d = window.doc
    # A product that states Ra 90 in its EULUMDAT file: the Ra check passes.
    ledvance = Path(__file__).resolve().parents[1] / "data" / "photometry"
    rect = (0.0, 0.0, *d.zone_size("lum_west"))
    lum = LuminaireArray("A1", "lum_west", str(ledvance / "ledvance-panel-600.ldt"), rect, rows=3)
    d.set_arrays((lum,))
    window.findChild(QtWidgets.QDockWidget, "luminaires").raise_()
    panel = window.luminaires_panel
    seen = {}

    def fill(dialog):
        edition = field(dialog, "EN 12464-1")
        presets = _preset_combo(dialog)
        seen["default"] = edition.currentText()
        choose(edition, EDITION_2011)
        seen["2011"] = [presets.itemText(i) for i in range(presets.count())]
        choose(edition, EDITION_2021)
        choose(presets, "Writing, typing, reading, data processing")
        seen["chosen"] = presets.currentText()
        dialog.grab().save(str(SHOTS / "workplane-dialog-2021.png"))
        ok(dialog)

    answer(lambda: click(button(panel, "Add work plane…")), fill)
    assert seen["default"] == EDITION_2021  # a new work plane follows 2021
    assert any(t.startswith("Classrooms, tutorial rooms: 300 lux") for t in seen["2011"])
    assert seen["chosen"].startswith(
        "Writing, typing, reading, data processing: 500 lux (modified 1000), U0 0.60"
    )
    (wp,) = d.design.workplanes
    assert wp.edition == EDITION_2021
    # The preset, and its UGR_L at two observers placed for it ("Add UGR limit from
    # preset", ticked by default; tests/app/test_observer_edit_gui.py).
    it, glare = d.design.intentions
    assert (glare.quantity, glare.max, len(d.design.observers)) == ("ugr", 19.0, 2)
    assert (it.grid, it.average, it.uniformity, it.scenario) == (wp.name, 500, 0.6, "night")
    # The work plane row shows its values and its edition; the status line the preset.
    table = panel.planes
    headers = [table.horizontalHeaderItem(j).text() for j in range(table.columnCount())]
    row = {h: table.item(0, j).text() for j, h in enumerate(headers)}
    assert row["EN 12464-1"] == "2021"
    assert int(row["points"]) > 20 and len(row["U0"].split(".")[1]) == 3
    status = panel.status.full_text()  # elided on screen, whole on hover
    assert "EN 12464-1:2021), Writing, typing, reading, data processing: Em 500 lux" in status
    assert "UGR_L 19, Ra 80" in status
    assert not any("Ra" in w for w in window_warnings(panel))
    assert tree_texts(window.tree, "Work planes")["wp"].endswith(", EN 12464-1:2021")
    # The panel's preset list follows the plane's edition.
    assert panel.preset.itemText(0).startswith(EDITION_2021)
    screenshot(window, SHOTS, "window-2021-office")
    # A product that states no Ra: the window warns.
    d.set_arrays((LuminaireArray("A1", "lum_west", "Panel 600 x 600 3600 lm 30 W", rect, rows=3),))
    warned = window_warnings(panel)
    assert any("states no Ra" in w and "Ra ≥ 80" in w for w in warned), warned


def window_warnings(panel) -> list[str]:
    label = panel.array_warnings
    return [w for w in label.text().split("\n") if w] if label.isVisible() else []
