"""Geometry of luminaire arrays: where each luminaire sits, and the arrays' rules.

Checked before any light, like the sources' rules (paper eq. 4): every array lies in
its zone with its luminaires apart (one column per array), then the ``shr`` and
``clearance`` rules (one column per array they name). Amounts are relative, 0 where a
rule holds.

An array's luminaire has a footprint (along u, along v) in metres: the product's
luminous opening, its length along the C0 plane, so a rotation of 90 degrees swaps
the two. The spacing-to-height ratio (SHR) is the spacing between neighbouring
luminaires over their mounting height above the work plane; only directions with
more than one luminaire have a spacing.

Spacing rules are on by default: an array that no ``shr`` rule names is held to
``DEFAULT_SHR`` (its own column, labelled "(default)"). An explicit ``shr`` rule
replaces it, e.g. with the SHR max of the product's data sheet.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.design.model import ARRAY_RULES, Design
from lightinv_core.design.variables import ArrayLayout
from lightinv_core.kinds import RuleKind
from lightinv_core.scene.zone_outline import outside_share

MIN_FOOTPRINT = 0.01  # m: a point-like product still needs room to be mounted
DEFAULT_SHR = 1.5
"""Spacing-to-height ratio an array keeps when no ``shr`` rule names it. The spacing
criterion (IES: "an estimated maximum ratio of the luminaire spacing to the luminaire
mounting height above the work plane for a regular array ... such that the work plane
illuminance will be acceptably uniform"; CIBSE TM5's SHR max) is a property of the
product's photometry; 1.5 is the figure the lumen-method texts use for wide
(Lambertian, batwing) ceiling luminaires. A narrow downlight needs less: give its data
sheet's value as an ``shr`` rule."""
OUTLINE_CHUNK = 1 << 20  # (candidate, luminaire, outline edge) triples checked at once


@dataclass(frozen=True)
class ArrayShapes:
    """What the array rules need beyond the layout: each array's zone ``size`` (A, 2) m,
    product ``opening`` (A, 2) as (width, length) m, and ``mount_height`` (A,) m, the
    height of its luminaires above the work plane; ``outline`` (A,) each zone's polygon
    outline (k, 2) m or None (a rectangle), empty for rectangles only."""

    size: np.ndarray
    opening: np.ndarray
    mount_height: np.ndarray
    outline: tuple = ()


@dataclass(frozen=True)
class ArrayGeometry:
    """Per candidate and array (m, A): extents of the filled rectangle (m), spacing
    along u and v (m), luminaire footprint along u and v (m)."""

    u_lo: np.ndarray
    u_hi: np.ndarray
    v_lo: np.ndarray
    v_hi: np.ndarray
    su: np.ndarray
    sv: np.ndarray
    fu: np.ndarray
    fv: np.ndarray


def array_geometry(layout: ArrayLayout, shapes: ArrayShapes) -> ArrayGeometry:
    """Spacings and footprints of candidate arrays."""
    r = layout.rect
    u_lo, u_hi = np.minimum(r[..., 0], r[..., 2]), np.maximum(r[..., 0], r[..., 2])
    v_lo, v_hi = np.minimum(r[..., 1], r[..., 3]), np.maximum(r[..., 1], r[..., 3])
    su = (u_hi - u_lo) / layout.columns
    sv = (v_hi - v_lo) / layout.rows
    width = np.maximum(shapes.opening[:, 0], MIN_FOOTPRINT)
    length = np.maximum(shapes.opening[:, 1], MIN_FOOTPRINT)
    turned = layout.rotation == 90
    fu = np.where(turned, width, length)
    fv = np.where(turned, length, width)
    return ArrayGeometry(u_lo, u_hi, v_lo, v_hi, su, sv, fu, fv)


def luminaire_positions(layout: ArrayLayout, j: int) -> tuple[np.ndarray, np.ndarray]:
    """Zone coordinates of array ``j``'s luminaires in each candidate: (u, v) each
    (m, P) m with P = the most luminaires any candidate has, and a mask (m, P) of the
    ones that exist (row by row)."""
    rows, cols = layout.rows[:, j], layout.columns[:, j]
    pmax_r, pmax_c = int(rows.max()), int(cols.max())
    r = layout.rect[:, j]
    u_lo, u_hi = np.minimum(r[:, 0], r[:, 2]), np.maximum(r[:, 0], r[:, 2])
    v_lo, v_hi = np.minimum(r[:, 1], r[:, 3]), np.maximum(r[:, 1], r[:, 3])
    ci = np.arange(pmax_c) + 0.5
    ri = np.arange(pmax_r) + 0.5
    u = u_lo[:, None] + ci[None] * ((u_hi - u_lo) / cols)[:, None]  # (m, C)
    v = v_lo[:, None] + ri[None] * ((v_hi - v_lo) / rows)[:, None]  # (m, R)
    U = np.broadcast_to(u[:, None, :], (len(rows), pmax_r, pmax_c))
    V = np.broadcast_to(v[:, :, None], (len(rows), pmax_r, pmax_c))
    mask = (np.arange(pmax_r)[None, :, None] < rows[:, None, None]) & (
        np.arange(pmax_c)[None, None, :] < cols[:, None, None]
    )
    m = len(rows)
    return U.reshape(m, -1), V.reshape(m, -1), mask.reshape(m, -1)


def _outside_outline(outline: np.ndarray, layout: ArrayLayout, g: ArrayGeometry, j: int):
    """(m,) the share of array ``j``'s luminaire footprints outside the zone's polygon
    outline, summed over its luminaires (each 0 to 1), less a rounding tolerance."""
    u, v, mask = luminaire_positions(layout, j)
    hu, hv = 0.5 * g.fu[:, j : j + 1], 0.5 * g.fv[:, j : j + 1]
    out = np.zeros(len(u))
    # In slices: the check holds (candidates, luminaires, outline edges) at once.
    step = max(1, OUTLINE_CHUNK // max(1, u.shape[1] * len(outline)))
    for a in range(0, len(u), step):
        s = slice(a, a + step)
        rect = np.stack(
            np.broadcast_arrays(u[s] - hu[s], v[s] - hv[s], u[s] + hu[s], v[s] + hv[s]), axis=-1
        )
        out[s] = (outside_share(outline, rect) * mask[s]).sum(axis=1)
    return out


def default_shr_arrays(design: Design) -> list[str]:
    """Names of the arrays no ``shr`` rule names: they keep ``DEFAULT_SHR``."""
    named = {a for r in design.rules if r.kind == RuleKind.SHR for a in r.sources}
    return [a.name for a in design.arrays if a.name not in named]


def array_rule_names(design: Design) -> list[str]:
    """Labels of the array columns of ``rule_violations``, in order."""
    names = [f"array {a.name} in its zone" for a in design.arrays]
    for r in design.rules:
        if r.kind in ARRAY_RULES:
            names += [f"{r.kind} {a}" for a in r.sources]
    names += [f"shr {a} (default {DEFAULT_SHR:g})" for a in default_shr_arrays(design)]
    return names


def _shr_excess(layout: ArrayLayout, g: ArrayGeometry, shapes: ArrayShapes, j: int, most: float):
    """(m,) relative excess of array ``j``'s spacing-to-height ratio over ``most``."""
    s = np.maximum(
        np.where(layout.columns[:, j] > 1, g.su[:, j], 0.0),
        np.where(layout.rows[:, j] > 1, g.sv[:, j], 0.0),
    )
    ratio = s / max(float(shapes.mount_height[j]), 1e-9)
    return np.maximum(0, ratio - most) / most


def array_violations(design: Design, layout: ArrayLayout, shapes: ArrayShapes) -> np.ndarray:
    """(m, R) relative violations of the array columns (see ``array_rule_names``)."""
    g = array_geometry(layout, shapes)
    w, h = shapes.size[:, 0], shapes.size[:, 1]
    # Outermost openings' edges: half a spacing in from the rectangle, half a footprint out.
    left = g.u_lo + 0.5 * g.su - 0.5 * g.fu
    right = w - (g.u_hi - 0.5 * g.su + 0.5 * g.fu)
    low = g.v_lo + 0.5 * g.sv - 0.5 * g.fv
    high = h - (g.v_hi - 0.5 * g.sv + 0.5 * g.fv)
    clear = np.minimum(np.minimum(left, right), np.minimum(low, high))
    # Neighbours must not overlap: spacing at least the footprint where there are two.
    overlap_u = np.where(layout.columns > 1, np.maximum(0, g.fu - g.su) / g.fu, 0.0)
    overlap_v = np.where(layout.rows > 1, np.maximum(0, g.fv - g.sv) / g.fv, 0.0)
    out = [np.maximum(0, -clear) / np.maximum(w, h) + overlap_u + overlap_v]
    for j, outline in enumerate(shapes.outline):
        if outline is not None:
            out[0][:, j] += _outside_outline(outline, layout, g, j)
    names = [a.name for a in design.arrays]
    for r in design.rules:
        if r.kind not in ARRAY_RULES:
            continue
        for a in r.sources:
            j = names.index(a)
            if r.kind == RuleKind.SHR:
                out.append(_shr_excess(layout, g, shapes, j, r.max))
            else:
                need = max(r.min, 1e-3)
                out.append(np.maximum(0, r.min - clear[:, j]) / need)
    for a in default_shr_arrays(design):
        out.append(_shr_excess(layout, g, shapes, names.index(a), DEFAULT_SHR))
    return np.column_stack(out)  # the first entry is (m, A): one column per array
