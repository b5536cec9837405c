"""The materials panel: the reflectance of each lighting group, with common presets.

Changing one re-meshes the scene (reflectances are part of the patches) and builds
the radiosity operator again, or loads it from the cache. The values go into the
project (``scene.reflectances``) and Edit > Undo takes them back.
"""

from __future__ import annotations

from PySide6 import QtWidgets

from app.dialogs import ask
from app.document import Document
from lightinv_core.errors import LightInvError

PRESETS = (
    ("white paint, ceiling tiles", 0.85),
    ("light walls (off-white)", 0.7),
    ("mid grey, light wood", 0.5),
    ("concrete, medium wood", 0.35),
    ("light floor, carpet", 0.25),
    ("dark wood, dark carpet", 0.15),
)
"""Typical diffuse reflectances. EN 12464-1 recommends 0.7-0.9 for ceilings, 0.5-0.8
for walls, 0.2-0.6 for working planes and 0.2-0.4 for floors."""


class MaterialsPanel(QtWidgets.QGroupBox):
    """Reflectance per lighting group: a value, or a preset; "scene's own" resets it."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__("Materials", parent)
        self.doc = doc
        form = QtWidgets.QFormLayout(self)
        self.group = QtWidgets.QComboBox()
        form.addRow("Group", self.group)
        self.value = QtWidgets.QDoubleSpinBox(decimals=2, singleStep=0.05)
        self.value.setRange(0.0, 0.99)
        self.value.setKeyboardTracking(False)
        form.addRow("Reflectance", self.value)
        self.preset = QtWidgets.QComboBox()
        self.preset.addItem("(presets)", None)
        for name, rho in PRESETS:
            self.preset.addItem(f"{name}: {rho:.2f}", rho)
        form.addRow("Preset", self.preset)
        self.reset = QtWidgets.QPushButton("Back to the scene's own")
        form.addRow(self.reset)
        self.group.currentIndexChanged.connect(self._show)
        self.value.valueChanged.connect(self._edited)
        self.preset.activated.connect(self._preset)
        self.reset.clicked.connect(lambda: self._set(None))
        doc.sceneChanged.connect(self.refresh)

    def refresh(self) -> None:
        current = self.group.currentText()
        self.group.blockSignals(True)
        self.group.clear()
        if self.doc.scene is not None:
            self.group.addItems(list(self.doc.scene.groups))
        index = self.group.findText(current)
        self.group.setCurrentIndex(max(index, 0))
        self.group.blockSignals(False)
        self._show()

    def _show(self) -> None:
        group = self.group.currentText()
        self.value.blockSignals(True)
        if group:
            self.value.setValue(self.doc.reflectance(group))
        self.value.blockSignals(False)
        given = dict(self.doc.project.scene.reflectances) if self.doc.project else {}
        self.reset.setEnabled(group in given)

    def _preset(self, index: int) -> None:
        rho = self.preset.itemData(index)
        self.preset.setCurrentIndex(0)
        if rho is not None:
            self._set(rho)

    def _edited(self, value: float) -> None:
        self._set(value)

    def _set(self, value: float | None) -> None:
        group = self.group.currentText()
        if not group:
            return
        try:
            self.doc.set_reflectance(group, value)
        except LightInvError as exc:
            ask.warn(self, str(exc))
        self.refresh()
