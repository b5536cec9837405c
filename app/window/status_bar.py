"""The status bar, whose messages fit, and the window title, whose project name shows.

A status message longer than the room left of the permanent widgets (warnings, patch
count, operator, progress) was cut off mid-word ("Precomputing the luminaire arrays'
li"); it is now elided with "…" and its whole text is the status bar's tooltip. A long
window title lost the project's name to the window manager's cut; the name now comes
first and the folder is shortened in its middle.
"""

from __future__ import annotations

import time
from pathlib import Path

from PySide6 import QtCore, QtGui, QtWidgets

MARGIN = 24
"""Pixels of the message area the status bar's own spacing takes."""
FOLDER_CHARS = 40
"""The most characters of a project's folder in the window title."""


class ElidingStatusBar(QtWidgets.QStatusBar):
    """A status bar whose messages are elided to fit, the whole text in the tooltip."""

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.full_message = ""
        self._deadline: float | None = None  # when the message goes (monotonic s)
        self._permanent: list[QtWidgets.QWidget] = []
        self.messageChanged.connect(self._message_changed)

    def addPermanentWidget(self, widget: QtWidgets.QWidget, stretch: int = 0) -> None:
        self._permanent.append(widget)
        super().addPermanentWidget(widget, stretch)

    def room(self) -> int:
        """Pixels a message may take: the width less the visible permanent widgets."""
        taken = sum(w.width() for w in self._permanent if w.isVisible())
        return max(40, self.width() - taken - MARGIN - 6 * len(self._permanent))

    def showMessage(self, text: str, timeout: int = 0) -> None:
        """Show ``text`` for ``timeout`` ms (0: until replaced), elided to fit."""
        self.full_message = text
        self._deadline = time.monotonic() + timeout / 1000 if timeout else None
        self._show(timeout)

    def _show(self, timeout: int) -> None:
        text = " ".join(self.full_message.split("\n"))
        shown = self.fontMetrics().elidedText(text, QtCore.Qt.ElideRight, self.room())
        super().showMessage(shown, timeout)
        self.setToolTip(self.full_message if shown != text else "")

    def _message_changed(self, text: str) -> None:
        if not text:  # timed out or cleared: no tooltip of a message gone
            self.full_message = ""
            self.setToolTip("")

    def resizeEvent(self, event: QtGui.QResizeEvent) -> None:
        super().resizeEvent(event)
        if self.full_message and self.currentMessage():
            left = 0
            if self._deadline is not None:
                left = max(1, int(1000 * (self._deadline - time.monotonic())))
            self._show(left)


def shortened(folder: str, limit: int = FOLDER_CHARS) -> str:
    """``folder`` with the home folder as "~" and its middle cut to ``limit`` characters
    ("~/projects/…/lighting/2026")."""
    home = str(Path.home())
    if folder == home or folder.startswith(home + "/"):
        folder = "~" + folder[len(home) :]
    if len(folder) <= limit:
        return folder
    keep = limit - 1
    return folder[: keep // 2] + "…" + folder[len(folder) - (keep - keep // 2) :]


def window_title(name: str, folder: str | None, dirty: bool) -> str:
    """ "meeting_room.json - ~/rooms - LightInv *": the project's name first, whole; its
    folder shortened; the unsaved mark last, where the title always had it."""
    parts = [name, shortened(folder)] if folder else [name]
    return " - ".join([*[p for p in parts if p], "LightInv"]) + (" *" if dirty else "")
