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
from PySide6 import QtCore, QtWidgets
from pyvistaqt import QtInteractor
from vtkmodules.vtkCommonDataModel import vtkPlane

from app.view.picking import camera_ray, scene_cells_in
from app.view.vtk_shapes import (
    carried_values,
    draw_point_marks,
    draw_zone_axes,
    hint_box,
    material_colours,
    polylines,
    remove_zone_axes,
    show_materials,
    surface_edges,
    veil,
)
from app.view.zone_drawing import ZoneDrawing
from app.view.zone_frame import ZoneFrame
from lightinv_core.scene.patches import Patches

CAMERAS = {
    "iso": ((1.0, -1.3, 1.2), (0, 0, 1)),
    "top": ((0.0, 0.0, 1.0), (0, 1, 0)),
    "front": ((0.0, -1.0, 0.25), (0, 0, 1)),
    # From the other side, to see (and draw on) the inside of the wall Front view looks
    # through: a room's faces face into it, so the near wall is culled in each view.
    "back": ((0.0, 1.0, 0.25), (0, 0, 1)),
    "left": ((-1.0, 0.0, 0.25), (0, 0, 1)),
    "right": ((1.0, 0.0, 0.25), (0, 0, 1)),
}


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
        self.has_values = False  # the patches show light (not their materials: no light yet)
        self.edges: pv.PolyData | None = None  # the surfaces' outlines, drawn with materials
        self.cut: float | None = None  # m: the model above this height is hidden
        self.hint: str | None = None  # what to do next (set_hint), along the bottom
        self.keep_camera = False  # the next set_scene keeps the camera (the same room)
        self.busy_text: str | None = None
        self.axes_frame: ZoneFrame | None = None  # the frame whose axes are drawn
        self.axes_title = ""
        self.axes_focus: tuple[ZoneFrame | None, str] = (None, "")  # shown when not drawing
        self.show_zone_axes = True
        self._veil = veil()
        self.tri_patch: np.ndarray | None = None
        self.frames: dict[str, ZoneFrame] = {}
        self.cmap = "inferno"
        self.clim: tuple[float, float] | None = None  # None: automatic
        self.units = "lux"
        self.label_format = "%.0f"  # the colour bar's labels
        self.caption: str | None = None  # the line along the top (set_caption)
        self.mode = "navigate"  # navigate | select | move | zone | polygon
        # callable(patch id seen or None, ray near point, ray far point) -> ZoneFrame of the
        # surface a zone drawn there goes on, or None
        self.surface_frame = None
        self.drawing = ZoneDrawing(self)  # a zone being drawn (zone and polygon modes)
        self.drag_zone: str | None = None
        self.press: QtCore.QPoint | None = None
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
        keep_camera = (keep_picture or self.keep_camera) and self.mesh is not None
        camera = self.plotter.camera_position if keep_camera else None
        self.keep_camera = False
        self.mesh = pv.PolyData(vertices.astype(float), cells)
        self.mesh.cell_data["value"] = np.zeros(len(faces), np.float32)
        self.mesh.cell_data["material"] = material_colours(patches.rho)[tri_patch]
        span = float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))
        self.edges = surface_edges(patches, max(0.004 * span, 0.005))
        if old is not None:
            self.mesh.cell_data["value"] = carried_values(old, self.mesh)
        self.tri_patch = tri_patch
        self.frames = {z: ZoneFrame(patches, z) for z in zones}
        self.plotter.clear()  # every actor goes, the veil and the axes too, and the lights
        # A headlight for the materials' Lambert shading (the light's colours ignore it).
        self.plotter.add_light(pv.Light(light_type="headlight"))
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
        self._apply_cut()
        self.set_caption(caption)
        self._draw_hint()
        self.set_zone_outlines()
        self.axes_frame = None
        self.has_values = True  # as the scene actor is made: _show_materials switches
        if old is not None:
            lo, hi = self.clim or (0.0, float(max(self.mesh.cell_data["value"].max(), 1e-6)))
            self.plotter.actors["scene"].mapper.scalar_range = (lo, hi)
        else:
            self._show_materials(True)
        if camera is not None:
            self.plotter.camera_position = camera
            self.render_now()
        else:
            self.camera("iso")

    def set_values(
        self, per_patch: np.ndarray | None, units: str = "lux", fmt: str = "%.0f"
    ) -> None:
        """Colour the patches (in place, no new actor); None shows their materials
        instead (no light yet: ``_show_materials``). ``units`` titles the colour bar,
        ``fmt`` its labels (printf style)."""
        if self.mesh is None:
            return
        values = (
            np.zeros(len(self.tri_patch), np.float32)
            if per_patch is None
            else np.asarray(per_patch, dtype=np.float32)[self.tri_patch]
        )
        if (per_patch is None) == self.has_values:
            self._show_materials(per_patch is None)
        self.mesh.cell_data["value"][:] = values
        lo, hi = self.clim if self.clim is not None else (0.0, float(max(values.max(), 1e-6)))
        actor = self.plotter.actors.get("scene")
        if actor is None:  # the window closing: its scene is gone before a late repaint
            return
        actor.mapper.scalar_range = (lo, hi)
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

    def _show_materials(self, on: bool) -> None:
        """No light yet (no light model, or a design that emits none): the patches in
        the grey of their reflectance, headlit, outlined, no colour bar
        (``vtk_shapes.show_materials``); ``on`` False: back to the light's colours."""
        self.has_values = not on
        show_materials(self.plotter, on, self.edges)
        self._apply_cut()

    def set_hint(self, text: str | None) -> None:
        """What to do next on the design (a box along the bottom of the view); None
        removes it."""
        if text == self.hint:
            return
        self.hint = text
        self._draw_hint()
        self.request_render()

    def _draw_hint(self) -> None:
        self.plotter.remove_actor("hint", render=False)
        if self.hint:
            lines = [w for line in self.hint.split("\n") for w in textwrap.wrap(line, 60)]
            self.plotter.add_actor(
                hint_box("\n".join(lines)), name="hint", reset_camera=False, render=False
            )

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
        drawn on), labelled ``title`` at the origin (``vtk_shapes.draw_zone_axes``); None
        hides them."""
        self.axes_frame, self.axes_title = frame, title
        if frame is None or not self.show_zone_axes or self.mesh is None:
            remove_zone_axes(self.plotter)
        else:
            draw_zone_axes(self.plotter, frame, title)
        self.request_render()

    def set_axes_focus(self, frame: ZoneFrame | None, title: str = "") -> None:
        """The zone whose axes are shown while no zone is being drawn (the window's
        current source's zone, or a drawn zone's surface); redrawn only when it changes."""
        same = self.axes_focus[0] is frame and self.axes_focus[1] == title
        self.axes_focus = (frame, title)
        if self.drawing.draft is None and not (same and self.axes_frame is frame):
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
        self.outlines("zones", loops, "#3070ff", 2)

    def outlines(self, name: str, loops: list[np.ndarray], color: str, width: int) -> None:
        """Polylines as one named actor (replacing the previous one), no render."""
        if loops:
            self.plotter.add_mesh(
                polylines(loops),
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
        self.outlines("sources", loops, "#00a0a0", 3)
        self.outlines("current", cur, "#00d000", 5)
        self.request_render()

    def set_selection(self, patch_ids: np.ndarray) -> None:
        """Highlight the picked patches."""
        self._overlay("selection", patch_ids, "#00ff66", 0.55)

    def set_highlight(self, patch_ids: np.ndarray) -> None:
        """Paint ``patch_ids`` red over the lighting (patches breaking an intention)."""
        self._overlay("offending", patch_ids, "#ff1010", 0.6)

    def set_point_marks(self, points: np.ndarray | None) -> None:
        """Red dots at ``points`` (k, 3) m (work-plane points breaking an intention);
        None removes them."""
        draw_point_marks(self.plotter, points)
        self.request_render()

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
        """Camera presets: iso, top (roof culled), front, back, left, right (the near wall
        culled)."""
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
    def display(self, pos: QtCore.QPoint) -> tuple[int, int]:
        """Qt widget coordinates -> VTK display coordinates (origin bottom-left)."""
        ratio = self.plotter.interactor.devicePixelRatioF()
        h = self.plotter.interactor.height() * ratio
        return int(pos.x() * ratio), int(h - 1 - pos.y() * ratio)

    def pick_area(self, x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
        """Patch ids visible in a display rectangle (hardware selection: hidden ones excluded)."""
        if self.mesh is None:
            return np.zeros(0, np.int64)
        return np.unique(self.tri_patch[scene_cells_in(self.plotter, x0, y0, x1, y1)])

    def pick_at(self, x: int, y: int) -> np.ndarray:
        """The patch under a display point (empty if none)."""
        return self.pick_area(x, y, x, y)

    def ray(self, x: int, y: int) -> tuple[np.ndarray, np.ndarray]:
        """World points on the camera ray through a display point (near, far); with a
        cut, the ray starts where it comes down through the cut, so what is hidden above
        it is never crossed (a zone goes on the ceiling under the cut)."""
        near, far = camera_ray(self.plotter.renderer, x, y)
        if self.cut is not None and near[2] > self.cut > far[2]:
            near = near + (far - near) * (near[2] - self.cut) / (near[2] - far[2])
        return near, far

    # -- the cut ---------------------------------------------------------------------------
    def set_cut(self, height: float | None) -> None:
        """Hide the model above ``height`` m (None: show all of it), for drawing and
        picking too: clipped triangles are not drawn, so hardware picking skips them."""
        self.cut = height
        self._apply_cut()
        self.request_render()

    def _apply_cut(self) -> None:
        """The cut on the scene and its surfaces' outlines (both remade now and then)."""
        for name in ("scene", "edges"):
            actor = self.plotter.actors.get(name)
            if actor is None:
                continue
            mapper = actor.GetMapper()
            mapper.RemoveAllClippingPlanes()
            if self.cut is not None:
                plane = vtkPlane()
                plane.SetOrigin(0.0, 0.0, self.cut)
                plane.SetNormal(0.0, 0.0, -1.0)  # keeps what is below the cut
                mapper.AddClippingPlane(plane)

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
            return self.drawing.polygon_event(et, event)
        if et == QtCore.QEvent.Type.MouseButtonPress and event.button() == QtCore.Qt.LeftButton:
            self.press = event.position().toPoint()
            if self.mode == "move" and self.drag_zone:
                self._last_uv = self.zone_point(self.drag_zone, *self.display(self.press))
            if self.mode == "zone":
                self.drawing.start_draft(*self.display(self.press))
            return True
        if et == QtCore.QEvent.Type.MouseMove and self.press is not None:
            if self.mode == "move" and self.drag_zone and self._last_uv is not None:
                uv = self.zone_point(self.drag_zone, *self.display(event.position().toPoint()))
                if uv is not None:
                    self.sourceDragged.emit(uv[0] - self._last_uv[0], uv[1] - self._last_uv[1])
                    self._last_uv = uv
            if self.mode == "zone" and self.drawing.draft is not None:
                self.drawing.show_draft(*self.display(event.position().toPoint()))
            return True
        if et == QtCore.QEvent.Type.MouseButtonRelease and self.press is not None:
            start, end = self.press, event.position().toPoint()
            self.press, self._last_uv = None, None
            if self.mode == "select":
                add = bool(event.modifiers() & QtCore.Qt.ShiftModifier)
                self.picked.emit(self.pick_area(*self.display(start), *self.display(end)), add)
            if self.mode == "zone" and self.drawing.draft is not None:
                self.drawing.finish_draft(*self.display(end))
            return True
        return False

    # -- zone drawing (zone_drawing.py) ------------------------------------------------------
    def polygon_corners(self) -> list[tuple[float, float]]:
        """The corners of the polygon being drawn (m on its surface), empty if none."""
        return self.drawing.corners()

    def finish_polygon(self) -> None:
        """Close the polygon being drawn and emit it (three corners or more)."""
        self.drawing.finish_polygon()

    def cancel_polygon(self) -> None:
        """Drop the polygon being drawn."""
        self.drawing.cancel_polygon()

    def screenshot(self, path: str | None = None) -> np.ndarray:
        """The rendered 3D view as an (h, w, 3) image, saved to ``path`` if given."""
        self.render_now()
        return self.plotter.screenshot(path, return_img=True)

    def close_plotter(self) -> None:
        """Release VTK's window (call before the widget is destroyed)."""
        self.plotter.close()
