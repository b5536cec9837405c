"""Where the window's file dialogs start: the folder the user last chose a file in,
else the open project's folder, else the home folder (never the installation's folder,
the process's working directory, where they used to start).

The last folder is kept in the window's ``QSettings`` ("lastFolder"). Every file
dialog of the app is one of Qt's ``QFileDialog`` static functions with no start folder
(``app/dialogs/ask.py``); Qt starts those in its last visited folder, which
``QFileDialog.setDirectory`` sets, so pointing one dialog object there steers them all,
the array dialog's photometric file and the climate panel's weather file included.
"""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtWidgets

KEY = "lastFolder"
"""The settings key of the folder the user last chose a file in."""


class FolderMemory(QtCore.QObject):
    """The start folder of a main window's file dialogs (see the module)."""

    def __init__(self, window):
        super().__init__(window)
        self.settings, self.doc = window.settings, window.doc
        self._pointed: str | None = None  # the folder the dialogs were last pointed at
        self.doc.pathChanged.connect(lambda: self.point())
        self.point()

    def last_used(self) -> Path | None:
        """The folder the user last chose a file in, if it still exists."""
        value = self.settings.value(KEY)
        if not value or not Path(str(value)).is_dir():
            return None
        return Path(str(value))

    def project_folder(self) -> Path | None:
        """The open project's folder: its file's, or an unsaved import's model's."""
        d = self.doc
        if d.project is None:
            return None
        if d.path is not None:
            return Path(d.path).resolve().parent
        model = getattr(d.project.scene, "obj", None)
        return Path(model).resolve().parent if model else None

    def start(self) -> Path:
        """The folder the next file dialog starts in."""
        for folder in (self.last_used(), self.project_folder()):
            if folder is not None and folder.is_dir():
                return folder
        return Path.home()

    def point(self) -> None:
        """Make the next file dialog start in ``start()`` (the path event comes with
        every edit: a dialog object is made only when the folder changes)."""
        folder = str(self.start())
        if folder != self._pointed:
            QtWidgets.QFileDialog().setDirectory(folder)  # Qt's last visited folder
            self._pointed = folder

    def chosen(self, path: str | Path) -> None:
        """Remember the folder of a file the user chose ("": cancelled, nothing)."""
        if not path:
            return
        folder = Path(path).resolve().parent
        if folder.is_dir():
            self.settings.setValue(KEY, str(folder))
        self._pointed = None  # a dialog went elsewhere meanwhile: point it again
        self.point()

    def keep_visited(self) -> None:
        """Remember the folder a dialog of another part of the window went to (Qt's
        last visited one), when it is not where the dialogs were pointed (closing)."""
        visited = QtWidgets.QFileDialog().directory().absolutePath()
        if visited != self._pointed and Path(visited).is_dir():
            self.settings.setValue(KEY, visited)
