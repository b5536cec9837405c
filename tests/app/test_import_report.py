"""File > Import model says what the import made of the file: the status bar's summary
for a clean import, the import report beside the window when something needs a look."""

from __future__ import annotations

import pytest
from PySide6 import QtCore, QtTest, QtWidgets

from app.dialogs.import_dialog import ImportDialog
from app.dialogs.import_report_dialog import ImportReportDialog
from tests.app.conftest import wait_for_operator

pytest.importorskip("ifcopenshell")


def click(widget: QtWidgets.QWidget, text: str) -> None:
    """Click the button of ``widget`` showing ``text``, as a user would."""
    (button,) = [
        b
        for b in widget.findChildren(QtWidgets.QAbstractButton)
        if b.text().replace("&", "") == text
    ]
    QtTest.QTest.mouseClick(button, QtCore.Qt.LeftButton)


def import_through_the_dialog(window, path) -> None:
    dialog = ImportDialog(path, window)
    dialog.resolution.setValue(0.5)
    dialog.setResult(QtWidgets.QDialog.Accepted)
    assert window.files.import_obj_dialog(dialog)


def shown_reports(window) -> list[ImportReportDialog]:
    return [d for d in window.findChildren(ImportReportDialog) if d.isVisible()]


def test_a_clean_import_says_its_summary_in_the_status_bar(qtbot, window, tmp_path):
    from tests.core.test_ifc_import import ifc_room

    import_through_the_dialog(window, ifc_room(tmp_path / "office.ifc"))
    assert window.statusBar().currentMessage() == (
        "Imported office.ifc: 13 elements: 3 zones, 6 groups, 4 dropped"
    )
    assert shown_reports(window) == []  # spaces and openings are no cause for a look
    wait_for_operator(qtbot, window)


def test_an_import_that_drops_something_shows_its_report(qtbot, window, tmp_path):
    """A model without floor slabs: two walls and the roof window have only faces that
    look out of the building. The import report opens beside the window (not blocking
    it): its summary, what needs a look, and the whole report under Show details."""
    from tests.core.test_ifc_import import ifc_room

    import_through_the_dialog(window, ifc_room(tmp_path / "open.ifc", floor=False))
    (report,) = shown_reports(window)
    assert report.windowTitle() == "Import report: open.ifc"
    assert not report.isModal()
    assert report.summary.text() == "open.ifc: 12 elements: 2 zones, 3 groups, 7 dropped"
    assert report.attention.text() == (
        "3 dropped (IfcWall, IfcWindow): none of them is in the scene"
    )
    assert window.statusBar().currentMessage() == (
        "Imported open.ifc: 12 elements: 2 zones, 3 groups, 7 dropped; see the import report"
    )
    assert report.details.isHidden()
    click(report, "Show details")
    assert report.details.isVisible()
    details = report.details.toPlainText()
    assert details.splitlines()[0] == report.summary.text()
    assert "  1 IfcWindow: every face of it looks out of the building" in details
    report.grab().save("/tmp/import-report-dialog.png")
    click(report, "Hide details")
    assert report.details.isHidden()
    click(report, "Close")
    assert shown_reports(window) == []
    wait_for_operator(qtbot, window)


def test_a_second_import_replaces_the_report(qtbot, window, tmp_path):
    from tests.core.test_ifc_import import ifc_room

    import_through_the_dialog(window, ifc_room(tmp_path / "open.ifc", floor=False))
    wait_for_operator(qtbot, window)
    import_through_the_dialog(window, ifc_room(tmp_path / "office.ifc"))
    assert shown_reports(window) == []
    wait_for_operator(qtbot, window)
