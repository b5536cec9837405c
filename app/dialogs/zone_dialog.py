"""The name and kind of an emitter zone just drawn (the kinds: every registered source
type), with the surface it is on and its size."""

from __future__ import annotations

from PySide6 import QtWidgets

from app.dialogs.fields import ok_cancel, source_kind_box
from lightinv_core.editing.zones import surface_label, zone_size


def size_text(rect=None, outline=None) -> str:
    """'2.00 x 1.20 m (2.40 m²)' of a zone's rectangle or polygon ('' for neither)."""
    if rect is None and outline is None:
        return ""
    w, h, area = zone_size(rect, outline)
    shape = "polygon within " if outline is not None else ""
    return f"{shape}{w:.2f} x {h:.2f} m ({area:.2f} m²)"


class ZoneDialog(QtWidgets.QDialog):
    """Name and kind of a zone just drawn on ``surface``; ``rect`` (u0, v0, u1, v1) or
    ``outline`` (its corners), metres of the surface, give the size shown."""

    def __init__(
        self,
        surface: str,
        default_name: str,
        parent: QtWidgets.QWidget | None = None,
        rect=None,
        outline=None,
    ):
        super().__init__(parent)
        where = surface_label(surface)
        self.setWindowTitle(f"New emitter zone on {where}")
        form = QtWidgets.QFormLayout(self)
        form.addRow("Surface", QtWidgets.QLabel(where))
        self.size = QtWidgets.QLabel(size_text(rect, outline))
        if self.size.text():
            form.addRow("Size", self.size)
        self.name = QtWidgets.QLineEdit(default_name)
        form.addRow("Name", self.name)
        self.kind = source_kind_box()  # the kind is the item's data
        self.kind.setToolTip(
            "Luminaire: electric light (ceilings, roofs, walls). Skylight: glazing on a "
            "ceiling or roof. Window (glazing): daylight through any planar face, a "
            "wall's included; the sky and ground on its plane light it."
        )
        form.addRow("Kind", self.kind)
        form.addRow(ok_cancel(self))
