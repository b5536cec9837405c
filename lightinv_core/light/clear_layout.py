"""One layout's clear light at the work-plane points from the zone cells.

When the optimiser moves a clear shape (``light.clear_cells``), the layout it reports
is judged on the cells' sum; ``layout_daylight`` (``lightinv-cli solve``, the report,
the window) reads the work plane the same way, so the figures a user sees are the ones
the optimiser judged. This module turns the cells' sum for one layout into the fixed
glazing's ``ClearLight`` (the columns as ``light.clear_build`` lays them out: a block
per clear source, then each source's closed-blinds glow), so every reader of a fixed
clear glazing reads it unchanged. The patches (the 3D view) are traced afresh at the
layout's rectangles (``light.clear_build``).
"""

from __future__ import annotations

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.light.clear_build import _blinds
from lightinv_core.light.clear_cells import ClearCells
from lightinv_core.light.clear_glazing import ClearColumns, ClearLight
from lightinv_core.light.grids import design_receivers
from lightinv_core.sources.emission import source_stack


def laid_clear(light, design: Design, sources, as_laid: Design):
    """(at the patches, at the work-plane points) the clear light of the layout
    ``sources`` of ``design`` (``as_laid``: the design with them): traced afresh at
    their rectangles (``clear_build``, cached per shape), and, once a problem has made
    the cells of a clear shape the optimiser moves, the work plane as it judged it, the
    cells' sum (the window does not trace cells for a view); (None, None) without."""
    from lightinv_core.light.clear_build import clear_light
    from lightinv_core.light.clear_cells import clear_cells

    clear = clear_light(light, as_laid)
    if clear is None:
        return None, None
    cells = clear_cells(light, design, build=False)
    if cells is not None:
        return clear.patches, layout_clear(light, design, sources, cells)
    return clear.patches, clear.points


def layout_clear(light, design: Design, sources, cells: ClearCells) -> ClearLight | None:
    """The clear light of the layout ``sources`` (the design's, as laid) at the design's
    work-plane points, summed from ``cells``; None without work planes."""
    grids = design_receivers(light, design)
    if grids is None or cells.points == 0:
        return None
    rect, _, filt = source_stack(sources)
    s = cells.shares(light, design, rect, filt)[0]
    pts = len(cells.year_rows) + np.arange(cells.points)
    G, B, H = cells.sources, cells.coef.shape[2], cells.weights.shape[1]
    coefficients = np.zeros((cells.points, G * B + G))
    direct = np.zeros((G, cells.points, H), np.float32)
    for g in range(G):
        mine = np.flatnonzero((cells.cell_source == g) & (s > 0))
        for c in mine:
            coefficients[:, g * B : (g + 1) * B] += s[c] * cells.coef[c, pts]
            coefficients[:, G * B + g] += s[c] * cells.glow[c, pts]
            direct[g] += s[c] * cells.direct[c].toarray()
    closed = _blinds(design, grids, direct, H)
    every = np.zeros((G * B + G, H), np.float32)
    blinds = np.zeros_like(every)
    over = np.zeros(G * B + G)
    K = cells.over_weights.shape[0]
    for g in range(G):
        rows = slice(g * B, (g + 1) * B)
        every[rows] = cells.weights
        blinds[rows] = every[rows] * ~closed[g]
        every[G * B + g] = cells.outside[g]
        blinds[G * B + g] = every[G * B + g] * closed[g]
        over[g * B : g * B + K] = cells.over_weights
    sun = np.concatenate([g * B + cells.sun_cols for g in range(G)])
    columns = ClearColumns(every, blinds, over, sun, closed, cells.outward)
    return ClearLight(columns, coefficients, direct)
