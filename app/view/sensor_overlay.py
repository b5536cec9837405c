"""Control groups' sensors drawn in the 3-D view: each group's sensor rectangle outlined
on its work plane, in a colour of its own, labelled with the group's name (the work
plane's iso-lines are thin and coloured by the light; these are thick and flat). Named
actors (``sensors``, and ``sensor-label-K`` per group, its label in the group's colour,
and ``sensor-handles``: a ball at each corner of a declared group's region, which
Move mode drags, ``sensor_drag``), so a redraw after an edit or an undo replaces them; a
design without control groups draws nothing (``light.control_groups.sensor_outlines``)."""

from __future__ import annotations

import numpy as np
import pyvista as pv

from lightinv_core.light.control_groups import SensorOutline, sensor_outlines

NAME = "sensors"
HANDLES = "sensor-handles"
HANDLE_PX = 13  # a corner handle's width on screen, pixels
LABEL = "sensor-label-{}"
LIFT = 0.03  # m above the work plane, so its own iso-lines do not hide the outline
PALETTE = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2")
"""One colour per group, in the design's order (matplotlib's tab10, less its greys)."""


def sensor_colour(k: int) -> str:
    """The colour of the k-th group's sensor (hex)."""
    return PALETTE[k % len(PALETTE)]


def outline_mesh(outlines: tuple[SensorOutline, ...]) -> pv.PolyData | None:
    """The outlines as closed polylines, one per group, each cell coloured (``rgb``)."""
    if not outlines:
        return None
    points, lines, colours = [], [], []
    for k, o in enumerate(outlines):
        start = 4 * k
        points.append(o.corners + np.array([0.0, 0.0, LIFT]))
        lines += [5, start, start + 1, start + 2, start + 3, start]
        rgb = [int(sensor_colour(k)[i : i + 2], 16) for i in (1, 3, 5)]
        colours.append(rgb)
    mesh = pv.PolyData(np.vstack(points), lines=np.array(lines))
    mesh.cell_data["rgb"] = np.array(colours, dtype=np.uint8)
    return mesh


def handle_mesh(outlines, declared: set[str]) -> pv.PolyData | None:
    """A point at each corner of the declared groups' outlines (the default group, when
    undeclared, has no region to drag), each in its group's colour (``rgb``); drawn as
    balls ``HANDLE_PX`` pixels wide whatever the zoom."""
    points, colours = [], []
    for k, o in enumerate(outlines):
        if o.name not in declared:
            continue
        rgb = [int(sensor_colour(k)[i : i + 2], 16) for i in (1, 3, 5)]
        points += [c + np.array([0.0, 0.0, LIFT]) for c in o.corners]
        colours += [rgb] * len(o.corners)
    if not points:
        return None
    mesh = pv.PolyData(np.array(points, float))
    mesh.point_data["rgb"] = np.array(colours, dtype=np.uint8)
    return mesh


def draw(plotter, design, patches, grids=None) -> tuple[SensorOutline, ...]:
    """Draw (or clear) the sensors of ``design``'s control groups; the outlines drawn."""
    plotter.remove_actor(NAME, render=False)
    plotter.remove_actor(HANDLES, render=False)
    for name in getattr(plotter, "_sensor_labels", ()):
        plotter.remove_actor(name, render=False)
    plotter._sensor_labels = []
    outlines = sensor_outlines(design, patches, grids) if design is not None else ()
    mesh = outline_mesh(outlines)
    if mesh is None:
        return ()
    plotter.add_mesh(
        mesh, name=NAME, scalars="rgb", rgb=True, line_width=4, lighting=False, render=False
    )
    handles = handle_mesh(outlines, {c.name for c in design.control_groups})
    if handles is not None:
        plotter.add_mesh(
            handles,
            name=HANDLES,
            scalars="rgb",
            rgb=True,
            point_size=HANDLE_PX,
            render_points_as_spheres=True,
            render=False,
        )
    for k, o in enumerate(outlines):
        name = LABEL.format(k)
        plotter.add_point_labels(
            (o.corners[3] + np.array([0.15, -0.15, LIFT]))[None],
            [f"sensor: {o.name}"],
            name=name,
            font_size=12,
            bold=True,
            text_color=sensor_colour(k),
            shape_color="#ffffff",
            shape_opacity=0.75,
            show_points=False,
            always_visible=True,
            render=False,
        )
        plotter._sensor_labels.append(f"{name}-labels")  # pyvista names its actor so
    return outlines
