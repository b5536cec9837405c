"""Drawing a zone in the viewport: a rectangle dragged on a surface, or a polygon clicked
corner by corner, each corner snapped (within a few pixels) to the surface's corners and
edges, the corners of zones already on it, and a 0.1 m grid (``snap_uv``).

``ZoneDrawing`` holds what is being drawn (the rectangle's first corner, the polygon's
corners so far) and draws it as a red outline; the viewport hands it the mouse and key
events of its zone and polygon modes and emits the finished zone (``zoneDrawn``,
``polygonDrawn``). The surface a zone goes on is the window's choice
(``Viewport.surface_frame``), by the kind of zone being drawn.
"""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore

CLOSE_SNAP = 0.02  # of the surface's size: a click this near the first corner closes
SNAP_PIXELS = 8  # a corner this near (on screen) a vertex, an edge or a grid line snaps to it
GRID_STEP = 0.1  # m: the grid corners snap to, along the surface's u and v axes
COPLANAR = 0.02  # m: another zone's corners this near the surface's plane snap too


def snap_uv(
    uv: tuple[float, float],
    size: tuple[float, float],
    tol: float,
    vertices=(),
    grid: float = GRID_STEP,
) -> tuple[float, float]:
    """``uv`` (m on a surface of ``size`` (w, h) m) snapped within ``tol`` m: to a vertex
    (the surface's corners and ``vertices``, e.g. other zones' corners) first; else each
    coordinate to an edge (the surface's, or a vertex's line), else to the ``grid``."""
    w, h = size
    points = np.array([(0.0, 0.0), (w, 0.0), (w, h), (0.0, h), *vertices], float)
    dist = np.hypot(*(points - uv).T)
    if dist.min() <= tol:
        u, v = points[int(np.argmin(dist))]
        return float(u), float(v)

    def along(x: float, lines) -> float:
        lines = np.asarray(lines, float)
        near = np.abs(lines - x)
        if near.min() <= tol:
            return float(lines[int(np.argmin(near))])
        g = grid * round(x / grid)
        return float(g) if abs(g - x) <= tol else float(x)

    return along(uv[0], points[:, 0]), along(uv[1], points[:, 1])


class ZoneDrawing:
    """The zone being drawn in a viewport (``view``), rectangle or polygon."""

    def __init__(self, view):
        self.view = view
        self.draft = None  # a rectangle: (ZoneFrame of its surface, its first corner (u, v))
        self.poly = None  # a polygon: (ZoneFrame of its surface, its corners [(u, v), ...])
        self.skip_release = False  # the release that follows a closing double-click

    def snapped(self, frame, x: int, y: int) -> tuple[float, float] | None:
        """The point of ``frame``'s surface under display point (x, y), snapped
        (``snap_uv``) within ``SNAP_PIXELS`` on screen: to its corners and edges, the
        corners of zones drawn on it, and a 0.1 m grid. None if the ray misses."""
        ray = self.view.ray(x, y)
        uv = frame.from_ray(*ray)
        if uv is None:
            return None
        tol = 0.0
        for dx, dy in ((SNAP_PIXELS, 0), (0, SNAP_PIXELS)):
            other = frame.from_ray(*self.view.ray(x + dx, y + dy))
            if other is not None:
                tol = max(tol, float(np.hypot(*np.subtract(other, uv))))
        return snap_uv(uv, frame.size, tol, self._zone_corners(frame))

    def _zone_corners(self, frame) -> list[tuple[float, float]]:
        """The corners of the zones in the view that lie on ``frame``'s plane, in its
        metres."""
        out = []
        for zone in self.view.frames.values():
            for p in zone.outline_loop()[:-1]:
                q = p - frame.origin
                if abs(float(np.dot(q, frame.normal))) < COPLANAR:
                    out.append((float(np.dot(q, frame.u)), float(np.dot(q, frame.v))))
        return out

    def polygon_event(self, et, event) -> bool:
        """Polygon mode: each click adds a corner on the surface; a double-click, Enter or
        a click on the first corner closes the polygon; Backspace takes back the last
        corner, Escape drops the polygon. Right-drag and the wheel still move the camera."""
        left = getattr(event, "button", lambda: None)() == QtCore.Qt.LeftButton
        if et == QtCore.QEvent.Type.MouseButtonPress and left:
            self.view.press = event.position().toPoint()
            return True
        if et == QtCore.QEvent.Type.MouseButtonRelease and left:
            self.view.press = None
            if self.skip_release:
                self.skip_release = False
                return True
            self.polygon_click(*self.view.display(event.position().toPoint()))
            return True
        if et == QtCore.QEvent.Type.MouseButtonDblClick and left:
            self.skip_release = True
            self.finish_polygon()
            return True
        if et == QtCore.QEvent.Type.MouseMove and self.poly is not None:
            self.show_polygon(*self.view.display(event.position().toPoint()))
            return False  # VTK keeps its own bookkeeping of the cursor
        if et == QtCore.QEvent.Type.KeyPress and self.poly is not None:
            key = event.key()
            if key in (QtCore.Qt.Key_Return, QtCore.Qt.Key_Enter):
                self.finish_polygon()
            elif key == QtCore.Qt.Key_Escape:
                self.cancel_polygon()
            elif key == QtCore.Qt.Key_Backspace:
                self.poly[1].pop()
                if not self.poly[1]:
                    self.cancel_polygon()
                else:
                    self.show_polygon()
            else:
                return False
            return True
        return False

    def polygon_click(self, x: int, y: int) -> None:
        """A corner at a display point (the first one picks the surface; the polygon may
        run on over the coplanar cells of the same material that continue it, so corners
        are not clipped to that surface: ``apply_zone_edits`` checks what it covers)."""
        if self.poly is None:
            self.start_draft(x, y)
            if self.draft is not None:
                frame, uv = self.draft
                self.draft = None
                self.poly = (frame, [uv])
                self.show_polygon()
            return
        frame, corners = self.poly
        uv = self.snapped(frame, x, y)
        if uv is None:
            return
        if len(corners) >= 3 and np.hypot(*np.subtract(uv, corners[0])) < CLOSE_SNAP * max(
            frame.size
        ):
            self.finish_polygon()
            return
        corners.append(uv)
        self.show_polygon()

    def show_polygon(self, x: int | None = None, y: int | None = None) -> None:
        """Draw the corners so far, and the edge to the cursor at display point (x, y)."""
        frame, corners = self.poly
        pts = list(corners)
        if x is not None:
            uv = self.snapped(frame, x, y)
            if uv is not None:
                pts.append(uv)
        loop = np.array([frame.to_world(u, v) for u, v in [*pts, pts[0]]])
        self.view.outlines("draft", [loop], "#ff2020", 4)
        self.view.request_render()

    def corners(self) -> list[tuple[float, float]]:
        """The corners of the polygon being drawn (m on its surface), empty if none."""
        return [] if self.poly is None else list(self.poly[1])

    def finish_polygon(self) -> None:
        """Close the polygon being drawn and emit it (three corners or more)."""
        if self.poly is None:
            return
        frame, corners = self.poly
        self.cancel_polygon()
        if len(corners) >= 3:
            self.view.polygonDrawn.emit(frame.name, corners)

    def cancel_polygon(self) -> None:
        """Drop the polygon being drawn."""
        self.poly = None
        self.view.plotter.remove_actor("draft", render=False)
        self.view.show_axes(*self.view.axes_focus)
        self.view.request_render()

    def start_draft(self, x: int, y: int) -> None:
        """Begin a zone rectangle on the surface the window picks for the cursor: the one
        seen if it suits, else one the view ray crosses (the culled ceiling, from above)."""
        self.draft = None
        if self.view.surface_frame is None:
            return
        hit = self.view.pick_at(x, y)
        near, far = self.view.ray(x, y)
        frame = self.view.surface_frame(int(hit[0]) if len(hit) else None, near, far)
        if frame is None:
            return
        uv = self.snapped(frame, x, y)
        if uv is not None:
            self.draft = (frame, uv)
            self.view.show_axes(frame, f"{frame.name} (0, 0)")

    def show_draft(self, x: int, y: int) -> tuple[float, float, float, float] | None:
        """Draw the rectangle being dragged; returns it (m, clipped to the surface)."""
        frame, (u0, v0) = self.draft
        uv = self.snapped(frame, x, y)
        if uv is None:
            return None
        w, h = frame.size
        u1, v1 = float(np.clip(uv[0], 0, w)), float(np.clip(uv[1], 0, h))
        u0, v0 = float(np.clip(u0, 0, w)), float(np.clip(v0, 0, h))
        self.view.outlines("draft", [frame.rectangle(u0, v0, u1, v1)], "#ff2020", 4)
        self.view.request_render()
        return u0, v0, u1, v1

    def finish_draft(self, x: int, y: int) -> None:
        """The rectangle's last corner at display point (x, y): emit it (clipped to its
        surface) and go back to the axes shown before."""
        rect = self.show_draft(x, y)
        frame = self.draft[0]
        self.draft = None
        self.view.plotter.remove_actor("draft", render=False)
        self.view.show_axes(*self.view.axes_focus)  # back from the surface's axes
        if rect is not None:
            self.view.zoneDrawn.emit(frame.name, *rect)
