"""The name and kind of an emitter zone just drawn (the kinds: every registered source
type)."""

from __future__ import annotations

from PySide6 import QtWidgets

from app.dialogs.fields import ok_cancel, source_kind_box


class ZoneDialog(QtWidgets.QDialog):
    """Name and kind of a zone just drawn."""

    def __init__(self, surface: str, default_name: str, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.setWindowTitle(f"New emitter zone on {surface}")
        form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(default_name)
        form.addRow("Name", self.name)
        self.kind = source_kind_box()  # the kind is the item's data
        form.addRow("Kind", self.kind)
        form.addRow(ok_cancel(self))
