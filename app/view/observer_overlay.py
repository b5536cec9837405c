"""Observers drawn in the 3-D view: a small ball at each eye and an arrow along its view,
so where glare is judged from reads at a glance. Named actors (``observers``, and
``observer-current`` for the one picked, in green), so a redraw replaces them; an
observer outside the room is not drawn (the Achieved tab and the solve say why).

Coloured by a map at the observers (``set_colours``, View > Colour by's glare maps,
``observer_maps``): each glyph in its value's colour, a colour bar of its own
(``observer-bar``, a VTK scalar bar kept out of pyvista's, which the patches' colouring
retitles and hides) and a label beside each eye (``observer-values``); the one picked
keeps its colour inside a green cage. The colours stay set on the plotter until
``set_colours(plotter, None)``, so a redraw after a pick keeps them.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv
import vtk

from app.view.observer_maps import ObserverColours
from lightinv_core.errors import LightInvError
from lightinv_core.light.glare import observer_eyes

COLOUR = "#ff4fa3"
CURRENT_COLOUR = "#00d000"  # as the current source's outline
NAME = "observers"
CURRENT = "observer-current"
BAR = "observer-bar"
LABELS = "observer-values"
ARROW = 1.2  # m: the view arrow's length


def observer_glyphs(patches, observers, values: dict[str, float] | None = None):
    """A 0.15 m ball at each eye and an arrow ``ARROW`` m along its view; with
    ``values``, each glyph's points carry its observer's value (``value``)."""
    blocks = []
    for ob in observers:
        try:
            eyes = observer_eyes(patches, (ob,))
        except LightInvError:
            continue
        eye, view = eyes.points[0], eyes.views[0]
        glyph = pv.Sphere(radius=0.15, center=eye) + pv.Arrow(
            start=eye,
            direction=view,
            scale=ARROW,
            tip_length=0.3,
            tip_radius=0.12,
            shaft_radius=0.04,
        )
        if values is not None:
            glyph.point_data["value"] = np.full(glyph.n_points, values.get(ob.name, np.nan))
        blocks.append(glyph)
    return pv.merge(blocks) if blocks else None


def set_colours(plotter, colours: ObserverColours | None) -> bool:
    """Colour the observers by ``colours`` from the next ``draw`` on (None: in pink, as
    before); whether that changed anything."""
    changed = getattr(plotter, "_observer_colours", None) != colours
    plotter._observer_colours = colours
    return changed


def colours_of(plotter) -> ObserverColours | None:
    """The colours the observers are drawn in (None: plain)."""
    return getattr(plotter, "_observer_colours", None)


def draw(plotter, patches, observers, current: str | None = None) -> None:
    """Draw (or clear) the design's observers; ``current`` (the one picked) in green."""
    for name in (NAME, CURRENT, BAR, LABELS, f"{LABELS}-labels"):
        plotter.remove_actor(name, render=False)
    colours = colours_of(plotter)
    if colours is not None:
        _draw_coloured(plotter, patches, observers, current, colours)
        return
    for name, colour, group in (
        (NAME, COLOUR, [o for o in observers if o.name != current]),
        (CURRENT, CURRENT_COLOUR, [o for o in observers if o.name == current]),
    ):
        glyphs = observer_glyphs(patches, group) if group else None
        if glyphs is not None:
            plotter.add_mesh(glyphs, name=name, color=colour, lighting=False, render=False)


def lookup_table(colours: ObserverColours) -> pv.LookupTable:
    """The colour map of ``colours`` over its range (one colour per value with
    annotations: EN 17037's levels)."""
    if isinstance(colours.cmap, str):
        lut = pv.LookupTable(colours.cmap, n_values=256)
    else:
        rgba = [[int(c[i : i + 2], 16) for i in (1, 3, 5)] + [255] for c in colours.cmap]
        lut = pv.LookupTable(values=np.array(rgba, np.uint8))
    lut.scalar_range = colours.clim
    lut.nan_color = "#bbbbbb"
    return lut


def _draw_coloured(plotter, patches, observers, current, colours: ObserverColours) -> None:
    glyphs = observer_glyphs(patches, observers, colours.values)
    if glyphs is None:
        return
    lut = lookup_table(colours)
    actor = plotter.add_mesh(
        glyphs, name=NAME, scalars="value", show_scalar_bar=False, lighting=False, render=False
    )
    actor.mapper.lookup_table = lut
    actor.mapper.scalar_range = colours.clim
    eyes, texts = [], []
    for ob in observers:
        try:
            eye = observer_eyes(patches, (ob,)).points[0]
        except LightInvError:
            continue
        if ob.name in colours.labels:
            eyes.append(eye + np.array([0.0, 0.0, 0.3]))
            texts.append(colours.labels[ob.name])
        if ob.name == current:  # a cage around the picked one, its colour kept inside
            cage = pv.Sphere(radius=0.26, center=eye, theta_resolution=10, phi_resolution=6)
            plotter.add_mesh(
                cage,
                name=CURRENT,
                color=CURRENT_COLOUR,
                style="wireframe",
                line_width=2,
                lighting=False,
                render=False,
            )
    if eyes:
        plotter.add_point_labels(
            np.array(eyes),
            texts,
            name=LABELS,
            font_size=11,
            bold=True,
            text_color="#202020",
            shape_color="#ffffff",
            shape_opacity=0.8,
            show_points=False,
            always_visible=True,
            render=False,
        )
    plotter.add_actor(scalar_bar(lut, colours), name=BAR, reset_camera=False, render=False)


def scalar_bar(lut: pv.LookupTable, colours: ObserverColours) -> vtk.vtkScalarBarActor:
    """The observers' colour bar, where the patches' stands (theirs is hidden: the
    surfaces show their materials under a map at the observers)."""
    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(colours.title)
    bar.SetLabelFormat(colours.fmt)
    if colours.annotations:
        for value, text in colours.annotations.items():
            lut.SetAnnotation(vtk.vtkVariant(value), text)
        bar.SetNumberOfLabels(0)
        bar.SetDrawAnnotations(True)
        bar.SetAnnotationLeaderPadding(4)
    else:
        bar.SetNumberOfLabels(6)
    bar.SetOrientationToVertical()
    bar.SetUnconstrainedFontSize(True)  # the font sizes below, not scaled with the bar
    coord = bar.GetPositionCoordinate()
    coord.SetCoordinateSystemToNormalizedViewport()
    coord.SetValue(0.86, 0.15)
    bar.SetWidth(0.1)
    bar.SetHeight(0.7)
    for prop in (
        bar.GetTitleTextProperty(),
        bar.GetLabelTextProperty(),
        bar.GetAnnotationTextProperty(),
    ):
        prop.SetColor(0.1, 0.1, 0.1)
        prop.SetShadow(False)
        prop.SetBold(False)
        prop.SetItalic(False)
        prop.SetFontSize(12)
    return bar
