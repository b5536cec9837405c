"""After File > Import model: what the import made of the file (the core's
``ImportReport``): a one-line summary, what needs a look (elements dropped, windows or
ceilings that are no zones, cuts skipped, defaults assumed such as the reflectance of a
model without materials), and the whole report on request.

Shown without blocking the window when something needs a look; a clean import only says
its summary in the status bar (``import_summary``).
"""

from __future__ import annotations

from PySide6 import QtGui, QtWidgets

from lightinv_core.scene.importers.report import ImportReport

SHOW = "Show details"
HIDE = "Hide details"


def import_summary(report: ImportReport) -> str:
    """The status bar's line after an import."""
    tail = "; see the import report" if report.needs_attention else ""
    return f"Imported {report.summary()}{tail}"


def attention_lines(report: ImportReport) -> list[str]:
    """What needs a look, one line per kind of problem (empty for a clean import)."""
    out = []
    dropped = [it for it in report.dropped if not it.reason.startswith("not a surface")]
    if dropped:
        kinds = sorted({it.kind for it in dropped})
        out.append(f"{len(dropped)} dropped ({', '.join(kinds)}): none of them is in the scene")
    if report.not_zoned:
        out.append(f"{len(report.not_zoned)} window(s) or ceiling(s) are plain surfaces, no zones")
    if report.skipped:
        out.append(f"{len(report.skipped)} part(s) skipped within what was kept")
    out += [f"Assumed: {note}" for note in report.notes]
    return out


class ImportReportDialog(QtWidgets.QDialog):
    """The import report of one file: summary, what needs a look, details on request."""

    def __init__(self, report: ImportReport, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.report = report
        self.setWindowTitle(f"Import report: {report.source}")
        self.setModal(False)
        layout = QtWidgets.QVBoxLayout(self)
        self.summary = QtWidgets.QLabel(report.summary())
        self.summary.setWordWrap(True)
        layout.addWidget(self.summary)
        self.attention = QtWidgets.QLabel("\n".join(attention_lines(report)))
        self.attention.setWordWrap(True)
        self.attention.setVisible(bool(self.attention.text()))
        layout.addWidget(self.attention)
        self.details = QtWidgets.QPlainTextEdit("\n".join(report.lines()))
        self.details.setReadOnly(True)
        self.details.setLineWrapMode(QtWidgets.QPlainTextEdit.NoWrap)
        self.details.setFont(QtGui.QFontDatabase.systemFont(QtGui.QFontDatabase.FixedFont))
        self.details.setMinimumSize(640, 280)
        self.details.hide()
        layout.addWidget(self.details)
        buttons = QtWidgets.QDialogButtonBox()
        self.toggle = buttons.addButton(SHOW, QtWidgets.QDialogButtonBox.ActionRole)
        self.toggle.clicked.connect(self._toggle)
        close = buttons.addButton(QtWidgets.QDialogButtonBox.Close)
        close.clicked.connect(self.close)
        layout.addWidget(buttons)

    def _toggle(self) -> None:
        shown = self.details.isHidden()
        self.details.setVisible(shown)
        self.toggle.setText(HIDE if shown else SHOW)
        self.adjustSize()
