"""Project files from the window: new, open, import, save, export, recent files.

Errors are shown, never half-applied: a file that does not load leaves the open project
as it was, a failed save keeps the old file. Unsaved changes are asked about before
they are discarded (unless the window's ``ask_before_discard`` is off: scripts, tests).
"""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtWidgets

from app.dialogs import ask
from app.window import actions
from app.window.workers import LoadWorker
from lightinv_core.editing import blank_project, obj_project
from lightinv_core.errors import LightInvError
from lightinv_core.project import Project, load_project
from lightinv_core.scene.importers.report import report_of

MAX_RECENT = 8
LOAD_DIALOG_MS = 500  # a load shorter than this shows no progress dialog
SHIPPED = Path(__file__).resolve().parents[2] / "resources"
"""The installation's own files (demo projects): opened as untitled copies."""


def is_shipped(path: Path) -> bool:
    """Whether ``path`` lies in the installation's resources folder."""
    try:
        return path.resolve().is_relative_to(SHIPPED)
    except OSError:
        return False


class ProjectFiles(QtCore.QObject):
    """Opening and saving the project of a main window."""

    def __init__(self, window):
        super().__init__(window)
        self.win, self.doc = window, window.doc
        self._abandoned: list = []  # loads cancelled but still running
        self.loading = False  # a load_scene is under way (its event loop is running)

    # -- opening -------------------------------------------------------------------------------
    def may_discard(self) -> bool:
        """Whether the open project may be replaced (nothing unsaved, or the user agrees)."""
        d = self.doc
        if d.project is None or not d.dirty or not self.win.ask_before_discard:
            return True
        answer = ask.ask_unsaved(self.win)
        if answer == "save":
            return self.save()  # Save As when untitled; cancelling it keeps the project
        return answer == "discard"

    def load_project(self, project: Project, path: Path | None = None) -> bool:
        """Open a project (its scene loaded and meshed off the GUI thread); errors
        shown, nothing half-done; a cancelled load keeps the open project."""
        if not self.may_discard():
            return False
        try:
            loaded = self.load_scene(project, path)
            if loaded is None:
                self.win.statusBar().showMessage("Loading cancelled", 4000)
                return False
            # The open project's work (a precompute) goes on while the new one loads.
            self.win.stop_worker()
            self.doc.set_project(project, path, loaded=loaded)
        except LightInvError as exc:
            ask.error(self.win, "cannot open", str(exc))
            return False
        self.win.undo_stack.clear()  # another project: earlier edits are not undoable
        return True

    def load_scene(self, project: Project, path: Path | None):
        """(scene, patches) of ``project``, loaded by a worker while the window stays
        responsive (a progress dialog with Cancel shows after half a second); None if
        cancelled (the worker's result is then dropped); LightInvError on a bad scene."""
        self._abandoned = [w for w in self._abandoned if w.isRunning()]
        worker = LoadWorker(project, path)
        got: dict = {}
        loop = QtCore.QEventLoop()
        worker.succeeded.connect(lambda r: got.update(result=r))
        worker.failed.connect(lambda m: got.update(error=m))
        worker.finished.connect(loop.quit)
        what = Path(project.scene.obj).name if project.scene.obj else project.scene.builtin
        # No parent: the window is disabled meanwhile (no second Open, no edits), and a
        # disabled parent would disable its dialog too.
        box = QtWidgets.QProgressDialog(f"Loading {what}...", "Cancel", 0, 0)
        box.setWindowTitle("LightInv")
        box.setAutoReset(False)
        box.setAutoClose(False)
        box.hide()  # shown only if the load lasts (its own timer needs setValue calls)
        later = QtCore.QTimer(singleShot=True, interval=LOAD_DIALOG_MS)
        later.timeout.connect(box.show)
        cancelled: list[bool] = []
        box.canceled.connect(lambda: cancelled.append(True))
        box.canceled.connect(loop.quit)
        self.loading = True
        self.win.setEnabled(False)
        try:
            worker.start()
            later.start()
            if not worker.isFinished():
                loop.exec()
        finally:
            later.stop()
            box.hide()
            box.deleteLater()
            self.win.setEnabled(True)
            self.loading = False
        if cancelled:  # drop the result; the worker ends on its own (waited for on close)
            worker.cancel()
            worker.succeeded.disconnect()
            worker.failed.disconnect()
            self._abandoned.append(worker)
            return None
        worker.wait()
        QtWidgets.QApplication.processEvents()  # its result signals, if still queued
        if "error" in got:
            raise LightInvError(got["error"])
        return got["result"]

    def wait_abandoned(self) -> None:
        """Wait for cancelled loads still running (before the window goes)."""
        for w in self._abandoned:
            w.wait()
        self._abandoned.clear()

    def new_project(self, scene: str, resolution: float | None = None) -> bool:
        """A new project on a built-in scene."""
        return self.load_project(blank_project(scene, resolution))

    def open_path(self, path: str | Path) -> bool:
        """Open a project file (remembered among the recent files)."""
        try:
            project = load_project(path)
        except LightInvError as exc:
            ask.error(self.win, "cannot open", str(exc))
            return False
        if is_shipped(Path(path)):
            # A demo in the installation: open an untitled copy, so Save asks where to
            # keep the work and the demo stays as shipped.
            if self.load_project(project, None):
                self.win.statusBar().showMessage(
                    f"Opened a copy of {Path(path).name}; Save asks where to keep it", 8000
                )
                return True
            return False
        if self.load_project(project, Path(path)):
            self.remember(Path(path))
            return True
        return False

    def import_obj(self, path: str | Path, **options) -> bool:
        """A new project on a model file, OBJ, glTF/GLB, PLY or IFC (groups, materials and
        zones from the file) with import ``options`` (scale, up, materials, resolution,
        skip_degenerate, group_by)."""
        try:
            project = obj_project(path, **options)
        except LightInvError as exc:
            ask.error(self.win, "cannot import", str(exc))
            return False
        if not self.load_project(project):
            return False
        self.show_import_report()
        return True

    def show_import_report(self) -> None:
        """Say what the import made of the file: its summary in the status bar, and the
        import report (not blocking the window) when something was dropped, skipped or
        is no zone."""
        from app.dialogs.import_report_dialog import ImportReportDialog, import_summary

        report = report_of(self.doc.scene) if self.doc.scene is not None else None
        if report is None:
            return
        old = getattr(self.win, "import_report", None)
        if old is not None:  # the report of the file imported before
            old.close()
            old.deleteLater()
            self.win.import_report = None
        self.win.statusBar().showMessage(import_summary(report), 15000)
        if report.needs_attention:
            self.win.import_report = ImportReportDialog(report, self.win)
            self.win.import_report.show()

    def open_dialog(self) -> None:
        path = ask.open_file(self.win, "Open project")
        self.win.folders.chosen(path)
        if path:
            self.open_path(path)

    def import_obj_dialog(self, dialog=None) -> bool:
        """Choose a model file (OBJ, glTF, GLB, PLY, IFC), then its import options (units,
        up axis, group names, materials)."""
        if dialog is None:
            from app.dialogs.import_dialog import ImportDialog, model_filter

            path = ask.open_file(self.win, "Import model", model_filter())
            self.win.folders.chosen(path)
            if not path:
                return False

            dialog = ImportDialog(Path(path), self.win)
        if not ask.accepted(dialog):
            return False
        return self.import_obj(dialog.path, **dialog.options())

    # -- saving and exporting ------------------------------------------------------------------
    def save(self) -> bool:
        """Save to the project's file (Save As when it has none)."""
        if self.doc.path is None:
            return self.save_as_dialog()
        return self.save_to(self.doc.path)

    def save_to(self, path: str | Path) -> bool:
        """Save atomically; errors are shown and the old file is kept."""
        try:
            saved = self.doc.save(path)
        except (LightInvError, OSError) as exc:
            ask.error(self.win, "cannot save", str(exc))
            return False
        self.remember(saved)
        self.win.autosaver.save_now()  # nothing unsaved: removes the autosave (unless running)
        self.win.statusBar().showMessage(f"Saved {saved}", 4000)
        return True

    def save_as_dialog(self) -> bool:
        path = ask.save_file(self.win, "Save project", suffix=".json")
        self.win.folders.chosen(path)
        return bool(path) and self.save_to(path)

    def export_png_dialog(self) -> None:
        path = ask.save_file(self.win, "Export viewport", "PNG image (*.png)", suffix=".png")
        self.win.folders.chosen(path)
        if path:
            self.win.viewport.screenshot(path)

    def export_report_dialog(self) -> None:
        path = ask.save_file(self.win, "Export report", "PDF (*.pdf)", suffix=".pdf")
        self.win.folders.chosen(path)
        if path:
            self.win.export_report(path)

    def export_design_dialog(self, name: str) -> None:
        """File > Export design > a format: its save dialog, then the export."""
        from lightinv_core.export import exporter

        e = exporter(name)
        path = ask.save_file(self.win, f"Export design: {e.label}", e.filter, suffix=e.suffixes[0])
        self.win.folders.chosen(path)
        if path:
            self.win.tasks.export_design(name, path)

    # -- recent files --------------------------------------------------------------------------
    def recent_files(self) -> list[str]:
        """The recently opened or saved project files, newest first."""
        value = self.win.settings.value("recent") or []
        return [value] if isinstance(value, str) else list(value)

    def remember(self, path: Path) -> None:
        """Put ``path`` first among the recent files."""
        resolved = str(path.resolve())
        recent = [resolved] + [p for p in self.recent_files() if p != resolved]
        self.win.settings.setValue("recent", recent[:MAX_RECENT])
        self.fill_recent()

    def fill_recent(self) -> None:
        """Refresh File > Open recent."""
        actions.fill_recent(self.win, self.recent_files())
