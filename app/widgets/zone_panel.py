"""The Properties panel's drawn zones: rename, retype, resize or delete the emitter zones
drawn on the project's scene (the scene is re-meshed), and make the face picked in the
view a zone (a window on a wall: any planar face may become glazing)."""

from __future__ import annotations

from PySide6 import QtWidgets

from app.dialogs import ask
from app.dialogs.fields import source_kind_box
from app.dialogs.zone_dialog import ZoneDialog
from app.document import Document
from lightinv_core.editing.zones import surface_label
from lightinv_core.errors import LightInvError, SceneError

WINDOW = "window"
"""The kind the picked face becomes first (the dialog offers every kind)."""


class ZonePanel(QtWidgets.QGroupBox):
    """The emitter zones drawn on this project's scene: rename, retype, resize, delete."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__("Drawn zones", parent)
        self.doc = doc
        form = QtWidgets.QFormLayout(self)
        # First, so the two clicks that make a side window need no scrolling.
        self.face_button = QtWidgets.QPushButton("Make picked face a zone...")
        self.face_button.setToolTip(
            "The whole planar face under the first patch picked (Select patches mode) "
            "becomes a zone: a window (glazing) first, any kind in the dialog"
        )
        form.addRow(self.face_button)
        self.zone = QtWidgets.QComboBox()
        form.addRow("Zone", self.zone)
        self.name = QtWidgets.QLineEdit()
        form.addRow("Name", self.name)
        self.kind = source_kind_box()  # the kind is the item's data
        form.addRow("Kind", self.kind)
        self.corners = []
        for label in ("u0", "v0", "u1", "v1"):
            box = QtWidgets.QDoubleSpinBox(decimals=3, singleStep=0.1, suffix=" m")
            box.setRange(-1000.0, 1000.0)  # a zone may run on from its surface
            self.corners.append(box)
            form.addRow(label, box)
        self.outline = QtWidgets.QLineEdit()
        self.outline.setPlaceholderText("rectangle (u0 v0 u1 v1 above)")
        self.outline.setToolTip(
            "A polygon zone's corners, metres along the surface's u, v axes: "
            "'u v; u v; u v; ...' in order around it. Empty: the rectangle above."
        )
        form.addRow("Polygon", self.outline)
        row = QtWidgets.QHBoxLayout()
        self.apply_button = QtWidgets.QPushButton("Apply")
        self.delete_button = QtWidgets.QPushButton("Delete zone")
        row.addWidget(self.apply_button)
        row.addWidget(self.delete_button)
        form.addRow(row)
        self.hint = QtWidgets.QLabel(
            "Draw zone: pick the kind in the toolbar, drag a rectangle (Draw polygon "
            "zone: click corners). Skylights go on ceilings and roofs, luminaires also on "
            "walls, windows (glazing) on any planar face. Or pick a face (Select patches) "
            "and press Make picked face a zone. Corners: metres along the surface's u, v."
        )
        self.hint.setWordWrap(True)
        form.addRow(self.hint)
        self.zone.currentIndexChanged.connect(self._show)
        self.apply_button.clicked.connect(self.apply)
        self.delete_button.clicked.connect(self.delete)
        self.face_button.clicked.connect(lambda: self.zone_from_face())
        doc.sceneChanged.connect(self.refresh)

    def refresh(self) -> None:
        self.zone.blockSignals(True)
        self.zone.clear()
        for z in self.doc.user_zones:
            self.zone.addItem(f"{z.name} on {surface_label(z.surface)}", z.name)
        self.zone.blockSignals(False)
        has = bool(self.doc.user_zones)
        widgets = (self.name, self.kind, *self.corners, self.outline)
        for w in (*widgets, self.apply_button, self.delete_button):
            w.setEnabled(has)
        self._show()

    def _current(self):
        name = self.zone.currentData()
        return next((z for z in self.doc.user_zones if z.name == name), None)

    def _show(self) -> None:
        z = self._current()
        if z is None:
            return
        self.name.setText(z.name)
        self.kind.setCurrentIndex(max(0, self.kind.findData(str(z.kind))))
        for box, value in zip(self.corners, z.rect, strict=True):
            box.setValue(value)
            box.setEnabled(z.outline is None)  # a polygon's rectangle is its bounds
        self.outline.setText(
            # Enough digits that Apply (a rename) gives back the same corners.
            "" if z.outline is None else "; ".join(f"{u:.12g} {v:.12g}" for u, v in z.outline)
        )

    def apply(self) -> None:
        """Write the fields back (the scene is re-meshed)."""
        from dataclasses import replace

        z = self._current()
        if z is None:
            return
        text = self.outline.text().strip()
        try:
            outline = parse_corners(text) if text else None
            new = replace(
                z,
                name=self.name.text().strip(),
                kind=self.kind.currentData(),
                rect=None if outline else tuple(b.value() for b in self.corners),
                outline=outline,
            )
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            return
        self._set([new if u.name == z.name else u for u in self.doc.user_zones])

    def zone_from_face(self, dialog: ZoneDialog | None = None) -> bool:
        """Make the whole face under the first picked patch a zone, named and typed in
        the zone dialog (a window first); says why not when it cannot."""
        picked = getattr(self.doc, "selection", ())
        if len(picked) == 0:
            QtWidgets.QMessageBox.information(
                self, "LightInv", "Pick a face first: Select patches mode, click the face."
            )
            return False
        try:
            surface, rect = self.doc.face_zone(int(picked[0]))
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            return False
        if dialog is None:
            dialog = ZoneDialog(surface, self.doc.new_zone_name(), self, rect=rect)
            dialog.kind.setCurrentIndex(max(0, dialog.kind.findData(WINDOW)))
        if not ask.accepted(dialog):
            return False
        from lightinv_core.scene.edits import ZoneEdit

        try:
            edit = ZoneEdit(dialog.name.text().strip(), dialog.kind.currentData(), surface, rect)
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            return False
        self._set([*self.doc.user_zones, edit])
        return True

    def delete(self) -> None:
        """Remove the zone (and any source placed in it)."""
        z = self._current()
        if z is not None:
            self._set([u for u in self.doc.user_zones if u.name != z.name])

    def _set(self, zones) -> None:
        try:
            self.doc.set_user_zones(zones)
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))


def parse_corners(text: str) -> tuple[tuple[float, float], ...]:
    """Corners typed as 'u v; u v; ...' (commas also separate the two numbers);
    SceneError on anything else."""
    corners = []
    for k, part in enumerate(p for p in text.split(";") if p.strip()):
        items = part.replace(",", " ").split()
        try:
            u, v = (float(x) for x in items)
        except ValueError:
            raise SceneError(
                f"polygon corner {k + 1} ({part.strip()!r}): give two numbers, 'u v', and "
                "separate corners with ';'"
            ) from None
        corners.append((u, v))
    return tuple(corners)
