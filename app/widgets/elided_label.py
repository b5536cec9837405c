"""A label whose lines are elided to its width, its whole text in the tooltip.

For status lines in narrow panels (the run panel's "Precomputing the luminaire arrays'
light: 45% (12 s); the search starts after it" was cut off mid-word at 1366 x 768):
each line that does not fit ends in "…", and hovering shows the text whole.
"""

from __future__ import annotations

from PySide6 import QtCore, QtGui, QtWidgets


class ElidedLabel(QtWidgets.QLabel):
    """A plain-text label: ``setText`` keeps the whole text, the label shows each line
    elided to the width it has; ``full_text()`` is what was set."""

    def __init__(self, text: str = "", parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self._full = ""
        # Any width will do: the text is elided to it (a long line must not widen the
        # panel past the screen).
        self.setSizePolicy(QtWidgets.QSizePolicy.Ignored, QtWidgets.QSizePolicy.Preferred)
        self.setText(text)

    def full_text(self) -> str:
        """The text as set, not elided."""
        return self._full

    def setText(self, text: str) -> None:
        self._full = text
        self._elide()

    def minimumSizeHint(self) -> QtCore.QSize:
        lines = max(1, self._full.count("\n") + 1)
        return QtCore.QSize(40, lines * self.fontMetrics().lineSpacing())

    def sizeHint(self) -> QtCore.QSize:
        widths = [self.fontMetrics().horizontalAdvance(t) for t in self._full.split("\n")]
        return QtCore.QSize(max(widths, default=0), self.minimumSizeHint().height())

    def _elide(self) -> None:
        room = max(10, self.contentsRect().width())
        metrics = self.fontMetrics()
        lines = [metrics.elidedText(t, QtCore.Qt.ElideRight, room) for t in self._full.split("\n")]
        shown = "\n".join(lines)
        super().setText(shown)
        self.setToolTip(self._full if shown != self._full else "")

    def resizeEvent(self, event: QtGui.QResizeEvent) -> None:
        super().resizeEvent(event)
        self._elide()
