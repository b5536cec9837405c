"""Observers drawn in the 3-D view: a small ball at each eye and an arrow along its view,
so where glare is judged from reads at a glance. Named actors (``observers``, and
``observer-current`` for the one picked, in green), so a redraw replaces them; an
observer outside the room is not drawn (the Achieved tab and the solve say why)."""

from __future__ import annotations

import pyvista as pv

from lightinv_core.errors import LightInvError
from lightinv_core.light.glare import observer_eyes

COLOUR = "#ff4fa3"
CURRENT_COLOUR = "#00d000"  # as the current source's outline
NAME = "observers"
CURRENT = "observer-current"
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


def draw(plotter, patches, observers, current: str | None = None) -> None:
    """Draw (or clear) the design's observers; ``current`` (the one picked) in green."""
    for name, colour, group in (
        (NAME, COLOUR, [o for o in observers if o.name != current]),
        (CURRENT, CURRENT_COLOUR, [o for o in observers if o.name == current]),
    ):
        plotter.remove_actor(name, render=False)
        glyphs = observer_glyphs(patches, group) if group else None
        if glyphs is not None:
            plotter.add_mesh(glyphs, name=name, color=colour, lighting=False, render=False)
