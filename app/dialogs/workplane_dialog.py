"""The dialog that adds a work plane: a grid of points at a height over a floor group,
where the EN 12464-1 values are read, the edition of EN 12464-1 it follows (its grid
rule and presets; 2021 for a new one) and, optionally, a preset of that edition to ask
of it (the list follows the edition), with its glare limit UGR_L at the design's
observers, or at two placed at the plane's edges when it has none
(``design.preset_glare``)."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore, QtWidgets

from app.dialogs import ask
from app.dialogs.fields import number_box, ok_cancel
from lightinv_core.design.en12464 import DEFAULT_EDITION, EDITIONS, requirement, requirements
from lightinv_core.design.model import Workplane
from lightinv_core.errors import LightInvError
from lightinv_core.scene.patches import Patches

FLOOR_SHARE = 0.5
"""A group is a floor candidate when its upward-facing area is at least this share of the
largest one's (a stair's treads or a sill are not a floor)."""


def floor_default(groups: list[str], patches: Patches | None = None) -> str:
    """The floor group a new work plane is proposed over: "floor" (built-in scenes, OBJ
    rooms named so); else, with the patches, the lowest of the groups with the most
    upward-facing area (``FLOOR_SHARE``): an IFC house's ground slab or footing; else
    the first group with "floor" in its name, else the first group."""
    if "floor" in groups:
        return "floor"
    # An IFC house proposed its first group, a spiral stair, as the floor.
    if patches is not None:
        up = patches.normal[:, 2] > 0.9
        area = np.bincount(patches.group_id[up], patches.area[up], len(patches.group_names))
        if area.max() > 0:
            height = np.bincount(
                patches.group_id[up],
                patches.area[up] * patches.centroid[up, 2],
                len(patches.group_names),
            ) / np.maximum(area, 1e-12)
            floors = np.flatnonzero(area >= FLOOR_SHARE * area.max())
            best = patches.group_names[min(floors, key=lambda k: height[k])]
            if best in groups:
                return best
    return next((g for g in groups if "floor" in g.lower()), groups[0])


class WorkplaneDialog(QtWidgets.QDialog):
    """Fields of one ``Workplane``: name, height, border, floor group, edition; and a
    preset of the edition to add as its intention (``preset()``)."""

    def __init__(
        self,
        groups: list[str],
        base: Workplane | None = None,
        name: str = "wp",
        parent: QtWidgets.QWidget | None = None,
        patches: Patches | None = None,
        observers: int | None = None,
    ):
        super().__init__(parent)
        self.setWindowTitle("Work plane")
        doc = getattr(parent, "doc", None)  # the Luminaires panel's, when it is the parent
        if patches is None:
            patches = getattr(doc, "patches", None)
        if observers is None:
            design = getattr(doc, "design", None) if getattr(doc, "project", None) else None
            observers = len(design.observers) if design is not None else 0
        base = base or Workplane(
            name, group=floor_default(groups, patches), edition=DEFAULT_EDITION
        )
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
        self.edition = QtWidgets.QComboBox()
        self.edition.addItems([str(e) for e in EDITIONS])
        self.edition.setCurrentText(str(base.edition))
        self.edition.setToolTip(
            "The edition's grid rule (2011: points per side rounded up; 2021: the cell "
            "from the longer side, points rounded) and its presets"
        )
        self.preset_box = QtWidgets.QComboBox()
        # The longest activity would widen the dialog past a laptop's screen.
        self.preset_box.setSizeAdjustPolicy(
            QtWidgets.QComboBox.AdjustToMinimumContentsLengthWithIcon
        )
        self.preset_box.setMinimumContentsLength(28)
        standard = QtWidgets.QHBoxLayout()
        standard.addWidget(self.edition)
        standard.addWidget(self.preset_box, 1)
        form.addRow("EN 12464-1", standard)
        # The preset's UGR_L as a limit at the observers (default ones when none yet).
        self.glare = QtWidgets.QCheckBox()
        self.glare.setChecked(True)
        self.glare.setToolTip(
            f"A lighting intention: UGR (CIE 117) at most the preset's UGR_L at the design's "
            f"{observers} observers"
            if observers
            else "A lighting intention: UGR (CIE 117) at most the preset's UGR_L, at two seated "
            "observers (eye 1.2 m) placed at the middle of the plane's edges of least y and "
            "least x, looking across it (the design has none yet)"
        )
        form.addRow("", self.glare)
        self.edition.currentTextChanged.connect(self._fill_presets)
        self.preset_box.currentIndexChanged.connect(self._preset_changed)
        self._fill_presets(self.edition.currentText())
        form.addRow(ok_cancel(self))

    def _fill_presets(self, edition: str) -> None:
        """The preset list of ``edition``, keeping the chosen activity when it has one."""
        key = self.preset_box.currentData()
        self.preset_box.clear()
        self.preset_box.addItem("no preset", None)
        for r in requirements(edition):
            mod = f" (modified {r.em_mod:g})" if r.em_mod is not None else ""
            self.preset_box.addItem(f"{r.activity}: {r.em:g} lux{mod}, U0 {r.u0:.2f}", r.key)
            self.preset_box.setItemData(
                self.preset_box.count() - 1, f"{r.label}; {r.values}", QtCore.Qt.ToolTipRole
            )
        self.preset_box.setCurrentIndex(max(0, self.preset_box.findData(key)))

    def _preset_changed(self) -> None:
        """The glare box names the chosen preset's UGR_L (greyed without one)."""
        key = self.preset_box.currentData()
        ugr = requirement(key, self.edition.currentText()).ugr_l if key else None
        limit = f" (UGR_L {ugr:g})" if ugr is not None else ""
        self.glare.setText(f"Add UGR limit from preset{limit}")
        self.glare.setEnabled(ugr is not None)

    def ugr_limit(self) -> bool:
        """Whether to add the chosen preset's UGR_L as a limit at observers."""
        return self.glare.isEnabled() and self.glare.isChecked()

    def preset(self) -> str | None:
        """The key of the preset chosen to ask of the work plane (None: none)."""
        return self.preset_box.currentData()

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
            self.edition.currentText(),
        )
