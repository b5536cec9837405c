"""Geometric rules checked before any radiosity (paper eq. 4, the c_i^NoRad).

``rule_violations`` returns, for a stack of candidates, the relative amount by
which each rule is broken (0 where it holds); a candidate with any positive
amount is rejected without a radiosity evaluation. Every source must also lie
inside its zone (and inside the zone's polygon outline, if it has one) and have a
positive area. ``mirror`` and ``centred`` rules are
tied by the variables (see variables.py) and so always hold.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from lightinv_core.design.arrays import ArrayShapes, array_rule_names, array_violations
from lightinv_core.design.model import ARRAY_RULES, Design
from lightinv_core.design.variables import ArrayLayout
from lightinv_core.scene.zone_outline import outside_share

ALIGN_TOL = 0.01  # m
MIN_SIDE = 1e-3  # m: a thinner source is degenerate


def _extents(rect: np.ndarray) -> tuple[np.ndarray, ...]:
    """(u_lo, u_hi, v_lo, v_hi) arrays of shape (m, S)."""
    u_lo = np.minimum(rect[..., 0], rect[..., 2])
    u_hi = np.maximum(rect[..., 0], rect[..., 2])
    v_lo = np.minimum(rect[..., 1], rect[..., 3])
    v_hi = np.maximum(rect[..., 1], rect[..., 3])
    return u_lo, u_hi, v_lo, v_hi


def rule_names(design: Design) -> list[str]:
    """One label per checked rule, in the column order of ``rule_violations``."""
    names = ["inside zone and non-degenerate"]
    for r in design.rules:
        if r.kind in ("mirror", "centred", *ARRAY_RULES):
            continue
        for s in r.sources if r.kind in ("area", "aspect") else [",".join(r.sources)]:
            names.append(f"{r.kind} {s}")
    return names + array_rule_names(design)


def rule_violations(
    design: Design,
    rect: np.ndarray,
    zone_size: np.ndarray,
    arrays: tuple[ArrayLayout, ArrayShapes] | None = None,
    outlines: Sequence[np.ndarray | None] = (),
) -> np.ndarray:
    """(m, R) relative violations of the geometric rules for rectangles (m, S, 4).

    zone_size : (S, 2) width and height (m) of each source's zone.
    arrays : the candidates' luminaire arrays and their shapes; needed when the design
    has arrays (their columns come last, see ``design/arrays.py``).
    outlines : per source, its zone's polygon outline (k, 2) m, or None (or nothing)
    where the zone is its whole rectangle; a source must then lie inside the polygon,
    the share of its area outside counting in the first column.
    """
    names = [s.name for s in design.sources]
    u_lo, u_hi, v_lo, v_hi = _extents(rect)
    w, h = u_hi - u_lo, v_hi - v_lo
    area = w * h
    out = []
    outside = (
        np.maximum(0, -u_lo)
        + np.maximum(0, u_hi - zone_size[:, 0])
        + np.maximum(0, -v_lo)
        + np.maximum(0, v_hi - zone_size[:, 1])
    )
    thin = np.maximum(0, MIN_SIDE - np.minimum(w, h)) / MIN_SIDE
    for i, outline in enumerate(outlines):
        if outline is not None:
            thin[:, i] += outside_share(outline, rect[:, i])
    scale = zone_size.max() if zone_size.size else 1.0
    out.append((outside / scale + thin).sum(axis=1))
    for r in design.rules:
        if r.kind in ARRAY_RULES:
            continue
        idx = [names.index(s) for s in r.sources]
        if r.kind == "area":
            for i in idx:
                v = np.zeros(len(rect))
                if r.min is not None and r.min > 0:
                    v += np.maximum(0, r.min - area[:, i]) / r.min
                if r.max is not None:
                    v += np.maximum(0, area[:, i] - r.max) / max(r.max, 1e-12)
                out.append(v)
        elif r.kind == "aspect":
            for i in idx:
                ratio = np.maximum(w[:, i], h[:, i]) / np.maximum(
                    np.minimum(w[:, i], h[:, i]), 1e-12
                )
                out.append(np.maximum(0, ratio - r.max) / r.max)
        elif r.kind == "spacing":
            a, b = idx
            gu = np.maximum(u_lo[:, a], u_lo[:, b]) - np.minimum(u_hi[:, a], u_hi[:, b])
            gv = np.maximum(v_lo[:, a], v_lo[:, b]) - np.minimum(v_hi[:, a], v_hi[:, b])
            gap = np.where((gu > 0) & (gv > 0), np.hypot(gu, gv), np.maximum(gu, gv))
            out.append(np.maximum(0, r.min - gap) / max(r.min, 1e-12))
        elif r.kind == "align":
            # Aligned along u: on one line parallel to u, so the v centres agree.
            lo, hi = (v_lo, v_hi) if r.axis == "u" else (u_lo, u_hi)
            centre = 0.5 * (lo[:, idx] + hi[:, idx])
            spread = centre.max(axis=1) - centre.min(axis=1)
            out.append(np.maximum(0, spread - ALIGN_TOL) / ALIGN_TOL)
    G = np.stack(out, axis=1)
    if not design.arrays:
        return G
    if arrays is None:
        raise ValueError("the design has luminaire arrays: give their layout and shapes")
    return np.hstack([G, array_violations(design, *arrays)])
