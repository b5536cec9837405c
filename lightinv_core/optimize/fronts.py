"""The two-objective fronts every front method builds: which pair of goals it trades,
and the non-dominated feasible points of a set of solutions.

Power against light power (W minimised, lm maximised) by default; the climate pair,
annual energy (kWh) against glazing area (m²), both minimised, for a design whose goals
are that pair and not both power goals.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.design.model import CORNERS, Design, Goal
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.goals import goal_spec, is_goal
from lightinv_core.kinds import GoalKind
from lightinv_core.optimize.pareto import non_dominated
from lightinv_core.sources.types import daylit

POWER, LIGHT = GoalKind.MIN_ELECTRIC_POWER, GoalKind.MAX_LIGHT_POWER
OBJECTIVES = (POWER, LIGHT)
CLIMATE = (GoalKind.MIN_ANNUAL_ENERGY, GoalKind.MIN_GLAZING_AREA)
"""The climate front: least annual energy for each bound on the glazing area."""


def design_goal(design: Design, kind: str) -> Goal:
    """The design's goal of ``kind`` (with its settings), or a plain one."""
    return next((g for g in design.goals if g.kind == kind), Goal(kind))


def design_pair(design: Design) -> tuple[str, str] | None:
    """The two goals a front of ``design`` trades (minimised or swept first, bounded
    second): power against light power when the design has both, else annual energy
    against glazing area when it has both, else its two goals in its order; None when
    it has fewer than two goals, or more than two without one of those pairs."""
    kinds = [str(g.kind) for g in design.goals]
    for pair in (OBJECTIVES, CLIMATE):
        if set(map(str, pair)) <= set(kinds):
            return tuple(map(str, pair))
    return (kinds[0], kinds[1]) if len(kinds) == 2 else None


def front_pair(design: Design) -> tuple[str, str]:
    """The two objectives a sweep trades: (minimised, bounded). The design's pair
    (``design_pair``); power against light power (the paper's front) when it has none."""
    return design_pair(design) or tuple(map(str, OBJECTIVES))


def _goal_names(design: Design) -> str:
    return ", ".join(goal_spec(g.kind).label.lower() for g in design.goals if is_goal(g.kind))


def front_refusal(design: Design, method: str = "A Pareto front") -> str | None:
    """Why ``method`` (its label) cannot make a front of ``design``'s goals, in words for
    the user; None when it can."""
    n = len(design.goals)
    if n < 2:
        have = f"one ({_goal_names(design)})" if n else "none"
        return (
            f"{method} trades two of the design's goals and this design has {have}: "
            "add a second goal (Design > Goals), or choose a method that finds one best "
            "layout"
        )
    pair = design_pair(design)
    if pair is None:
        return (
            f"{method} trades two goals and this design has {n} ({_goal_names(design)}): "
            "keep the two to trade (Design > Goals)"
        )
    for kind in pair:
        why = _constant(design, kind)
        if why:
            return f"{method} cannot trade {goal_spec(kind).label.lower()}: {why}"
    return None


def _constant(design: Design, kind: str) -> str:
    """Why goal ``kind`` cannot change (or cannot be computed) for ``design``; "" when
    it can."""
    if not is_goal(kind):
        return f"{kind!r} is not a registered goal"
    spec = goal_spec(kind)
    builtin = kind in tuple(map(str, GoalKind))
    if not builtin and spec.value is None:
        return "nothing computes its value (its goal has no value function)"
    if kind == GoalKind.MIN_GLAZING_AREA and not any(
        set(CORNERS) & set(map(str, s.free)) for s in daylit(design.sources)
    ):
        return "no skylight or glazing has free corners, so its area never changes"
    counted = (GoalKind.MIN_LUMINAIRE_COUNT, GoalKind.MIN_INSTALLED_POWER)
    if kind in counted and not any({"rows", "columns"} & set(a.free) for a in design.arrays):
        return "it changes only with a luminaire array's free rows or columns, and none has them"
    return ""


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
