"""The product's glare rating where products are chosen: the luminaires panel's catalogue
has a UGR column (CIE 190, 4H x 8H, 70/50/20, crosswise / endwise) and the array dialog
says it for the product chosen, a catalogue name or a file from disk."""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtWidgets
from PySide6.QtTest import QTest

from app.dialogs.array_dialog import ArrayDialog
from lightinv_core.luminaires import builtin_catalogue, read_photometry
from lightinv_core.luminaires.ugr_table import ugr_table
from tests.app import user as u

DATA = Path(__file__).resolve().parents[1] / "data" / "photometry"
SHOTS = Path("/tmp/lightinv-shots")


def _expected(ph) -> str:
    table = ugr_table(ph)  # the whole table, not the panel's one-room shortcut
    return f"{table.at():.1f} / {table.at(orientation='endwise'):.1f}"


def test_catalogue_lists_each_products_ugr(qtbot, window):
    u.tab(window, "Luminaires")
    table = window.luminaires_panel.catalogue
    headers = [table.horizontalHeaderItem(c).text() for c in range(table.columnCount())]
    assert headers[-1] == "UGR"
    for entry in builtin_catalogue():
        u.click_cell(table, entry.name)
        row = table.currentRow()
        cell = table.item(row, headers.index("UGR"))
        table.scrollToItem(cell)
        QTest.qWait(50)
        # On screen, as the user sees it, and the table's value.
        assert table.viewport().rect().contains(table.visualItemRect(cell).center())
        assert cell.text() == _expected(entry.photometry()), entry.name
        assert "4H x 8H" in cell.toolTip()
    SHOTS.mkdir(exist_ok=True)
    window.luminaires_panel.grab().save(str(SHOTS / "catalogue-ugr.png"))


def test_array_dialog_says_the_chosen_products_ugr(qtbot, tmp_path):
    dialog = ArrayDialog({"lum": (3.0, 3.0)}, name="A1")
    qtbot.addWidget(dialog)
    dialog.show()
    dialog.activateWindow()
    QTest.qWaitForWindowActive(dialog)
    glare = u.field(dialog, "Glare (UGR, CIE 190)")
    panel = next(e for e in builtin_catalogue() if e.name.startswith("Panel 600"))
    # The product box is editable: a click lands in its text, where the name is typed.
    u.type_text(u.field(dialog, "Product"), panel.name)
    assert dialog.product.currentText() == panel.name
    assert glare.text().startswith(_expected(panel.photometry()) + " crosswise / endwise")
    # A manufacturer's file typed in: its own rating.
    ldt = DATA / "ledvance-panel-600.ldt"
    u.type_text(u.field(dialog, "Product"), str(ldt))
    assert u.wait_for(lambda: glare.text().startswith(_expected(read_photometry(ldt))), 2000)
    SHOTS.mkdir(exist_ok=True)
    dialog.grab().save(str(SHOTS / "array-dialog-ugr.png"))
    # A file without a luminous opening: said, not a number.
    from lightinv_core.luminaires import lambertian_panel, write_photometry

    point = tmp_path / "point.ies"
    write_photometry(lambertian_panel(1000.0, watts=10.0, size_m=(0.0, 0.0, 0.0)), point)
    u.type_text(u.field(dialog, "Product"), str(point))
    assert u.wait_for(lambda: "no luminous opening" in glare.text(), 2000), dialog.summary.text()
    assert isinstance(glare, QtWidgets.QLabel)
    dialog.reject()
