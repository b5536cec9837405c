"""The geometric rule dialog: a rule's kind, the sources (or luminaire arrays) it binds,
its bounds or axis. Mirror and centred rules are set in the Properties panel."""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets

from app.dialogs.fields import ok_cancel, optional_number
from lightinv_core.design.model import DesignError, Rule

RULE_KINDS = {
    "area": "area of each source (m²)",
    "aspect": "aspect ratio of each source (long / short side)",
    "spacing": "gap between two sources in one zone (m)",
    "align": "sources on one line along a zone axis",
    "shr": "luminaire arrays: spacing / mounting height",
    "clearance": "luminaire arrays: clearance to the zone's edges (m)",
}
ARRAY_KINDS = ("shr", "clearance")


class RuleDialog(QtWidgets.QDialog):
    """A new geometric rule: its kind, the sources it binds, its bounds or axis.
    (Mirror and centred rules are set in the Properties panel.)"""

    def __init__(self, sources: list[str], parent: QtWidgets.QWidget | None = None, arrays=()):
        super().__init__(parent)
        self.setWindowTitle("Add a geometric rule")
        self.names = {"sources": list(sources), "arrays": list(arrays)}
        form = QtWidgets.QFormLayout(self)
        self.kind = QtWidgets.QComboBox()
        for key, text in RULE_KINDS.items():
            if (key in ARRAY_KINDS and arrays) or (key not in ARRAY_KINDS and sources):
                self.kind.addItem(text, key)
        form.addRow("Rule", self.kind)
        self.sources = QtWidgets.QListWidget()
        self.sources.setMaximumHeight(110)
        form.addRow("Sources", self.sources)
        self.bounds = {}
        for key, label, value in (("min", "at least", 0.5), ("max", "at most", 4.0)):
            self.bounds[key] = optional_number(form, label, value, 1e4, step=0.25)
        self.bounds["max"][0].setChecked(True)
        self.axis = QtWidgets.QComboBox()
        self.axis.addItems(["u", "v"])
        form.addRow("Axis", self.axis)
        form.addRow(ok_cancel(self))
        self.kind.currentIndexChanged.connect(self._kind_changed)
        self._kind_changed()

    def _kind_changed(self) -> None:
        kind = self.kind.currentData()
        # Rules on arrays list the arrays, the others the sources.
        names = self.names["arrays" if kind in ARRAY_KINDS else "sources"]
        if [self.sources.item(i).text() for i in range(self.sources.count())] != names:
            self.sources.clear()
            for name in names:
                item = QtWidgets.QListWidgetItem(name)
                item.setFlags(item.flags() | QtCore.Qt.ItemIsUserCheckable)
                item.setCheckState(QtCore.Qt.Checked)
                self.sources.addItem(item)
        if kind == "shr":
            self.bounds["max"][0].setChecked(True)
            self.bounds["max"][1].setValue(1.5)
        elif kind == "clearance":
            self.bounds["min"][0].setChecked(True)
            self.bounds["min"][1].setValue(0.1)
        for key, (check, box) in self.bounds.items():
            usable = (
                kind in ("area", "spacing")
                or (kind in ("aspect", "shr") and key == "max")
                or (kind == "clearance" and key == "min")
            )
            check.setEnabled(usable)
            box.setEnabled(usable and check.isChecked())
        self.axis.setEnabled(kind == "align")

    def set_rule(self, kind: str, sources: list[str], **bounds) -> None:
        """Fill the dialog (tests, scripts): ``bounds`` min / max / axis, None unticks."""
        self.kind.setCurrentIndex(self.kind.findData(kind))
        for i in range(self.sources.count()):
            item = self.sources.item(i)
            item.setCheckState(QtCore.Qt.Checked if item.text() in sources else QtCore.Qt.Unchecked)
        for key, value in bounds.items():
            if key == "axis":
                self.axis.setCurrentText(value)
                continue
            check, box = self.bounds[key]
            check.setChecked(value is not None)
            if value is not None:
                box.setValue(value)

    def rule(self) -> Rule:
        """The rule described (DesignError if it cannot hold, e.g. no source ticked)."""
        kind = self.kind.currentData()
        names = [
            self.sources.item(i).text()
            for i in range(self.sources.count())
            if self.sources.item(i).checkState() == QtCore.Qt.Checked
        ]
        if not names:
            raise DesignError("tick at least one source")
        fields = {}
        if kind == "align":
            fields["axis"] = self.axis.currentText()
        else:
            for key, (check, box) in self.bounds.items():
                if check.isEnabled() and check.isChecked():
                    fields[key] = box.value()
        return Rule(kind, tuple(names), **fields)
