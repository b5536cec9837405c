"""What the window calls each goal: in the Design > Goals menu, the run panel's goal
list, and on the axes of the plots (names with the units of ``GOAL_UNITS``)."""

from __future__ import annotations

from lightinv_core.kinds import GoalKind
from lightinv_core.optimize.problem import GOAL_UNITS

GOAL_TEXT = {
    GoalKind.MIN_ELECTRIC_POWER: ("Least electric power", "least electric power", "electric power"),
    GoalKind.MAX_LIGHT_POWER: (
        "Most reflected light power",
        "most light power",
        "light power",
    ),
    GoalKind.MATCH: ("Match a target lighting", "match a target lighting", "match error e"),
    GoalKind.MIN_INSTALLED_POWER: (
        "Least installed power",
        "least installed power",
        "installed power",
    ),
    GoalKind.MIN_LUMINAIRE_COUNT: ("Fewest luminaires", "fewest luminaires", "luminaires"),
    GoalKind.MIN_ANNUAL_ENERGY: (
        "Least annual lighting energy (dimming with daylight)",
        "least annual energy",
        "annual energy",
    ),
    GoalKind.MAX_SDA: (
        "Most daylight: sDA300/50% of the control work plane",
        "most daylight (sDA)",
        "sDA300/50% (fraction)",
    ),
    GoalKind.MIN_GLAZING_AREA: ("Least glazing area", "least glazing area", "glazing area"),
}
"""Per goal kind: (menu text, short name, axis name), all without units."""

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
    return GOAL_UNITS[GoalKind(kind)]


def with_units(name: str, kind: str) -> str:
    """``name (units)``, or just the name for a plain number."""
    u = units(kind)
    return f"{name} ({u})" if u else name


def menu_text(kind: str) -> str:
    """The Design > Goals entry of a goal, with its units."""
    return with_units(GOAL_TEXT[GoalKind(kind)][0], kind)


def short_name(kind: str) -> str:
    """The run panel's name of a goal."""
    return GOAL_TEXT[GoalKind(kind)][1]


def axis_label(kind: str) -> str:
    """A goal's value on a plot axis, with its units: "annual energy (kWh)"."""
    return with_units(GOAL_TEXT[GoalKind(kind)][2], kind)
