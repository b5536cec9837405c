"""What the window calls each goal: in the Design > Goals menu, the run panel's goal
list, and on the axes of the plots (the names and units of its ``GoalSpec``)."""

from __future__ import annotations

from lightinv_core.goals import goal_spec
from lightinv_core.kinds import GoalKind

MENU_GOALS = (
    GoalKind.MIN_ELECTRIC_POWER,
    GoalKind.MAX_LIGHT_POWER,
    GoalKind.MIN_ANNUAL_ENERGY,
    GoalKind.MAX_SDA,
    GoalKind.MIN_GLAZING_AREA,
)
"""The goals Design > Goals and the run panel offer (match too when the design has a
target lighting)."""


def units(kind: str) -> str:
    """The units of a goal's value ("" for a plain number)."""
    return goal_spec(kind).unit


def with_units(name: str, kind: str) -> str:
    """``name (units)``, or just the name for a plain number."""
    return goal_spec(kind).with_units(name)


def menu_text(kind: str) -> str:
    """The Design > Goals entry of a goal, with its units."""
    return with_units(goal_spec(kind).menu, kind)


def short_name(kind: str) -> str:
    """The run panel's name of a goal."""
    return goal_spec(kind).short


def axis_label(kind: str) -> str:
    """A goal's value on a plot axis, with its units: "annual energy (kWh)"."""
    return with_units(goal_spec(kind).axis, kind)
