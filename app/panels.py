"""Side panels: the scene/design tree, the source editor and the intention dialog.

Each widget reads the document when it changes (signals blocked while it fills
its fields) and writes back only through the document's setters.
"""

from __future__ import annotations

from PySide6 import QtCore, QtGui, QtWidgets

from app import dialogs
from app.document import Document
from lightinv_core.design.model import CORNERS, DesignError, Intention, Rule
from lightinv_core.editing.rules import rule_text
from lightinv_core.errors import LightInvError, SceneError
from lightinv_core.kinds import Bound, Scenario, SourceKind
from lightinv_core.quantities import quantity_spec, quantity_specs


class DesignTree(QtWidgets.QTreeWidget):
    """Surfaces (groups), emitter zones, sources, lighting intentions and goals."""

    groupActivated = QtCore.Signal(str)
    intentionActivated = QtCore.Signal(str)  # edit it
    intentionDeleted = QtCore.Signal(str)
    ruleDeleted = QtCore.Signal(int)

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        self.setHeaderLabels(["item", "details"])
        self.setColumnWidth(0, 170)
        for sig in (doc.sceneChanged, doc.designChanged, doc.operatorChanged):
            sig.connect(self.refresh)
        self.itemClicked.connect(self._clicked)
        self.itemDoubleClicked.connect(self._double_clicked)
        self.setContextMenuPolicy(QtCore.Qt.CustomContextMenu)
        self.customContextMenuRequested.connect(self._context_menu)

    def refresh(self) -> None:
        self.clear()
        d, p = self.doc, self.doc.patches
        if p is None:
            return
        groups = QtWidgets.QTreeWidgetItem(self, ["Surfaces", f"{p.n:,} patches"])
        for k, g in enumerate(p.group_names):
            n = int((p.group_id == k).sum())
            QtWidgets.QTreeWidgetItem(groups, [g, f"{n:,} patches"]).setData(0, 256, ("group", g))
        zones = QtWidgets.QTreeWidgetItem(self, ["Emitter zones", str(len(d.scene.zones))])
        for z in d.scene.zones:
            w, h = d.zone_size(z.name)
            QtWidgets.QTreeWidgetItem(zones, [z.name, f"{z.kind}, {w:.2f} x {h:.2f} m"]).setData(
                0, 256, ("zone", z.name)
            )
        srcs = QtWidgets.QTreeWidgetItem(self, ["Sources", str(len(d.design.sources))])
        for s in d.design.sources:
            item = QtWidgets.QTreeWidgetItem(
                srcs, [s.name, f"{s.kind} in {s.zone}, {s.area:.2f} m²"]
            )
            item.setData(0, 256, ("source", s.name))
            if s.name == d.current_source:
                item.setSelected(True)
        its = QtWidgets.QTreeWidgetItem(
            self, ["Lighting intentions", str(len(d.design.intentions))]
        )
        for it in d.design.intentions:
            bounds = ", ".join(
                f"{k} {getattr(it, k):g}" for k in Bound if getattr(it, k) is not None
            )
            QtWidgets.QTreeWidgetItem(
                its, [it.name, f"{intention_target(it)}: {bounds} {it.quantity}, {it.scenario}"]
            ).setData(0, 256, ("intention", it.name))
        if d.design.arrays:
            arrays = QtWidgets.QTreeWidgetItem(
                self, ["Luminaire arrays", str(sum(a.count for a in d.design.arrays))]
            )
            for a in d.design.arrays:
                QtWidgets.QTreeWidgetItem(
                    arrays, [a.name, f"{a.rows} x {a.columns} {a.product} in {a.zone}"]
                )
        if d.design.workplanes:
            planes = QtWidgets.QTreeWidgetItem(self, ["Work planes", str(len(d.design.workplanes))])
            for w in d.design.workplanes:
                QtWidgets.QTreeWidgetItem(
                    planes, [w.name, f"{w.height:g} m over {w.group}, border {w.border:g} m"]
                )
        rules_item = QtWidgets.QTreeWidgetItem(self, ["Rules", str(len(d.design.rules))])
        for k, rule in enumerate(d.design.rules):
            what, bounds = rule_text(rule)
            QtWidgets.QTreeWidgetItem(rules_item, [what, bounds]).setData(0, 256, ("rule", k))
        goals = QtWidgets.QTreeWidgetItem(self, ["Goals", ""])
        for g in d.design.goals:
            QtWidgets.QTreeWidgetItem(goals, [g.kind, ", ".join(g.kinds)])
        self.expandAll()

    def _clicked(self, item, _col) -> None:
        data = item.data(0, 256)
        if data and data[0] == "source":
            self.doc.set_current_source(data[1])

    def _double_clicked(self, item, _col) -> None:
        data = item.data(0, 256)
        if data and data[0] == "group":
            self.groupActivated.emit(data[1])
        elif data and data[0] == "intention":
            self.intentionActivated.emit(data[1])

    def intention_menu(self, name: str) -> QtWidgets.QMenu:
        """The menu of an intention's item: edit it, delete it."""
        menu = QtWidgets.QMenu(self)
        menu.addAction("Edit...", lambda: self.intentionActivated.emit(name))
        menu.addAction("Delete", lambda: self.intentionDeleted.emit(name))
        return menu

    def _context_menu(self, pos: QtCore.QPoint) -> None:
        item = self.itemAt(pos)
        data = item.data(0, 256) if item is not None else None
        if data and data[0] == "intention":
            self.intention_menu(data[1]).exec(self.viewport().mapToGlobal(pos))
        elif data and data[0] == "rule":
            menu = QtWidgets.QMenu(self)
            menu.addAction("Delete", lambda: self.ruleDeleted.emit(data[1]))
            menu.exec(self.viewport().mapToGlobal(pos))
        elif data and data[0] == "group":
            menu = QtWidgets.QMenu(self)
            menu.addAction("Add a lighting intention...", lambda: self.groupActivated.emit(data[1]))
            menu.exec(self.viewport().mapToGlobal(pos))

    def keyPressEvent(self, event: QtGui.QKeyEvent) -> None:
        """Delete removes the selected intention."""
        item = self.currentItem()
        data = item.data(0, 256) if item is not None else None
        deleting = event.key() in (QtCore.Qt.Key_Delete, QtCore.Qt.Key_Backspace)
        if deleting and data and data[0] == "intention":
            self.intentionDeleted.emit(data[1])
            return
        if deleting and data and data[0] == "rule":
            self.ruleDeleted.emit(data[1])
            return
        super().keyPressEvent(event)


class SourcePanel(QtWidgets.QGroupBox):
    """Edits the current source numerically; adding and removing sources."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__("Source", parent)
        self.doc = doc
        form = QtWidgets.QFormLayout(self)
        self.zone = QtWidgets.QComboBox()
        self.add_button = QtWidgets.QPushButton("Add source in zone")
        self.remove_button = QtWidgets.QPushButton("Remove source")
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.zone)
        row.addWidget(self.add_button)
        form.addRow("Zone", row)
        self.name = QtWidgets.QLabel("-")
        form.addRow("Current", self.name)
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
        ]
        for b in boxes:
            b.blockSignals(True)
        try:
            if name is None or name not in {s.name for s in self.doc.design.sources}:
                self.name.setText("no source: add one in a zone")
                for b in boxes:
                    b.setEnabled(False)
                return
            s = self.doc.design.source(name)
            self.name.setText(f"{s.name} ({s.kind} in {s.zone})")
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
            if s.kind == SourceKind.SKYLIGHT:
                self.strength_label.setText("filter (0-1)")
                self.strength.setDecimals(3)
                self.strength.setRange(0.0, 1.0)
                self.strength.setSingleStep(0.05)
                self.strength.setSuffix("")
                self.strength.setValue(s.filter)
            elif s.flux is not None:
                self.strength_label.setText("flux")
                self.strength.setDecimals(0)  # whole lumens: what a datasheet gives
                self.strength.setRange(0.0, 1e7)
                self.strength.setSingleStep(100.0)
                self.strength.setSuffix(" lm")
                self.strength.setValue(s.flux)
            else:
                self.strength_label.setText("exitance")
                self.strength.setDecimals(1)
                self.strength.setRange(0.0, 1e7)
                self.strength.setSuffix(" lm/m²")
                self.strength.setValue(s.exitance)
        finally:
            for b in boxes:
                b.blockSignals(False)

    def _show_freedom(self, s, tied: bool) -> None:
        """The optimiser's freedom over source ``s`` (as written), its flux range and
        efficacy; a mirror's copy follows its original and has none of its own."""
        light = s.kind == SourceKind.LUMINAIRE
        strength = "flux" if light else "filter"
        self.free_strength.setText(strength)
        self.free_place.setChecked(any(v in s.free for v in CORNERS))
        self.free_strength.setChecked(strength in s.free)
        self.free_place.setEnabled(not tied)
        self.free_strength.setEnabled(not tied and (not light or s.flux is not None))
        self.flux_min.setValue(s.flux_range[0])
        self.flux_max.setValue(s.flux_range[1])
        self.efficacy.setValue(s.efficacy)
        for w in (self.flux_min, self.flux_max, self.range_label):
            w.setVisible(light)
            w.setEnabled(not tied and light and strength in s.free)
        for w in (self.efficacy, self.efficacy_label):
            w.setVisible(light)
            w.setEnabled(not tied and light)

    def _free_edited(self) -> None:
        name = self.doc.current_source
        if name is None:
            return
        s = self.doc.design.source(name)
        strength = "flux" if s.kind == SourceKind.LUMINAIRE else "filter"
        free = (CORNERS if self.free_place.isChecked() else ()) + (
            (strength,) if self.free_strength.isChecked() else ()
        )
        self._apply(free=tuple(free))

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
        key = (
            "filter"
            if s.kind == SourceKind.SKYLIGHT
            else ("flux" if s.flux is not None else "exitance")
        )
        self._apply(**{key: self.strength.value()})

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


BOUND_FIELDS = {
    Bound.MIN: ("Minimum", 300.0),
    Bound.MAX: ("Maximum", 1000.0),
    Bound.AVERAGE: ("Average at least", 500.0),
    Bound.UNIFORMITY: ("Uniformity U0 at least", 0.6),
}
"""Each bound of an intention: its label and the value the dialog offers."""


def optional_number(
    form: QtWidgets.QFormLayout,
    label: str,
    value: float,
    hi: float,
    decimals: int = 2,
    step: float = 1.0,
) -> tuple[QtWidgets.QCheckBox, QtWidgets.QDoubleSpinBox]:
    """A form row "label [x] [value]": a bound that counts when ticked (unticked, its
    number is greyed out)."""
    check = QtWidgets.QCheckBox()
    box = QtWidgets.QDoubleSpinBox(decimals=decimals, singleStep=step)
    box.setRange(0.0, hi)
    box.setValue(value)
    box.setEnabled(False)
    check.toggled.connect(box.setEnabled)
    row = QtWidgets.QHBoxLayout()
    row.addWidget(check)
    row.addWidget(box)
    form.addRow(label, row)
    return check, box


SCENARIOS = {
    Scenario.DESIGN: "design: luminaires + skylights at the design exterior lux",
    Scenario.NIGHT: "night: luminaires only",
    Scenario.OVERCAST: "overcast: luminaires + the CIE overcast sky",
    Scenario.ANNUAL: "annual: every occupied hour of the weather year",
}
"""The scenarios an intention is judged in (annual: the daylight metrics only)."""


class IntentionDialog(QtWidgets.QDialog):
    """Name, quantity, scenario and bounds of a lighting intention on a group, the
    selection or a work plane."""

    def __init__(self, target: str, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.setWindowTitle(f"Lighting intention on {target}")
        form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(target)
        form.addRow("Name", self.name)
        self.quantity = QtWidgets.QComboBox()
        for q in quantity_specs():
            self.quantity.addItem(q.label, str(q.name))
        form.addRow("Quantity", self.quantity)
        self.scenario = QtWidgets.QComboBox()
        for sc, text in SCENARIOS.items():
            self.scenario.addItem(text, str(sc))
        self.scenario.setToolTip(
            "The light the intention is judged in. A daylight metric has its own: the "
            "daylight factor the overcast sky, DA, UDI and sDA the weather year (Climate tab)."
        )
        form.addRow("Scenario", self.scenario)
        self.fields = {}
        for bound, (label, default) in BOUND_FIELDS.items():
            key, u0 = str(bound), bound == Bound.UNIFORMITY
            self.fields[key] = optional_number(
                form, label, default, 1.0 if u0 else 1e6, decimals=2 if u0 else 1
            )
        self.fields[str(Bound.AVERAGE)][0].setChecked(True)
        self.fields[str(Bound.UNIFORMITY)][0].setChecked(True)
        form.addRow(dialogs.ok_cancel(self))
        self.quantity.currentIndexChanged.connect(self._quantity_changed)
        self._quantity_changed()

    def _quantity_changed(self) -> None:
        """A daylight metric fixes the scenario and takes bounds in its own units."""
        q = quantity_spec(self.quantity.currentData())
        forced = q.scenario
        annual = self.scenario.model().item(self.scenario.findData(str(Scenario.ANNUAL)))
        annual.setEnabled(forced == Scenario.ANNUAL)
        if forced is not None:
            self.scenario.setCurrentIndex(self.scenario.findData(str(forced)))
        elif self.scenario.currentData() in (Scenario.ANNUAL, Scenario.OVERCAST) and (
            self._last_metric()
        ):
            self.scenario.setCurrentIndex(self.scenario.findData(str(Scenario.DESIGN)))
        self.scenario.setEnabled(forced is None)
        self._metric = forced is not None
        decimals, top, defaults = q.decimals, q.high, q.defaults
        for key, value in zip(("min", "max", "average"), defaults, strict=False):
            box = self.fields[key][1]
            box.setDecimals(decimals)
            box.setMaximum(top)
            box.setValue(value)
        self.fields["uniformity"][1].setValue(defaults[3])
        if q.average_only:  # sDA is the average of a 0/1 mark: only that bound tells
            self.set_values(min=None, max=None, uniformity=None, average=defaults[2])

    def _last_metric(self) -> bool:
        return getattr(self, "_metric", False)

    def load(self, intention: Intention) -> None:
        """Show an existing intention's name, quantity, scenario and bounds (to edit
        it)."""
        self.setWindowTitle(f"Edit lighting intention {intention.name}")
        self.name.setText(intention.name)
        self.quantity.setCurrentIndex(max(0, self.quantity.findData(str(intention.quantity))))
        self.scenario.setCurrentIndex(max(0, self.scenario.findData(str(intention.scenario))))
        self.set_values(**{str(b): getattr(intention, str(b)) for b in Bound})

    def set_quantity(self, quantity: str, scenario: str | None = None) -> None:
        """Choose the quantity (and the scenario of lux or C) (tests, scripted use)."""
        self.quantity.setCurrentIndex(self.quantity.findData(str(quantity)))
        if scenario is not None and self.scenario.isEnabled():
            self.scenario.setCurrentIndex(self.scenario.findData(str(scenario)))

    def set_values(self, **values) -> None:
        """Pre-fill bounds (tests, scripted use): key=None unticks a bound."""
        for key, value in values.items():
            check, box = self.fields[key]
            check.setChecked(value is not None)
            if value is not None:
                box.setValue(value)

    def intention(self, group: str | None = None, patches=None, grid=None) -> Intention:
        """The intention described (DesignError if inconsistent, e.g. min above max)."""
        bounds = {k: box.value() for k, (check, box) in self.fields.items() if check.isChecked()}
        if not bounds:
            raise DesignError("tick at least one bound")
        return Intention(
            self.name.text().strip() or "intention",
            group=group,
            patches=None if patches is None else tuple(int(i) for i in patches),
            quantity=self.quantity.currentData(),
            grid=grid,
            scenario=self.scenario.currentData(),
            **bounds,
        )


def intention_target(it: Intention) -> str:
    """What an intention bounds, in words: a group, picked patches, a work plane."""
    if it.grid is not None:
        return f"work plane {it.grid}"
    return it.group if it.group is not None else f"{len(it.patches)} picked patches"


class ZonePanel(QtWidgets.QGroupBox):
    """The emitter zones drawn on this project's scene: rename, retype, resize, delete."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__("Drawn zones", parent)
        self.doc = doc
        form = QtWidgets.QFormLayout(self)
        self.zone = QtWidgets.QComboBox()
        form.addRow("Zone", self.zone)
        self.name = QtWidgets.QLineEdit()
        form.addRow("Name", self.name)
        self.kind = QtWidgets.QComboBox()
        self.kind.addItems([str(k) for k in SourceKind])
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
            "Draw zone mode: pick luminaire or skylight zone in the toolbar, then drag a "
            "rectangle on a ceiling or roof (from below, or from above in Top view); Draw "
            "polygon zone mode: click its corners. The corners are metres from the "
            "surface's origin along its u, v axes (shown when a zone is chosen here)."
        )
        self.hint.setWordWrap(True)
        form.addRow(self.hint)
        self.zone.currentIndexChanged.connect(self._show)
        self.apply_button.clicked.connect(self.apply)
        self.delete_button.clicked.connect(self.delete)
        doc.sceneChanged.connect(self.refresh)

    def refresh(self) -> None:
        self.zone.blockSignals(True)
        self.zone.clear()
        for z in self.doc.user_zones:
            self.zone.addItem(f"{z.name} on {z.surface}", z.name)
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
        self.kind.setCurrentText(z.kind)
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
                kind=self.kind.currentText(),
                rect=None if outline else tuple(b.value() for b in self.corners),
                outline=outline,
            )
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            return
        self._set([new if u.name == z.name else u for u in self.doc.user_zones])

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


class ZoneDialog(QtWidgets.QDialog):
    """Name and kind of a zone just drawn."""

    def __init__(self, surface: str, default_name: str, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.setWindowTitle(f"New emitter zone on {surface}")
        form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(default_name)
        form.addRow("Name", self.name)
        self.kind = QtWidgets.QComboBox()
        self.kind.addItems([str(k) for k in SourceKind])
        form.addRow("Kind", self.kind)
        form.addRow(dialogs.ok_cancel(self))


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
        form.addRow(dialogs.ok_cancel(self))
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
