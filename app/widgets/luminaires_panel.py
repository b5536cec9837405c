"""The luminaires panel: the catalogue with polar curves, the design's luminaire arrays
and its work planes with their EN 12464-1 values, live.

The catalogue lists the shipped products, then every product of the photometric files
the design's arrays use (each variant of a GLDF on its own row, named product +
variant), so a product brought in by the array dialog's File… shows its polar curve
and glare rating like the others.

Every edit goes through the editing model (``set_arrays``, ``set_workplanes``,
``add_intention``), so Edit > Undo takes it back, and the light shown (the arrays placed
exactly, about a second for a room) follows; the work planes' Em, Emin, Emax and U0 come
from the light shown. EN 12464-1 presets add an intention on a work plane. The arrays'
photometry warnings (a tilt table not applied, a light output ratio above 100%) show
under the arrays and in the status bar's warnings, with the Ra check: a product whose
stated Ra is below a preset's (or that states none) is named there. Each work plane
follows an edition of EN 12464-1 (its grid rule and presets): the preset list follows
the selected plane's edition.
"""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtWidgets

from app.dialogs import ask
from app.dialogs.array_dialog import UGR_TIP, ArrayDialog, product_ugr
from app.dialogs.workplane_dialog import WorkplaneDialog
from app.document import Document
from app.view.polar_plot import PolarPlot
from app.widgets.compact_table import compact_table, product_title
from app.widgets.elided_label import ElidedLabel
from lightinv_core.design.en12464 import (
    DEFAULT_EDITION,
    plane_presets,
    preset_intention,
    ra_warnings,
    requirements,
)
from lightinv_core.design.preset_glare import preset_glare_limit
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Scenario
from lightinv_core.light.arrays import resolve_product
from lightinv_core.luminaires import builtin_catalogue
from lightinv_core.luminaires.catalogue import CatalogueEntry, file_entries
from lightinv_core.luminaires.formats import split_reference
from lightinv_core.luminaires.photometry import light_warnings
from lightinv_core.scenarios import scenario_spec
from lightinv_core.sources.types import source_type
from lightinv_core.value_text import u0_text

ARRAY_COLUMNS = ("array", "zone", "product", "layout", "spacing m", "C0", "dimming", "W")
PLANE_COLUMNS = (
    "work plane",
    "height m",
    "points",
    "Em lux",
    "Emin lux",
    "Emax lux",
    "U0",
    "EN 12464-1",
)


class LuminairesPanel(QtWidgets.QWidget):
    """Catalogue, arrays and work planes of the open design (see the module)."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        lay = QtWidgets.QVBoxLayout(self)
        cat_box = QtWidgets.QGroupBox("Catalogue")
        cat = QtWidgets.QVBoxLayout(cat_box)
        self.catalogue = compact_table(("product", "lm", "W", "lm/W", "UGR"))
        self.catalogue.horizontalHeaderItem(4).setToolTip(UGR_TIP)
        self.catalogue.horizontalHeader().setStretchLastSection(True)
        self.catalogue.setMaximumHeight(130)
        cat.addWidget(self.catalogue)
        self.polar = PolarPlot()
        cat.addWidget(self.polar)
        lay.addWidget(cat_box)

        arr_box = QtWidgets.QGroupBox("Luminaire arrays")
        arr = QtWidgets.QVBoxLayout(arr_box)
        self.arrays = compact_table(ARRAY_COLUMNS)
        self.arrays.doubleClicked.connect(lambda _: self.edit_array())
        arr.addWidget(self.arrays)
        row = QtWidgets.QHBoxLayout()
        self.add_array_button = QtWidgets.QPushButton("Add array…")
        self.edit_array_button = QtWidgets.QPushButton("Edit…")
        self.remove_array_button = QtWidgets.QPushButton("Remove")
        for b in (self.add_array_button, self.edit_array_button, self.remove_array_button):
            row.addWidget(b)
        arr.addLayout(row)
        # The arrays' photometry warnings (what changes their light), also in the status
        # bar's warnings beside the scene's, and in the report's luminaire schedule.
        self.array_warnings = QtWidgets.QLabel()
        self.array_warnings.setWordWrap(True)
        self.array_warnings.setStyleSheet("color: #a05a00")
        self.array_warnings.hide()
        arr.addWidget(self.array_warnings)
        self.add_array_button.clicked.connect(lambda: self.add_array())
        self.edit_array_button.clicked.connect(lambda: self.edit_array())
        self.remove_array_button.clicked.connect(self.remove_array)
        lay.addWidget(arr_box)

        wp_box = QtWidgets.QGroupBox("Work planes (EN 12464-1, maintained)")
        wp = QtWidgets.QVBoxLayout(wp_box)
        self.planes = compact_table(PLANE_COLUMNS)
        wp.addWidget(self.planes)
        row = QtWidgets.QHBoxLayout()
        self.add_plane_button = QtWidgets.QPushButton("Add work plane…")
        self.remove_plane_button = QtWidgets.QPushButton("Remove")
        self.preset = QtWidgets.QComboBox()
        # A preset is judged in its own scenario (night: the luminaires alone), not in the
        # design scenario of the table's Em: the list says which.
        self._judged = scenario_spec(preset_intention("office", "-").scenario)
        self.preset.setToolTip(
            f"Adds Em and U0 of the selected work plane's EN 12464-1 edition as an "
            f"intention on it, judged in the {self._judged.label} scenario (the Achieved tab)"
        )
        self._fill_presets(DEFAULT_EDITION)
        # The longest activity would widen the dock past a laptop's (1366 px) screen and
        # push the Remove buttons out of sight: the box shrinks, its list stays whole.
        self.preset.setSizeAdjustPolicy(QtWidgets.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        self.preset.setMinimumContentsLength(16)
        for w in (self.add_plane_button, self.remove_plane_button, self.preset):
            row.addWidget(w)
        wp.addLayout(row)
        self.add_plane_button.clicked.connect(lambda: self.add_workplane())
        self.remove_plane_button.clicked.connect(self.remove_workplane)
        self.preset.activated.connect(self._preset)
        self.planes.itemSelectionChanged.connect(lambda: self._fill_presets(self._edition()))
        self.status = ElidedLabel()  # never wider than the dock; whole on hover
        wp.addWidget(self.status)
        lay.addWidget(wp_box)

        self._fill_catalogue()
        self.catalogue.itemSelectionChanged.connect(self._show_product)
        self.catalogue.selectRow(0)
        doc.designChanged.connect(self.refresh)
        doc.lightingChanged.connect(self.refresh)
        doc.sceneChanged.connect(self.refresh)
        self.refresh()

    # -- catalogue ------------------------------------------------------------------------
    def _fill_catalogue(self, files: tuple[Path, ...] = ()) -> None:
        """The shipped products, then those of ``files`` (a file that cannot be read
        any more is left out: its arrays say why)."""
        self._files = files
        # A shipped product is named by its name, a file's by its reference.
        entries: list[tuple[CatalogueEntry, str]] = [(e, e.name) for e in builtin_catalogue()]
        for f in files:
            try:
                entries += [(e, e.reference) for e in file_entries(f)]
            except LightInvError:
                continue
        selected = self.selected_product() if self.catalogue.rowCount() else None
        blocked = self.catalogue.blockSignals(True)  # one redraw of the curve, below
        self.catalogue.setRowCount(len(entries))
        for i, (e, ref) in enumerate(entries):
            glare, tip = product_ugr(ref)
            efficacy = f"{e.efficacy:.0f}" if e.watts > 0 else "-"
            for j, text in enumerate((e.name, f"{e.lumens:,.0f}", f"{e.watts:g}", efficacy, glare)):
                self.catalogue.setItem(i, j, QtWidgets.QTableWidgetItem(text))
            self.catalogue.item(i, 0).setData(QtCore.Qt.UserRole, ref)
            self.catalogue.item(i, 0).setToolTip("\n".join(t for t in (ref, e.description) if t))
            self.catalogue.item(i, 4).setToolTip(tip)
            if ref == selected:
                self.catalogue.selectRow(i)
        self.catalogue.blockSignals(blocked)
        self.catalogue.resizeColumnsToContents()
        if self.catalogue.currentItem() is not None:
            # Refilled, the list keeps its scroll position: keep the chosen row in view
            # (it may lie below the first rows now that the catalogue has six products).
            self.catalogue.scrollToItem(self.catalogue.currentItem())
        if selected is not None:
            self._show_product()

    def _used_files(self) -> tuple[Path, ...]:
        """The photometric files the design's arrays use, in order, once each."""
        d = self.doc
        files: list[Path] = []
        for a in d.design.arrays if d.project is not None else ():
            ref = split_reference(a.product)
            if ref is not None and ref[0] not in files:
                files.append(ref[0])
        return tuple(files)

    def _show_product(self) -> None:
        product = self.selected_product()
        if product is None:
            self.polar.show_product(None)
            return
        try:
            self.polar.show_product(resolve_product(product))
        except LightInvError:
            self.polar.show_product(None)

    def selected_product(self) -> str | None:
        """The catalogue product selected: a shipped product's name, or a file's
        reference (``FILE`` or ``FILE.gldf#VARIANT``)."""
        rows = self.catalogue.selectionModel().selectedRows()
        if not rows:
            return None
        item = self.catalogue.item(rows[0].row(), 0)
        return item.data(QtCore.Qt.UserRole) or item.text()

    # -- arrays ---------------------------------------------------------------------------
    def _luminaire_zones(self) -> dict[str, tuple[float, float]]:
        d = self.doc
        if d.project is None:
            return {}
        return {
            z: d.zone_size(z) for z in d.patches.zone_names if source_type(d.zone_kind(z)).electric
        }

    def _new_name(self, prefix: str, taken) -> str:
        k = 1
        while f"{prefix}{k}" in taken:
            k += 1
        return f"{prefix}{k}"

    def add_array(self, dialog: ArrayDialog | None = None) -> bool:
        """Ask for a new array (``dialog`` given: take it as answered) and add it."""
        zones = self._luminaire_zones()
        if not zones:
            ask.warn(self, "The scene has no luminaire zone to mount an array in.")
            return False
        d = self.doc.design
        taken = {s.name for s in d.sources} | {a.name for a in d.arrays}
        if dialog is None:
            dialog = ArrayDialog(
                zones,
                name=self._new_name("A", taken),
                parent=self,
                others=d.arrays,
                groups=self.doc.control_group_names(),
            )
            product = self.selected_product()
            if product:
                dialog.product.setCurrentText(product)
            if not ask.accepted(dialog):
                return False
        try:
            array = dialog.array()
            resolve_product(array.product, array.watts)
            self.doc.set_arrays((*d.arrays, array), f"add array {array.name}")
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return False
        return True

    def current_array(self) -> int | None:
        rows = self.arrays.selectionModel().selectedRows()
        return rows[0].row() if rows else None

    def edit_array(self, dialog: ArrayDialog | None = None) -> bool:
        """Edit the selected array."""
        i = self.current_array()
        if i is None:
            return False
        arrays = self.doc.design.arrays
        if dialog is None:
            others = arrays[:i] + arrays[i + 1 :]
            dialog = ArrayDialog(
                self._luminaire_zones(),
                arrays[i],
                parent=self,
                others=others,
                groups=self.doc.control_group_names(),
            )
            if not ask.accepted(dialog):
                return False
        try:
            new = dialog.array()
            resolve_product(new.product, new.watts)
            self.doc.set_arrays(
                (*arrays[:i], new, *arrays[i + 1 :]), f"edit array {arrays[i].name}"
            )
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return False
        return True

    def remove_array(self) -> None:
        i = self.current_array()
        if i is None:
            return
        arrays = self.doc.design.arrays
        self.doc.set_arrays(arrays[:i] + arrays[i + 1 :], f"remove array {arrays[i].name}")

    # -- work planes ----------------------------------------------------------------------
    def add_workplane(self, dialog: WorkplaneDialog | None = None) -> bool:
        """Ask for a new work plane and add it."""
        d = self.doc
        if d.project is None:
            return False
        if dialog is None:
            taken = {w.name for w in d.design.workplanes}
            name = "wp" if "wp" not in taken else self._new_name("wp", taken)
            dialog = WorkplaneDialog(list(d.patches.group_names), name=name, parent=self)
            if not ask.accepted(dialog):
                return False
        try:
            wp = dialog.workplane()
            d.set_workplanes((*d.design.workplanes, wp), f"add work plane {wp.name}")
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return False
        key = dialog.preset()
        if key is None or not self.add_preset(key, wp.name):
            return key is None
        return not dialog.ugr_limit() or self.add_preset_glare(key, wp)

    def add_preset_glare(self, key: str, wp) -> bool:
        """The preset's UGR_L at the observers (``design.preset_glare``): one undo step."""
        d = self.doc
        try:
            new, it = preset_glare_limit(d.design, d.patches, wp, key)
            d.add_observers(new, it, f"add {it.name} {it.max:g}")
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return False
        return True

    def remove_workplane(self) -> None:
        rows = self.planes.selectionModel().selectedRows()
        if not rows:
            return
        i = rows[0].row()
        planes = self.doc.design.workplanes
        self.doc.set_workplanes(planes[:i] + planes[i + 1 :], f"remove work plane {planes[i].name}")

    def _preset(self, index: int) -> None:
        key = self.preset.itemData(index)
        self.preset.setCurrentIndex(0)
        if key is not None:
            self.add_preset(key)

    def _edition(self) -> str:
        """The edition of the selected (or first) work plane; 2021 without one."""
        planes = self.doc.design.workplanes if self.doc.project is not None else ()
        rows = self.planes.selectionModel().selectedRows()
        i = rows[0].row() if rows else 0
        return planes[i].edition if i < len(planes) else DEFAULT_EDITION

    def _fill_presets(self, edition: str) -> None:
        """The preset list of ``edition`` (the selected work plane's)."""
        if self.preset.count() and self.preset.itemText(0).endswith(f"{edition})…"):
            return
        self.preset.clear()
        self.preset.addItem(f"{edition} intention ({self._judged.label})…", None)
        for r in requirements(edition):
            self.preset.addItem(f"{r.activity}: {r.em:g} lux, U0 {r.u0:.2f}", r.key)

    def add_preset(self, key: str, plane: str | None = None) -> bool:
        """Add the EN 12464-1 preset ``key`` of the plane's edition as an intention on
        work plane ``plane`` (default: the selected, or first, one)."""
        d = self.doc
        planes = d.design.workplanes
        if not planes:
            ask.warn(self, "Add a work plane first: EN 12464-1 values apply to its grid.")
            return False
        rows = self.planes.selectionModel().selectedRows()
        chosen = planes[rows[0].row() if rows else 0]
        wp = next((w for w in planes if w.name == plane), chosen)
        taken = {i.name for i in d.design.intentions}
        it = preset_intention(key, wp.name, edition=wp.edition)
        name = it.name if it.name not in taken else self._new_name(f"{it.name}-", taken)
        try:
            d.add_intention(preset_intention(key, wp.name, name, edition=wp.edition))
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return False
        return True

    # -- refresh --------------------------------------------------------------------------
    def refresh(self) -> None:
        files = self._used_files()
        if files != self._files:
            self._fill_catalogue(files)
        d = self.doc
        design = d.design if d.project is not None else None
        arrays = design.arrays if design is not None else ()
        self.arrays.setRowCount(len(arrays))
        products = []
        for i, a in enumerate(arrays):
            try:
                p = resolve_product(a.product, a.watts)
                (product, about), watts = (
                    product_title(a.product, p),
                    f"{a.count * p.watts * a.dimming:,.1f}",
                )
                products.append(p)
            except LightInvError:
                product, about, watts = a.product, "", "?"
            su, sv = a.spacing
            cells = (
                a.name,
                a.zone,
                product,
                f"{a.rows} x {a.columns}",
                f"{su:.2f} x {sv:.2f}",
                f"{a.rotation}°",
                f"{100 * a.dimming:.0f}%",
                watts,
            )
            for j, text in enumerate(cells):
                item = QtWidgets.QTableWidgetItem(text)
                if j == ARRAY_COLUMNS.index("product"):
                    item.setToolTip(about)
                self.arrays.setItem(i, j, item)
        self.arrays.resizeColumnsToContents()
        column = ARRAY_COLUMNS.index("product")  # a long catalogue number is elided
        self.arrays.setColumnWidth(column, min(self.arrays.columnWidth(column), 240))
        presets = plane_presets(design) if design is not None else []
        ra = ra_warnings(design) if design is not None else []
        self._show_warnings(light_warnings(p.photometry for p in products) + ra)
        planes = design.workplanes if design is not None else ()
        stats = d.grid_stats() if design is not None else {}
        self.planes.setRowCount(len(planes))
        for i, w in enumerate(planes):
            st = stats.get(w.name)
            cells = [w.name, f"{w.height:.2f}"]
            if st is None:
                cells += ["—"] * 5
            else:
                cells += [
                    str(st["points"]),
                    f"{st['Em']:.0f}",
                    f"{st['Emin']:.0f}",
                    f"{st['Emax']:.0f}",
                    u0_text(st["U0"]),
                ]
            cells.append(str(w.edition).split(":")[-1])
            for j, text in enumerate(cells):
                self.planes.setItem(i, j, QtWidgets.QTableWidgetItem(text))
        self.planes.resizeColumnsToContents()
        lines = []
        if design is not None and planes and not stats:
            lines.append("Values appear once the radiosity operator is ready.")
        elif planes:
            # The view's light, not a preset's (judged at night, the Achieved tab).
            light = scenario_spec(Scenario.DESIGN).describe(design.daylight)
            lines.append(f"Em, Emin, Emax, U0 in the {Scenario.DESIGN} scenario: {light}")
        for plane, r in presets:
            lines.append(f"{plane} ({r.edition}), {r.activity}: {r.values}")
        if design is not None and arrays:
            total, n = sum(a.count for a in arrays), len(arrays)
            lines.append(f"{total} luminaire{'s' * (total != 1)} in {n} array{'s' * (n != 1)}.")
        self.status.setText("\n".join(lines))

    def _show_warnings(self, warnings: list[str]) -> None:
        """The arrays' photometry warnings under the arrays and in the main window's
        status-bar warnings (source "luminaires"), where the scene's import warnings are."""
        self.array_warnings.setText("\n".join(f"\u26a0 {w}" for w in warnings))
        self.array_warnings.setVisible(bool(warnings))
        window = self.parentWidget()
        while window is not None and not hasattr(window, "set_warnings"):
            window = window.parentWidget()  # the dock, then the main window
        if window is not None:
            window.set_warnings("luminaires", warnings)
