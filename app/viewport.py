"""The 3D viewport: patches coloured by lighting, zone and source outlines, picking, dragging.

One pyvista ``QtInteractor``. The scene mesh is built once per scene; a lighting
change only rewrites ``mesh.cell_data`` in place and re-renders (no new actors).
VTK cells are triangles; ``tri_patch`` maps them to patch ids, in this one place.
Rooms face inwards, so back-face culling lets the camera look in from outside
(the ceiling seen from above is its back and disappears).

Around the picture: an orientation axes widget (x, y, z) in a corner; the origin and u, v
axes of the zone in focus (``show_axes``: the current source's zone, or the surface a
zone is being drawn on), which the corners in Properties are measured along; and, while
the light model is being built, a veil and a line of text (``set_busy``) over the picture,
which a rebuild of the same scene keeps (the previous light carried onto the new patches)
rather than blanking.
"""

from __future__ import annotations

import textwrap

import numpy as np
import pyvista as pv
import vtk
from PySide6 import QtCore, QtWidgets
from pyvistaqt import QtInteractor
from scipy.spatial import cKDTree

from lightinv_core.scene.patches import Patches
from lightinv_core.scene.zone_grid import zone_grid

CAMERAS = {
    "iso": ((1.0, -1.3, 1.2), (0, 0, 1)),
    "top": ((0.0, 0.0, 1.0), (0, 1, 0)),
    "front": ((0.0, -1.0, 0.25), (0, 0, 1)),
}
OUTLINE_LIFT = 0.01  # m: outlines float 1 cm off their surface (no z-fighting)
AXIS_COLOURS = {"u": "#d62020", "v": "#1a9a1a"}  # as the x (red) and y (green) of the widget
VEIL_OPACITY = 0.55  # the white veil over a picture whose light is out of date
CLOSE_SNAP = 0.02  # of the surface's size: a click this near the first corner closes
AXIS_ACTORS = ("axis-u", "axis-v", "axis-u-label", "axis-v-label", "axis-origin-label")


class ZoneFrame:
    """A rectangle's origin, unit u/v axes and size (an emitter zone, or a surface a zone
    may be drawn on), for 2D <-> 3D conversions."""

    def __init__(self, patches: Patches | None, name: str, rect=None):
        self.name = name
        if rect is not None:  # a scene Rect
            self.origin = np.asarray(rect.origin, float)
            self.u = rect.u / np.linalg.norm(rect.u)
            self.v = rect.v / np.linalg.norm(rect.v)
            self.normal = rect.normal
            self.size = rect.size
            self.outline = None
            return
        g = zone_grid(patches, name)
        first = g.patch[0, 0]
        self.origin = patches.origin[first]
        self.u = patches.edge1[first] / np.linalg.norm(patches.edge1[first])
        self.v = patches.edge2[first] / np.linalg.norm(patches.edge2[first])
        self.normal = patches.normal[first]
        self.size = g.size
        self.outline = patches.zone_outline(name)

    def to_world(self, u: float, v: float) -> np.ndarray:
        """3D point of zone coordinates (m), lifted off the surface."""
        return self.origin + u * self.u + v * self.v + OUTLINE_LIFT * self.normal

    def from_ray(self, p0: np.ndarray, p1: np.ndarray) -> tuple[float, float] | None:
        """Zone coordinates where the ray p0 -> p1 meets the zone's plane (None if parallel)."""
        d = p1 - p0
        den = float(np.dot(d, self.normal))
        if abs(den) < 1e-12:
            return None
        t = float(np.dot(self.origin - p0, self.normal)) / den
        q = p0 + t * d - self.origin
        return float(np.dot(q, self.u)), float(np.dot(q, self.v))

    def outline_loop(self) -> np.ndarray:
        """Closed polyline (k + 1, 3) of the zone's outline: its polygon, or its rectangle."""
        if self.outline is None:
            return self.rectangle(0, 0, *self.size)
        return np.array([self.to_world(u, v) for u, v in [*self.outline, self.outline[0]]])

    def rectangle(self, u0: float, v0: float, u1: float, v1: float) -> np.ndarray:
        """Closed polyline (5, 3) of a rectangle in zone coordinates."""
        return np.array(
            [self.to_world(a, b) for a, b in ((u0, v0), (u1, v0), (u1, v1), (u0, v1), (u0, v0))]
        )


def _carried(old: pv.PolyData, new: pv.PolyData) -> np.ndarray:
    """The values of ``old``'s cells carried to ``new``'s: each new triangle takes the
    value of the old triangle whose centre is nearest its own (the same room re-meshed)."""
    tree = cKDTree(old.cell_centers().points)
    _, nearest = tree.query(new.cell_centers().points)
    return np.asarray(old.cell_data["value"], np.float32)[nearest]


def _label(text: str, point, side: str) -> vtk.vtkTextActor:
    """Text at a 3D point, drawn over the picture on a pale box (``side``: where the text
    lies from the point, "left" or "right"). A 2D text actor anchored at a world point
    costs a fraction of a millisecond a render; pyvista's point labels (placed anew each
    render) cost about 2 ms, which every drag would pay."""
    actor = vtk.vtkTextActor()
    actor.SetInput(text)
    actor.GetPositionCoordinate().SetCoordinateSystemToWorld()
    actor.GetPositionCoordinate().SetValue(*map(float, point))
    prop = actor.GetTextProperty()
    prop.SetFontSize(14)
    prop.SetBold(True)
    prop.SetColor(0.0, 0.0, 0.0)
    prop.SetBackgroundColor(1.0, 1.0, 1.0)
    prop.SetBackgroundOpacity(0.75)
    if side == "right":  # the text ends at the point
        prop.SetJustificationToRight()
    prop.SetVerticalJustificationToCentered()
    actor.SetPickable(False)
    return actor


def _veil() -> vtk.vtkActor2D:
    """A white, half-transparent rectangle over the whole view (a picture out of date)."""
    points = vtk.vtkPoints()
    for x, y in ((0, 0), (1, 0), (1, 1), (0, 1)):
        points.InsertNextPoint(x, y, 0)
    quad = vtk.vtkCellArray()
    quad.InsertNextCell(4, (0, 1, 2, 3))
    poly = vtk.vtkPolyData()
    poly.SetPoints(points)
    poly.SetPolys(quad)
    coordinate = vtk.vtkCoordinate()
    coordinate.SetCoordinateSystemToNormalizedViewport()
    mapper = vtk.vtkPolyDataMapper2D()
    mapper.SetInputData(poly)
    mapper.SetTransformCoordinate(coordinate)
    actor = vtk.vtkActor2D()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(1.0, 1.0, 1.0)
    actor.GetProperty().SetOpacity(VEIL_OPACITY)
    return actor


def _polylines(loops: list[np.ndarray]) -> pv.PolyData:
    pts = np.concatenate(loops)
    lines, start = [], 0
    for loop in loops:
        lines += [len(loop), *range(start, start + len(loop))]
        start += len(loop)
    return pv.PolyData(pts, lines=np.array(lines))


class Viewport(QtWidgets.QWidget):
    """The lighting view of one scene; emits picks and drags, holds no design state."""

    picked = QtCore.Signal(object, bool)  # patch ids (np.ndarray), add to selection
    sourceDragged = QtCore.Signal(float, float)  # du, dv in metres
    zoneDrawn = QtCore.Signal(str, float, float, float, float)  # surface, u0, v0, u1, v1
    polygonDrawn = QtCore.Signal(str, object)  # surface, corners [(u, v), ...] m

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        layout = QtWidgets.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        # No multisampling: under software GL (Xvfb, VMs) 4x MSAA doubles the frame time and
        # flat patches need no anti-aliasing.
        self.plotter = QtInteractor(self, multi_samples=0)
        layout.addWidget(self.plotter.interactor)
        self.plotter.set_background("white")
        self.plotter.add_axes(interactive=False, color="black")  # which way x, y, z point
        self.mesh: pv.PolyData | None = None
        self.has_values = False  # the patches show light (not the grey of no light model)
        self.busy_text: str | None = None
        self.axes_frame: ZoneFrame | None = None  # the frame whose axes are drawn
        self.axes_title = ""
        self.axes_focus: tuple[ZoneFrame | None, str] = (None, "")  # shown when not drawing
        self.show_zone_axes = True
        self._veil = _veil()
        self.tri_patch: np.ndarray | None = None
        self.frames: dict[str, ZoneFrame] = {}
        self.cmap = "inferno"
        self.clim: tuple[float, float] | None = None  # None: automatic
        self.units = "lux"
        self.label_format = "%.0f"  # the colour bar's labels
        self.caption: str | None = None  # the line along the top (set_caption)
        self.mode = "navigate"  # navigate | select | move | zone | polygon
        # A polygon zone being drawn: its surface and the corners clicked so far.
        self._poly: tuple[ZoneFrame, list[tuple[float, float]]] | None = None
        self._skip_release = False  # the release that follows a closing double-click
        # callable(patch id seen or None, ray near point, ray far point) -> ZoneFrame of the
        # surface a zone drawn there goes on, or None
        self.surface_frame = None
        self._draft: tuple[ZoneFrame, tuple[float, float]] | None = None
        self.drag_zone: str | None = None
        self._press: QtCore.QPoint | None = None
        self._last_uv: tuple[float, float] | None = None
        self._render_pending = False
        self.render_count = 0
        self.plotter.interactor.installEventFilter(self)

    # -- rendering ------------------------------------------------------------------------
    def request_render(self) -> None:
        """Render once when control returns to the event loop (edits coalesce)."""
        if not self._render_pending:
            self._render_pending = True
            QtCore.QTimer.singleShot(0, self._flush_render)

    def _flush_render(self) -> None:
        if self._render_pending:
            self.render_now()

    def render_now(self) -> None:
        """Render immediately (and drop a pending request)."""
        self._render_pending = False
        self.plotter.render()
        self.render_count += 1

    # -- scene ----------------------------------------------------------------------------
    def set_scene(self, patches: Patches, zones: list[str], keep_picture: bool = False) -> None:
        """Build the mesh of ``patches`` (replacing any previous scene). ``keep_picture``:
        the same scene re-meshed (a zone drawn, a reflectance): each new triangle keeps
        the light of the nearest old one and the camera stays, instead of a blank view
        until the new light model is ready."""
        vertices, faces, tri_patch = patches.triangle_mesh()
        cells = np.hstack([np.full((len(faces), 1), 3), faces]).ravel()
        old = self.mesh if keep_picture and self.has_values else None
        camera = self.plotter.camera_position if keep_picture else None
        self.mesh = pv.PolyData(vertices.astype(float), cells)
        self.mesh.cell_data["value"] = np.zeros(len(faces), np.float32)
        if old is not None:
            self.mesh.cell_data["value"] = _carried(old, self.mesh)
        self.tri_patch = tri_patch
        self.frames = {z: ZoneFrame(patches, z) for z in zones}
        self.plotter.clear()  # every actor goes, the veil and the axes too
        self.busy_text = None
        caption, self.caption = self.caption, None
        self.plotter.add_mesh(
            self.mesh,
            name="scene",
            scalars="value",
            cmap=self.cmap,
            show_scalar_bar=True,
            lighting=False,
            culling="back",
            scalar_bar_args={
                "title": self.units,
                "vertical": True,
                "position_x": 0.9,
                "position_y": 0.15,
                "width": 0.06,
                "height": 0.7,
                "color": "black",
                "fmt": self.label_format,
            },
        )
        self.set_caption(caption)
        self.set_zone_outlines()
        self.axes_frame = None
        if old is not None:
            lo, hi = self.clim or (0.0, float(max(self.mesh.cell_data["value"].max(), 1e-6)))
            self.plotter.actors["scene"].mapper.scalar_range = (lo, hi)
        else:
            self._paint_grey(True)
        if camera is not None:
            self.plotter.camera_position = camera
            self.render_now()
        else:
            self.camera("iso")

    def set_values(
        self, per_patch: np.ndarray | None, units: str = "lux", fmt: str = "%.0f"
    ) -> None:
        """Colour the patches (in place, no new actor); None paints them grey (no
        lighting). ``units`` titles the colour bar, ``fmt`` its labels (printf style)."""
        if self.mesh is None:
            return
        values = (
            np.zeros(len(self.tri_patch), np.float32)
            if per_patch is None
            else np.asarray(per_patch, dtype=np.float32)[self.tri_patch]
        )
        if (per_patch is None) == self.has_values:
            self._paint_grey(per_patch is None)
        self.mesh.cell_data["value"][:] = values
        lo, hi = self.clim if self.clim is not None else (0.0, float(max(values.max(), 1e-6)))
        self.plotter.actors["scene"].mapper.scalar_range = (lo, hi)
        if units != self.units or fmt != self.label_format:
            self.units, self.label_format = units, fmt
            for bar in self.plotter.scalar_bars.values():
                bar.SetTitle(units)
                bar.SetLabelFormat(fmt)
        self.render_now()

    def set_caption(self, text: str | None) -> None:
        """A line or two of text in the top corner of the view (what the colours show:
        the hour of the year, a daylight map, or why it cannot be shown); None removes
        it. Hidden while the view is veiled (its own text is there)."""
        if text == self.caption:
            return
        self.caption = text
        self._draw_caption()

    def _draw_caption(self) -> None:
        self.plotter.remove_actor("caption", render=False)
        if self.caption and self.busy_text is None:
            lines = [w for line in self.caption.split("\n") for w in textwrap.wrap(line, 64)]
            self.plotter.add_text(
                "\n".join(lines),
                position="upper_left",
                font_size=11,
                color="#202020",
                name="caption",
                render=False,
            )
        self.request_render()

    def _paint_grey(self, grey: bool) -> None:
        """No light model: the patches plain light grey (a colour map at zero is black)."""
        actor = self.plotter.actors.get("scene")
        self.has_values = not grey
        if actor is not None:
            actor.mapper.scalar_visibility = not grey
            actor.prop.color = "#d8d8d8"
        for bar in self.plotter.scalar_bars.values():
            bar.SetVisibility(not grey)  # no colours: no scale of zeros either

    def set_busy(self, text: str | None) -> None:
        """Veil the picture and say why (the light model being built: ``text``); None
        lifts the veil. The patches and outlines stay, so the view is never blank."""
        if text == self.busy_text:
            return
        self.busy_text = text
        self.plotter.remove_actor("busy", render=False)
        self.plotter.remove_actor("veil", render=False)
        if text is not None:
            self.plotter.add_actor(self._veil, name="veil", reset_camera=False, render=False)
            self.plotter.add_text(
                text, position="upper_left", font_size=11, color="#202020", name="busy"
            )
        self._draw_caption()

    def show_axes(self, frame: ZoneFrame | None, title: str = "") -> None:
        """The origin and u, v axes of ``frame`` (a zone, or the surface a zone is being
        drawn on) as two arrows labelled u and v from the origin, labelled ``title`` ("Z1
        (0, 0)") just outside the corner: the corners in Properties are metres along them.
        None hides them."""
        for name in AXIS_ACTORS:
            self.plotter.remove_actor(name, render=False)
        self.axes_frame, self.axes_title = frame, title
        if frame is None or not self.show_zone_axes or self.mesh is None:
            self.request_render()
            return
        w, h = frame.size
        length = float(np.clip(0.3 * max(w, h), 0.3, 1.5))
        origin = frame.to_world(0.0, 0.0) + OUTLINE_LIFT * frame.normal
        for axis, direction in (("u", frame.u), ("v", frame.v)):
            arrow = pv.Arrow(
                start=origin,
                direction=direction,
                scale=length,
                tip_length=0.25,
                tip_radius=0.07,
                shaft_radius=0.025,
            )
            self.plotter.add_mesh(
                arrow,
                name=f"axis-{axis}",
                color=AXIS_COLOURS[axis],
                lighting=False,
                pickable=False,
                reset_camera=False,
                render=False,
            )
        tips = [origin + 1.12 * length * frame.u, origin + 1.12 * length * frame.v]
        # The origin's label sits just outside the corner, so that it hides neither arrow.
        outside = origin - 0.12 * length * (frame.u + frame.v)
        labels = (("u", tips[0], "left"), ("v", tips[1], "left"), ("origin", outside, "right"))
        for name, point, side in labels:
            self.plotter.add_actor(
                _label(title or "(0, 0)" if name == "origin" else name, point, side),
                name=f"axis-{name}-label",
                reset_camera=False,
                render=False,
            )
        self.request_render()

    def set_axes_focus(self, frame: ZoneFrame | None, title: str = "") -> None:
        """The zone whose axes are shown while no zone is being drawn (the window's
        current source's zone, or a drawn zone's surface); redrawn only when it changes."""
        same = self.axes_focus[0] is frame and self.axes_focus[1] == title
        self.axes_focus = (frame, title)
        if self._draft is None and not (same and self.axes_frame is frame):
            self.show_axes(frame, title)

    def axes_shown(self) -> bool:
        """Whether the zone axes are drawn."""
        return "axis-u" in self.plotter.actors

    def set_colormap(self, cmap: str) -> None:
        """Change the colour map (rebuilds the scene actor's lookup table)."""
        self.cmap = cmap
        actor = self.plotter.actors.get("scene")
        if actor is not None:
            lut = pv.LookupTable(cmap)
            lut.scalar_range = actor.mapper.scalar_range
            actor.mapper.lookup_table = lut
            for bar in self.plotter.scalar_bars.values():
                bar.SetLookupTable(lut)
            self.plotter.render()

    def set_zone_outlines(self) -> None:
        """Dashed-looking thin outlines of every emitter zone."""
        if not self.frames:
            return
        loops = [f.outline_loop() for f in self.frames.values()]
        self._outlines("zones", loops, "#3070ff", 2)

    def _outlines(self, name: str, loops: list[np.ndarray], color: str, width: int) -> None:
        """Polylines as one named actor (replacing the previous one), no render."""
        if loops:
            self.plotter.add_mesh(
                _polylines(loops),
                name=name,
                color=color,
                line_width=width,
                lighting=False,
                reset_camera=False,
                render=False,
            )

    def set_sources(self, sources, current: str | None) -> None:
        """Outlines of the design's sources; the current one thicker and green."""
        for name in ("sources", "current"):
            self.plotter.remove_actor(name, render=False)
        loops, cur = [], []
        for s in sources:
            f = self.frames.get(s.zone)
            if f is None:
                continue
            (a, b), (c, d) = s.u_range, s.v_range
            (cur if s.name == current else loops).append(f.rectangle(a, c, b, d))
        self._outlines("sources", loops, "#00a0a0", 3)
        self._outlines("current", cur, "#00d000", 5)
        self.request_render()

    def set_selection(self, patch_ids: np.ndarray) -> None:
        """Highlight the picked patches."""
        self._overlay("selection", patch_ids, "#00ff66", 0.55)

    def set_highlight(self, patch_ids: np.ndarray) -> None:
        """Paint ``patch_ids`` red over the lighting (patches breaking an intention)."""
        self._overlay("offending", patch_ids, "#ff1010", 0.6)

    def _overlay(self, name: str, patch_ids: np.ndarray, color: str, opacity: float) -> None:
        """A translucent, named layer over some patches (replacing the previous one)."""
        self.plotter.remove_actor(name, render=False)
        if self.mesh is not None and len(patch_ids):
            cells = np.flatnonzero(np.isin(self.tri_patch, patch_ids))
            self.plotter.add_mesh(
                self.mesh.extract_cells(cells),
                name=name,
                color=color,
                opacity=opacity,
                lighting=False,
                reset_camera=False,
                show_scalar_bar=False,
                culling="back",
                render=False,
            )
        self.request_render()

    def camera(self, preset: str) -> None:
        """Camera presets: iso, top (roof culled), front."""
        direction, up = CAMERAS[preset]
        if self.mesh is None:
            return
        c = np.array(self.mesh.center)
        r = float(np.linalg.norm(np.array(self.mesh.bounds[1::2]) - self.mesh.bounds[::2]))
        d = np.asarray(direction, float)
        self.plotter.camera_position = [tuple(c + 1.6 * r * d / np.linalg.norm(d)), tuple(c), up]
        self.plotter.reset_camera(render=False)  # keeps the direction, fits the whole scene
        self.render_now()

    # -- picking ------------------------------------------------------------------------------
    def _display(self, pos: QtCore.QPoint) -> tuple[int, int]:
        """Qt widget coordinates -> VTK display coordinates (origin bottom-left)."""
        ratio = self.plotter.interactor.devicePixelRatioF()
        h = self.plotter.interactor.height() * ratio
        return int(pos.x() * ratio), int(h - 1 - pos.y() * ratio)

    def pick_area(self, x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
        """Patch ids visible in a display rectangle (hardware selection: hidden ones excluded)."""
        if self.mesh is None:
            return np.zeros(0, np.int64)
        # A drag may end outside the view (negative or beyond its size): the selector
        # takes unsigned pixel coordinates inside the window, so clip to it.
        w, h = self.plotter.render_window.GetSize()
        xs = sorted(min(max(int(x), 0), max(w - 1, 0)) for x in (x0, x1))
        ys = sorted(min(max(int(y), 0), max(h - 1, 0)) for y in (y0, y1))
        sel = vtk.vtkHardwareSelector()
        sel.SetRenderer(self.plotter.renderer)
        sel.SetFieldAssociation(vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS)
        sel.SetArea(xs[0], ys[0], xs[1], ys[1])
        result = sel.Select()
        scene_actor = self.plotter.actors.get("scene")
        ids = []
        for i in range(result.GetNumberOfNodes()):
            node = result.GetNode(i)
            prop = node.GetProperties().Get(vtk.vtkSelectionNode.PROP())
            if prop is scene_actor and node.GetSelectionList() is not None:
                arr = node.GetSelectionList()
                ids.append(np.array([arr.GetValue(j) for j in range(arr.GetNumberOfTuples())]))
        if not ids:
            return np.zeros(0, np.int64)
        cells = np.concatenate(ids).astype(np.int64)
        return np.unique(self.tri_patch[cells])

    def pick_at(self, x: int, y: int) -> np.ndarray:
        """The patch under a display point (empty if none)."""
        return self.pick_area(x, y, x, y)

    def ray(self, x: int, y: int) -> tuple[np.ndarray, np.ndarray]:
        """World points on the camera ray through a display point (near, far)."""
        ren = self.plotter.renderer
        out = []
        for z in (0.0, 1.0):
            ren.SetDisplayPoint(x, y, z)
            ren.DisplayToWorld()
            w = np.array(ren.GetWorldPoint())
            out.append(w[:3] / w[3])
        return out[0], out[1]

    def zone_point(self, zone: str, x: int, y: int) -> tuple[float, float] | None:
        """Zone coordinates under a display point."""
        frame = self.frames.get(zone)
        return None if frame is None else frame.from_ray(*self.ray(x, y))

    def eventFilter(self, obj, event) -> bool:
        """In select and move modes, mouse drags pick or move instead of orbiting; in
        zone and polygon modes, they draw."""
        if self.mode == "navigate" or obj is not self.plotter.interactor:
            return False
        et = event.type()
        if self.mode == "polygon":
            return self._polygon_event(et, event)
        if et == QtCore.QEvent.Type.MouseButtonPress and event.button() == QtCore.Qt.LeftButton:
            self._press = event.position().toPoint()
            if self.mode == "move" and self.drag_zone:
                self._last_uv = self.zone_point(self.drag_zone, *self._display(self._press))
            if self.mode == "zone":
                self._start_draft(*self._display(self._press))
            return True
        if et == QtCore.QEvent.Type.MouseMove and self._press is not None:
            if self.mode == "move" and self.drag_zone and self._last_uv is not None:
                uv = self.zone_point(self.drag_zone, *self._display(event.position().toPoint()))
                if uv is not None:
                    self.sourceDragged.emit(uv[0] - self._last_uv[0], uv[1] - self._last_uv[1])
                    self._last_uv = uv
            if self.mode == "zone" and self._draft is not None:
                self._show_draft(*self._display(event.position().toPoint()))
            return True
        if et == QtCore.QEvent.Type.MouseButtonRelease and self._press is not None:
            start, end = self._press, event.position().toPoint()
            self._press, self._last_uv = None, None
            if self.mode == "select":
                add = bool(event.modifiers() & QtCore.Qt.ShiftModifier)
                self.picked.emit(self.pick_area(*self._display(start), *self._display(end)), add)
            if self.mode == "zone" and self._draft is not None:
                rect = self._show_draft(*self._display(end))
                frame = self._draft[0]
                self._draft = None
                self.plotter.remove_actor("draft", render=False)
                self.show_axes(*self.axes_focus)  # back from the surface's axes
                if rect is not None:
                    self.zoneDrawn.emit(frame.name, *rect)
            return True
        return False

    # -- zone drawing -----------------------------------------------------------------------
    def _polygon_event(self, et, event) -> bool:
        """Polygon mode: each click adds a corner on the surface; a double-click, Enter or
        a click on the first corner closes the polygon; Backspace takes back the last
        corner, Escape drops the polygon. Right-drag and the wheel still move the camera."""
        left = getattr(event, "button", lambda: None)() == QtCore.Qt.LeftButton
        if et == QtCore.QEvent.Type.MouseButtonPress and left:
            self._press = event.position().toPoint()
            return True
        if et == QtCore.QEvent.Type.MouseButtonRelease and left:
            self._press = None
            if self._skip_release:
                self._skip_release = False
                return True
            self._polygon_click(*self._display(event.position().toPoint()))
            return True
        if et == QtCore.QEvent.Type.MouseButtonDblClick and left:
            self._skip_release = True
            self.finish_polygon()
            return True
        if et == QtCore.QEvent.Type.MouseMove and self._poly is not None:
            self._show_polygon(*self._display(event.position().toPoint()))
            return False  # VTK keeps its own bookkeeping of the cursor
        if et == QtCore.QEvent.Type.KeyPress and self._poly is not None:
            key = event.key()
            if key in (QtCore.Qt.Key_Return, QtCore.Qt.Key_Enter):
                self.finish_polygon()
            elif key == QtCore.Qt.Key_Escape:
                self.cancel_polygon()
            elif key == QtCore.Qt.Key_Backspace:
                self._poly[1].pop()
                if not self._poly[1]:
                    self.cancel_polygon()
                else:
                    self._show_polygon()
            else:
                return False
            return True
        return False

    def _polygon_click(self, x: int, y: int) -> None:
        """A corner at a display point (the first one picks the surface; the polygon may
        run on over the coplanar cells of the same material that continue it, so corners
        are not clipped to that surface: ``apply_zone_edits`` checks what it covers)."""
        if self._poly is None:
            self._start_draft(x, y)
            if self._draft is not None:
                frame, uv = self._draft
                self._draft = None
                self._poly = (frame, [uv])
                self._show_polygon()
            return
        frame, corners = self._poly
        uv = frame.from_ray(*self.ray(x, y))
        if uv is None:
            return
        if len(corners) >= 3 and np.hypot(*np.subtract(uv, corners[0])) < CLOSE_SNAP * max(
            frame.size
        ):
            self.finish_polygon()
            return
        corners.append(uv)
        self._show_polygon()

    def _show_polygon(self, x: int | None = None, y: int | None = None) -> None:
        """Draw the corners so far, and the edge to the cursor at display point (x, y)."""
        frame, corners = self._poly
        pts = list(corners)
        if x is not None:
            uv = frame.from_ray(*self.ray(x, y))
            if uv is not None:
                pts.append(uv)
        loop = np.array([frame.to_world(u, v) for u, v in [*pts, pts[0]]])
        self._outlines("draft", [loop], "#ff2020", 4)
        self.request_render()

    def polygon_corners(self) -> list[tuple[float, float]]:
        """The corners of the polygon being drawn (m on its surface), empty if none."""
        return [] if self._poly is None else list(self._poly[1])

    def finish_polygon(self) -> None:
        """Close the polygon being drawn and emit it (three corners or more)."""
        if self._poly is None:
            return
        frame, corners = self._poly
        self.cancel_polygon()
        if len(corners) >= 3:
            self.polygonDrawn.emit(frame.name, corners)

    def cancel_polygon(self) -> None:
        """Drop the polygon being drawn."""
        self._poly = None
        self.plotter.remove_actor("draft", render=False)
        self.show_axes(*self.axes_focus)
        self.request_render()

    def _start_draft(self, x: int, y: int) -> None:
        """Begin a zone rectangle on the surface the window picks for the cursor: the one
        seen if it suits, else one the view ray crosses (the culled ceiling, from above)."""
        self._draft = None
        if self.surface_frame is None:
            return
        hit = self.pick_at(x, y)
        near, far = self.ray(x, y)
        frame = self.surface_frame(int(hit[0]) if len(hit) else None, near, far)
        if frame is None:
            return
        uv = frame.from_ray(near, far)
        if uv is not None:
            self._draft = (frame, uv)
            self.show_axes(frame, f"{frame.name} (0, 0)")

    def _show_draft(self, x: int, y: int) -> tuple[float, float, float, float] | None:
        """Draw the rectangle being dragged; returns it (m, clipped to the surface)."""
        frame, (u0, v0) = self._draft
        uv = frame.from_ray(*self.ray(x, y))
        if uv is None:
            return None
        w, h = frame.size
        u1, v1 = float(np.clip(uv[0], 0, w)), float(np.clip(uv[1], 0, h))
        u0, v0 = float(np.clip(u0, 0, w)), float(np.clip(v0, 0, h))
        self._outlines("draft", [frame.rectangle(u0, v0, u1, v1)], "#ff2020", 4)
        self.request_render()
        return u0, v0, u1, v1

    def screenshot(self, path: str | None = None) -> np.ndarray:
        """The rendered 3D view as an (h, w, 3) image, saved to ``path`` if given."""
        self.render_now()
        return self.plotter.screenshot(path, return_img=True)

    def close_plotter(self) -> None:
        """Release VTK's window (call before the widget is destroyed)."""
        self.plotter.close()
