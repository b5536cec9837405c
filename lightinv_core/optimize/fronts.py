"""The two-objective fronts every front method builds: which pair of goals it trades,
and the non-dominated feasible points of a set of solutions.

Power against light power (W minimised, lm maximised) by default; the climate pair,
annual energy (kWh) against glazing area (m²), both minimised, for a design whose goals
are that pair and not both power goals.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.design.model import Design, Goal
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.goals import goal_spec
from lightinv_core.kinds import GoalKind
from lightinv_core.optimize.pareto import non_dominated

POWER, LIGHT = GoalKind.MIN_ELECTRIC_POWER, GoalKind.MAX_LIGHT_POWER
OBJECTIVES = (POWER, LIGHT)
CLIMATE = (GoalKind.MIN_ANNUAL_ENERGY, GoalKind.MIN_GLAZING_AREA)
"""The climate front: least annual energy for each bound on the glazing area."""


def design_goal(design: Design, kind: str) -> Goal:
    """The design's goal of ``kind`` (with its settings), or a plain one."""
    return next((g for g in design.goals if g.kind == kind), Goal(kind))


def front_pair(design: Design) -> tuple[GoalKind, GoalKind]:
    """The two objectives a sweep trades: (minimised, bounded). Power against light
    power, unless the design's goals are the climate pair and not both power goals."""
    kinds = {str(g.kind) for g in design.goals}
    if set(CLIMATE) <= kinds and not set(OBJECTIVES) <= kinds:
        return CLIMATE
    return OBJECTIVES


def minimised(s: Solution, kind: str) -> float:
    """Objective ``kind`` of ``s`` as minimised (negated for a maximised goal)."""
    value = s.objectives[kind]
    return -value if goal_spec(kind).maximise else value


def front_of(solutions: list[Solution], method: str, pair=OBJECTIVES) -> ParetoFront:
    """The non-dominated feasible solutions of the two objectives ``pair`` (power
    minimised and light maximised by default), each objective point once."""
    feasible = [s for s in solutions if s.feasible]
    if feasible:
        F = np.array([[minimised(s, k) for k in pair] for s in feasible])
        keep = non_dominated(F)
        # Two epsilon runs can end on the same layout (a bound below the previous
        # optimum): a front lists each point once, the first run that found it.
        _, first = np.unique(F, axis=0, return_index=True)
        keep &= np.isin(np.arange(len(F)), first)
        order = np.argsort(F[:, 0], kind="stable")
        front = tuple(feasible[i] for i in order if keep[i])
    else:
        front = ()
    return ParetoFront(tuple(map(str, pair)), front, method, tuple(solutions))
