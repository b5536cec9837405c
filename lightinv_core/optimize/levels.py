"""The receivers of a multilevel stage: about n/d representative patches and the grids.

A ``Level`` lists the patches the search reads at divisor d (one representative per
cluster of about d patches, standing for the cluster's area), where each intention and
the match goal find theirs among them, and every work-plane grid point after them.
``build_level`` makes one from the clusters and Phi's rows kept with the operator
(``level_cache.py``: a second run on the same operator builds neither);
``DesignProblem.level`` keeps each divisor's.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.light.arrays import ArrayLight
from lightinv_core.light.grids import DesignGrids
from lightinv_core.light.model import LightModel, Receivers
from lightinv_core.optimize.level_cache import cluster_labels, receivers
from lightinv_core.scene.patches import Patches


@dataclass(frozen=True)
class Level:
    """Receivers of one multilevel stage (divisor d: about n/d representative patches).

    ``rows`` are patch ids; ``intent_pos[i]`` indexes the receivers for intention i and
    ``intent_w[i]`` holds the area each representative stands for (1 per grid point);
    ``match_pos`` indexes the representatives of all patches (match goal). The
    receivers are the ``rows`` then every work-plane grid point; ``arrays_R`` holds the
    luminaire arrays' responses at them (None without arrays).
    """

    divisor: int
    receivers: Receivers
    intent_pos: tuple[np.ndarray, ...]
    intent_w: tuple[np.ndarray, ...]
    match_pos: np.ndarray
    arrays_R: np.ndarray | None = None

    @property
    def rows(self) -> np.ndarray:
        """Patch ids of the representatives."""
        return self.receivers.rows


class LevelSource(Protocol):
    """What ``build_level`` reads of its problem (``DesignProblem``)."""

    design: Design
    light: LightModel
    patches: Patches
    grids: DesignGrids | None
    intent_sets: list
    match: object

    @property
    def arrays(self) -> ArrayLight | None: ...


def representatives(patches: Patches, idx: np.ndarray, labels: np.ndarray):
    """For the patches ``idx``: one representative per cluster (the member nearest the
    members' mean centroid) and the area it stands for."""
    lab = labels[idx]
    order = np.argsort(lab, kind="stable")
    idx, lab = idx[order], lab[order]
    starts = np.flatnonzero(np.r_[True, lab[1:] != lab[:-1]])
    area = patches.area[idx]
    c = patches.centroid[idx]
    sums = np.add.reduceat(c * area[:, None], starts, axis=0)
    tot = np.add.reduceat(area, starts)
    mean = sums / tot[:, None]
    group = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, len(idx)]))
    d = np.linalg.norm(c - mean[group], axis=1)
    best = np.lexsort((d, group))
    first = best[np.r_[True, group[best][1:] != group[best][:-1]]]
    return idx[first], tot


def build_level(problem: LevelSource, divisor: int) -> Level:
    """The representative receivers of ``problem`` for divisor d (1 = every patch)."""
    patches = problem.patches
    n = patches.n
    coarse = divisor > 1
    # The clusters and Phi's rows are the costly parts: kept with the operator.
    labels = cluster_labels(problem.light, max(1, n // divisor)) if coarse else np.arange(n)
    sets = [s for s in problem.intent_sets if s is not None]
    if problem.match is not None:
        sets.append(np.arange(n))
    reps = [representatives(patches, s, labels) for s in sets]
    rows = np.unique(np.concatenate([r for r, _ in reps])) if reps else np.zeros(0, int)
    patch_pos = [np.searchsorted(rows, r) for r, _ in reps]
    match_pos = patch_pos.pop() if problem.match is not None else np.zeros(0, int)
    patch_w = [w for _, w in reps][: len(patch_pos)]
    pos, weights = [], []
    for it in problem.design.intentions:
        if it.grid is None:
            pos.append(patch_pos.pop(0))
            weights.append(patch_w.pop(0))
        else:
            span = problem.grids.span(it.grid)
            pos.append(len(rows) + np.arange(span.start, span.stop))
            weights.append(np.ones(span.stop - span.start))
    got = receivers(problem.light, rows)
    grids = problem.grids
    if grids is not None and len(grids.points):
        top = got.Phi_rows
        if top is None:  # over the basis budget: the rows from the factors, once
            top = problem.light.op.phi_rows(rows)
        got = Receivers(rows, np.asfortranarray(np.vstack([top, grids.Phi])))
    arrays_R = None
    arrays = problem.arrays
    if arrays is not None:
        at = np.searchsorted(arrays.rows, rows)
        q = arrays.n_points
        idx = np.concatenate([at, len(arrays.rows) + np.arange(q)])
        arrays_R = np.ascontiguousarray(arrays.R[idx])
    return Level(divisor, got, tuple(pos), tuple(weights), match_pos, arrays_R)
