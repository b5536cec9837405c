"""File > Import model: the model's units, up axis, materials and patch size, asked once.

Models come in millimetres from some tools and with y up from others; asked nothing,
a millimetre model was meshed as a 4 km room. The dialog counts the file's vertices
and faces (OBJ: the streaming size check, no parse; glTF and PLY: trimesh reads them)
and shows the model's extent in metres for the units chosen, so a wrong unit shows
before the import. glTF files are y-up and in metres by their specification; IFC files
carry their own unit (converted to metres on import), so the units are not asked.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PySide6 import QtWidgets

from app.dialogs import ask
from app.dialogs.fields import ok_cancel
from lightinv_core.errors import LightInvError
from lightinv_core.scene.importers.obj_size import count_obj_lines
from lightinv_core.scene.importers.registry import (
    default_up,
    importer_for,
    importers,
    model_suffixes,
)

UNITS = (
    ("metres", 1.0),
    ("centimetres", 0.01),
    ("millimetres", 0.001),
    ("inches", 0.0254),
    ("feet", 0.3048),
)
MAX_PREVIEW_BYTES = 200 * 2**20


def model_filter() -> str:
    """The file dialog's filter for File > Import model: all models, then each
    registered format."""
    models = "Models (" + " ".join(f"*{s}" for s in model_suffixes()) + ")"
    return ";;".join([models, *(i.filter for i in importers())])


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


def mesh_preview(path: Path) -> tuple[str, float | None]:
    """Summary ("1,204 vertices, 2,310 triangles") and extent in model units of a glTF
    or PLY file, read with trimesh (node transforms applied); the extent is None when
    the file is too big to preview. LightInvError if trimesh cannot read it."""
    import trimesh

    if path.stat().st_size > MAX_PREVIEW_BYTES:
        return f"{path.stat().st_size / 2**20:,.0f} MB (too big to preview)", None
    try:
        scene = trimesh.load_scene(str(path), process=False)
    except Exception as exc:  # trimesh raises many kinds on a damaged file
        raise LightInvError(f"cannot read it: {type(exc).__name__}") from None
    nv = nf = 0
    for node in scene.graph.nodes_geometry:
        geom = scene.geometry[scene.graph[node][1]]
        nv += len(getattr(geom, "vertices", ()))
        nf += len(getattr(geom, "faces", ()))
    bounds = scene.bounds if nv else None
    extent = float(np.ptp(bounds, axis=0).max()) if bounds is not None else None
    return f"{nv:,} vertices, {nf:,} triangles", extent


class ImportDialog(QtWidgets.QDialog):
    """Units, up axis, group names, materials file and patch size for a model import."""

    def __init__(self, path: Path, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.path = Path(path)
        self.suffix = self.path.suffix.lower()
        importer = importer_for(self.path)
        self.format_options = importer.options if importer is not None else ()
        self.setWindowTitle(f"Import {self.path.name}")
        form = QtWidgets.QFormLayout(self)
        summary, self.extent = self._preview()
        self.summary = QtWidgets.QLabel(summary)
        form.addRow("File", self.summary)
        self.units = QtWidgets.QComboBox()
        for name, scale in UNITS:
            self.units.addItem(name, scale)
        form.addRow("Drawn in", self.units)
        self.size = QtWidgets.QLabel()
        form.addRow("Model size", self.size)
        self.up = QtWidgets.QComboBox()
        self.up.addItem("z (SketchUp, Rhino, Revit, IFC)", "z")
        self.up.addItem("y (glTF, Blender OBJ export default, 3ds Max)", "y")
        self.up.setCurrentIndex(self.up.findData(default_up(self.path)))
        form.addRow("Up axis", self.up)
        self.group_by = QtWidgets.QComboBox()
        self.group_by.addItem("node names", "node")
        self.group_by.addItem("material names", "material")
        if "group_by" in self.format_options:
            form.addRow("Lighting groups", self.group_by)
        else:
            self.group_by.hide()
        self.materials = QtWidgets.QLineEdit()
        self.materials.setPlaceholderText(
            "none: EN 12464-1 defaults by role (floor 0.2, walls 0.5, ceiling 0.7)"
            if self.suffix == ".ifc"
            else "none: the materials' colours, else reflectance 0.5"
        )
        browse = QtWidgets.QPushButton("Choose...")
        browse.setAutoDefault(False)  # Enter is OK, not another file chooser
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
        form.addRow(ok_cancel(self))
        self.units.currentIndexChanged.connect(self._show_size)
        if self.suffix == ".ifc":
            # IFC files state their length unit; ifcopenshell converts it to metres.
            self.units.setEnabled(False)
            self.units.setToolTip("IFC files carry their unit; lengths are read in metres")
        elif self.extent is not None and self.extent > 1000:  # probably millimetres
            self.units.setCurrentIndex(2)
        self._show_size()

    def _preview(self) -> tuple[str, float | None]:
        """What the file holds and its extent in model units (None: unknown)."""
        try:
            if self.suffix == ".obj":
                counts = count_obj_lines(self.path)
                return f"{counts.vertices:,} vertices, {counts.faces:,} faces", raw_extent(
                    self.path
                )
            if self.suffix == ".ifc":
                size = self.path.stat().st_size
                return f"IFC model, {size / 1024:,.0f} kB (elements read on import)", None
            return mesh_preview(self.path)
        except OSError as exc:
            return f"cannot read it: {exc.strerror}", None
        except LightInvError as exc:
            return str(exc), None

    def _browse(self) -> None:
        path = ask.open_file(self, "Materials mapping", "Materials JSON (*.json)")
        if path:
            self.materials.setText(path)

    def _show_size(self) -> None:
        if self.extent is None:
            self.size.setText("unknown" if self.suffix != ".ifc" else "read from the file")
            return
        metres = self.extent * self.units.currentData()
        warn = "  (too big for a building: check the units)" if metres > 1000 else ""
        self.size.setText(f"{metres:,.2f} m across{warn}")

    def options(self) -> dict:
        """The scene's import settings (obj_project's options)."""
        out = {
            "scale": float(self.units.currentData()) if self.suffix != ".ifc" else 1.0,
            "up": self.up.currentData(),
            "resolution": float(self.resolution.value()),
            "skip_degenerate": self.skip.isChecked(),
        }
        if "group_by" in self.format_options:
            out["group_by"] = self.group_by.currentData()
        if self.materials.text().strip():
            out["materials"] = self.materials.text().strip()
        return out

    def accept(self) -> None:
        try:
            if self.materials.text().strip() and not Path(self.materials.text()).is_file():
                raise LightInvError(f"no materials file {self.materials.text()!r}")
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return
        super().accept()
