"""The LightInv main window: menus, toolbar, tree, viewport, source panel, status bar."""

from __future__ import annotations

import contextlib
import time
from pathlib import Path

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

from app.autosave import Autosaver, Recoverable, orphaned_autosaves
from app.document import Document, blank_project
from app.panels import DesignTree, IntentionDialog, SourcePanel, ZoneDialog, ZonePanel
from app.results_panel import SolutionsPanel, ViolationsPanel
from app.run_control import RunController
from app.run_panel import RunPanel
from app.viewport import Viewport
from app.workers import PrecomputeWorker, ReportWorker
from lightinv_core.errors import LightInvError
from lightinv_core.project import Project, SceneSpec
from lightinv_core.scene.builtin import BUILTIN_SCENES

COLORMAPS = ("inferno", "viridis", "plasma", "coolwarm", "gray")
MAX_RECENT = 8


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
        self.worker: PrecomputeWorker | None = None
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
        self._docks()
        self._actions()
        self.runs = RunController(self)
        self.autosaver = Autosaver(self, autosave_seconds, autosave_folder)
        self._menus()
        self._status()
        self._connect()
        self.resize(1400, 900)
        geometry = self.settings.value("geometry")
        if geometry is not None:
            self.restoreGeometry(geometry)
            self.restoreState(self.settings.value("windowState"))

    # -- building ----------------------------------------------------------------------------
    def _docks(self) -> None:
        left = QtWidgets.QDockWidget("Scene and design", self)
        left.setObjectName("tree")
        left.setWidget(self.tree)
        self.addDockWidget(QtCore.Qt.LeftDockWidgetArea, left)
        right = QtWidgets.QDockWidget("Properties", self)
        right.setObjectName("properties")
        box = QtWidgets.QWidget()
        lay = QtWidgets.QVBoxLayout(box)
        lay.addWidget(self.source_panel)
        lay.addWidget(self.zone_panel)
        lay.addWidget(self._view_options())
        lay.addStretch(1)
        right.setWidget(box)
        self.addDockWidget(QtCore.Qt.RightDockWidgetArea, right)
        bottom = QtWidgets.QDockWidget("Optimisation", self)
        bottom.setObjectName("optimisation")
        self.tabs = QtWidgets.QTabWidget()
        self.tabs.addTab(self.run_panel, "Run")
        self.tabs.addTab(self.solutions_panel, "Solutions")
        self.tabs.addTab(self.violations_panel, "Violations")
        self.tabs.setMinimumHeight(self.run_panel.sizeHint().height() + 40)
        bottom.setWidget(self.tabs)
        self.addDockWidget(QtCore.Qt.BottomDockWidgetArea, bottom)

    def _view_options(self) -> QtWidgets.QGroupBox:
        group = QtWidgets.QGroupBox("View")
        form = QtWidgets.QFormLayout(group)
        self.colour_by = QtWidgets.QComboBox()
        self.colour_by.addItem("illuminance (lux)", "lux")
        self.colour_by.addItem("radiosity B (lm/m²)", "B")
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
        self.colour_by.currentIndexChanged.connect(self._recolour)
        self.cmap.currentTextChanged.connect(self.viewport.set_colormap)
        self.auto_range.toggled.connect(lambda on: self.range_max.setEnabled(not on))
        self.auto_range.toggled.connect(self._recolour)
        self.range_max.valueChanged.connect(self._recolour)
        return group

    def _action(self, text: str, slot, shortcut=None, checkable=False) -> QtGui.QAction:
        act = QtGui.QAction(text, self)
        if shortcut:
            act.setShortcut(shortcut)
        act.setCheckable(checkable)
        act.triggered.connect(slot)
        return act

    def _actions(self) -> None:
        ks = QtGui.QKeySequence
        self.act_open = self._action("&Open project...", self.open_dialog, ks.Open)
        self.act_save = self._action("&Save", self.save, ks.Save)
        self.act_save_as = self._action("Save &As...", self.save_as_dialog, ks.SaveAs)
        self.act_import = self._action("&Import OBJ...", self.import_obj_dialog)
        self.act_png = self._action("Export viewport &PNG...", self.export_png_dialog)
        self.act_report = self._action("Export &report (PDF)...", self.export_report_dialog)
        self.act_quit = self._action("&Quit", self.close, ks.Quit)
        self.act_precompute = self._action("Precompute", self.start_precompute)
        self.act_cancel = self._action("Cancel", self.cancel_precompute)
        self.act_cancel.setEnabled(False)
        self.act_run = self._action("&Run optimisation", lambda: self.runs.start(), "F5")
        self.act_cancel_run = self._action("Cancel optimisation", lambda: self.runs.cancel())
        self.act_cancel_run.setEnabled(False)
        self.act_intention = self._action(
            "Add intention on selection...", self.add_intention_on_selection
        )
        self.act_clear = self._action("Clear selection", lambda: self.doc.set_selection([]))
        self.mode_group = QtGui.QActionGroup(self)
        self.mode_actions = {}
        for mode, text in (
            ("navigate", "Navigate"),
            ("select", "Select patches"),
            ("move", "Move source"),
            ("zone", "Draw zone"),
        ):
            act = self._action(text, lambda _=False, m=mode: self.set_mode(m), checkable=True)
            self.mode_group.addAction(act)
            self.mode_actions[mode] = act
        self.mode_actions["navigate"].setChecked(True)
        self.camera_actions = {
            name: self._action(
                f"{name.title()} view", lambda _=False, n=name: self.viewport.camera(n)
            )
            for name in ("iso", "top", "front")
        }

    def _menus(self) -> None:
        bar = self.menuBar()
        file = bar.addMenu("&File")
        new = file.addMenu("&New from built-in scene")
        for name in BUILTIN_SCENES:
            new.addAction(self._action(name, lambda _=False, n=name: self.new_project(n)))
        for act in (self.act_import, self.act_open):
            file.addAction(act)
        self.recent_menu = file.addMenu("Open &recent")
        file.addSeparator()
        for act in (self.act_save, self.act_save_as, self.act_png, self.act_report):
            file.addAction(act)
        file.addSeparator()
        file.addAction(self.act_quit)
        view = bar.addMenu("&View")
        for act in self.camera_actions.values():
            view.addAction(act)
        design = bar.addMenu("&Design")
        for act in (self.act_intention, self.act_clear, *self.mode_actions.values()):
            design.addAction(act)
        compute = bar.addMenu("&Compute")
        for act in (self.act_precompute, self.act_cancel, self.act_run, self.act_cancel_run):
            compute.addAction(act)
        tools = self.addToolBar("Main")
        tools.setObjectName("main toolbar")
        for act in (self.act_open, self.act_save, self.act_precompute, self.act_cancel):
            tools.addAction(act)
        tools.addSeparator()
        tools.addAction(self.act_run)
        tools.addAction(self.act_cancel_run)
        tools.addSeparator()
        for act in self.mode_actions.values():
            tools.addAction(act)
        tools.addAction(self.act_intention)
        tools.addSeparator()
        for act in self.camera_actions.values():
            tools.addAction(act)
        self._fill_recent()

    def _status(self) -> None:
        self.status_patches = QtWidgets.QLabel()
        self.status_rank = QtWidgets.QLabel()
        self.status_eval = QtWidgets.QLabel()
        self.progress = QtWidgets.QProgressBar()
        self.progress.setRange(0, 1000)
        self.progress.setMaximumWidth(220)
        self.progress.hide()
        for w in (self.status_patches, self.status_rank, self.status_eval):
            self.statusBar().addPermanentWidget(w)
        self.statusBar().addPermanentWidget(self.progress)

    def _connect(self) -> None:
        d = self.doc
        d.sceneChanged.connect(self._scene_changed)
        d.lightingChanged.connect(self._recolour)
        d.designChanged.connect(self._sources_changed)
        d.selectionChanged.connect(lambda: self.viewport.set_selection(d.selection))
        d.pathChanged.connect(self._title)
        self.viewport.picked.connect(self._picked)
        self.viewport.sourceDragged.connect(self._dragged)
        self.viewport.zoneDrawn.connect(self._zone_drawn)
        self.viewport.surface_frame = self._surface_frame
        self.tree.groupActivated.connect(self.add_intention_on_group)
        self.run_panel.runRequested.connect(self.runs.start)
        self.run_panel.cancelRequested.connect(self.runs.cancel)
        self.solutions_panel.compareChanged.connect(self._recolour)
        self.violations_panel.highlightChanged.connect(
            lambda: self.viewport.set_highlight(self.violations_panel.highlighted())
        )

    # -- document -> views -----------------------------------------------------------------
    def _scene_changed(self) -> None:
        d = self.doc
        self.viewport.set_scene(d.patches, [z.name for z in d.scene.zones])
        self.viewport.set_values(None)
        self.status_patches.setText(f"{d.patches.n:,} patches")
        self.status_rank.setText("operator: not built")
        self.status_eval.setText("")
        self._sources_changed()
        self.start_precompute()

    def _shown_sources(self) -> tuple:
        preview = self.doc.preview_sources()
        return preview if preview is not None else self.doc.effective_sources()

    def _sources_changed(self) -> None:
        self.viewport.set_sources(self._shown_sources(), self.doc.current_source)
        if self.doc.current_source:
            self.viewport.drag_zone = self.doc.design.source(self.doc.current_source).zone
        self._title()

    def _recolour(self) -> None:
        lux = self.doc.lighting()
        if lux is not None:
            self.viewport.set_sources(self._shown_sources(), self.doc.current_source)
        t0 = time.perf_counter()
        self.viewport.clim = None if self.auto_range.isChecked() else (0.0, self.range_max.value())
        if lux is None:
            self.viewport.set_values(None)
            return
        other = self.solutions_panel.compared()
        cmap = "coolwarm" if other is not None else self.cmap.currentText()
        if cmap != self.viewport.cmap:
            self.viewport.set_colormap(cmap)
        if other is not None:
            # Difference view: the loaded layout minus a pinned one, centred on zero.
            values = lux - self.doc.lux_of_sources(other.sources)
            m = float(np.abs(values).max()) or 1.0
            self.viewport.clim = (-m, m)
            units = "lux, loaded − pinned"
        elif self.colour_by.currentData() == "B":
            values, units = self._radiosity(lux), "lm/m²"
        else:
            values, units = lux, "lux"
        self.viewport.set_values(values, units)
        self.last_render_ms = 1e3 * (time.perf_counter() - t0)
        self.status_eval.setText(
            f"lighting {self.doc.last_eval_ms:.1f} ms, view {self.last_render_ms:.1f} ms"
        )

    def _radiosity(self, lux: np.ndarray) -> np.ndarray:
        """B = E + rho H for the current sources."""
        p = self.doc.problem()
        B = self.doc.patches.rho * lux
        if p is not None and self.doc.design.sources:
            rect, flux, filt = p.vars.decode(p.vars.initial()[None])
            V = p.emission.matrix(rect, flux, filt)[:, 0]
            B[self.doc.operator.zone_patches] += V
        return B

    def _title(self) -> None:
        d = self.doc
        name = d.path.name if d.path else (d.project.name if d.project else "")
        self.setWindowTitle(f"LightInv - {name}{' *' if d.dirty else ''}")

    # -- picking and dragging ---------------------------------------------------------------
    def set_mode(self, mode: str) -> None:
        """navigate (orbit), select (click/drag picks patches), move (drag the source)."""
        self.viewport.mode = mode
        self.mode_actions[mode].setChecked(True)

    def _picked(self, ids: np.ndarray, add: bool) -> None:
        ids = np.union1d(self.doc.selection, ids) if add else ids
        self.doc.set_selection(ids)
        self.statusBar().showMessage(f"{len(ids)} patches selected", 4000)

    def _dragged(self, du: float, dv: float) -> None:
        if self.doc.current_source is not None:
            self.doc.move_source(self.doc.current_source, du, dv)

    def _surface_frame(self, patch: int):
        from app.viewport import ZoneFrame

        found = self.doc.drawable_surface(patch)
        if found is None:
            self.statusBar().showMessage(
                "Zones are drawn on planar rectangular surfaces that are not zones yet", 4000
            )
            return None
        return ZoneFrame(None, found[0], rect=found[1])

    def _zone_drawn(self, surface, u0, v0, u1, v1, dialog: ZoneDialog | None = None) -> bool:
        """Ask for the new zone's name and kind, then rebuild the scene with it."""
        from lightinv_core.scene.edits import ZoneEdit

        if abs(u1 - u0) < 0.05 or abs(v1 - v0) < 0.05:
            self.statusBar().showMessage("Zone too small: drag a larger rectangle", 4000)
            return False
        taken = {z.name for z in self.doc.scene.zones}
        default = next(f"Z{i}" for i in range(1, 10_000) if f"Z{i}" not in taken)
        dialog = dialog or ZoneDialog(surface, default, self)
        if (
            dialog.result() != QtWidgets.QDialog.Accepted
            and dialog.exec() != QtWidgets.QDialog.Accepted
        ):
            return False
        try:
            edit = ZoneEdit(
                dialog.name.text().strip(), dialog.kind.currentText(), surface, (u0, v0, u1, v1)
            )
            self.stop_worker()
            self.doc.set_user_zones((*self.doc.user_zones, edit))
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            return False
        return True

    def add_intention_on_selection(self, dialog: IntentionDialog | None = None) -> bool:
        """Ask for bounds and add an intention on the picked patches."""
        if len(self.doc.selection) == 0:
            QtWidgets.QMessageBox.information(
                self, "LightInv", "Select patches first (Select patches mode)."
            )
            return False
        return self._add_intention(
            f"{len(self.doc.selection)} patches", None, self.doc.selection, dialog
        )

    def add_intention_on_group(self, group: str, dialog: IntentionDialog | None = None) -> bool:
        """Ask for bounds and add an intention on a group's patches."""
        return self._add_intention(group, group, None, dialog)

    def _add_intention(self, label, group, patches, dialog) -> bool:
        dialog = dialog or IntentionDialog(label, self)
        if (
            dialog.result() != QtWidgets.QDialog.Accepted
            and dialog.exec() != QtWidgets.QDialog.Accepted
        ):
            return False
        try:
            self.doc.add_intention(dialog.intention(group=group, patches=patches))
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            return False
        return True

    # -- precompute ----------------------------------------------------------------------------
    def start_precompute(self) -> None:
        """Build or load the operator in a worker thread (progress bar, cancel)."""
        if self.doc.patches is None or self.worker is not None:
            return
        self.worker = PrecomputeWorker(self.doc.patches, self.doc.operator_settings, self)
        self.worker.progress.connect(lambda f: self.progress.setValue(int(1000 * f)))
        self.worker.succeeded.connect(self._precomputed)
        self.worker.failed.connect(self._precompute_failed)
        self.worker.cancelled.connect(self._precompute_cancelled)
        self.worker.finished.connect(self._worker_done)
        self.progress.setValue(0)
        self.progress.show()
        self.act_cancel.setEnabled(True)
        self.act_precompute.setEnabled(False)
        self.statusBar().showMessage("Precomputing the radiosity operator...")
        self.worker.start()

    def cancel_precompute(self) -> None:
        if self.worker is not None:
            self.worker.cancel()

    def _precomputed(self, got) -> None:
        if got.operator.digest != self.doc.patches.digest():
            return  # the scene changed while the worker ran
        self.doc.set_operator(got.operator)
        info = got.operator.info
        self.status_rank.setText(
            f"rank k = {got.operator.k} (error {100 * info['estimated_rel_error']:.2f}%)"
        )
        how = "loaded from the cache" if got.from_cache else "built"
        self.statusBar().showMessage(f"Operator {how} in {got.seconds:.1f} s", 6000)
        for w in self.worker.warnings:
            self.statusBar().showMessage(w, 8000)

    def _precompute_failed(self, message: str) -> None:
        QtWidgets.QMessageBox.critical(self, "LightInv: precompute failed", message)

    def _precompute_cancelled(self) -> None:
        self.statusBar().showMessage(
            "Precompute cancelled: lighting unavailable until it runs", 6000
        )

    def _worker_done(self) -> None:
        self.progress.hide()
        self.act_cancel.setEnabled(False)
        self.act_precompute.setEnabled(True)
        self.worker.deleteLater()
        self.worker = None
        if self.run_after_precompute and self.doc.operator is not None:
            self.run_after_precompute = False
            self.runs.start()

    def stop_worker(self) -> None:
        """Cancel and wait for running workers (closing, switching projects); a cancelled
        optimisation still delivers its best result first."""
        self.runs.stop()
        if self.worker is not None:
            self.worker.cancel()
            self.worker.wait()
            QtWidgets.QApplication.processEvents()

    # -- files ----------------------------------------------------------------------------------
    def _confirm_discard(self) -> bool:
        if self.doc.project is None or not self.doc.dirty or not self.ask_before_discard:
            return True
        answer = QtWidgets.QMessageBox.question(
            self,
            "LightInv",
            "The project has unsaved changes. Discard them?",
            QtWidgets.QMessageBox.Discard | QtWidgets.QMessageBox.Cancel,
        )
        return answer == QtWidgets.QMessageBox.Discard

    def load_project(self, project: Project, path: Path | None = None) -> bool:
        """Open a project (its scene loaded and meshed); errors shown, nothing half-done."""
        if not self._confirm_discard():
            return False
        self.stop_worker()
        try:
            self.doc.set_project(project, path)
        except LightInvError as exc:
            QtWidgets.QMessageBox.critical(self, "LightInv: cannot open", str(exc))
            return False
        return True

    def new_project(self, scene: str, resolution: float | None = None) -> bool:
        return self.load_project(blank_project(scene, resolution))

    def open_path(self, path: str | Path) -> bool:
        """Open a project file."""
        from lightinv_core.project import load_project

        try:
            project = load_project(path)
        except LightInvError as exc:
            QtWidgets.QMessageBox.critical(self, "LightInv: cannot open", str(exc))
            return False
        if self.load_project(project, Path(path)):
            self._remember(Path(path))
            return True
        return False

    def open_dialog(self) -> None:
        path, _ = QtWidgets.QFileDialog.getOpenFileName(
            self, "Open project", "", "LightInv project (*.json)"
        )
        if path:
            self.open_path(path)

    def import_obj_dialog(self) -> None:
        path, _ = QtWidgets.QFileDialog.getOpenFileName(
            self, "Import OBJ model", "", "Wavefront OBJ (*.obj)"
        )
        if path:
            self.import_obj(path)

    def import_obj(self, path: str | Path) -> bool:
        """A new project on an OBJ model (groups, materials and zones from the file)."""
        from lightinv_core.design.model import Design, Goal

        project = Project(
            name=Path(path).stem,
            scene=SceneSpec(obj=str(Path(path).resolve())),
            design=Design((), (Goal("min_electric_power"),)),
        )
        return self.load_project(project)

    def save(self) -> bool:
        if self.doc.path is None:
            return self.save_as_dialog()
        return self.save_to(self.doc.path)

    def save_to(self, path: str | Path) -> bool:
        """Save atomically; errors are shown and the old file is kept."""
        try:
            saved = self.doc.save(path)
        except (LightInvError, OSError) as exc:
            QtWidgets.QMessageBox.critical(self, "LightInv: cannot save", str(exc))
            return False
        self._remember(saved)
        self.autosaver.save_now()  # nothing unsaved: removes the autosave (unless running)
        self.statusBar().showMessage(f"Saved {saved}", 4000)
        return True

    def save_as_dialog(self) -> bool:
        path, _ = QtWidgets.QFileDialog.getSaveFileName(
            self, "Save project", "", "LightInv project (*.json)"
        )
        return bool(path) and self.save_to(path)

    def export_png_dialog(self) -> None:
        path, _ = QtWidgets.QFileDialog.getSaveFileName(
            self, "Export viewport", "", "PNG image (*.png)"
        )
        if path:
            self.viewport.screenshot(path)

    def export_report_dialog(self) -> None:
        path, _ = QtWidgets.QFileDialog.getSaveFileName(self, "Export report", "", "PDF (*.pdf)")
        if path:
            self.export_report(path)

    def export_report(self, path: str | Path) -> bool:
        """Write the PDF report of the project's saved solution in a worker (progress bar,
        Cancel); needs the operator and a solution saved by a run."""
        from lightinv_core.study import Prepared

        d = self.doc
        if d.operator is None or self.worker is not None:
            QtWidgets.QMessageBox.information(
                self, "LightInv", "Wait for the radiosity operator first."
            )
            return False
        if not d.project.solutions and d.project.pareto is None:
            QtWidgets.QMessageBox.information(
                self,
                "LightInv",
                "The project has no results yet: press Run (Optimisation panel) first.",
            )
            return False
        prepared = Prepared(d.scene, d.patches, d.operator, True, 0.0)
        self.worker = ReportWorker(d.project, prepared, Path(path), self)
        self.worker.progress.connect(lambda f: self.progress.setValue(int(1000 * f)))
        self.worker.succeeded.connect(
            lambda info: self.statusBar().showMessage(
                f"Report written: {info.path} ({len(info.pages)} pages)", 8000
            )
        )
        self.worker.failed.connect(
            lambda msg: QtWidgets.QMessageBox.critical(self, "LightInv: report failed", msg)
        )
        self.worker.cancelled.connect(
            lambda: self.statusBar().showMessage("Report cancelled; no file written", 6000)
        )
        self.worker.finished.connect(self._worker_done)
        self.progress.setValue(0)
        self.progress.show()
        self.act_cancel.setEnabled(True)
        self.act_precompute.setEnabled(False)
        self.worker.start()
        return True

    def _remember(self, path: Path) -> None:
        recent = [str(path.resolve())] + [
            p for p in self.recent_files() if p != str(path.resolve())
        ]
        self.settings.setValue("recent", recent[:MAX_RECENT])
        self._fill_recent()

    def recent_files(self) -> list[str]:
        value = self.settings.value("recent") or []
        return [value] if isinstance(value, str) else list(value)

    def _fill_recent(self) -> None:
        self.recent_menu.clear()
        for p in self.recent_files():
            self.recent_menu.addAction(self._action(p, lambda _=False, q=p: self.open_path(q)))
        self.recent_menu.setEnabled(bool(self.recent_files()))

    def closeEvent(self, event: QtGui.QCloseEvent) -> None:
        if not self._confirm_discard():
            event.ignore()
            return
        self.stop_worker()
        self.autosaver.timer.stop()
        self.autosaver.discard()  # a clean exit: nothing to recover
        self.settings.setValue("geometry", self.saveGeometry())
        self.settings.setValue("windowState", self.saveState())
        self.viewport.close_plotter()
        event.accept()

    # -- crash recovery -------------------------------------------------------------------------
    def offer_recovery(self, ask=None) -> bool:
        """Offer the autosaves of LightInv sessions that ended without closing (a crash, a
        kill). ``ask(recoverable) -> "recover" | "discard" | "keep"`` replaces the dialog
        (tests). Returns True if a project was recovered."""
        ask = ask or self._ask_recovery
        for rec in orphaned_autosaves(self.autosaver.folder):
            answer = ask(rec)
            if answer == "recover" and rec.project is not None and self.recover(rec):
                return True
            if answer == "discard":
                rec.path.unlink(missing_ok=True)
        return False

    def _ask_recovery(self, rec: Recoverable) -> str:
        box = QtWidgets.QMessageBox(self)
        box.setWindowTitle("LightInv: recover unsaved work")
        if rec.project is None:
            box.setText(f"An autosave could not be read:\n{rec.path}\n{rec.error}")
            delete = box.addButton("Delete it", QtWidgets.QMessageBox.DestructiveRole)
            box.addButton("Keep it", QtWidgets.QMessageBox.RejectRole)
            box.exec()
            return "discard" if box.clickedButton() is delete else "keep"
        where = str(rec.original) if rec.original else "a project never saved"
        box.setText(
            f"LightInv did not close normally. Recover the work autosaved at {rec.saved_at} "
            f"({rec.note}) for {where}?"
        )
        recover = box.addButton("Recover", QtWidgets.QMessageBox.AcceptRole)
        discard = box.addButton("Discard", QtWidgets.QMessageBox.DestructiveRole)
        box.addButton("Not now", QtWidgets.QMessageBox.RejectRole)
        box.exec()
        clicked = box.clickedButton()
        return "recover" if clicked is recover else ("discard" if clicked is discard else "keep")

    def recover(self, rec: Recoverable) -> bool:
        """Open an autosave as the project (unsaved; Save writes to the original file).
        The best layout of an interrupted run is loaded into the design."""
        if not self.load_project(rec.project, rec.original):
            return False
        self.doc.dirty = True
        self.doc.pathChanged.emit()
        running = [s for s in rec.project.solutions if s.info.get("status") == "running"]
        if running:
            with contextlib.suppress(LightInvError):
                self.doc.apply_solution(running[-1])
        rec.path.unlink(missing_ok=True)
        self.autosaver.save_now()
        self.statusBar().showMessage(
            f"Recovered the work autosaved at {rec.saved_at}"
            + (" with the interrupted run's best layout" if running else ""),
            10_000,
        )
        return True
