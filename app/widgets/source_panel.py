"""The Properties panel's source editor: the current source's corners, strength, the
optimiser's freedom over it and its rules; adding and removing sources.

It reads the document when it changes (signals blocked while it fills its fields) and
writes back only through the document's setters. What a source's strength is, and
whether it has a flux range and an efficacy, its ``SourceType`` says."""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets

from app.document import Document
from app.widgets.elided_label import ElidedLabel
from lightinv_core.design.model import CORNERS
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import GlazingKind
from lightinv_core.sources.types import source_type

GLAZING_TEXT = {
    GlazingKind.DIFFUSING: "diffusing (a glow)",
    GlazingKind.CLEAR: "clear (sky and sun)",
}
"""The glazing choice's entries for people."""

STRENGTH_BOXES = {
    # Source field: (label, decimals, largest, step, suffix)
    "flux": ("flux", 0, 1e7, 100.0, " lm"),  # whole lumens: what a datasheet gives
    "filter": ("filter (0-1)", 3, 1.0, 0.05, ""),
    "exitance": ("exitance", 1, 1e7, 100.0, " lm/m²"),
}
"""How the strength field shows each ``Source`` field a source type may name as its
strength (``SourceType.strength``); another field shows as its type's
``strength_label``."""


def strength_field(s) -> str:
    """The ``Source`` field that sets how much ``s`` emits: its type's strength, or a
    luminous panel's fixed exitance when it has no flux."""
    t = source_type(s.kind)
    if getattr(s, t.strength, None) is None and "exitance" in t.fields:
        return "exitance"
    return t.strength


def zone_text(doc: Document, zone: str) -> str:
    """A zone with its kind and size: "downlights (luminaire zone, 2.00 x 0.50 m)"."""
    try:
        w, h = doc.zone_size(zone)
        return f"{zone} ({doc.zone_kind(zone)} zone, {w:.2f} x {h:.2f} m)"
    except (KeyError, LightInvError):  # a zone the scene no longer has
        return zone


class SourcePanel(QtWidgets.QGroupBox):
    """Edits the current source numerically; adding and removing sources."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__("Source", parent)
        self.doc = doc
        form = QtWidgets.QFormLayout(self)
        # The selected source and its own zone first; the zone a new source goes in is
        # asked for with the Add button below (the one "Zone" box above the fields read
        # as the selected source's zone).
        self.name = QtWidgets.QLabel("-")
        form.addRow("Selected source", self.name)
        self.own_zone = ElidedLabel("-")  # a long zone name must not widen the dock
        form.addRow("In zone", self.own_zone)
        self.zone = QtWidgets.QComboBox()
        self.zone.setToolTip("The emitter zone a new source is added in")
        self.add_button = QtWidgets.QPushButton("Add source")
        self.remove_button = QtWidgets.QPushButton("Remove source")
        self.corners = []
        for label in ("u0", "v0", "u1", "v1"):
            box = QtWidgets.QDoubleSpinBox(decimals=3, singleStep=0.05, suffix=" m")
            box.setRange(-1000.0, 1000.0)  # a zone may run on from its surface
            box.setKeyboardTracking(False)
            box.valueChanged.connect(self._rect_edited)
            self.corners.append(box)
            form.addRow(label, box)
        self.strength = QtWidgets.QDoubleSpinBox(decimals=3, singleStep=100.0)
        self.strength.setRange(0.0, 1e7)
        self.strength.setKeyboardTracking(False)
        self.strength.valueChanged.connect(self._strength_edited)
        self.strength_label = QtWidgets.QLabel("flux")
        form.addRow(self.strength_label, self.strength)
        # Glazing kinds (daylit sources whose type takes the field): clear glazing's shape
        # and filter may be free like a diffusing one's (docs/daylight.md).
        self.glazing = QtWidgets.QComboBox()
        for kind in GlazingKind:
            self.glazing.addItem(GLAZING_TEXT[kind], str(kind))
        self.glazing.setToolTip(
            "Diffusing: the glass glows with the light on its outside. Clear: the sky and "
            "the sun seen through it by direction"
        )
        self.glazing.currentIndexChanged.connect(self._glazing_edited)
        self.glazing_label = QtWidgets.QLabel("Glazing")
        form.addRow(self.glazing_label, self.glazing)
        # The daylight-linked control group a luminaire is dimmed with (Climate tab).
        self.control = QtWidgets.QComboBox()
        self.control.setToolTip("The control group whose daylight sensor dims it (Climate tab)")
        self.control.activated.connect(self._control_edited)
        self.control_label = QtWidgets.QLabel("Control group")
        form.addRow(self.control_label, self.control)
        # What the optimiser may change, and within what: without these a luminaire kept
        # its 3,000 lm and a least-power run could not reach the target.
        self.free_place = QtWidgets.QCheckBox("position and size")
        self.free_strength = QtWidgets.QCheckBox("flux")
        frow = QtWidgets.QHBoxLayout()
        frow.addWidget(self.free_place)
        frow.addWidget(self.free_strength)
        form.addRow("Optimise", frow)
        self.free_place.toggled.connect(self._free_edited)
        self.free_strength.toggled.connect(self._free_edited)
        self.flux_min = QtWidgets.QDoubleSpinBox(decimals=0, singleStep=500.0, suffix=" lm")
        self.flux_max = QtWidgets.QDoubleSpinBox(decimals=0, singleStep=500.0, suffix=" lm")
        rrow = QtWidgets.QHBoxLayout()
        for box in (self.flux_min, self.flux_max):
            box.setRange(0.0, 1e7)
            box.setKeyboardTracking(False)
            box.valueChanged.connect(self._range_edited)
            rrow.addWidget(box)
        self.range_label = QtWidgets.QLabel("flux range")
        form.addRow(self.range_label, rrow)
        self.efficacy = QtWidgets.QDoubleSpinBox(decimals=1, singleStep=10.0, suffix=" lm/W")
        self.efficacy.setRange(0.1, 1000.0)
        self.efficacy.setKeyboardTracking(False)
        self.efficacy.valueChanged.connect(lambda v: self._apply(efficacy=v))
        self.efficacy_label = QtWidgets.QLabel("efficacy")
        form.addRow(self.efficacy_label, self.efficacy)
        self.centred = QtWidgets.QCheckBox("centred in its zone")
        self.centred.toggled.connect(self._centred_edited)
        form.addRow("Rule", self.centred)
        self.mirror = QtWidgets.QComboBox()
        self.mirror_axis = QtWidgets.QComboBox()
        self.mirror_axis.addItems(["u", "v"])
        mrow = QtWidgets.QHBoxLayout()
        mrow.addWidget(self.mirror)
        mrow.addWidget(self.mirror_axis)
        form.addRow("Mirror of", mrow)
        self.mirror.currentIndexChanged.connect(self._mirror_edited)
        self.mirror_axis.currentIndexChanged.connect(self._mirror_edited)
        form.addRow(self.remove_button)
        line = QtWidgets.QFrame()
        line.setFrameShape(QtWidgets.QFrame.HLine)
        line.setFrameShadow(QtWidgets.QFrame.Sunken)
        form.addRow(line)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.zone, 1)
        row.addWidget(self.add_button)
        form.addRow("New source in", row)
        self.add_button.clicked.connect(self._add)
        self.remove_button.clicked.connect(self._remove)
        doc.sceneChanged.connect(self._fill_zones)
        doc.designChanged.connect(self.refresh)

    def _fill_zones(self) -> None:
        self.zone.clear()
        for z in self.doc.scene.zones:
            self.zone.addItem(f"{z.name} ({z.kind})", z.name)

    def refresh(self) -> None:
        name = self.doc.current_source
        boxes = [
            *self.corners,
            self.strength,
            self.centred,
            self.mirror,
            self.mirror_axis,
            self.free_place,
            self.free_strength,
            self.flux_min,
            self.flux_max,
            self.efficacy,
            self.glazing,
            self.control,
        ]
        for b in boxes:
            b.blockSignals(True)
        try:
            if name is None or name not in {s.name for s in self.doc.design.sources}:
                self.name.setText("none: add one in a zone below")
                self.own_zone.setText("-")
                for b in boxes:
                    b.setEnabled(False)
                return
            s = self.doc.design.source(name)
            self.name.setText(f"{s.name} ({s.kind})")
            self.own_zone.setText(zone_text(self.doc, s.zone))
            self.centred.setEnabled(True)
            self.centred.setChecked(self.doc.centred(name))
            self.mirror.clear()
            self.mirror.addItem("(none)", None)
            for other in self.doc.design.sources:
                if other.name != name and other.kind == s.kind:
                    self.mirror.addItem(other.name, other.name)
            tie = self.doc.mirror_of(name)
            self.mirror.setEnabled(True)
            self.mirror_axis.setEnabled(True)
            self.mirror.setCurrentIndex(max(0, self.mirror.findData(tie[0])) if tie else 0)
            self.mirror_axis.setCurrentText(tie[1] if tie else "u")
            w, h = self.doc.zone_size(s.zone)
            # Show the source as lit: a mirror's copy and a centred source's far corner
            # follow their rule, so those fields show the rule's numbers, read-only.
            light = self.doc.light  # the layout of the design now (the view may lag)
            lit = light.layout(self.doc.design) if light is not None else self.doc.design.sources
            shown = {x.name: x for x in lit}.get(name, s)
            tied = {0, 1, 2, 3} if self.doc.mirror_of(name) else set()
            if self.doc.centred(name):
                tied |= {2, 3}
            for k, (box, value, top) in enumerate(
                zip(self.corners, shown.rect, (w, h, w, h), strict=True)
            ):
                box.setEnabled(k not in tied)
                box.setMaximum(top)
                box.setValue(value)
            self.strength.setEnabled(not self.doc.mirror_of(name))
            self._show_freedom(s, tied=bool(self.doc.mirror_of(name)))
            s = shown
            field = strength_field(s)
            label, decimals, top, step, suffix = STRENGTH_BOXES.get(
                field, (source_type(s.kind).strength_label, 3, 1e7, 1.0, "")
            )
            self.strength_label.setText(label)
            self.strength.setDecimals(decimals)
            self.strength.setRange(0.0, top)
            self.strength.setSingleStep(step)
            self.strength.setSuffix(suffix)
            self.strength.setValue(getattr(s, field))
        finally:
            for b in boxes:
                b.blockSignals(False)

    def _show_freedom(self, s, tied: bool) -> None:
        """The optimiser's freedom over source ``s`` (as written), its flux range and
        efficacy; a mirror's copy follows its original and has none of its own."""
        t = source_type(s.kind)
        strength = t.strength
        self.free_strength.setText(strength)
        self.free_place.setChecked(any(v in s.free for v in CORNERS))
        self.free_strength.setChecked(strength in s.free)
        self.free_place.setEnabled(not tied)
        # A luminous panel's fixed exitance (no flux) has no strength to free.
        self.free_strength.setEnabled(not tied and getattr(s, strength, None) is not None)
        self.flux_min.setValue(s.flux_range[0])
        self.flux_max.setValue(s.flux_range[1])
        self.efficacy.setValue(s.efficacy)
        glazed = "glazing" in t.fields
        for w in (self.glazing, self.glazing_label):
            w.setVisible(glazed)
        self.glazing.setEnabled(glazed and not tied)
        self.glazing.setCurrentIndex(max(0, self.glazing.findData(str(s.glazing))))
        if glazed and s.glazing == GlazingKind.CLEAR:  # frees its rectangle, not its filter
            self.free_strength.setEnabled(False)
        ranged, rated = "flux_range" in t.fields, "efficacy" in t.fields
        for w in (self.flux_min, self.flux_max, self.range_label):
            w.setVisible(ranged)
            w.setEnabled(not tied and ranged and strength in s.free)
        for w in (self.efficacy, self.efficacy_label):
            w.setVisible(rated)
            w.setEnabled(not tied and rated)
        grouped = "control_group" in t.fields
        for w in (self.control, self.control_label):
            w.setVisible(grouped)
        self.control.setEnabled(grouped)
        self.control.clear()
        for g in self.doc.control_group_names():
            self.control.addItem(g, g)
        self.control.setCurrentIndex(max(0, self.control.findData(s.control_group)))

    def _free_edited(self) -> None:
        name = self.doc.current_source
        if name is None:
            return
        s = self.doc.design.source(name)
        strength = source_type(s.kind).strength
        free = (CORNERS if self.free_place.isChecked() else ()) + (
            (strength,) if self.free_strength.isChecked() else ()
        )
        self._apply(free=tuple(free))

    def _glazing_edited(self) -> None:
        name = self.doc.current_source
        kind = self.glazing.currentData()
        if name is None or kind is None or self.doc.design.source(name).glazing == kind:
            return
        free = self.doc.design.source(name).free
        if kind == GlazingKind.CLEAR:  # its rectangle stays free, its filter not
            free = tuple(v for v in free if v in CORNERS)
        if kind != GlazingKind.CLEAR:
            self._apply(glazing=kind, free=free)
            return
        # The first clear glazing traces its sky and sun before the view relights: a few
        # seconds in which the window says so rather than looking hung.
        win = self.window()
        bar = win.statusBar() if isinstance(win, QtWidgets.QMainWindow) else None
        if bar is not None:
            bar.showMessage("Tracing the sky and the sun through the clear glazing...")
            bar.repaint()
        QtWidgets.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        try:
            self._apply(glazing=kind, free=free)
        finally:
            QtWidgets.QApplication.restoreOverrideCursor()
            if bar is not None:
                bar.clearMessage()

    def _control_edited(self) -> None:
        name, group = self.doc.current_source, self.control.currentData()
        if name is not None and group is not None:
            self._guard(self.doc.set_luminaire_group, name, group)

    def _range_edited(self) -> None:
        self._apply(flux_range=(self.flux_min.value(), self.flux_max.value()))

    def _apply(self, **fields) -> None:
        try:
            self.doc.update_source(self.doc.current_source, **fields)
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            self.refresh()

    def _rect_edited(self) -> None:
        self._apply(rect=tuple(b.value() for b in self.corners))

    def _strength_edited(self) -> None:
        s = self.doc.design.source(self.doc.current_source)
        self._apply(**{strength_field(s): self.strength.value()})

    def _centred_edited(self, on: bool) -> None:
        if self.doc.current_source is not None:
            self._guard(self.doc.set_centred, self.doc.current_source, on)

    def _mirror_edited(self) -> None:
        if self.doc.current_source is not None:
            self._guard(
                self.doc.set_mirror,
                self.doc.current_source,
                self.mirror.currentData(),
                self.mirror_axis.currentText(),
            )

    def _guard(self, fn, *args) -> None:
        try:
            fn(*args)
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            self.refresh()

    def _add(self) -> None:
        zone = self.zone.currentData()
        if zone is not None:
            self.doc.add_source(zone)

    def _remove(self) -> None:
        if self.doc.current_source is not None:
            self.doc.remove_source(self.doc.current_source)
