"""The LightInv main window: its layout (docks, view options, status bar) and the wiring
of the document's signals to the views.

The jobs around it live beside it: actions, menus and toolbar in actions.py; project
files in files.py; the operator and report workers in tasks.py, the optimisation in
run_control.py; dialogs in dialogs.py (and panels.py); crash recovery in autosave.py.
The public methods here (new_project, open_path, save_to, export_report, set_mode, ...)
are what menus, ``python -m app``, tests and scripts call.
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

from app import actions, dialogs, luminaire_overlay
from app.achieved_panel import AchievedPanel
from app.autosave import Autosaver, Recoverable
from app.autosave import offer_recovery as _offer_recovery
from app.autosave import recover as _recover
from app.climate_panel import MAPS, ClimatePanel, map_values
from app.document import Document
from app.files import MAX_RECENT, ProjectFiles
from app.luminaires_panel import LuminairesPanel
from app.materials_panel import MaterialsPanel
from app.panels import (
    DesignTree,
    IntentionDialog,
    RuleDialog,
    SourcePanel,
    ZoneDialog,
    ZonePanel,
    intention_target,
)
from app.results_panel import SolutionsPanel, ViolationsPanel
from app.run_control import RunController
from app.run_panel import RunPanel
from app.tasks import BackgroundTasks
from app.undo import undo_stack
from app.viewport import Viewport, ZoneFrame
from app.workers import PrecomputeWorker, Worker
from lightinv_core.errors import LightInvError
from lightinv_core.light.arrays import array_escape_warnings
from lightinv_core.project import Project
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.scene.model import Rect

__all__ = ["COLORMAPS", "MAX_RECENT", "MainWindow"]

COLORMAPS = ("inferno", "viridis", "plasma", "coolwarm", "gray")
MIN_ZONE = 0.05  # m: a drawn zone narrower than this is a slip of the mouse
DOCS = Path(__file__).resolve().parent.parent / "docs"
"""The documentation pages (docs/ in the source tree and in the bundle)."""


def surface_frame_of(zone: ZoneFrame, edit: ZoneEdit) -> ZoneFrame:
    """The frame of the surface a drawn zone was cut from (its corners are measured along
    it): the zone's own axes, its origin moved back by the zone's first corner."""
    u0, v0, u1, v1 = edit.rect
    origin = zone.origin - u0 * zone.u - v0 * zone.v
    return ZoneFrame(None, edit.surface, rect=Rect(origin, u1 * zone.u, v1 * zone.v))


class MainWindow(QtWidgets.QMainWindow):
    """One open project at a time."""

    def __init__(
        self,
        settings: QtCore.QSettings | None = None,
        autosave_seconds: float | None = None,
        autosave_folder: Path | None = None,
    ):
        super().__init__()
        self.settings = settings or QtCore.QSettings("LightInv", "LightInv")
        self.doc = Document(self)
        self.run_after_precompute = False  # lightinv --run: start once the operator is there
        self.last_render_ms = float("nan")
        self.ask_before_discard = True  # False: discard unsaved changes silently (scripts, tests)
        self.setWindowTitle("LightInv")
        self.viewport = Viewport(self)
        self.setCentralWidget(self.viewport)
        self.tree = DesignTree(self.doc)
        self.source_panel = SourcePanel(self.doc)
        self.zone_panel = ZonePanel(self.doc)
        self.run_panel = RunPanel(self.doc)
        self.solutions_panel = SolutionsPanel(self.doc)
        self.violations_panel = ViolationsPanel(self.doc)
        self.achieved_panel = AchievedPanel(self.doc)
        self.materials_panel = MaterialsPanel(self.doc)
        self.luminaires_panel = LuminairesPanel(self.doc)
        self.climate_panel = ClimatePanel(self.doc)
        self._docks()
        self.files = ProjectFiles(self)
        self.tasks = BackgroundTasks(self)
        self.undo_stack = undo_stack(self)
        actions.create_actions(self)
        self.runs = RunController(self)
        self.autosaver = Autosaver(self, autosave_seconds, autosave_folder)
        actions.build_menus(self)
        self.files.fill_recent()
        self._status()
        self._connect()
        self.resize(1400, 900)
        self._initial_state = self.saveState()  # View > Restore the panel layout
        geometry = self.settings.value("geometry")
        if geometry is not None:
            self.restoreGeometry(geometry)
            self.restoreState(self.settings.value("windowState"))

    # -- layout --------------------------------------------------------------------------------
    def _dock(self, title: str, name: str, widget, area, scroll: bool = False) -> None:
        dock = QtWidgets.QDockWidget(title, self)
        dock.setObjectName(name)
        if scroll:
            # A panel taller than the screen scrolls instead of making the window taller
            # than a laptop's (1366 x 768) screen.
            area_ = QtWidgets.QScrollArea()
            area_.setWidgetResizable(True)
            area_.setFrameShape(QtWidgets.QFrame.NoFrame)
            area_.setWidget(widget)
            widget = area_
        dock.setWidget(widget)
        self.addDockWidget(area, dock)

    def _docks(self) -> None:
        self._dock("Scene and design", "tree", self.tree, QtCore.Qt.LeftDockWidgetArea)
        box = QtWidgets.QWidget()
        lay = QtWidgets.QVBoxLayout(box)
        lay.addWidget(self.source_panel)
        lay.addWidget(self.zone_panel)
        lay.addWidget(self.materials_panel)
        lay.addWidget(self._view_options())
        lay.addStretch(1)
        self._dock("Properties", "properties", box, QtCore.Qt.RightDockWidgetArea, scroll=True)
        self._dock(
            "Luminaires", "luminaires", self.luminaires_panel, QtCore.Qt.RightDockWidgetArea, True
        )
        # One column on the right: Properties and Luminaires as tabs (a laptop's height).
        self.tabifyDockWidget(
            self.findChild(QtWidgets.QDockWidget, "properties"),
            self.findChild(QtWidgets.QDockWidget, "luminaires"),
        )
        self.findChild(QtWidgets.QDockWidget, "properties").raise_()
        self.tabs = QtWidgets.QTabWidget()
        self.tabs.addTab(self.run_panel, "Run")
        self.tabs.addTab(self.achieved_panel, "Achieved")
        self.tabs.addTab(self.solutions_panel, "Solutions")
        self.tabs.addTab(self.violations_panel, "Violations")
        self.tabs.addTab(self.climate_panel, "Climate")
        self._dock(
            "Optimisation", "optimisation", self.tabs, QtCore.Qt.BottomDockWidgetArea, scroll=True
        )
        for tab in (self.run_panel, self.solutions_panel, self.violations_panel):
            tab.setMinimumHeight(0)
        self.climate_panel.setMinimumHeight(0)

    def _view_options(self) -> QtWidgets.QGroupBox:
        group = QtWidgets.QGroupBox("View")
        form = QtWidgets.QFormLayout(group)
        self.colour_by = QtWidgets.QComboBox()
        self.colour_by.addItem("illuminance (lux)", "lux")
        self.colour_by.addItem("radiosity B (lm/m²)", "B")
        for key, (text, _units, _fmt) in MAPS.items():
            self.colour_by.addItem(text, key)
        self.colour_by.setToolTip(
            "The design's light (illuminance: the design scenario), or a daylight map of the "
            "layout shown (weather, occupancy and the hour of the year: the Climate tab). "
            "DA and UDI are drawn 0-100%; the daylight factor on its own range."
        )
        form.addRow("Colour by", self.colour_by)
        self.cmap = QtWidgets.QComboBox()
        self.cmap.addItems(COLORMAPS)
        form.addRow("Colour map", self.cmap)
        self.auto_range = QtWidgets.QCheckBox("automatic")
        self.auto_range.setChecked(True)
        self.range_max = QtWidgets.QDoubleSpinBox(decimals=0, suffix="", maximum=1e7)
        self.range_max.setValue(1000.0)
        self.range_max.setEnabled(False)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.auto_range)
        row.addWidget(self.range_max)
        form.addRow("Range 0 to", row)
        self.zone_axes = QtWidgets.QCheckBox("zone origin and u, v axes")
        self.zone_axes.setChecked(True)
        self.zone_axes.setToolTip(
            "Where the corners u0 v0 u1 v1 in Properties are measured from, and along"
        )
        form.addRow("Show", self.zone_axes)
        self.zone_axes.toggled.connect(self._zone_axes_toggled)
        self.colour_by.currentIndexChanged.connect(self._recolour)
        self.cmap.currentTextChanged.connect(self.viewport.set_colormap)
        self.auto_range.toggled.connect(lambda on: self.range_max.setEnabled(not on))
        self.auto_range.toggled.connect(self._recolour)
        self.range_max.valueChanged.connect(self._recolour)
        return group

    def _status(self) -> None:
        self.status_patches = QtWidgets.QLabel()
        self.status_rank = QtWidgets.QLabel()
        self.status_eval = QtWidgets.QLabel()
        self.progress = QtWidgets.QProgressBar()
        self.progress.setRange(0, 1000)
        self.progress.setMaximumWidth(220)
        self.progress.hide()
        # Warnings of the scene import and the operator stay here until the next scene:
        # a status message alone would be gone in seconds.
        self.warnings_button = QtWidgets.QToolButton()
        self.warnings_button.setAutoRaise(True)
        self.warnings_button.clicked.connect(self.show_warnings)
        self.warnings_button.hide()
        self._warnings: dict[str, list[str]] = {}
        widgets = (self.warnings_button, self.status_patches, self.status_rank, self.status_eval)
        for w in (*widgets, self.progress):
            self.statusBar().addPermanentWidget(w)

    def _connect(self) -> None:
        d = self.doc
        d.sceneChanged.connect(self._scene_changed)
        d.lightingChanged.connect(self._recolour)
        d.designChanged.connect(self._sources_changed)
        d.selectionChanged.connect(lambda: self.viewport.set_selection(d.selection))
        d.pathChanged.connect(self._title)
        d.operatorChanged.connect(self._update_busy)
        self.progress.valueChanged.connect(self._update_busy)
        # A precompute ended (enabled again); its worker is let go just after.
        self.act_precompute.changed.connect(lambda: QtCore.QTimer.singleShot(0, self._update_busy))
        self.zone_panel.zone.activated.connect(self._drawn_zone_chosen)
        self.viewport.picked.connect(self._picked)
        self.viewport.sourceDragged.connect(self._dragged)
        self.viewport.zoneDrawn.connect(self._zone_drawn)
        self.viewport.polygonDrawn.connect(self._polygon_drawn)
        self.viewport.surface_frame = self._surface_frame
        self.tree.groupActivated.connect(self.add_intention_on_group)
        self.tree.intentionActivated.connect(self.edit_intention)
        self.tree.intentionDeleted.connect(self.delete_intention)
        self.tree.ruleDeleted.connect(self.delete_rule)
        d.designChanged.connect(lambda: actions.check_goals(self))
        self.run_panel.runRequested.connect(self.runs.start)
        self.run_panel.cancelRequested.connect(self.runs.cancel)
        self.solutions_panel.compareChanged.connect(self._recolour)
        self.solutions_panel.runDeleted.connect(
            lambda n: self.statusBar().showMessage(
                f"Deleted run {n} (Edit > Undo to restore)", 6000
            )
        )
        self.violations_panel.highlightChanged.connect(
            lambda: self.viewport.set_highlight(self.violations_panel.highlighted())
        )
        self.climate_panel.hourChanged.connect(self._hour_moved)
        self.climate_panel.showHourToggled.connect(self._show_hour)
        self.colour_by.currentIndexChanged.connect(self._colour_by_changed)

    # -- document -> views ---------------------------------------------------------------------
    def set_warnings(self, source: str, messages: list[str]) -> None:
        """Keep the warnings of one ``source`` ("scene", "operator") for the status bar's
        warnings button; an empty list clears them."""
        self._warnings[source] = list(messages)
        every = self.warnings()
        self.warnings_button.setVisible(bool(every))
        self.warnings_button.setText(f"\u26a0 {len(every)} warning{'s' * (len(every) != 1)}")
        self.warnings_button.setToolTip("\n\n".join(every))

    def warnings(self) -> list[str]:
        """Every warning kept, scene first."""
        return [m for msgs in self._warnings.values() for m in msgs]

    def show_warnings(self) -> None:
        """The warnings in full (the status bar's button)."""
        dialogs.inform(self, "\n\n".join(self.warnings()) or "No warnings.")

    def _scene_changed(self) -> None:
        d = self.doc
        self.set_warnings("scene", list(d.scene.info.get("warnings", [])))
        self.set_warnings("operator", [])
        # The same scene re-meshed (a zone drawn, a reflectance, an undo) keeps its
        # picture, veiled, until the new light model is ready; it used to go blank.
        keep = d.rebuilt and self.viewport.has_values
        self.viewport.set_scene(d.patches, [z.name for z in d.scene.zones], keep_picture=keep)
        if not keep:
            self.viewport.set_values(None)
        self.status_patches.setText(f"{d.patches.n:,} patches")
        self.status_rank.setText("operator: not built")
        self.status_eval.setText("")
        self._sources_changed()
        self.start_precompute()
        self._update_busy()

    def _update_busy(self) -> None:
        """Say over the view why its light is missing or out of date: the light model is
        being built (with its progress), or was not (cancelled)."""
        d = self.doc
        if d.patches is None or d.operator is not None:
            text = None
        elif isinstance(self.worker, PrecomputeWorker):
            again = self.viewport.has_values
            text = (
                f"{'Rebuilding' if again else 'Building'} the light model... "
                f"{self.progress.value() / 10:.0f}%"
            )
            if again:
                text += "\nThe light shown is from before the change."
        else:
            text = "No light model: Compute > Precompute builds it."
        self.viewport.set_busy(text)

    def _focus_axes(self) -> None:
        """Show the axes of the current source's zone (its corners are measured along
        them)."""
        d = self.doc
        zone = d.design.source(d.current_source).zone if d.current_source else None
        frame = self.viewport.frames.get(zone) if zone else None
        self.viewport.set_axes_focus(frame, f"{zone} (0, 0)" if frame is not None else "")

    def _drawn_zone_chosen(self) -> None:
        """Show the axes of the surface a drawn zone was drawn on: its corners in the
        Drawn zones panel are measured along them."""
        z = self.zone_panel._current()
        frame = self.viewport.frames.get(z.name) if z is not None else None
        if frame is None:
            return
        self.viewport.set_axes_focus(surface_frame_of(frame, z), f"{z.surface} (0, 0)")

    def _zone_axes_toggled(self, on: bool) -> None:
        self.viewport.show_zone_axes = on
        self.viewport.show_axes(*self.viewport.axes_focus)

    def _shown_sources(self) -> tuple:
        preview = self.doc.preview_sources()
        return preview if preview is not None else self.doc.effective_sources()

    def _sources_changed(self) -> None:
        self.viewport.set_sources(self._shown_sources(), self.doc.current_source)
        if self.doc.current_source:
            self.viewport.drag_zone = self.doc.design.source(self.doc.current_source).zone
        self._focus_axes()
        self._title()

    def _luminaire_warnings(self, patches, arrays) -> None:
        """Name the design's luminaires whose light mostly leaves the model (the status
        bar's warnings), traced again only when the patches or the arrays change."""
        key = (id(patches), tuple(arrays))
        if getattr(self, "_luminaire_key", None) == key:
            return
        self._luminaire_key = key
        try:
            lost = array_escape_warnings(patches, arrays)
        except LightInvError:
            lost = []  # a product that cannot be read is reported where it is set
        self.set_warnings("luminaire placement", lost)

    def _recolour(self) -> None:
        field = self.doc.field
        if field is not None:
            self.viewport.set_sources(self._shown_sources(), self.doc.current_source)
        t0 = time.perf_counter()
        self.viewport.clim = None if self.auto_range.isChecked() else (0.0, self.range_max.value())
        d = self.doc
        if d.project is not None and self.viewport.mesh is not None:
            luminaire_overlay.draw(self.viewport.plotter, d.patches, d.design.arrays)
            self._luminaire_warnings(d.patches, d.design.arrays)
        if field is None:
            self.viewport.set_caption(None)
            self.viewport.set_values(None)
            return
        self._paint(field)
        self.last_render_ms = 1e3 * (time.perf_counter() - t0)
        self.status_eval.setText(
            f"lighting {self.doc.last_eval_ms:.1f} ms, view {self.last_render_ms:.1f} ms"
        )

    def _paint(self, field) -> None:
        """Colour the patches as View > Colour by says: the light shown, a pinned
        result's difference, or a daylight map (``climate_panel.map_values``)."""
        other = self.solutions_panel.compared()
        cmap = "coolwarm" if other is not None else self.cmap.currentText()
        if cmap != self.viewport.cmap:
            self.viewport.set_colormap(cmap)
        key, fmt, caption = self.colour_by.currentData(), "%.0f", None
        grids, grid_values = self.doc.shown_grids()
        label, plane_clim = "{:.0f}", None
        if other is not None:
            # Difference view: the loaded layout minus a pinned one, centred on zero.
            values = field.illuminance - self.doc.lighting_of(other.sources)
            m = float(np.abs(values).max()) or 1.0
            self.viewport.clim = (-m, m)
            units = "lux, loaded − pinned"
        elif key == "B":
            values, units = field.radiosity, "lm/m²"
        elif key in MAPS:
            shown = map_values(self.doc, key, self.climate_panel.current_hour())
            values, units, fmt, caption = shown.values, shown.units, shown.fmt, shown.caption
            grids, grid_values = shown.grids, shown.grid_values
            label, plane_clim = shown.label_format, shown.clim
            if shown.clim is not None:
                self.viewport.clim = shown.clim
            elif key == "df":
                self.viewport.clim = None  # a few percent: the lux range means nothing
        else:
            values, units = field.illuminance, "lux"
        if self.viewport.mesh is not None:
            # The work planes show the same quantity as the patches, iso-lines labelled.
            luminaire_overlay.draw_planes(
                self.viewport.plotter, grids, grid_values, label, plane_clim
            )
        self.viewport.set_caption(caption)
        self.viewport.set_values(values, units, fmt)

    def _hour_moved(self, _hour: int) -> None:
        """The hour slider moved: relight the view if it shows that hour (a sum over the
        layout's light built once per design change: no new light is computed)."""
        if self.colour_by.currentData() == "hour" and self.doc.field is not None:
            auto = self.auto_range.isChecked()
            self.viewport.clim = None if auto else (0.0, self.range_max.value())
            self._paint(self.doc.field)

    def _show_hour(self, on: bool) -> None:
        """The Climate tab's "light the view at this hour" ticked or not."""
        want = "hour" if on else "lux"
        if (self.colour_by.currentData() == "hour") != on:
            self.colour_by.setCurrentIndex(self.colour_by.findData(want))

    def _colour_by_changed(self) -> None:
        box = self.climate_panel.show_hour
        box.blockSignals(True)
        box.setChecked(self.colour_by.currentData() == "hour")
        box.blockSignals(False)

    def _title(self) -> None:
        d = self.doc
        name = d.path.name if d.path else (d.project.name if d.project else "")
        self.setWindowTitle(f"LightInv - {name}{' *' if d.dirty else ''}")

    # -- picking, dragging, drawing, intentions ------------------------------------------------
    def set_mode(self, mode: str) -> None:
        """navigate (orbit), select (pick patches), move (drag the source), zone (draw a
        rectangle), polygon (click a polygon's corners)."""
        if mode != "polygon":
            self.viewport.cancel_polygon()
        self.viewport.mode = mode
        self.mode_actions[mode].setChecked(True)
        if mode == "polygon":
            self.statusBar().showMessage(
                "Click the zone's corners on a ceiling or roof; double-click, Enter or a click "
                "on the first corner closes it; Backspace takes back a corner, Esc drops it",
                10000,
            )

    def _picked(self, ids: np.ndarray, add: bool) -> None:
        ids = np.union1d(self.doc.selection, ids) if add else ids
        self.doc.set_selection(ids)
        self.statusBar().showMessage(f"{len(ids)} patches selected", 4000)

    def _dragged(self, du: float, dv: float) -> None:
        if self.doc.current_source is not None:
            self.doc.move_source(self.doc.current_source, du, dv)

    def _surface_frame(self, seen: int | None, near, far) -> ZoneFrame | None:
        """The surface a zone of the kind being drawn goes on, for the view ray near ->
        far through the cursor (``seen``: the patch under it, if any)."""
        try:
            name, rect = self.doc.zone_surface(self.draw_kind(), near, far - near, seen)
        except LightInvError as exc:
            self.statusBar().showMessage(str(exc), 6000)
            return None
        self.statusBar().showMessage(f"Drawing a {self.draw_kind()} zone on {name}", 4000)
        return ZoneFrame(None, name, rect=rect)

    def draw_kind(self) -> str:
        """The kind of zone Draw zone makes (the toolbar's choice)."""
        return self.zone_kind_box.currentData()

    def _zone_drawn(self, surface, u0, v0, u1, v1, dialog: ZoneDialog | None = None) -> bool:
        """Ask for the new zone's name and kind, then rebuild the scene with it."""
        if abs(u1 - u0) < MIN_ZONE or abs(v1 - v0) < MIN_ZONE:
            self.statusBar().showMessage("Zone too small: drag a larger rectangle", 4000)
            return False
        return self._add_zone(surface, dialog, rect=(u0, v0, u1, v1))

    def _add_zone(self, surface: str, dialog: ZoneDialog | None, **shape) -> bool:
        """Ask for a drawn zone's name and kind, then rebuild the scene with it
        (``shape``: its ``rect`` or its ``outline``); errors shown, nothing changed."""
        if dialog is None:
            dialog = ZoneDialog(surface, self.doc.new_zone_name(), self)
            dialog.kind.setCurrentText(self.draw_kind())
        if not dialogs.accepted(dialog):
            return False
        try:
            name, kind = dialog.name.text().strip(), dialog.kind.currentText()
            edit = ZoneEdit(name, kind, surface, **shape)  # a bad name stops nothing
            self.stop_worker()
            self.doc.set_user_zones((*self.doc.user_zones, edit))
        except LightInvError as exc:
            dialogs.warn(self, str(exc))
            return False
        return True

    def _polygon_drawn(self, surface: str, corners, dialog: ZoneDialog | None = None) -> bool:
        """Ask for the new polygon zone's name and kind, then rebuild the scene with it."""
        pts = np.asarray(corners, float)
        span = pts.max(axis=0) - pts.min(axis=0) if len(pts) else np.zeros(2)
        if len(pts) < 3 or span.min() < MIN_ZONE:
            self.statusBar().showMessage("Zone too small: click at least 3 corners apart", 4000)
            return False
        return self._add_zone(surface, dialog, outline=tuple(map(tuple, pts)))

    def add_intention_on_selection(self, dialog: IntentionDialog | None = None) -> bool:
        """Ask for bounds and add an intention on the picked patches."""
        if len(self.doc.selection) == 0:
            dialogs.inform(self, "Select patches first (Select patches mode).")
            return False
        label = f"{len(self.doc.selection)} patches"
        return self._add_intention(label, None, self.doc.selection, dialog)

    def add_intention_on_group(self, group: str, dialog: IntentionDialog | None = None) -> bool:
        """Ask for bounds and add an intention on a group's patches."""
        return self._add_intention(group, group, None, dialog)

    def edit_intention(self, name: str, dialog: IntentionDialog | None = None) -> bool:
        """Change an intention's name, quantity or bounds in the intention dialog."""
        old = next((i for i in self.doc.design.intentions if i.name == name), None)
        if old is None:
            return False
        target = intention_target(old)
        if dialog is None:
            dialog = IntentionDialog(target, self)
            dialog.load(old)
        if not dialogs.accepted(dialog):
            return False
        try:
            new = dialog.intention(group=old.group, patches=old.patches, grid=old.grid)
            self.doc.replace_intention(name, replace(new, weight=old.weight))
        except LightInvError as exc:
            dialogs.warn(self, str(exc))
            return False
        return True

    def add_rule(self, dialog=None) -> bool:
        """Ask for a geometric rule (area, aspect, spacing, align; spacing-to-height and
        clearance on luminaire arrays) and add it."""
        d = self.doc.design if self.doc.project else None
        names = [x.name for x in d.sources] if d is not None else []
        arrays = [a.name for a in d.arrays] if d is not None else []
        if not names and not arrays:
            dialogs.inform(self, "Add sources or luminaire arrays first: rules bind them.")
            return False
        dialog = dialog or RuleDialog(names, self, arrays)
        if not dialogs.accepted(dialog):
            return False
        try:
            self.doc.add_rule(dialog.rule())
        except LightInvError as exc:
            dialogs.warn(self, str(exc))
            return False
        return True

    def delete_rule(self, index: int) -> None:
        """Remove a geometric rule (Edit > Undo brings it back)."""
        self.doc.remove_rule(index)
        self.statusBar().showMessage("Deleted a rule (Edit > Undo to restore)", 6000)

    def set_goal(self, kind: str, on: bool) -> None:
        """Add or remove a goal (Design > Goals); both power goals give a Pareto front."""
        try:
            self.doc.set_goal(kind, on)
        except LightInvError as exc:
            dialogs.warn(self, str(exc))
        actions.check_goals(self)

    def delete_intention(self, name: str) -> None:
        """Remove a lighting intention (Edit > Undo brings it back)."""
        self.doc.remove_intention(name)
        self.statusBar().showMessage(f"Deleted intention {name} (Edit > Undo to restore)", 6000)

    def _add_intention(self, label, group, patches, dialog) -> bool:
        dialog = dialog or IntentionDialog(label, self)
        if not dialogs.accepted(dialog):
            return False
        try:
            self.doc.add_intention(dialog.intention(group=group, patches=patches))
        except LightInvError as exc:
            dialogs.warn(self, str(exc))
            return False
        return True

    # -- workers (tasks.py, run_control.py) ----------------------------------------------------
    @property
    def worker(self) -> Worker | None:
        """The precompute or report worker running, if any."""
        return self.tasks.worker

    def start_precompute(self) -> None:
        """Build or load the operator in a worker thread (progress bar, cancel)."""
        self.tasks.start_precompute()

    def cancel_precompute(self) -> None:
        """Cancel the precompute (or report) worker."""
        self.tasks.cancel()

    # -- help and layout ----------------------------------------------------------------------
    def doc_url(self, name: str) -> QtCore.QUrl:
        """The URL of a documentation page (``""``: the folder), in the source tree or
        the bundle."""
        return QtCore.QUrl.fromLocalFile(str(DOCS / name) if name else str(DOCS))

    def open_doc(self, name: str) -> bool:
        """Open a documentation page in the desktop's viewer; a message if none opens."""
        url = self.doc_url(name)
        if not (DOCS / name).exists() or not QtGui.QDesktopServices.openUrl(url):
            dialogs.inform(self, f"The documentation is in {url.toLocalFile()}")
            return False
        return True

    def about(self) -> None:
        """Version, licence and where the documentation is."""
        from importlib.metadata import PackageNotFoundError, version

        try:
            v = version("lightinv")
        except PackageNotFoundError:
            v = "(source tree)"
        dialogs.inform(
            self,
            f"LightInv {v}\nInverse lighting design for building interiors.\n"
            f"MIT licence. Documentation: {DOCS}",
        )

    def restore_layout(self) -> None:
        """Every panel shown and docked where it starts."""
        for dock in self.findChildren(QtWidgets.QDockWidget):
            dock.setFloating(False)
            dock.show()
        self.restoreState(self._initial_state)

    def export_report(self, path: str | Path) -> bool:
        """Write the PDF report of the project's results in a worker (see tasks.py)."""
        return self.tasks.export_report(path)

    def stop_worker(self) -> None:
        """Cancel and wait for running workers (closing, switching projects); a cancelled
        optimisation still delivers its best result first."""
        self.runs.stop()
        self.tasks.stop()

    # -- files (files.py) ----------------------------------------------------------------------
    def load_project(self, project: Project, path: Path | None = None) -> bool:
        """Open a project (its scene loaded and meshed); errors shown, nothing half-done."""
        return self.files.load_project(project, path)

    def new_project(self, scene: str, resolution: float | None = None) -> bool:
        """A new project on a built-in scene."""
        return self.files.new_project(scene, resolution)

    def open_path(self, path: str | Path) -> bool:
        """Open a project file."""
        return self.files.open_path(path)

    def import_obj(self, path: str | Path, **options) -> bool:
        """A new project on an OBJ model, with import options (files.py)."""
        return self.files.import_obj(path, **options)

    def save(self) -> bool:
        """Save to the project's file (Save As when it has none)."""
        return self.files.save()

    def save_to(self, path: str | Path) -> bool:
        """Save atomically; errors are shown and the old file is kept."""
        return self.files.save_to(path)

    def recent_files(self) -> list[str]:
        """Recently opened or saved project files, newest first."""
        return self.files.recent_files()

    def open_dialog(self) -> None:
        self.files.open_dialog()

    def import_obj_dialog(self, dialog=None) -> bool:
        return self.files.import_obj_dialog(dialog)

    def save_as_dialog(self) -> bool:
        return self.files.save_as_dialog()

    def export_png_dialog(self) -> None:
        self.files.export_png_dialog()

    def export_report_dialog(self) -> None:
        self.files.export_report_dialog()

    # -- crash recovery (autosave.py) ----------------------------------------------------------
    def offer_recovery(self, ask=None) -> bool:
        """Offer the autosaves of sessions that ended without closing. ``ask(recoverable)
        -> "recover" | "discard" | "keep"`` replaces the dialog (tests). True if a project
        was recovered."""
        return _offer_recovery(self, ask or (lambda rec: dialogs.ask_recovery(self, rec)))

    def recover(self, rec: Recoverable) -> bool:
        """Open an autosave as the project, an interrupted run's best layout loaded."""
        return _recover(self, rec)

    def closeEvent(self, event: QtGui.QCloseEvent) -> None:
        if self.files.loading:  # a project is being loaded: Cancel it first
            event.ignore()
            return
        if not self.files.may_discard():
            event.ignore()
            return
        self.stop_worker()
        self.files.wait_abandoned()  # loads cancelled but still running end first
        self.autosaver.close()  # a clean exit: nothing to recover
        self.settings.setValue("geometry", self.saveGeometry())
        self.settings.setValue("windowState", self.saveState())
        self.viewport.close_plotter()
        event.accept()
