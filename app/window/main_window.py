"""The LightInv main window: its layout (docks, status bar) and the wiring of the
document's signals to the views.

The jobs around it live beside it in app/window/: actions, menus and toolbar in
actions.py; project files in files.py; the operator and report workers in tasks.py, the
optimisation in run_control.py; the design edits of the view and the dialogs in
design_edits.py; the viewport's colours in view_colouring.py; autosave and crash
recovery in recovery.py. The panels are in app/widgets/, the dialogs in app/dialogs/,
the viewport and plots in app/view/. The public methods here (new_project, open_path,
save_to, export_report, set_mode, ...) and those of ``files``, ``edits`` and ``runs``
are what menus, ``python -m app``, tests and scripts call.
"""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtGui, QtWidgets

from app.dialogs import ask
from app.dialogs.ask import ask_recovery
from app.document import Document
from app.view.sensor_drag import SensorDrag
from app.view.viewport import Viewport
from app.widgets.achieved_panel import AchievedPanel
from app.widgets.climate_panel import ClimatePanel
from app.widgets.design_tree import DesignTree
from app.widgets.luminaires_panel import LuminairesPanel
from app.widgets.materials_panel import MaterialsPanel
from app.widgets.run_panel import RunPanel
from app.widgets.solutions_panel import SolutionsPanel
from app.widgets.source_panel import SourcePanel
from app.widgets.view_options import ViewOptions
from app.widgets.violations_panel import ViolationsPanel
from app.widgets.zone_panel import ZonePanel
from app.window import actions
from app.window.collector import GarbageCollector
from app.window.design_edits import DesignEdits, surface_frame_of
from app.window.files import MAX_RECENT, ProjectFiles
from app.window.folders import FolderMemory
from app.window.recovery import Autosaver, Recoverable
from app.window.recovery import offer_recovery as _offer_recovery
from app.window.recovery import recover as _recover
from app.window.run_control import RunController
from app.window.scroll_page import FitScrollArea, page
from app.window.status_bar import ElidingStatusBar, window_title
from app.window.tasks import BackgroundTasks
from app.window.undo import undo_stack
from app.window.view_colouring import ViewColouring
from app.window.workers import ClearLightWorker, PrecomputeWorker, Worker
from lightinv_core.editing.changes import CURRENT_SOURCE
from lightinv_core.project import Project

__all__ = ["MAX_RECENT", "MainWindow"]

PREFERRED_SIZE = QtCore.QSize(1400, 900)
"""The window's size on a screen with room for it (px)."""


class MainWindow(QtWidgets.QMainWindow):
    """One open project at a time."""

    def __init__(
        self,
        settings: QtCore.QSettings | None = None,
        autosave_seconds: float | None = None,
        autosave_folder: Path | None = None,
    ):
        super().__init__()
        GarbageCollector.install(self)  # cycles collected between events, never mid-render
        self._fitted = False  # fitted to the screen with its title bar (showEvent)
        self.settings = settings or QtCore.QSettings("LightInv", "LightInv")
        self.doc = Document(self)
        self.run_after_precompute = False  # lightinv --run: start once the operator is there
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
        self.view_options = ViewOptions()
        self._docks()
        self.files = ProjectFiles(self)
        self.folders = FolderMemory(self)  # where the file dialogs start
        self.tasks = BackgroundTasks(self)
        self.undo_stack = undo_stack(self)
        self.edits = DesignEdits(self)
        actions.create_actions(self)
        self.runs = RunController(self)
        self.autosaver = Autosaver(self, autosave_seconds, autosave_folder)
        actions.build_menus(self)
        self.files.fill_recent()
        self._status()
        self.colouring = ViewColouring(self)
        # Control groups' sensor regions dragged in Move mode (an observer's ball first).
        self.sensor_drag = SensorDrag(
            self.viewport,
            self.doc,
            lambda: self.colouring.sensors,
            self.statusBar().showMessage,
            self.edits.observer_drag.observer_at,
        )
        self._connect()
        self.fit_to_screen()
        self._initial_state = self.saveState()  # View > Restore the panel layout
        geometry = self.settings.value("geometry")
        if geometry is not None:
            self.restoreGeometry(geometry)
            self.restoreState(self.settings.value("windowState"))
            self.fit_to_screen(self.size())  # saved on a larger screen: fit this one

    # -- layout --------------------------------------------------------------------------------
    def fit_to_screen(self, preferred: QtCore.QSize = PREFERRED_SIZE) -> None:
        """Take ``preferred`` pixels, or the screen's available area (less the taskbar
        and the title bar) if smaller, on that area: Run and the status bar stay on a
        1366 x 768 laptop screen."""
        screen = self.screen() or QtGui.QGuiApplication.primaryScreen()
        if screen is None:
            self.resize(preferred)
            return
        avail = screen.availableGeometry()
        # The frame (a window manager's title bar and borders) once shown; a guess before.
        frame = QtCore.QSize(0, 0)
        if self.isVisible():
            frame = (self.frameGeometry().size() - self.geometry().size()).expandedTo(frame)
        size = preferred.boundedTo(avail.size() - frame)
        self.resize(size)
        geo = self.frameGeometry()
        if not avail.contains(geo):
            geo.moveTopLeft(avail.topLeft())
            self.move(geo.topLeft())

    def showEvent(self, event: QtGui.QShowEvent) -> None:
        super().showEvent(event)
        if not self._fitted:  # the title bar is known once shown: fit with it
            self._fitted = True
            QtCore.QTimer.singleShot(0, lambda: self.fit_to_screen(self.size()))

    def _dock(self, title: str, name: str, widget, area, scroll: bool = False) -> None:
        dock = QtWidgets.QDockWidget(title, self)
        dock.setObjectName(name)
        if scroll:
            # A panel taller than the screen scrolls instead of making the window taller
            # than a laptop's (1366 x 768) screen.
            widget = FitScrollArea(widget)
        dock.setWidget(widget)
        self.addDockWidget(area, dock)

    def _docks(self) -> None:
        self._dock("Scene and design", "tree", self.tree, QtCore.Qt.LeftDockWidgetArea)
        # Properties as pages: the four panels in one column were twice a laptop's
        # height (1366 x 768), so its buttons were reached by scrolling.
        self.properties = QtWidgets.QTabWidget()
        pages = {
            "Source": (self.source_panel,),
            "Drawn zones": (self.zone_panel,),
            "Materials and view": (self.materials_panel, self.view_options),
        }
        for title, panels in pages.items():
            self.properties.addTab(page(*panels), title)
        self._dock("Properties", "properties", self.properties, QtCore.Qt.RightDockWidgetArea)
        self._dock(
            "Luminaires", "luminaires", self.luminaires_panel, QtCore.Qt.RightDockWidgetArea, True
        )
        # One column on the right: Properties and Luminaires as tabs (a laptop's height).
        self.tabifyDockWidget(
            self.findChild(QtWidgets.QDockWidget, "properties"),
            self.findChild(QtWidgets.QDockWidget, "luminaires"),
        )
        self.findChild(QtWidgets.QDockWidget, "properties").raise_()
        # The right column runs down to the status bar, beside the Optimisation dock: on
        # a laptop's 768 px the panels there would otherwise get a third of the height.
        self.setCorner(QtCore.Qt.BottomRightCorner, QtCore.Qt.RightDockWidgetArea)
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

    def _status(self) -> None:
        self.setStatusBar(ElidingStatusBar())  # messages elided to fit, whole in the tooltip
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
        d.lightingChanged.connect(self.colouring.recolour)
        d.designChanged.connect(self._sources_changed)
        d.selectionChanged.connect(lambda: self.viewport.set_selection(d.selection))
        d.pathChanged.connect(self._title)
        d.operatorChanged.connect(self._update_busy)
        self.progress.valueChanged.connect(self._update_busy)
        # A precompute ended (enabled again); its worker is let go just after.
        self.act_precompute.changed.connect(lambda: QtCore.QTimer.singleShot(0, self._update_busy))
        self.zone_panel.zone.activated.connect(self._drawn_zone_chosen)
        e = self.edits
        self.viewport.picked.connect(e.picked)
        self.viewport.sourceDragged.connect(e.dragged)
        self.viewport.zoneDrawn.connect(e.zone_drawn)
        self.viewport.polygonDrawn.connect(e.polygon_drawn)
        for drawn in (self.viewport.zoneDrawn, self.viewport.polygonDrawn):  # its fields
            drawn.connect(lambda *_: self.show_properties(self.zone_panel))
        d.designChanged.connect(self._source_chosen)
        self.viewport.surface_frame = e.surface_frame
        self.tree.groupActivated.connect(e.add_intention_on_group)
        self.tree.workplaneActivated.connect(e.add_intention_on_grid)
        self.tree.intentionActivated.connect(e.edit_intention)
        self.tree.intentionDeleted.connect(e.delete_intention)
        self.tree.ruleDeleted.connect(e.delete_rule)
        self.tree.calcActivated.connect(e.edit_calc_object)
        self.tree.calcDeleted.connect(e.delete_calc_object)
        d.designChanged.connect(lambda: actions.check_goals(self))
        self.run_panel.runRequested.connect(self.runs.start)
        self.run_panel.cancelRequested.connect(self.runs.cancel)
        self.solutions_panel.compareChanged.connect(self.colouring.recolour)
        self.solutions_panel.runDeleted.connect(
            lambda n: self.statusBar().showMessage(
                f"Deleted run {n} (Edit > Undo to restore)", 6000
            )
        )
        self.violations_panel.highlightChanged.connect(
            lambda: self.viewport.set_highlight(self.violations_panel.highlighted())
        )
        self.climate_panel.hourChanged.connect(self.colouring.hour_moved)
        self.climate_panel.showHourToggled.connect(self.colouring.show_hour)

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

    def show_properties(self, page: QtWidgets.QWidget) -> None:
        """Bring the Properties page holding ``page`` (a panel) to the front."""
        for i in range(self.properties.count()):
            if self.properties.widget(i).isAncestorOf(page):
                self.properties.setCurrentIndex(i)
        self.findChild(QtWidgets.QDockWidget, "properties").raise_()

    def _source_chosen(self, change) -> None:
        """A source added or chosen (not a project opened): its page of Properties."""
        if CURRENT_SOURCE in change.changed and len(change.changed) <= 2 and change.current_source:
            self.show_properties(self.source_panel)

    def show_warnings(self) -> None:
        """The warnings in full (the status bar's button)."""
        ask.inform(self, "\n\n".join(self.warnings()) or "No warnings.")

    def _scene_changed(self) -> None:
        d = self.doc
        self.set_warnings("scene", list(d.scene.info.get("warnings", [])))
        self.set_warnings("operator", [])
        # The same scene re-meshed (a zone drawn, a reflectance, an undo) keeps its
        # picture, veiled, until the new light model is ready; it used to go blank.
        keep = d.rebuilt and self.viewport.has_values
        self.viewport.set_scene(d.patches, [z.name for z in d.scene.zones], keep_picture=keep)
        low, high = self.viewport.mesh.bounds[4:6]
        self.view_options.model_heights(low, high)
        if not keep:
            self.viewport.set_values(None)
        self.status_patches.setText(f"{d.patches.n:,} patches")
        self.status_rank.setText("operator: not built")
        self.status_eval.setText("")
        self._sources_changed()
        self.start_precompute()
        self._update_busy()

    def _update_busy(self) -> None:
        """Say over the view why its light is missing or out of date: the light model or
        the clear glazing's light is being built (with its progress), or was not
        (cancelled)."""
        d = self.doc
        if isinstance(self.worker, ClearLightWorker):
            text = (
                f"Tracing the clear glazing's light... {self.progress.value() / 10:.0f}%\n"
                "The light shown leaves it out until then."
            )
        elif d.patches is None or d.operator is not None:
            text = None
        elif isinstance(self.worker, PrecomputeWorker) and self.worker.phase == "layout":
            text = f"Laying out the light (grids, arrays)... {self.progress.value() / 10:.0f}%"
            if self.viewport.has_values:
                text += "\nThe light shown is from before the change."
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

    def _sources_changed(self) -> None:
        self.viewport.set_sources(self.colouring.shown_sources(), self.doc.current_source)
        if self.doc.current_source:
            self.viewport.drag_zone = self.doc.design.source(self.doc.current_source).zone
        self._focus_axes()
        self._title()

    def _title(self) -> None:
        d = self.doc
        if d.project is None:
            self.setWindowTitle("LightInv")
            return
        name = d.path.name if d.path else d.project.name
        folder = str(Path(d.path).resolve().parent) if d.path else None
        self.setWindowTitle(window_title(name, folder, d.dirty))

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

    # -- layout ------------------------------------------------------------------------------
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

    # -- crash recovery (autosave.py) ----------------------------------------------------------
    def offer_recovery(self, ask=None) -> bool:
        """Offer the autosaves of sessions that ended without closing. ``ask(recoverable)
        -> "recover" | "discard" | "keep"`` replaces the dialog (tests). True if a project
        was recovered."""
        return _offer_recovery(self, ask or (lambda rec: ask_recovery(self, rec)))

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
        self.folders.keep_visited()
        self.settings.setValue("geometry", self.saveGeometry())
        self.settings.setValue("windowState", self.saveState())
        self.viewport.close_plotter()
        GarbageCollector.release(self)
        event.accept()
