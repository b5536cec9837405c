"""Observers drawn in the 3-D view: a small ball at each eye and an arrow along its view,
so where glare is judged from reads at a glance. One named actor (``observers``), so a
redraw replaces it; an observer outside the room is not drawn (the Achieved tab and
the solve say why)."""

from __future__ import annotations

import pyvista as pv

from lightinv_core.errors import LightInvError
from lightinv_core.light.glare import observer_eyes

COLOUR = "#ff4fa3"
NAME = "observers"
ARROW = 1.2  # m: the view arrow's length


def observer_glyphs(patches, observers) -> pv.PolyData | None:
    """A 0.15 m ball at each eye and an arrow ``ARROW`` m along its view."""
    blocks = []
    for ob in observers:
        try:
            eyes = observer_eyes(patches, (ob,))
        except LightInvError:
            continue
        eye, view = eyes.points[0], eyes.views[0]
        blocks.append(pv.Sphere(radius=0.15, center=eye))
        blocks.append(
            pv.Arrow(
                start=eye,
                direction=view,
                scale=ARROW,
                tip_length=0.3,
                tip_radius=0.12,
                shaft_radius=0.04,
            )
        )
    return pv.merge(blocks) if blocks else None


def draw(plotter, patches, observers) -> None:
    """Draw (or clear) the design's observers."""
    plotter.remove_actor(NAME, render=False)
    glyphs = observer_glyphs(patches, observers) if observers else None
    if glyphs is not None:
        plotter.add_mesh(glyphs, name=NAME, color=COLOUR, lighting=False, render=False)
