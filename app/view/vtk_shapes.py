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


def material_colours(rho: np.ndarray) -> np.ndarray:
    """(n, 3) uint8 grey of each reflectance ``rho`` (n,): lighter for a lighter
    material, never black (a 5% floor still reads as a surface under the headlight)."""
    grey = 0.25 + 0.7 * np.clip(np.asarray(rho, float), 0.0, 1.0)
    return np.repeat(np.round(255 * grey).astype(np.uint8)[:, None], 3, axis=1)


def surface_edges(patches, width: float) -> pv.PolyData | None:
    """The outlines of the scene's surfaces (the model's edges and corners, the cuts
    zones made) as thin strips ``width`` m wide lying on their faces, facing as the
    faces do: back-face culling hides them with their face, so a wall culled to look
    into the room takes its edges along (lines would be drawn through it). An outline
    edge is a patch edge no other patch of the same surface shares (ends matched to
    the millimetre): a surface's inner patch grid is left out."""
    quads = ~patches.is_triangle
    o, e1, e2 = patches.origin, patches.edge1, patches.edge2
    corners = np.stack([o, o + e1, np.where(quads[:, None], o + e1 + e2, o + e2), o + e2], 1)
    count = np.where(quads, 4, 3)
    a, b, pid = [], [], []
    for k in range(4):  # edge k runs from corner k to corner k + 1 (3 -> 0 for a quad)
        has = np.flatnonzero(k < count)
        nxt = np.where(count[has] == 3, (k + 1) % 3, (k + 1) % 4)
        a.append(corners[has, k])
        b.append(corners[has, nxt])
        pid.append(has)
    a, b, pid = np.concatenate(a), np.concatenate(b), np.concatenate(pid)
    ka, kb = np.round(a * 1000).astype(np.int64), np.round(b * 1000).astype(np.int64)
    d = ka - kb  # each edge's ends in one order (lexicographic), so shared edges match
    first = d[np.arange(len(d)), np.argmax(d != 0, axis=1)] < 0
    lo, hi = np.where(first[:, None], ka, kb), np.where(first[:, None], kb, ka)
    keys = np.concatenate([patches.surface_id[pid, None].astype(np.int64), lo, hi], 1)
    _, inverse, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    outer = counts[inverse.ravel()] == 1
    if not outer.any():
        return None
    a, b, pid = a[outer], b[outer], pid[outer]
    n = patches.normal[pid]
    inward = np.cross(n, b - a)
    inward /= np.maximum(np.linalg.norm(inward, axis=1, keepdims=True), 1e-12)
    towards = np.einsum("ij,ij->i", patches.centroid[pid] - a, inward) < 0
    inward[towards] *= -1.0  # into the patch, not out of it
    lift = 0.002 * n  # just off the face: no z-fighting
    quad = np.stack([a + lift, b + lift, b + lift + width * inward, a + lift + width * inward], 1)
    # Wound as the face is (its normal ``n``), so culling treats it as the face.
    wrong = np.einsum("ij,ij->i", np.cross(quad[:, 1] - quad[:, 0], quad[:, 2] - quad[:, 0]), n) < 0
    quad[wrong] = quad[wrong][:, ::-1]
    m = len(quad)
    faces = np.column_stack([np.full(m, 4), 4 * np.arange(m)[:, None] + np.arange(4)]).ravel()
    return pv.PolyData(quad.reshape(-1, 3), faces=faces)


def hint_box(text: str) -> vtk.vtkTextActor:
    """A hint along the bottom of the view: dark text on a pale yellow box."""
    actor = vtk.vtkTextActor()
    actor.SetInput(text)
    actor.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    actor.GetPositionCoordinate().SetValue(0.985, 0.015)  # bottom right: the axes are left
    prop = actor.GetTextProperty()
    prop.SetFontSize(13)
    prop.SetColor(0.1, 0.1, 0.1)
    prop.SetBackgroundColor(1.0, 0.96, 0.75)
    prop.SetBackgroundOpacity(0.92)
    prop.SetFrame(True)
    prop.SetFrameColor(0.75, 0.6, 0.2)
    prop.SetJustificationToRight()
    actor.SetPickable(False)
    return actor


def show_materials(plotter, on: bool, edges: pv.PolyData | None) -> None:
    """The "scene" actor in its materials (``on``: the "material" colours, lit by the
    headlight, Lambert-shaded, ``edges`` outlining the surfaces, no colour bar: a scale
    of zeros over a black room said nothing) or in the light's colours (the "value"
    array through the colour map, unlit, with its colour bar). No render."""
    actor = plotter.actors.get("scene")
    if actor is not None:
        mapper = actor.mapper
        mapper.array_name = "material" if on else "value"
        mapper.color_mode = "direct" if on else "map"
        mapper.scalar_visibility = True
        actor.prop.lighting = on
        actor.prop.ambient, actor.prop.diffuse = (0.45, 0.55) if on else (0.0, 1.0)
    for bar in plotter.scalar_bars.values():
        bar.SetVisibility(not on)
    plotter.remove_actor("edges", render=False)
    if on and edges is not None:
        plotter.add_mesh(
            edges,
            name="edges",
            color="#303030",
            lighting=False,
            culling="back",
            pickable=False,
            reset_camera=False,
            render=False,
        )


def draw_point_marks(plotter, points: np.ndarray | None) -> None:
    """Red dots at ``points`` (k, 3) m, 2 cm above them, as the "grid-marks" actor
    (replacing it; None or none: removed). Not named "offending-...": pyvista's
    add_mesh(name="offending") removes the actors whose names begin so. No render."""
    plotter.remove_actor("grid-marks", render=False)
    if points is not None and len(points):
        plotter.add_mesh(
            pv.PolyData(np.asarray(points, float) + np.array([0.0, 0.0, 0.02])),
            name="grid-marks",
            color="#ff1010",
            point_size=9,
            render_points_as_spheres=True,
            lighting=False,
            pickable=False,
            reset_camera=False,
            render=False,
        )
