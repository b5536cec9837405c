"""Picking and dragging observers in the 3D view. In Move mode a press on an observer's
ball (within ``PICK_PX`` pixels of where its eye is drawn) picks that observer instead
of moving the current source, and the drag moves it in plan: the cursor's ray is cut
with the horizontal plane at the eye's height, so the ball stays under the cursor. A
double-click on the ball asks to edit it. Anywhere else the viewport's own handling
(the source's drag, zone drawing, orbiting) goes on as before.

``ObserverDrag`` filters the interactor's mouse events ahead of the viewport (an event
filter installed later runs first) and emits ``picked(name)``, ``dragged(name, dx, dy)``
(m, per mouse move) and ``activated(name)``; it holds no design state: ``eyes()`` gives
the eyes drawn, {name: (x, y, z) m}.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from PySide6 import QtCore

from app.view.picking import plan_point

PICK_PX = 14
"""How near (pixels) to an eye drawn a press picks its observer."""


class ObserverDrag(QtCore.QObject):
    """Observer picks and drags in ``viewport`` (see the module)."""

    picked = QtCore.Signal(str)
    dragged = QtCore.Signal(str, float, float)  # name, dx, dy in metres
    activated = QtCore.Signal(str)  # double-click: edit it

    def __init__(self, viewport, eyes: Callable[[], dict[str, np.ndarray]]):
        super().__init__(viewport)
        self.viewport, self.eyes = viewport, eyes
        self.name: str | None = None  # the observer being dragged
        self._z = 0.0
        self._last: np.ndarray | None = None
        viewport.plotter.interactor.installEventFilter(self)

    def observer_at(self, pos: QtCore.QPoint) -> str | None:
        """The observer whose eye is drawn nearest the widget point ``pos``, within
        ``PICK_PX``; None if none is."""
        vp = self.viewport
        x, y = vp.display(pos)
        ratio = vp.plotter.interactor.devicePixelRatioF()
        ren = vp.plotter.renderer
        best: tuple[float, str] | None = None
        for name, eye in self.eyes().items():
            ren.SetWorldPoint(*(float(c) for c in eye), 1.0)
            ren.WorldToDisplay()
            ex, ey, _ = ren.GetDisplayPoint()
            d = math.hypot(ex - x, ey - y)
            if d <= PICK_PX * ratio and (best is None or d < best[0]):
                best = (d, name)
        return None if best is None else best[1]

    def _plan_point(self, pos: QtCore.QPoint) -> np.ndarray | None:
        """(x, y) m where the cursor's ray meets the plane z = the dragged eye's."""
        return plan_point(self.viewport, pos, self._z)

    def eventFilter(self, obj, event) -> bool:
        vp = self.viewport
        if vp.mode != "move" or obj is not vp.plotter.interactor:
            return False
        et, types = event.type(), QtCore.QEvent.Type
        left = getattr(event, "button", lambda: None)() == QtCore.Qt.LeftButton
        if et in (types.MouseButtonPress, types.MouseButtonDblClick) and left:
            pos = event.position().toPoint()
            name = self.observer_at(pos)
            if name is None:
                return False
            if et == types.MouseButtonDblClick:
                self.name = None
                self.activated.emit(name)
                return True
            self.name, self._z = name, float(self.eyes()[name][2])
            self._last = self._plan_point(pos)
            self.picked.emit(name)
            return True
        if et == types.MouseMove and self.name is not None:
            p = self._plan_point(event.position().toPoint())
            if p is not None and self._last is not None:
                dx, dy = p - self._last
                if dx or dy:
                    self.dragged.emit(self.name, float(dx), float(dy))
            self._last = p if p is not None else self._last
            return True
        if et == types.MouseButtonRelease and self.name is not None:
            self.name, self._last = None, None
            return True
        return False
