"""Catmull-Rom interpolation over a line of lattice nodes: the weights of the four
nodes around a point and the taps that extrapolate past the line's ends
(``light.arrays``' luminaire lattices blend precomputed responses with them)."""

from __future__ import annotations

import numpy as np


def catmull_rom(t: np.ndarray) -> tuple[np.ndarray, ...]:
    """Weights of the nodes at -1, 0, 1, 2 for a point ``t`` in [0, 1] past node 0: the
    Catmull-Rom cubic, exact for quadratics (its error falls as the step to the fourth
    power, the bilinear blend's only as its square)."""
    t2, t3 = t * t, t * t * t
    return (
        0.5 * (-t3 + 2 * t2 - t),
        0.5 * (3 * t3 - 5 * t2 + 2),
        0.5 * (-3 * t3 + 4 * t2 + t),
        0.5 * (t3 - t2),
    )


def taps(i0: np.ndarray, weights: tuple, n: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """(node index, weight) pairs of the four Catmull-Rom taps around ``i0`` on a line of
    ``n`` nodes; a tap past an end is the straight-line extrapolation of the last two
    nodes (2 R[0] - R[1]), so the blend stays exact for linear changes up to the edge."""
    out = []
    for d, w in zip((-1, 0, 1, 2), weights, strict=True):
        i = i0 + d
        low, high = i < 0, i > n - 1
        inside = np.clip(i, 0, n - 1)
        out.append((inside, np.where(low | high, 2.0 * w, w)))
        # The extrapolation's second node carries -w.
        out.append((np.where(low, 1, np.where(high, n - 2, inside)), np.where(low | high, -w, 0.0)))
    return out
