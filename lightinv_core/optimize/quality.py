"""How good a Pareto front is: hypervolume and spacing in normalised objectives.

Both fronts' objectives are electric power P (W, minimised) and reflected light power L
(lm, maximised). They are normalised by the design's own scales (``front_scales``):
P by the electric power of every luminaire covering its zone at its largest setting,
L by the light power of every source covering its zone at its largest exitance (the
scales the optimizer uses). The hypervolume is the area dominated in (P/P_max, L/L_max)
between the front and the reference point (1, 0), full power and no light: 0 for an
empty front, at most 1. The spacing (Schott 1995) is the standard deviation of each
point's L1 distance to its nearest neighbour in the same normalised plane: 0 for evenly
spread points; undefined (None) below two points.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.design.solution import Solution
from lightinv_core.kinds import GoalKind, SourceKind
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.pareto import hypervolume_2d
from lightinv_core.optimize.problem import electric_scale

POWER, LIGHT = str(GoalKind.MIN_ELECTRIC_POWER), str(GoalKind.MAX_LIGHT_POWER)
REFERENCE = (1.0, 0.0)
"""Reference point in (P/P_max, L/L_max): full electric power and no light."""


@dataclass(frozen=True)
class FrontQuality:
    """``hypervolume`` (0..1) and ``spacing`` (None below two points) of ``points``
    front points, normalised by ``power_scale`` (W) and ``light_scale`` (lm)."""

    hypervolume: float
    spacing: float | None
    points: int
    power_scale: float
    light_scale: float

    def to_dict(self) -> dict:
        """Plain data for JSON output."""
        return {
            "hypervolume": self.hypervolume,
            "spacing": self.spacing,
            "points": self.points,
            "power_scale_W": self.power_scale,
            "light_scale_lm": self.light_scale,
            "reference": list(REFERENCE),
        }


def front_scales(design: Design, light: LightModel) -> tuple[float, float]:
    """(P_max in W, L_max in lm): the normalisation of a front of ``design``."""
    goal = next((g for g in design.goals if g.kind == GoalKind.MAX_LIGHT_POWER), None)
    kinds = (goal.kinds if goal else ()) or tuple(SourceKind)
    counted = [s for s in design.sources if s.kind in kinds]
    return electric_scale(design, light), light.power_scale(counted, design.daylight)


def normalised(F: np.ndarray, scales: tuple[float, float]) -> np.ndarray:
    """(P, L) rows in W and lm as minimised normalised points (P/P_max, -L/L_max)."""
    F = np.asarray(F, dtype=float).reshape(-1, 2)
    return np.column_stack([F[:, 0] / scales[0], -F[:, 1] / scales[1]])


def hypervolume(F: np.ndarray, scales: tuple[float, float]) -> float:
    """Hypervolume of the (P, L) points F (W, lm) in the normalised plane (0..1)."""
    return hypervolume_2d(normalised(F, scales), (REFERENCE[0], -REFERENCE[1]))


def spacing(F: np.ndarray, scales: tuple[float, float]) -> float | None:
    """Schott's spacing of the (P, L) points F (W, lm), normalised; None below 2 points."""
    Z = normalised(F, scales)
    if len(Z) < 2:
        return None
    D = np.abs(Z[:, None, :] - Z[None, :, :]).sum(axis=2)
    np.fill_diagonal(D, np.inf)
    d = D.min(axis=1)
    return float(np.sqrt(np.sum((d - d.mean()) ** 2) / (len(d) - 1)))


def front_quality(solutions: Sequence[Solution], scales: tuple[float, float]) -> FrontQuality:
    """Hypervolume and spacing of a front's solutions (their P and L objectives)."""
    F = np.array([[s.objectives[POWER], s.objectives[LIGHT]] for s in solutions]).reshape(-1, 2)
    return FrontQuality(hypervolume(F, scales), spacing(F, scales), len(F), *scales)
