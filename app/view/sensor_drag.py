"""Dragging a control group's sensor region in the 3D view (Move mode). A press within
``PICK_PX`` pixels of a corner handle of a declared group's sensor outline
(``sensor_overlay``) resizes the region from that corner, the opposite corner staying; a
press within ``EDGE_PX`` of its outline moves the whole region. While the mouse moves the
new region is drawn as a black outline beside the old one (``sensor-drag``), so the
light is not recomputed on every move; at the release the region becomes the group's
sensor in one edit (``update_control_group``: Edit > Undo takes the whole drag back, and
the energy box, the Achieved tab and the outline follow it). The cursor's ray is cut
with the plane of the outline (the work plane's height), so the corner stays under it.

Observers come first (a press on an observer's ball is theirs: ``yields``); anywhere
else the viewport's own handling (the source's drag, orbiting) goes on as before. The
default group, when it is not declared, has no region to drag (it is outlined without
handles): Climate > Control groups declares it.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from PySide6 import QtCore

from app.view.picking import plan_point
from app.view.sensor_overlay import LIFT
from lightinv_core.errors import LightInvError

PICK_PX = 12
"""How near (pixels) to a corner handle a press resizes the region from it."""
EDGE_PX = 7
"""How near (pixels) to an outline's edge a press moves the region."""
MIN_SIDE = 0.1  # m: a region dragged narrower than this is a slip of the mouse
PREVIEW = "sensor-drag"


def _segment_px(p, a, b) -> float:
    """Distance (pixels) from display point p to the segment a-b."""
    ab, ap = b - a, p - a
    t = float(np.clip(ap @ ab / max(ab @ ab, 1e-12), 0.0, 1.0))
    return float(np.linalg.norm(ap - t * ab))


def dragged_rect(rect, corner: int | None, dx: float, dy: float) -> tuple[float, ...]:
    """``rect`` (x0, y0, x1, y1) m moved by (dx, dy) (``corner`` None), or with corner
    ``corner`` (0: x0 y0, 1: x1 y0, 2: x1 y1, 3: x0 y1, as ``sensor_outlines`` orders
    them) moved by it; ordered low to high, rounded to the centimetre."""
    x0, y0, x1, y1 = rect
    if corner is None:
        x0, y0, x1, y1 = x0 + dx, y0 + dy, x1 + dx, y1 + dy
    else:
        if corner in (0, 3):
            x0 += dx
        else:
            x1 += dx
        if corner in (0, 1):
            y0 += dy
        else:
            y1 += dy
    xs, ys = sorted((x0, x1)), sorted((y0, y1))
    return tuple(round(v, 2) for v in (xs[0], ys[0], xs[1], ys[1]))


class SensorDrag(QtCore.QObject):
    """Sensor-region drags in ``viewport`` of the document ``doc`` (see the module):
    ``outlines()`` gives the outlines drawn (``sensor_overlay.draw``'s), ``say(text,
    ms)`` tells the user (the status bar), ``yields(pos)`` whether a press at a widget
    point belongs to something else first (an observer's ball)."""

    dropped = QtCore.Signal(str, object)  # group, its new (x0, y0, x1, y1) m, edited

    def __init__(self, viewport, doc, outlines: Callable[[], tuple], say=None, yields=None):
        super().__init__(viewport)
        self.viewport, self.doc, self.outlines = viewport, doc, outlines
        self.say = say or (lambda _text, _ms=0: None)
        self.yields = yields or (lambda _pos: False)
        self.name: str | None = None  # the group whose region is being dragged
        self.corner: int | None = None  # the corner dragged (None: the whole region)
        self._rect: tuple[float, ...] = ()
        self._z = 0.0
        self._start: np.ndarray | None = None
        self._last: np.ndarray | None = None
        viewport.plotter.interactor.installEventFilter(self)

    def _declared(self) -> set[str]:
        d = self.doc
        return set() if d.project is None else {c.name for c in d.design.control_groups}

    def handle_at(self, pos: QtCore.QPoint) -> tuple[str, int | None, np.ndarray] | None:
        """(group, corner or None for an edge, its outline's corners) of the declared
        group's sensor drawn nearest the widget point ``pos``; None if none is near."""
        vp = self.viewport
        p = np.array(vp.display(pos), float)
        ratio = vp.plotter.interactor.devicePixelRatioF()
        ren = vp.plotter.renderer
        declared = self._declared()
        best: tuple[float, int, str, int | None, np.ndarray] | None = None
        for o in self.outlines():
            if o.name not in declared:
                continue
            px = []
            for c in o.corners:
                ren.SetWorldPoint(c[0], c[1], c[2] + LIFT, 1.0)
                ren.WorldToDisplay()
                px.append(np.array(ren.GetDisplayPoint()[:2]))
            for k in range(4):  # a corner wins over an edge at the same distance
                d = float(np.linalg.norm(px[k] - p))
                if d <= PICK_PX * ratio and (best is None or (0, d) < best[:2]):
                    best = (0, d, o.name, k, o.corners)
            for k in range(4):
                d = _segment_px(p, px[k], px[(k + 1) % 4])
                if d <= EDGE_PX * ratio and (best is None or (1, d) < best[:2]):
                    best = (1, d, o.name, None, o.corners)
        return None if best is None else best[2:]

    def _plan_point(self, pos: QtCore.QPoint) -> np.ndarray | None:
        """(x, y) m where the cursor's ray meets the outline's plane."""
        return plan_point(self.viewport, pos, self._z)

    def current(self) -> tuple[float, ...] | None:
        """The region as dragged so far (None: no drag)."""
        if self.name is None or self._start is None or self._last is None:
            return None
        dx, dy = self._last - self._start
        return dragged_rect(self._rect, self.corner, float(dx), float(dy))

    def _preview(self, rect) -> None:
        plotter = self.viewport.plotter
        plotter.remove_actor(PREVIEW, render=False)
        if rect is not None:
            x0, y0, x1, y1 = rect
            z = self._z + 2 * LIFT
            loop = np.array([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]])
            self.viewport.outlines(PREVIEW, [loop], "#000000", 3)
        self.viewport.request_render()

    def eventFilter(self, obj, event) -> bool:
        vp = self.viewport
        if vp.mode != "move" or obj is not vp.plotter.interactor:
            return False
        et, types = event.type(), QtCore.QEvent.Type
        left = getattr(event, "button", lambda: None)() == QtCore.Qt.LeftButton
        if et == types.MouseButtonPress and left:
            pos = event.position().toPoint()
            hit = None if self.yields(pos) else self.handle_at(pos)
            if hit is None:
                return False
            self.name, self.corner, corners = hit
            self._rect = (*corners[0, :2], *corners[2, :2])
            self._z = float(corners[0, 2]) + LIFT
            self._start = self._last = self._plan_point(pos)
            how = "a corner: resize" if self.corner is not None else "its edge: move"
            self.say(f"Sensor of {self.name}: {how} it; release to set it (Edit > Undo)", 6000)
            return True
        if et == types.MouseMove and self.name is not None:
            p = self._plan_point(event.position().toPoint())
            if p is not None and self._start is not None:
                self._last = p
                self._preview(self.current())
            return True
        if et == types.MouseButtonRelease and self.name is not None:
            name, rect = self.name, self.current()
            self.name, self._start, self._last = None, None, None
            self._preview(None)
            self._drop(name, rect)
            return True
        return False

    def _drop(self, name: str, rect) -> None:
        """The drag's end: the group's sensor set to ``rect`` in one edit, or why not."""
        if rect is None or rect == tuple(round(v, 2) for v in self._rect):
            return
        x0, y0, x1, y1 = rect
        if min(x1 - x0, y1 - y0) < MIN_SIDE:
            self.say(f"Sensor of {name} not changed: drag a region at least {MIN_SIDE} m wide")
            return
        try:
            self.doc.update_control_group(name, sensor=rect)
        except LightInvError as exc:
            self.say(f"Sensor of {name} not changed: {exc}", 8000)
            return
        where = f"x {x0:g}-{x1:g}, y {y0:g}-{y1:g} m"
        self.say(f"Sensor of {name}: {where} (Edit > Undo to restore)", 6000)
        self.dropped.emit(name, rect)
