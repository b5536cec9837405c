"""The VTK pieces the viewport draws besides the patches: text anchored at a 3D point,
the veil over a picture out of date, polylines, the light carried onto a re-meshed
scene, and the u, v axes of a zone."""

from __future__ import annotations

import numpy as np
import pyvista as pv
import vtk
from scipy.spatial import cKDTree

from app.view.zone_frame import OUTLINE_LIFT, ZoneFrame

VEIL_OPACITY = 0.55  # the white veil over a picture whose light is out of date
AXIS_COLOURS = {"u": "#d62020", "v": "#1a9a1a"}  # as the x (red) and y (green) of the widget
AXIS_ACTORS = ("axis-u", "axis-v", "axis-u-label", "axis-v-label", "axis-origin-label")


def carried_values(old: pv.PolyData, new: pv.PolyData) -> np.ndarray:
    """The values of ``old``'s cells carried to ``new``'s: each new triangle takes the
    value of the old triangle whose centre is nearest its own (the same room re-meshed)."""
    tree = cKDTree(old.cell_centers().points)
    _, nearest = tree.query(new.cell_centers().points)
    return np.asarray(old.cell_data["value"], np.float32)[nearest]


def text_label(text: str, point, side: str) -> vtk.vtkTextActor:
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


def veil() -> vtk.vtkActor2D:
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


def polylines(loops: list[np.ndarray]) -> pv.PolyData:
    pts = np.concatenate(loops)
    lines, start = [], 0
    for loop in loops:
        lines += [len(loop), *range(start, start + len(loop))]
        start += len(loop)
    return pv.PolyData(pts, lines=np.array(lines))


def draw_zone_axes(plotter, frame: ZoneFrame, title: str = "") -> None:
    """The origin and u, v axes of ``frame`` (a zone, or the surface a zone is being
    drawn on) as two arrows labelled u and v from the origin, labelled ``title`` ("Z1
    (0, 0)") just outside the corner: the corners in Properties are metres along them.
    Replaces the axes drawn before; no render."""
    remove_zone_axes(plotter)
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
        plotter.add_mesh(
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
        plotter.add_actor(
            text_label(title or "(0, 0)" if name == "origin" else name, point, side),
            name=f"axis-{name}-label",
            reset_camera=False,
            render=False,
        )


def remove_zone_axes(plotter) -> None:
    """Remove the zone axes (no render)."""
    for name in AXIS_ACTORS:
        plotter.remove_actor(name, render=False)
