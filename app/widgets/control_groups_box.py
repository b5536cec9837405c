"""The Climate tab's "Control groups" box: the design's daylight-linked control groups
(each a set of luminaires dimmed or switched by its own sensor region), added, edited
(renamed, its sensor's work plane and rectangle, its control mode, its own target, its
lowest level) and removed through
``ControlGroupDialog``; every change an undoable edit of the document. A luminaire joins
a group in Properties > Source (or the array's dialog)."""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets

from app.dialogs import ask
from app.dialogs.control_group_dialog import ControlGroupDialog
from app.document import Document
from lightinv_core.climate.control_modes import DIMMING
from lightinv_core.design.model import DEFAULT_CONTROL_GROUP, ControlGroup
from lightinv_core.editing.control_edits import new_group_name
from lightinv_core.errors import LightInvError
from lightinv_core.sources.types import electric


def group_text(group: ControlGroup, members: list[str]) -> str:
    """One line for people: the group, where its sensor reads and its luminaires."""
    where = "whole plane"
    if group.sensor is not None:
        x0, y0, x1, y1 = group.sensor
        where = f"x {x0:g}-{x1:g}, y {y0:g}-{y1:g} m"
    plane = group.workplane or "control plane"
    who = ", ".join(members) if members else "no luminaires yet"
    how = "" if group.mode == DIMMING else f"; {group.mode}"
    if group.target_lux is not None:
        how += f"; {group.target_lux:g} lux"
    if group.dead_band > 0:
        how += f"; dead band {100 * group.dead_band:g}%"
    return f"{group.name}: {plane}, {where}{how}; {who}"


class ControlGroupsBox(QtWidgets.QGroupBox):
    """The list of control groups and their buttons (see the module)."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__("Control groups", parent)
        self.doc = doc
        lay = QtWidgets.QHBoxLayout(self)
        self.list = QtWidgets.QListWidget()
        self.list.setMinimumHeight(70)
        self.list.setMaximumHeight(110)
        self.list.setToolTip(
            "Luminaires dimmed together by one daylight sensor; a luminaire in no group is "
            f"in {DEFAULT_CONTROL_GROUP!r}, read on the whole control work plane"
        )
        lay.addWidget(self.list, 1)
        row = QtWidgets.QVBoxLayout()
        self.add_button = QtWidgets.QPushButton("Add group...")
        self.edit_button = QtWidgets.QPushButton("Edit...")
        self.remove_button = QtWidgets.QPushButton("Remove")
        for b in (self.add_button, self.edit_button, self.remove_button):
            row.addWidget(b)
        row.addStretch(1)
        lay.addLayout(row)
        self.add_button.clicked.connect(lambda: self.add_group())
        self.edit_button.clicked.connect(lambda: self.edit_group())
        self.remove_button.clicked.connect(self.remove_group)
        self.list.itemDoubleClicked.connect(lambda _i: self.edit_group())
        doc.designChanged.connect(self.refresh)
        self.refresh()

    def refresh(self) -> None:
        """Show the design's groups (the selection kept by name)."""
        keep = self.current()
        self.list.clear()
        has = self.doc.project is not None
        self.add_button.setEnabled(has and bool(has and self.doc.design.workplanes))
        if not has:
            return
        d = self.doc.design
        members: dict[str, list[str]] = {}
        for x in (*electric(d.sources), *d.arrays):
            members.setdefault(x.control_group, []).append(x.name)
        for g in d.control_groups:
            item = QtWidgets.QListWidgetItem(group_text(g, members.get(g.name, [])))
            item.setData(QtCore.Qt.UserRole, g.name)
            self.list.addItem(item)
            if g.name == keep:
                self.list.setCurrentItem(item)
        if DEFAULT_CONTROL_GROUP not in {g.name for g in d.control_groups}:
            rest = members.get(DEFAULT_CONTROL_GROUP, [])
            text = group_text(ControlGroup(DEFAULT_CONTROL_GROUP), rest) + " (default)"
            item = QtWidgets.QListWidgetItem(text)
            item.setFlags(item.flags() & ~QtCore.Qt.ItemIsSelectable)
            self.list.addItem(item)
        self.edit_button.setEnabled(bool(d.control_groups))
        self.remove_button.setEnabled(bool(d.control_groups))

    def current(self) -> str | None:
        """The name of the group selected (a declared one), or None."""
        item = self.list.currentItem()
        return None if item is None else item.data(QtCore.Qt.UserRole)

    def _dialog(self, base: ControlGroup) -> ControlGroupDialog:
        d = self.doc.design
        planes = [w.name for w in d.workplanes]
        bounds = (0.0, 0.0, 1.0, 1.0)
        grids, _ = self.doc.shown_grids()
        if grids is not None and len(grids.points):
            lo, hi = grids.points[:, :2].min(axis=0), grids.points[:, :2].max(axis=0)
            bounds = (float(lo[0]), float(lo[1]), float(hi[0]) + 0.01, float(hi[1]) + 0.01)
        return ControlGroupDialog(
            planes,
            base,
            bounds,
            d.daylight.min_level,
            parent=self,
            target_lux=d.daylight.target_lux,
        )

    def add_group(self) -> bool:
        """Ask for a new group and add it."""
        dialog = self._dialog(ControlGroup(new_group_name(self.doc.design)))
        if not ask.accepted(dialog):
            return False
        return self._guard(lambda: self.doc.add_control_group(dialog.group()))

    def edit_group(self) -> bool:
        """Edit the selected group (rename, sensor, mode, target, lowest level)."""
        name = self.current()
        if name is None:
            return False
        base = next(g for g in self.doc.design.control_groups if g.name == name)
        dialog = self._dialog(base)
        if not ask.accepted(dialog):
            return False
        new = dialog.group()
        keys = ("name", "sensor", "workplane", "min_level", "mode", "target_lux", "dead_band")
        fields = {k: getattr(new, k) for k in keys}
        return self._guard(lambda: self.doc.update_control_group(name, **fields))

    def remove_group(self) -> None:
        """Remove the selected group; its luminaires go back to the default group."""
        name = self.current()
        if name is not None:
            self._guard(lambda: self.doc.remove_control_group(name))

    def _guard(self, fn) -> bool:
        try:
            fn()
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return False
        return True
