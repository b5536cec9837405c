"""The dialog that adds a work plane: a grid of points at a height over a floor group,
where the EN 12464-1 values are read."""

from __future__ import annotations

from PySide6 import QtWidgets

from app.dialogs import ask
from app.dialogs.fields import number_box, ok_cancel
from lightinv_core.design.model import Workplane
from lightinv_core.errors import LightInvError


class WorkplaneDialog(QtWidgets.QDialog):
    """Fields of one ``Workplane``: name, height, border, floor group."""

    def __init__(
        self,
        groups: list[str],
        base: Workplane | None = None,
        name: str = "wp",
        parent: QtWidgets.QWidget | None = None,
    ):
        super().__init__(parent)
        self.setWindowTitle("Work plane")
        base = base or Workplane(name, group="floor" if "floor" in groups else groups[0])
        form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(base.name)
        form.addRow("Name", self.name)
        self.height = number_box(0.0, 100.0, base.height)
        form.addRow("Height above the floor (m)", self.height)
        self.border = number_box(0.0, 100.0, base.border)
        form.addRow("Border left out (m)", self.border)
        self.group = QtWidgets.QComboBox()
        self.group.addItems(groups)
        self.group.setCurrentText(base.group)
        form.addRow("Floor group", self.group)
        form.addRow(ok_cancel(self))

    def accept(self) -> None:
        """Close only on a work plane that can be built (OK or Enter); else say why."""
        try:
            self.workplane()
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return
        super().accept()

    def workplane(self) -> Workplane:
        """The work plane as entered (DesignError naming the bad field)."""
        return Workplane(
            self.name.text().strip(),
            self.height.value(),
            self.border.value(),
            self.group.currentText(),
        )
