"""The dialog that places a calculation object: a task area of any polygon, a rectangle
on a wall or ceiling, cylindrical or semi-cylindrical illuminance points, or free points
(``design/model/calc_kinds.py``), typed as rows of coordinates; optionally a lighting
intention on it (its mean at least, U0 at least)."""

from __future__ import annotations

import re

from PySide6 import QtWidgets

from app.dialogs import ask
from app.dialogs.fields import number_box, ok_cancel, optional_number
from lightinv_core.design.model import CalcObject, Intention, calc_kind, calc_kind_names
from lightinv_core.errors import DesignError, LightInvError
from lightinv_core.kinds import Edition
from lightinv_core.transport.point_sets import parse_points_csv

ROWS_HELP = {
    "task_area": "the polygon's corners in plan: x, y (m), one corner a line",
    "surface": "three lines: a corner x, y, z; its first edge u; its second edge v (m); "
    "it faces u x v",
    "cylindrical": "the points in plan: x, y (m), one a line",
    "semi_cylindrical": "the points in plan: x, y (m), one a line",
    "points": "x, y, z (m) or x, y, z, nx, ny, nz, one point a line (facing up without nx..)",
}
"""What the rows box holds for each built-in kind (a registered kind: x, y, z rows)."""


def _rows(text: str, width: int, what: str) -> tuple[tuple[float, ...], ...]:
    """Lines of ``width`` numbers (commas, semicolons or spaces between them)."""
    out = []
    for k, line in enumerate(text.splitlines(), 1):
        cells = [c for c in re.split(r"[,;\s]+", line.strip()) if c]
        if not cells:
            continue
        try:
            values = tuple(float(c) for c in cells)
        except ValueError:
            raise DesignError(f"{what}, line {k}: {line.strip()!r} is not numbers") from None
        if len(values) != width:
            raise DesignError(f"{what}, line {k}: expected {width} numbers, got {len(values)}")
        out.append(values)
    return tuple(out)


class CalcObjectDialog(QtWidgets.QDialog):
    """Fields of one ``CalcObject`` (its kind's own enabled) and an optional intention."""

    def __init__(
        self,
        groups: list[str],
        name: str = "object 1",
        parent: QtWidgets.QWidget | None = None,
        obj: CalcObject | None = None,
    ):
        super().__init__(parent)
        self.setWindowTitle("Calculation object")
        form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(name)
        form.addRow("Name", self.name)
        self.kind = QtWidgets.QComboBox()
        for k in calc_kind_names():
            self.kind.addItem(calc_kind(k).label, k)
        form.addRow("Kind", self.kind)
        self.rows = QtWidgets.QPlainTextEdit()
        self.rows.setMinimumHeight(90)
        form.addRow("Rows (one per line)", self.rows)
        self.help = QtWidgets.QLabel(wordWrap=True)
        form.addRow("", self.help)
        self.height = number_box(0.0, 100.0, 0.8)
        form.addRow("Height above the floor (m)", self.height)
        self.border = number_box(0.0, 100.0, 0.0)
        form.addRow("Border (m)", self.border)
        self.facing = number_box(-360.0, 360.0, 90.0, decimals=1, step=15.0)
        self.facing.setToolTip("Degrees counter-clockwise from +x: 0 faces +x, 90 faces +y")
        form.addRow("Facing (deg)", self.facing)
        self.group = QtWidgets.QComboBox()
        self.group.addItems(groups)
        self.group.setCurrentText("floor" if "floor" in groups else groups[0])
        form.addRow("Floor group", self.group)
        self.edition = QtWidgets.QComboBox()
        self.edition.addItems([str(e) for e in Edition])
        self.edition.setCurrentText(str(Edition.EN12464_2021))
        form.addRow("Grid rule", self.edition)
        self.average = optional_number(form, "Mean at least (lux)", 150.0, 1e5, decimals=1)
        self.uniformity = optional_number(form, "U0 at least", 0.4, 1.0, step=0.05)
        form.addRow(ok_cancel(self))
        self._inputs = {
            "height": self.height,
            "border": self.border,
            "facing": self.facing,
            "group": self.group,
            "edition": self.edition,
        }
        self.kind.currentIndexChanged.connect(self._kind_changed)
        if obj is not None:
            self._show(obj)
        self._kind_changed()

    def _kind_changed(self) -> None:
        kind = self.kind.currentData()
        takes = calc_kind(kind).takes
        for key, widget in self._inputs.items():
            widget.setEnabled(key in takes)
        self.help.setText(ROWS_HELP.get(kind, "x, y, z (m), one a line"))
        if kind in ("cylindrical", "semi_cylindrical") and self.height.value() == 0.8:
            self.height.setValue(1.2)  # EN 12464-1's seated eye for Ez and Esc

    def _show(self, obj: CalcObject) -> None:
        """Fill the fields with ``obj`` (editing)."""
        self.name.setText(obj.name)
        self.kind.setCurrentIndex(self.kind.findData(obj.kind))
        rows = obj.corners or obj.positions or ()
        if obj.kind == "surface":
            rows = (obj.origin, obj.u, obj.v)
        if obj.points is not None:
            normals = obj.normals or [()] * len(obj.points)
            rows = tuple((*p, *n) for p, n in zip(obj.points, normals, strict=True))
        self.rows.setPlainText("\n".join(", ".join(f"{v:g}" for v in r) for r in rows))
        self.height.setValue(obj.height)
        self.border.setValue(obj.border)
        self.facing.setValue(obj.facing)
        self.group.setCurrentText(obj.group)
        self.edition.setCurrentText(str(obj.edition))

    def accept(self) -> None:
        """Close only on an object that can be built (OK or Enter); else say why."""
        try:
            self.calc_object()
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return
        super().accept()

    def calc_object(self) -> CalcObject:
        """The object as entered (DesignError naming what is wrong)."""
        kind = self.kind.currentData()
        text = self.rows.toPlainText()
        values: dict = {
            "height": self.height.value(),
            "border": self.border.value(),
            "facing": self.facing.value(),
            "group": self.group.currentText(),
            "edition": self.edition.currentText(),
        }
        if kind == "task_area":
            values["corners"] = _rows(text, 2, "the corners")
        elif kind == "surface":
            rows = _rows(text, 3, "the rectangle")
            if len(rows) != 3:
                raise DesignError("give the rectangle as three lines: a corner, u and v")
            values["origin"], values["u"], values["v"] = rows
        elif kind == "points":
            pts, normals = parse_points_csv(text, "the points")
            values["points"] = tuple(map(tuple, pts.tolist()))
            if normals is not None:
                values["normals"] = tuple(map(tuple, normals.tolist()))
        else:
            values["positions"] = _rows(text, 2, "the positions")
        takes = calc_kind(kind).takes
        kept = {k: v for k, v in values.items() if k in takes}
        return CalcObject(self.name.text().strip(), kind, **kept)

    def intention(self, taken: set[str]) -> Intention | None:
        """The intention on this object (its name not in ``taken``): its mean at least
        and its U0 at least, as ticked; None when neither is."""
        (avg_on, avg), (u0_on, u0) = self.average, self.uniformity
        if not avg_on.isChecked() and not u0_on.isChecked():
            return None
        base = self.name.text().strip()
        name = first = f"{base} ({calc_kind(self.kind.currentData()).symbol})"
        k = 2
        while name in taken:
            name, k = f"{first}-{k}", k + 1
        return Intention(
            name,
            grid=base,
            average=avg.value() if avg_on.isChecked() else None,
            uniformity=u0.value() if u0_on.isChecked() else None,
        )
