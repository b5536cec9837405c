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

A climate front (annual energy E in kWh against glazing area A in m², both minimised;
``fronts.front_pair``) is measured the same way in (E/E_max, A/A_max) with reference
point (1, 1): E_max the energy of every luminaire at full output all year, A_max the
area of the skylights' zones. Any other pair of goals likewise: each goal divided by
the scale the optimiser gives it, the reference 1 for a minimised goal and 0 for a
maximised one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.design.solution import Solution
from lightinv_core.goals import goal_spec
from lightinv_core.kinds import GoalKind
from lightinv_core.light.arrays import resolve_product
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.fronts import CLIMATE, OBJECTIVES, front_pair
from lightinv_core.optimize.objectives import (
    count_scale,
    electric_scale,
    energy_scale,
    glazing_scale,
    light_power_kinds,
)
from lightinv_core.optimize.pareto import hypervolume_2d

POWER, LIGHT = (str(k) for k in OBJECTIVES)
REFERENCE = (1.0, 0.0)
"""Reference point in (P/P_max, L/L_max): full electric power and no light."""


def _reference(pair) -> tuple[float, float]:
    """The reference point of ``pair`` in normalised values: 1 for a minimised
    objective (its largest value), 0 for a maximised one (none of it)."""
    return tuple(0.0 if goal_spec(k).maximise else 1.0 for k in pair)


@dataclass(frozen=True)
class FrontQuality:
    """``hypervolume`` (0..1) and ``spacing`` (None below two points) of ``points``
    front points of the two ``objectives``, normalised by ``scales`` (their units)."""

    hypervolume: float
    spacing: float | None
    points: int
    scales: tuple[float, float]
    objectives: tuple[str, str] = tuple(map(str, OBJECTIVES))

    def to_dict(self) -> dict:
        """Plain data for JSON output."""
        return {
            "hypervolume": self.hypervolume,
            "spacing": self.spacing,
            "points": self.points,
            "objectives": list(self.objectives),
            "scales": list(self.scales),
            "reference": list(_reference(self.objectives)),
        }


def front_scales(design: Design, light: LightModel, pair=None) -> tuple[float, float]:
    """The normalisation of a front of ``design``'s goals ``pair`` (default: its
    ``front_pair``): each goal's size, (P_max in W, L_max in lm) for power against light,
    (E_max in kWh, A_max in m²) for the climate pair; a goal of another pair by the
    scale the optimiser gives it."""
    pair = tuple(map(str, pair or front_pair(design)))
    # The arrays' products count towards the scales, as the optimiser's own.
    products = [resolve_product(a.product, a.watts) for a in design.arrays]
    builtin = {
        POWER: lambda: electric_scale(design, light, products),
        LIGHT: lambda: light.power_scale(
            [s for s in design.sources if s.kind in light_power_kinds(design)], design.daylight
        ),
        str(GoalKind.MIN_ANNUAL_ENERGY): lambda: energy_scale(design, light, products),
        str(GoalKind.MIN_GLAZING_AREA): lambda: glazing_scale(design, light),
        str(GoalKind.MIN_INSTALLED_POWER): lambda: electric_scale(design, light, products),
        str(GoalKind.MIN_LUMINAIRE_COUNT): lambda: count_scale(design),
        str(GoalKind.MAX_SDA): lambda: 1.0,
        str(GoalKind.MATCH): lambda: 1.0,
    }
    if all(k in builtin for k in pair):
        return builtin[pair[0]](), builtin[pair[1]]()
    # A registered goal's scale reads the problem (``GoalSpec.scale``).
    from lightinv_core.optimize.problem import DesignProblem

    scales = DesignProblem(design, light).scales
    return tuple(builtin[k]() if k in builtin else float(scales[k]) for k in pair)


def normalised(F: np.ndarray, scales: tuple[float, float], pair=OBJECTIVES) -> np.ndarray:
    """Rows of the two objectives ``pair`` (default P in W, L in lm) as minimised
    normalised points (P/P_max, -L/L_max)."""
    F = np.asarray(F, dtype=float).reshape(-1, 2)
    sign = [-1.0 if goal_spec(k).maximise else 1.0 for k in pair]
    return np.column_stack([sign[0] * F[:, 0] / scales[0], sign[1] * F[:, 1] / scales[1]])


def hypervolume(F: np.ndarray, scales: tuple[float, float], pair=OBJECTIVES) -> float:
    """Hypervolume of the points F (default (P, L) in W, lm) in the normalised plane."""
    ref = _reference(pair)
    sign = [-1.0 if goal_spec(k).maximise else 1.0 for k in pair]
    return hypervolume_2d(normalised(F, scales, pair), (sign[0] * ref[0], sign[1] * ref[1]))


def spacing(F: np.ndarray, scales: tuple[float, float], pair=OBJECTIVES) -> float | None:
    """Schott's spacing of the points F (default (P, L) in W, lm), normalised; None
    below 2 points."""
    Z = normalised(F, scales, pair)
    if len(Z) < 2:
        return None
    D = np.abs(Z[:, None, :] - Z[None, :, :]).sum(axis=2)
    np.fill_diagonal(D, np.inf)
    d = D.min(axis=1)
    return float(np.sqrt(np.sum((d - d.mean()) ** 2) / (len(d) - 1)))


def front_quality(
    solutions: Sequence[Solution], scales: tuple[float, float], pair=None
) -> FrontQuality:
    """Hypervolume and spacing of a front's solutions in its two objectives ``pair``
    (default: power and light, or the climate pair when the solutions have no power and
    light objectives), normalised by ``scales`` (``front_scales`` of the same pair)."""
    if pair is None:
        climate = bool(solutions) and all(
            POWER not in s.objectives and all(str(k) in s.objectives for k in CLIMATE)
            for s in solutions
        )
        pair = CLIMATE if climate else OBJECTIVES
    pair = tuple(map(str, pair))
    F = np.array([[s.objectives[k] for k in pair] for s in solutions]).reshape(-1, 2)
    return FrontQuality(
        hypervolume(F, scales, pair), spacing(F, scales, pair), len(F), tuple(scales), pair
    )
