"""Calculation objects drawn in the 3-D view: a small ball at each point where a value
is read (a task area's or a surface's grid points, each cylinder's axis point, each free
point), so what the design is judged on reads at a glance. One named actor
(``calc_objects``), so a redraw replaces it; an object that cannot be laid out (its
floor group is missing) is not drawn (the light and the solve say why)."""

from __future__ import annotations

import numpy as np
import pyvista as pv

from lightinv_core.errors import LightInvError

COLOUR = "#22d3ee"
NAME = "calc_objects"
RADIUS = 0.06  # m


def calc_points(patches, objects) -> np.ndarray:
    """(q, 3) m: where each object's values are read."""
    chunks = []
    for obj in objects:
        try:
            chunks.append(obj.spec.readings(obj, patches, None).at)
        except LightInvError:
            continue
    return np.vstack(chunks) if chunks else np.zeros((0, 3))


def draw(plotter, patches, objects) -> None:
    """Draw (or clear) the design's calculation objects."""
    plotter.remove_actor(NAME, render=False)
    pts = calc_points(patches, objects) if objects else np.zeros((0, 3))
    if len(pts):
        balls = pv.PolyData(pts).glyph(geom=pv.Sphere(radius=RADIUS), scale=False, orient=False)
        plotter.add_mesh(balls, name=NAME, color=COLOUR, lighting=False, render=False)
