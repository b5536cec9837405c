"""A GLDF product brought in by clicks (docs/photometry.md, "GLDF"): Add array…, File…,
the .gldf chosen in the file dialog; its variants become the product box's choices,
the dialog names the product, and after OK the catalogue lists each variant with its
flux, power, glare rating and polar curve."""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtWidgets
from PySide6.QtTest import QTest

from lightinv_core.luminaires import read_photometry
from lightinv_core.luminaires.ugr_table import ugr_table
from tests.app import user as u
from tests.core.gldf_variants import with_second_variant

DATA = Path(__file__).resolve().parents[1] / "data" / "gldf"
SHOTS = Path("/tmp/shots-gldf")


def test_a_gldf_file_chosen_in_the_array_dialog_joins_the_catalogue(qtbot, window, tmp_path):
    gldf = with_second_variant(DATA / "zumtobel-p-evo-r100l.gldf", tmp_path / "p-evo.gldf")
    assert window.new_project("office", 0.5)
    window.findChild(QtWidgets.QDockWidget, "luminaires").raise_()
    panel = window.luminaires_panel
    SHOTS.mkdir(exist_ok=True)
    seen: dict = {}

    def choose_the_file_then_ok(dialog):
        u.answer(lambda: u.click(u.button(dialog, "File…")), u.file_name(gldf))
        box = u.field(dialog, "Product")
        seen["choices"] = [box.itemText(i) for i in range(box.count())]
        seen["chosen"] = box.currentText()
        assert u.wait_for(lambda: "P-EVO R100L" in dialog.summary.text(), 5000)
        seen["summary"] = dialog.summary.text()
        seen["glare"] = u.field(dialog, "Glare (UGR, CIE 190)").text()
        dialog.grab().save(str(SHOTS / "array-dialog-gldf.png"))
        u.ok(dialog)

    u.answer(lambda: u.click(u.button(panel, "Add array…")), choose_the_file_then_ok)
    first, second = f"{gldf}#variant1", f"{gldf}#variant2"
    assert seen["chosen"] == first
    assert {first, second} <= set(seen["choices"])
    ph = read_photometry(first)
    table = ugr_table(ph)
    rating = f"{table.at():.1f} / {table.at(orientation='endwise'):.1f}"
    assert seen["glare"].startswith(rating), seen["glare"]

    # The array is the GLDF's first variant, and the catalogue lists both variants.
    assert u.wait_for(lambda: panel.arrays.rowCount() == 1, 5000)
    catalogue = panel.catalogue
    names = [catalogue.item(r, 0).text() for r in range(catalogue.rowCount())]
    product = "P-EVO R100L LED2500-830 BC AL WH [STD]"
    assert product in names and f"{product} wide" in names
    u.click_cell(catalogue, f"{product} wide")
    row = catalogue.currentRow()
    headers = [catalogue.horizontalHeaderItem(c).text() for c in range(catalogue.columnCount())]
    cells = {h: catalogue.item(row, c).text() for c, h in enumerate(headers)}
    assert cells["lm"] == f"{read_photometry(second).flux():,.0f}" and cells["W"] == "18"
    assert cells["UGR"] == rating  # the copy's table is the first variant's
    # What the GLDF states beyond the table, in the product's tooltip.
    tip = catalogue.item(row, 0).toolTip()
    assert "GLDF variant variant2: 2,400 lm, 18 W" in tip and tip.startswith(second)
    # Its polar curve, drawn from the variant's table (cd/klm in the C0 plane at nadir).
    curve = panel.polar.curves["C0"]
    nadir = curve[0]
    per_klm = ph.intensity(0.0, 0.0) * 1000.0 / ph.flux()
    assert abs(-nadir[1] - per_klm) < 1e-6 * per_klm
    # As the user sees it: the row chosen stays in view while the light is computed.
    QTest.qWait(300)
    cell = catalogue.item(row, 0)
    assert catalogue.viewport().rect().contains(catalogue.visualItemRect(cell).center())
    panel.grab().save(str(SHOTS / "catalogue-gldf.png"))
