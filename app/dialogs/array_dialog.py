"""The dialog that adds or edits a luminaire array.

An array is one product (from the catalogue, or an IES, EULUMDAT or GLDF file: File…
lists a GLDF's variants in the product box, each ``FILE.gldf#VARIANT``) laid out evenly in
a luminaire zone: rows and columns at the centres of equal cells of a rectangle, a
rotation of 0 or 90 degrees, a dimming level, and which of these the optimiser may
change: by default the rows and columns, every luminaire at full output (a dimmed
answer needs dimming controls; tick "dimming" to allow it). The dialog shows the
spacing and the array's power as they are typed, the product's photometry warnings
(what changes its light) once it is chosen, and its CIE 190 glare rating (UGR in the
4H x 8H room at 70/50/20, crosswise / endwise; docs/photometry.md), which the
luminaires panel's catalogue shows too.
"""

from __future__ import annotations

import functools
import html

from PySide6 import QtCore, QtWidgets

from app.dialogs import ask
from app.dialogs.fields import integer_box, number_box, ok_cancel
from lightinv_core.design.arrays import DEFAULT_SHR
from lightinv_core.design.model import ARRAY_VARIABLES, LuminaireArray, new_array
from lightinv_core.design.model.array import free_zone, overlapping
from lightinv_core.errors import LightInvError
from lightinv_core.light.arrays import resolve_product
from lightinv_core.luminaires import builtin_catalogue
from lightinv_core.luminaires.catalogue import file_entries
from lightinv_core.luminaires.formats import file_filter, split_reference
from lightinv_core.luminaires.photometry import light_warnings
from lightinv_core.luminaires.ugr_table import catalogue_ugr

UGR_TIP = (
    "Unified glare rating (CIE 190 table): 4H x 8H room, reflectances 70/50/20 "
    "(ceiling/walls/floor), viewed crosswise / endwise"
)


@functools.lru_cache(maxsize=64)
def _ugr_of(product: str, stamp: float) -> tuple[float, float] | str:
    try:
        return catalogue_ugr(resolve_product(product).photometry)
    except LightInvError as exc:
        return str(exc)


def product_ugr(product: str) -> tuple[str, str]:
    """(what to show, its tooltip) for the CIE 190 UGR of ``product`` (a catalogue name
    or a photometric file): "18.1 / 18.3" (crosswise / endwise), or "-" and why not."""
    ref = split_reference(product)
    try:
        stamp = ref[0].stat().st_mtime if ref is not None else 0.0
    except OSError:
        stamp = -1.0
    got = _ugr_of(product, stamp)
    if isinstance(got, str):
        return "-", f"UGR not computed: {got}"
    return f"{got[0]:.1f} / {got[1]:.1f}", UGR_TIP


FREE_LABELS = {
    "u0": "u0",
    "v0": "v0",
    "u1": "u1",
    "v1": "v1",
    "rows": "rows",
    "columns": "columns",
    "rotation": "rotation",
    "dimming": "dimming",
}
FREE_TIPS = {
    "dimming": "Let the optimiser dim the luminaires (it then needs dimming controls); "
    "unticked, every luminaire runs at the dimming above (full output by default) and "
    "the least power is the fewest luminaires.",
}


class ArrayDialog(QtWidgets.QDialog):
    """Fields of one ``LuminaireArray``; ``array()`` builds it (DesignError if bad)."""

    def __init__(
        self,
        zones: dict[str, tuple[float, float]],
        base: LuminaireArray | None = None,
        name: str = "A1",
        parent: QtWidgets.QWidget | None = None,
        others: tuple[LuminaireArray, ...] = (),
        groups: tuple[str, ...] = (),
    ):
        super().__init__(parent)
        self.setWindowTitle("Luminaire array" if base is None else f"Edit array {base.name}")
        self.zones = zones
        self.others = others  # the design's other arrays: a new one goes in a free zone
        zone = (
            base.zone if base is not None else (free_zone(zones, others) or next(iter(zones), ""))
        )
        w, h = zones.get(zone, (1.0, 1.0))
        base = base or new_array(name, zone, builtin_catalogue()[0].name, (w, h))
        form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(base.name)
        form.addRow("Name", self.name)
        self.zone = QtWidgets.QComboBox()
        self.zone.addItems(list(zones))
        self.zone.setCurrentText(base.zone)
        form.addRow("Zone", self.zone)
        self.product = QtWidgets.QComboBox(editable=True)
        self.product.addItems([e.name for e in builtin_catalogue()])
        self.product.setCurrentText(base.product)
        browse = QtWidgets.QPushButton("File…")
        browse.setAutoDefault(False)  # Enter is OK, not another file chooser
        browse.clicked.connect(self._browse)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.product, 1)
        row.addWidget(browse)
        form.addRow("Product", row)
        self.corners = [number_box(-1e3, 1e3, x) for x in base.rect]
        rect = QtWidgets.QHBoxLayout()
        for box in self.corners:
            rect.addWidget(box)
        form.addRow("Rectangle u0 v0 u1 v1 (m)", rect)
        self.rows = integer_box(1, 100, base.rows)
        self.columns = integer_box(1, 100, base.columns)
        counts = QtWidgets.QHBoxLayout()
        counts.addWidget(self.rows)
        counts.addWidget(QtWidgets.QLabel("rows (along v) x"))
        counts.addWidget(self.columns)
        counts.addWidget(QtWidgets.QLabel("columns (along u)"))
        form.addRow("Layout", counts)
        self.rotation = QtWidgets.QComboBox()
        self.rotation.addItems(["0° (C0 along u)", "90° (C0 along v)"])
        self.rotation.setCurrentIndex(0 if base.rotation == 0 else 1)
        form.addRow("Rotation", self.rotation)
        self.dimming = number_box(0.01, 1.0, base.dimming, 2, 0.05)
        form.addRow("Dimming", self.dimming)
        self.mf = number_box(0.01, 1.0, base.maintenance_factor, 2, 0.05)
        form.addRow("Maintenance factor", self.mf)
        self.control = QtWidgets.QComboBox()
        for g in dict.fromkeys((*groups, base.control_group)):
            self.control.addItem(g)
        self.control.setCurrentText(base.control_group)
        self.control.setToolTip("The control group whose daylight sensor dims it")
        form.addRow("Control group", self.control)
        self.free = {}
        free = QtWidgets.QHBoxLayout()
        for var in ARRAY_VARIABLES:
            box = QtWidgets.QCheckBox(FREE_LABELS[var])
            box.setChecked(var in base.free)
            box.setToolTip(FREE_TIPS.get(var, ""))
            self.free[var] = box
            free.addWidget(box)
        form.addRow("Free for the optimiser", free)
        self.rows_range = (
            integer_box(1, 100, base.rows_range[0]),
            integer_box(1, 100, base.rows_range[1]),
        )
        self.cols_range = (
            integer_box(1, 100, base.columns_range[0]),
            integer_box(1, 100, base.columns_range[1]),
        )
        self.dim_range = (
            number_box(0.01, 1.0, base.dimming_range[0], 2, 0.05),
            number_box(0.01, 1.0, base.dimming_range[1], 2, 0.05),
        )
        for label, pair in (
            ("Rows range", self.rows_range),
            ("Columns range", self.cols_range),
            ("Dimming range", self.dim_range),
        ):
            line = QtWidgets.QHBoxLayout()
            line.addWidget(pair[0])
            line.addWidget(QtWidgets.QLabel("to"))
            line.addWidget(pair[1])
            form.addRow(label, line)
        self.glare = QtWidgets.QLabel()
        self.glare.setToolTip(UGR_TIP)
        form.addRow("Glare (UGR, CIE 190)", self.glare)
        self.summary = QtWidgets.QLabel()
        self.summary.setWordWrap(True)  # a warning is a long line
        form.addRow(self.summary)
        for box in (*self.corners, self.dimming):
            box.valueChanged.connect(self._update)
        for box in (self.rows, self.columns):
            box.valueChanged.connect(self._update)
        self.product.currentTextChanged.connect(self._update)
        self.zone.currentTextChanged.connect(self._zone_changed)
        form.addRow(ok_cancel(self))
        self._update()

    def showEvent(self, event) -> None:
        """Open tall enough for the summary's wrapped lines."""
        super().showEvent(event)
        self.resize(self.width(), max(self.height(), self.heightForWidth(self.width())))

    def accept(self) -> None:
        """Close only on an array that can be built (OK or Enter); else say why and stay."""
        try:
            a = self.array()
            resolve_product(a.product, a.watts)
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return
        super().accept()

    def _browse(self) -> None:
        path = ask.open_file(self, "Photometric file", file_filter())
        if not path:
            return
        try:
            entries = file_entries(path)
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return
        # Each product of the file (a GLDF's variants) becomes a choice, the first chosen;
        # its name shows in the tooltip and under the fields.
        for e in entries:
            if self.product.findText(e.reference) < 0:
                self.product.addItem(e.reference)
            self.product.setItemData(
                self.product.findText(e.reference), e.name, QtCore.Qt.ToolTipRole
            )
        self.product.setCurrentText(entries[0].reference)

    def _zone_changed(self, zone: str) -> None:
        w, h = self.zones.get(zone, (1.0, 1.0))
        for box, value in zip(self.corners, (0.0, 0.0, w, h), strict=True):
            box.setValue(value)

    def _update(self) -> None:
        try:
            a = self.array()
            p = resolve_product(a.product, a.watts)
        except LightInvError as exc:
            self.summary.setText(f"<span style='color:#b00'>{exc}</span>")
            self.glare.setText("-")
            return
        shown, tip = product_ugr(a.product)
        self.glare.setText(
            f"{shown} crosswise / endwise (4H x 8H room, 70/50/20)" if shown != "-" else tip
        )
        su, sv = a.spacing
        named = split_reference(a.product) is not None and p.name != a.product
        text = f"<b>{html.escape(p.name)}</b><br>" if named else ""  # a file's product
        text += (
            f"{a.count} luminaires, spacing {su:.2f} x {sv:.2f} m; "
            f"{a.count * p.lumens * a.dimming:,.0f} lm, {a.count * p.watts * a.dimming:,.1f} W"
            f"<br>Spacing kept within {DEFAULT_SHR:g} x the mounting height above the work "
            "plane (a spacing/height rule overrides)."
        )
        # What changes the product's light (a tilt table not applied, a light output ratio
        # above 100%), as the panel, the status bar and the report say it.
        warnings = light_warnings([p.photometry])
        # Every zone already has an array: say so rather than stack two in one place.
        shared = overlapping(a, self.others)
        if shared:
            warnings.append(
                f"overlaps array{'s' * (len(shared) > 1)} {', '.join(shared)} in zone "
                f"{a.zone}: their luminaires would be mounted on the same ceiling area; "
                "choose another zone or rectangle"
            )
        for w in warnings:
            text += f"<br><span style='color:#a05a00'>\u26a0 {html.escape(w)}</span>"
        self.summary.setText(text)
        if self.isVisible():  # room for the wrapped lines
            self.resize(self.width(), max(self.height(), self.heightForWidth(self.width())))

    def array(self) -> LuminaireArray:
        """The array as entered (DesignError naming the bad field)."""
        return LuminaireArray(
            self.name.text().strip(),
            self.zone.currentText(),
            self.product.currentText().strip(),
            tuple(b.value() for b in self.corners),
            rows=self.rows.value(),
            columns=self.columns.value(),
            rotation=0 if self.rotation.currentIndex() == 0 else 90,
            dimming=self.dimming.value(),
            free=tuple(v for v, box in self.free.items() if box.isChecked()),
            rows_range=(self.rows_range[0].value(), self.rows_range[1].value()),
            columns_range=(self.cols_range[0].value(), self.cols_range[1].value()),
            dimming_range=(self.dim_range[0].value(), self.dim_range[1].value()),
            maintenance_factor=self.mf.value(),
            control_group=self.control.currentText(),
        )
