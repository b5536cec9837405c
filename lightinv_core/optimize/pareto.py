"""Pareto utilities: non-dominated filtering and the 2-D hypervolume."""

from __future__ import annotations

import numpy as np


def non_dominated(F: np.ndarray) -> np.ndarray:
    """Boolean mask of the rows of F (m, d) not dominated by any other row (all
    objectives minimised). Duplicated rows are all kept."""
    F = np.asarray(F, dtype=float)
    if F.ndim == 2 and F.shape[1] == 2 and len(F):
        return _non_dominated_2d(F)
    keep = np.ones(len(F), bool)
    for i in range(len(F)):
        dominated = np.all(F[i] >= F, axis=1) & np.any(F[i] > F, axis=1)
        keep[i] = not dominated.any()
    return keep


def hypervolume_2d(F: np.ndarray, ref: tuple[float, float]) -> float:
    """Area dominated by the points F (m, 2) (minimised) and bounded by ``ref``."""
    F = np.asarray(F, dtype=float)
    F = F[np.all(np.asarray(ref) > F, axis=1)]
    if len(F) == 0:
        return 0.0
    F = F[non_dominated(F)]
    F = F[np.argsort(F[:, 0])]
    area, prev_y = 0.0, ref[1]
    for x, y in F:
        if y < prev_y:
            area += (ref[0] - x) * (prev_y - y)
            prev_y = y
    return float(area)


def _non_dominated_2d(F: np.ndarray) -> np.ndarray:
    """``non_dominated`` for two objectives in O(m log m): a point is dominated when an
    earlier first objective has a second at most its own, or its own first objective
    has a smaller second."""
    first, group = np.unique(F[:, 0], return_inverse=True)
    group_min = np.full(len(first), np.inf)
    np.minimum.at(group_min, group, F[:, 1])
    before = np.r_[np.inf, np.minimum.accumulate(group_min)[:-1]]
    return ~((before[group] <= F[:, 1]) | (group_min[group] < F[:, 1]))
