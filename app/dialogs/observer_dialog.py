"""The dialog that places an observer: an eye at a point of the plan, seated or standing,
looking one way, where the glare rating (UGR) is judged; optionally a UGR limit there
(the strictest UGR_L of the design's EN 12464-1 presets when it has one). The same
dialog edits an observer placed before (``load``): its limit row is then hidden (the
limits at it are intentions, edited in the tree)."""

from __future__ import annotations

import math

from PySide6 import QtWidgets

from app.dialogs import ask
from app.dialogs.fields import number_box, ok_cancel, optional_number
from lightinv_core.design.model import SEATED_EYE, Intention, Observer
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Quantity

UGR_L = 19.0
"""The limit the dialog offers: EN 12464-1's UGR_L for offices, writing and reading."""


class ObserverDialog(QtWidgets.QDialog):
    """Fields of one ``Observer`` (name, x, y, eye height, view azimuth, floor group)
    and a ticked "UGR at most" that adds a glare intention at it."""

    def __init__(
        self,
        groups: list[str],
        name: str = "observer",
        centre: tuple[float, float] = (0.0, 0.0),
        parent: QtWidgets.QWidget | None = None,
        limit: float = UGR_L,
        limit_source: str | None = None,
    ):
        super().__init__(parent)
        self.setWindowTitle("Observer")
        self.form = form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(name)
        form.addRow("Name", self.name)
        self.x = number_box(-1e4, 1e4, centre[0])
        form.addRow("x (m)", self.x)
        self.y = number_box(-1e4, 1e4, centre[1])
        form.addRow("y (m)", self.y)
        self.height = number_box(0.0, 100.0, SEATED_EYE)
        self.height.setToolTip("1.2 m seated, 1.7 m standing")
        form.addRow("Eye height (m)", self.height)
        self.azimuth = number_box(-360.0, 360.0, 90.0, decimals=1, step=15.0)
        self.azimuth.setToolTip("Degrees counter-clockwise from +x: 0 looks along +x, 90 along +y")
        form.addRow("View azimuth (deg)", self.azimuth)
        self.group = QtWidgets.QComboBox()
        self.group.addItems(groups)
        self.group.setCurrentText("floor" if "floor" in groups else groups[0])
        form.addRow("Floor group", self.group)
        self.limit = optional_number(form, "UGR at most", limit, 40.0, decimals=1)
        self.limit[0].setChecked(True)
        source = f"the design's preset: {limit_source}; " if limit_source else ""
        self.limit[0].setToolTip(
            "Adds a lighting intention: UGR (CIE 117) at this eye at most this value "
            f"({source}EN 12464-1 UGR_L: 19 offices, 22 industry, 25 corridors)"
        )
        form.addRow(ok_cancel(self))

    def load(self, observer: Observer) -> None:
        """Show an observer placed before, to edit it (its place, eye height, view, floor
        group, name); the limit row is hidden. A view ``direction`` is shown as its
        azimuth and kept (its tilt too) unless the azimuth is changed."""
        self.setWindowTitle(f"Edit observer {observer.name}")
        self.name.setText(observer.name)
        self.x.setValue(observer.position[0])
        self.y.setValue(observer.position[1])
        self.height.setValue(observer.height)
        view = observer.view
        self.azimuth.setValue(round(math.degrees(math.atan2(view[1], view[0])), 1))
        self._direction = (observer.direction, self.azimuth.value())
        self.group.setCurrentText(observer.group)
        check = self.limit[0]
        check.setChecked(False)
        for row in range(self.form.rowCount()):  # the limit's row: hidden
            item = self.form.itemAt(row, QtWidgets.QFormLayout.FieldRole)
            if item is not None and item.layout() is not None and item.layout().indexOf(check) >= 0:
                self.form.setRowVisible(row, False)

    def accept(self) -> None:
        """Close only on an observer that can be built (OK or Enter); else say why."""
        try:
            self.observer()
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return
        super().accept()

    def observer(self) -> Observer:
        """The observer as entered (DesignError naming the bad field)."""
        direction, shown = getattr(self, "_direction", (None, None))
        keep = direction is not None and self.azimuth.value() == shown
        return Observer(
            self.name.text().strip(),
            (self.x.value(), self.y.value()),
            self.height.value(),
            azimuth=None if keep else self.azimuth.value(),
            direction=direction if keep else None,
            group=self.group.currentText(),
        )

    def intention(self, taken: set[str]) -> Intention | None:
        """The glare intention at this observer (its name not in ``taken``), None when
        "UGR at most" is not ticked."""
        check, box = self.limit
        if not check.isChecked():
            return None
        name = f"glare {self.name.text().strip()}"
        k = 2
        while name in taken:
            name, k = f"glare {self.name.text().strip()}-{k}", k + 1
        return Intention(
            name, observers=(self.observer().name,), quantity=Quantity.UGR, max=box.value()
        )
