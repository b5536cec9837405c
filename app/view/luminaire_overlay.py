"""Luminaires and work planes drawn in the 3-D view: glyphs and iso-lux lines.

Each luminaire of the design's arrays is its luminous opening (a thin box on the
ceiling, 2 cm below it) with a short stem along its aim, so rows, columns, spacing and
rotation read at a glance; each work plane shows its grid points coloured by their
illuminance and iso-lux lines on the plane. Actors are named (``luminaires``,
``workplane``, ``isolux``, ``isolux-labels``) so a redraw replaces them.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv

from lightinv_core.light.arrays import MOUNT_OFFSET, resolve_product, zone_frame

GLYPH_COLOUR = "#1ec8e6"
ISO_LEVELS = 6
NAMES = ("luminaires", "workplane", "isolux", "isolux-labels")


def luminaire_glyphs(patches, arrays) -> pv.PolyData | None:
    """One box per luminaire (its opening, 2 cm deep) and a stem along its aim."""
    blocks = []
    for a in arrays:
        prod = resolve_product(a.product, a.watts)
        f = zone_frame(patches, a.zone)
        w, length = (max(x, 0.05) for x in prod.opening)
        along = f.u if a.rotation == 0 else f.v
        across = f.v if a.rotation == 0 else f.u
        for u, v in a.positions():
            c = f.point(u, v, MOUNT_OFFSET)
            corners = [
                c + sa * 0.5 * length * along + sb * 0.5 * w * across
                for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1))
            ]
            face = pv.PolyData(np.array(corners), faces=[4, 0, 1, 2, 3])
            blocks.append(face.extrude(0.02 * f.normal, capping=True))
            blocks.append(pv.Line(c, c + 0.25 * f.normal))
    if not blocks:
        return None
    return pv.merge(blocks)


def grid_surface(points: np.ndarray, spacing: tuple[float, float], lux: np.ndarray):
    """The grid as a triangulated surface (Delaunay in plan) carrying ``lux`` per point."""
    # A copy: pyvista wraps the array it is given, and the grid's points are shared.
    cloud = pv.PolyData(np.array(points, dtype=float, copy=True))
    cloud.point_data["lux"] = np.asarray(lux, float)
    if len(points) < 3:
        return cloud
    # Triangles longer than 1.5 grid steps would bridge over furniture or a hole.
    alpha = 1.5 * float(np.hypot(*spacing))
    return cloud.delaunay_2d(alpha=alpha)


def draw(plotter, patches, arrays, grids=None, lux=None, fmt="{:.0f}", clim=None) -> None:
    """Draw (or clear) the luminaires of ``arrays`` and the work planes of ``grids`` with
    their illuminance ``lux`` at the points (or another value, e.g. a daylight metric:
    ``fmt`` labels the iso-lines, ``clim`` fixes the colour range)."""
    plotter.remove_actor("luminaires", render=False)
    glyphs = luminaire_glyphs(patches, arrays) if arrays else None
    if glyphs is not None:
        plotter.add_mesh(
            glyphs, name="luminaires", color=GLYPH_COLOUR, lighting=False, render=False
        )
    draw_planes(plotter, grids, lux, fmt, clim)


def draw_planes(plotter, grids, lux, fmt="{:.0f}", clim=None, cmap="inferno") -> None:
    """Draw (or clear: ``grids`` None) the work planes with a value at each grid point
    (lux by default) and iso-lines of it labelled with ``fmt``, coloured by ``cmap``
    (the difference view's: a signed one, "coolwarm")."""
    for name in NAMES[1:]:
        plotter.remove_actor(name, render=False)
    if grids is None or lux is None or not len(grids.points):
        return
    surfaces = []
    for name, span in grids.spans.items():
        surfaces.append(grid_surface(grids.points[span], grids.grids[name].spacing, lux[span]))
    plane = pv.merge(surfaces) if len(surfaces) > 1 else surfaces[0]
    plane.points[:, 2] += 0.01  # just above the plane, over the desks' tops
    plotter.add_mesh(
        plane,
        name="workplane",
        scalars="lux",
        cmap=cmap,
        opacity=0.55,
        show_scalar_bar=False,
        clim=clim,
        lighting=False,
        point_size=6,
        render_points_as_spheres=True,
        render=False,
    )
    lo, hi = float(np.min(lux)), float(np.max(lux))
    if plane.n_cells and hi > lo:
        levels = np.linspace(lo, hi, ISO_LEVELS + 2)[1:-1]
        lines = plane.contour(isosurfaces=levels, scalars="lux")
        if lines.n_points:
            plotter.add_mesh(
                lines, name="isolux", color="white", line_width=2, lighting=False, render=False
            )
            ends = lines.points[:: max(1, lines.n_points // 12)]
            labels = [
                fmt.format(v) for v in lines.point_data["lux"][:: max(1, lines.n_points // 12)]
            ]
            plotter.add_point_labels(
                ends,
                labels,
                name="isolux-labels",
                font_size=10,
                text_color="white",
                shape=None,
                show_points=False,
                always_visible=True,
                render=False,
            )
