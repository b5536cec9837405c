"""A dock's panel that scrolls only when the screen is too small for its minimum size.

``QScrollArea.setWidgetResizable`` sizes a panel with word-wrapped labels (their height
depends on the width) to its preferred height, not to the room there is: once the
Luminaires panel's status line had text ("4 luminaires in 1 arrays.") it grew to twice a
laptop's height (1366 x 768) and its Add, Edit and Remove buttons went out of sight
below. ``FitScrollArea`` gives the panel the room there is, or its minimum height when
that is more; only then does it scroll.
"""

from __future__ import annotations

from PySide6 import QtCore, QtGui, QtWidgets


class FitScrollArea(QtWidgets.QScrollArea):
    """Shows one panel at the viewport's size, never below the panel's minimum."""

    def __init__(self, widget: QtWidgets.QWidget, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.setWidgetResizable(False)
        self.setFrameShape(QtWidgets.QFrame.NoFrame)
        self.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAsNeeded)
        self.setWidget(widget)
        widget.installEventFilter(self)

    def sizeHint(self) -> QtCore.QSize:
        # The panel's wish, bounded as QScrollArea bounds it (36 x 24 lines): the docks
        # must not take the view's room.
        h = self.fontMetrics().height()
        return self.widget().sizeHint().boundedTo(QtCore.QSize(36 * h, 24 * h))

    def minimumSizeHint(self) -> QtCore.QSize:
        # As narrow as the panel may be, and short: the rest scrolls.
        return QtCore.QSize(self.widget().minimumSizeHint().width(), 60)

    def fit(self) -> None:
        """Size the panel to the viewport, or to its minimum when that is more."""
        w, room = self.widget(), self.maximumViewportSize()
        least = w.minimumSizeHint()
        width = max(room.width(), least.width())
        if width > room.width():  # a horizontal scroll bar takes some height
            room.setHeight(room.height() - self.horizontalScrollBar().sizeHint().height())
        lay = w.layout()
        if lay is not None and lay.hasHeightForWidth():
            least.setHeight(max(least.height(), lay.minimumHeightForWidth(width)))
        height = max(room.height(), least.height())
        if height > room.height() and width == room.width():  # a vertical bar takes some width
            width = max(least.width(), width - self.verticalScrollBar().sizeHint().width())
        w.resize(width, height)

    def resizeEvent(self, event: QtGui.QResizeEvent) -> None:
        super().resizeEvent(event)
        self.fit()

    def eventFilter(self, watched: QtCore.QObject, event: QtCore.QEvent) -> bool:
        if watched is self.widget() and event.type() == QtCore.QEvent.LayoutRequest:
            QtCore.QTimer.singleShot(0, self.fit)  # after the layout has its new minimum
        return super().eventFilter(watched, event)


def page(*panels: QtWidgets.QWidget) -> FitScrollArea:
    """``panels`` one above the other, scrolled only on a screen too small for them."""
    box = QtWidgets.QWidget()
    lay = QtWidgets.QVBoxLayout(box)
    for panel in panels:
        lay.addWidget(panel)
    lay.addStretch(1)
    return FitScrollArea(box)
