"""Lighting intentions judged on a light field: which patches, what values, how far off.

One set of formulas serves the optimizer (batches of candidates at representative
patches, each standing for an area), the window, the report and the CLI (one layout on
every patch, each standing for its own area):

- an intention's quantity q at its patches: illuminance H (lux) or C = rho * H (lm/m²);
- its statistics over them: min, max, area-weighted average, U0 = min / average;
- one relative violation c per bound it sets (0.05 = 5% past the bound):
  min: (min - q_min) / min, max: (q_max - max) / max, average: (average - q_avg) /
  average, uniformity: (U0_req - U0) / U0_req, max_average: (q_avg - max_average) /
  max_average (0.1 past a bound of 0). A bound of 0 on min, average or
  uniformity bounds nothing and is skipped.

A bound is met when c <= ``FEASIBILITY_TOL`` (0.1%).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lightinv_core.design.model import Intention
from lightinv_core.errors import DesignError
from lightinv_core.kinds import Bound
from lightinv_core.quantities import quantity_spec
from lightinv_core.scene.patches import Patches

FEASIBILITY_TOL = 1e-3
"""Relative precision to which a bound counts as met."""
ROUNDING_SLACK = 1e-6
"""How much more one layout judged alone may break a bound than the search allowed
(``JUDGED_TOL`` = ``FEASIBILITY_TOL`` + this). A search lights candidates in batches and
a single layout alone; the float32 sums run in another order, and a layout found on a
bound (as CMA-ES converges, exactly on it) came out 2.5e-9 over it alone (office demo).
A layout the search found feasible must be judged feasible."""
JUDGED_TOL = FEASIBILITY_TOL + ROUNDING_SLACK


@dataclass(frozen=True)
class IntentionStats:
    """Statistics of an intention's quantity over its patches, one value per candidate
    (arrays (m,)): in lux, or lm/m² for quantity C; ``uniformity`` is min / average."""

    min: np.ndarray
    max: np.ndarray
    average: np.ndarray
    uniformity: np.ndarray


class BoundCheck(NamedTuple):
    """One bound of one intention: the required ``limit``, the achieved ``value`` and the
    relative violation ``c`` (arrays (m,)); ``units`` of value and limit. (A named
    tuple: the optimizer makes several per batch.)"""

    intention: Intention
    bound: Bound
    limit: float
    value: np.ndarray
    c: np.ndarray
    units: str

    @property
    def met(self) -> np.ndarray:
        """Whether the bound holds to within ``JUDGED_TOL``, per candidate."""
        return self.c <= JUDGED_TOL


def intention_patches(intention: Intention, patches: Patches) -> np.ndarray:
    """The sorted patch ids an intention bounds: its group, every patch (``"*"``) or its
    listed patches; DesignError naming the intention when they are not in the scene."""
    if intention.grid is not None:
        raise DesignError(
            f"intention {intention.name!r} bounds work plane {intention.grid!r}'s grid "
            "points, not patches"
        )
    if intention.patches is not None:
        idx = np.asarray(intention.patches, dtype=np.int64)
        bad = idx[(idx < 0) | (idx >= patches.n)]
        if len(bad):
            raise DesignError(
                f"intention {intention.name!r}: patch id {int(bad[0])} is not in the scene "
                f"(ids 0..{patches.n - 1}); pick the patches again on this mesh"
            )
        return np.unique(idx)
    if intention.group == "*":
        return np.arange(patches.n)
    if intention.group not in patches.group_names:
        known = ", ".join(patches.group_names)
        raise DesignError(
            f"intention {intention.name!r}: no group {intention.group!r} in the scene "
            f"(groups: {known})"
        )
    return patches.group_index(intention.group)


def quantity_values(intention: Intention, H: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """The intention's quantity (float64) from illuminance H (p,) or (p, m) in lux at
    patches of reflectance ``rho`` (p,): H itself, or C = rho * H."""
    return quantity_spec(intention.quantity).from_lux(np.asarray(H).astype(np.float64), rho)


def intention_stats(q: np.ndarray, weights: np.ndarray) -> IntentionStats:
    """Statistics of q (p, m) over p patches standing for ``weights`` (p,) m² each."""
    w = weights[:, None]
    avg = (q * w).sum(axis=0) / w.sum()
    qmin, qmax = q.min(axis=0), q.max(axis=0)
    return IntentionStats(qmin, qmax, avg, qmin / np.maximum(avg, 1e-30))


@functools.lru_cache(maxsize=1024)
def bounds_set(intention: Intention) -> tuple[Bound, ...]:
    """The bounds an intention sets, in the order min, max, average, uniformity,
    max_average."""
    it = intention
    return tuple(
        b
        for b, on in (
            (Bound.MIN, it.min is not None and it.min > 0),
            (Bound.MAX, it.max is not None),
            (Bound.AVERAGE, it.average is not None and it.average > 0),
            (Bound.UNIFORMITY, it.uniformity is not None and it.uniformity > 0),
            (Bound.MAX_AVERAGE, it.max_average is not None),
        )
        if on
    )


def bound_checks(intention: Intention, stats: IntentionStats) -> list[BoundCheck]:
    """The checks of the bounds the intention sets (``bounds_set`` order)."""
    it, units = intention, quantity_spec(intention.quantity).unit
    out = []
    for b in bounds_set(it):
        if b == Bound.MIN:
            c, value = (it.min - stats.min) / it.min, stats.min
        elif b == Bound.MAX:
            c, value = (stats.max - it.max) / max(it.max, 1e-12), stats.max
        elif b == Bound.AVERAGE:
            c, value = (it.average - stats.average) / it.average, stats.average
        elif b == Bound.MAX_AVERAGE:
            c = (stats.average - it.max_average) / max(it.max_average, 1e-12)
            value = stats.average
        else:
            c, value = (it.uniformity - stats.uniformity) / it.uniformity, stats.uniformity
        limit = getattr(it, str(b))
        out.append(BoundCheck(it, b, limit, value, c, "" if b == Bound.UNIFORMITY else units))
    return out


def offending(check: BoundCheck, q: np.ndarray, average: float) -> np.ndarray:
    """Mask of the patches (q (p,) for one candidate) that break ``check``: below a min,
    above a max, below U0 x the average; every patch for a short average, those above
    the bound for a mean too high."""
    if check.bound == Bound.MIN:
        return q < check.limit
    if check.bound in (Bound.MAX, Bound.MAX_AVERAGE):
        return q > check.limit
    if check.bound == Bound.UNIFORMITY:
        return q < check.limit * average
    return np.ones(len(q), bool)
