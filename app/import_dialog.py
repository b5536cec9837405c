"""File > Import OBJ: the model's units, up axis, materials and patch size, asked once.

Models come in millimetres from some tools and with y up from others; asked nothing,
a millimetre model was meshed as a 4 km room. The dialog counts the file's vertices
and faces (the streaming size check, no parse) and shows the model's extent in metres
for the units chosen, so a wrong unit shows before the import.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PySide6 import QtWidgets

from app import dialogs
from lightinv_core.errors import LightInvError
from lightinv_core.scene.obj_size import count_obj_lines

UNITS = (
    ("metres", 1.0),
    ("centimetres", 0.01),
    ("millimetres", 0.001),
    ("inches", 0.0254),
    ("feet", 0.3048),
)
MAX_PREVIEW_BYTES = 200 * 2**20


def raw_extent(path: Path) -> float | None:
    """Largest bounding-box side of the file's vertices in model units (None if the file
    is too big to preview or has none): a quick look, not the import."""
    if path.stat().st_size > MAX_PREVIEW_BYTES:
        return None
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    with open(path, "rb") as fh:
        for line in fh:
            if line.startswith(b"v "):
                try:
                    xyz = np.array(line.split()[1:4], dtype=float)
                except ValueError:
                    continue
                if xyz.shape == (3,) and np.all(np.isfinite(xyz)):
                    lo, hi = np.minimum(lo, xyz), np.maximum(hi, xyz)
    return float((hi - lo).max()) if np.all(np.isfinite(lo)) else None


class ImportDialog(QtWidgets.QDialog):
    """Units, up axis, materials file and patch size for an OBJ import."""

    def __init__(self, path: Path, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.path = Path(path)
        self.setWindowTitle(f"Import {self.path.name}")
        form = QtWidgets.QFormLayout(self)
        try:
            counts = count_obj_lines(self.path)
            self.extent = raw_extent(self.path)
            summary = f"{counts.vertices:,} vertices, {counts.faces:,} faces"
        except OSError as exc:
            counts, self.extent = None, None
            summary = f"cannot read it: {exc.strerror}"
        form.addRow("File", QtWidgets.QLabel(summary))
        self.units = QtWidgets.QComboBox()
        for name, scale in UNITS:
            self.units.addItem(name, scale)
        form.addRow("Drawn in", self.units)
        self.size = QtWidgets.QLabel()
        form.addRow("Model size", self.size)
        self.up = QtWidgets.QComboBox()
        self.up.addItem("z (SketchUp, Rhino, Revit)", "z")
        self.up.addItem("y (Blender export default, 3ds Max, glTF)", "y")
        form.addRow("Up axis", self.up)
        self.materials = QtWidgets.QLineEdit()
        self.materials.setPlaceholderText("none: MTL colours, else reflectance 0.5")
        browse = QtWidgets.QPushButton("Choose...")
        browse.clicked.connect(self._browse)
        mrow = QtWidgets.QHBoxLayout()
        mrow.addWidget(self.materials)
        mrow.addWidget(browse)
        form.addRow("Materials JSON", mrow)
        self.resolution = QtWidgets.QDoubleSpinBox(decimals=2, singleStep=0.05, suffix=" m")
        self.resolution.setRange(0.05, 10.0)
        self.resolution.setValue(0.25)
        form.addRow("Patch size", self.resolution)
        self.skip = QtWidgets.QCheckBox("drop degenerate faces (with a warning) instead of failing")
        form.addRow("", self.skip)
        form.addRow(dialogs.ok_cancel(self))
        self.units.currentIndexChanged.connect(self._show_size)
        if self.extent is not None and self.extent > 1000:  # probably millimetres
            self.units.setCurrentIndex(2)
        self._show_size()

    def _browse(self) -> None:
        path = dialogs.open_file(self, "Materials mapping", "Materials JSON (*.json)")
        if path:
            self.materials.setText(path)

    def _show_size(self) -> None:
        if self.extent is None:
            self.size.setText("unknown")
            return
        metres = self.extent * self.units.currentData()
        warn = "  (too big for a building: check the units)" if metres > 1000 else ""
        self.size.setText(f"{metres:,.2f} m across{warn}")

    def options(self) -> dict:
        """The scene's import settings (obj_project's options)."""
        out = {
            "scale": float(self.units.currentData()),
            "up": self.up.currentData(),
            "resolution": float(self.resolution.value()),
            "skip_degenerate": self.skip.isChecked(),
        }
        if self.materials.text().strip():
            out["materials"] = self.materials.text().strip()
        return out

    def accept(self) -> None:
        try:
            if self.materials.text().strip() and not Path(self.materials.text()).is_file():
                raise LightInvError(f"no materials file {self.materials.text()!r}")
        except LightInvError as exc:
            dialogs.warn(self, str(exc))
            return
        super().accept()
