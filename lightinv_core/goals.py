"""The goals a design can optimise: one ``GoalSpec`` per goal kind, in one registry.

A spec says everything a view or the optimiser asks of a goal: its names for people
(the report's label, the window's menu entry, short name and plot axis), its unit, how
its value is written (the CLI's front lines, the labels of epsilon and front results),
whether it is maximised or needs the weather year, and, for a goal the problem does not
compute itself, its batch value and scale. The CLI, the report, the editing model and
the window look goals up here (``goal_spec``) and never branch on a kind; a new goal is
one ``register_goal`` call (tests/core/test_extension_points.py does it from a test).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from lightinv_core.kinds import GoalKind


@dataclass(frozen=True)
class GoalSpec:
    """One goal kind.

    ``kind``: its name in project files. ``label``: the report's name ("Electric
    power"); ``menu``, ``short``, ``axis``: the window's menu entry, run-panel name and
    plot-axis name, all without units; ``unit`` ("" for a plain number).
    ``text_format``: its value on a line of the CLI's front (``str.format`` of the value
    times ``text_factor``; default: 9 wide, one decimal, then the unit).
    ``bound_format``: the label of an epsilon-constraint result whose bound is on this
    goal ("{:,.0f} lm"); ``result_format``: the label of a front member a front method
    (NSGA-II) found, by this goal's value (None: not labelled by it).
    ``maximise``: maximised (else minimised); ``annual``: needs the weather year and a
    control work plane.
    ``value(batch) -> (m,)`` and ``scale(problem) -> float``: for a goal the problem does
    not compute itself, its value for a batch of candidates (``optimize.objectives.GoalBatch``)
    and the size of its value that scales it to about [0, 1] as a primary goal.
    """

    kind: str
    label: str
    menu: str
    short: str
    axis: str
    unit: str = ""
    text_format: str | None = None
    text_factor: float = 1.0
    bound_format: str | None = None
    result_format: str | None = None
    maximise: bool = False
    annual: bool = False
    value: Callable[[Any], Any] | None = None
    scale: Callable[[Any], float] | None = None

    def value_text(self, value: float) -> str:
        """The value with its unit as the CLI's front lines write it."""
        form = self.text_format or ("{:9.1f} " + self.unit)
        return form.format(self.text_factor * value).rstrip()

    def with_units(self, name: str) -> str:
        """``name (unit)``, or just the name for a plain number."""
        return f"{name} ({self.unit})" if self.unit else name


_GOALS: dict[str, GoalSpec] = {}


def register_goal(spec: GoalSpec) -> GoalSpec:
    """Add a goal kind (ValueError when its kind is taken); returns the spec."""
    if spec.kind in _GOALS:
        raise ValueError(f"goal {spec.kind!r} is already registered")
    _GOALS[spec.kind] = spec
    return spec


def unregister_goal(kind: str) -> None:
    """Remove a goal added by ``register_goal`` (the built-in goals stay)."""
    if kind in tuple(GoalKind):
        raise ValueError(f"goal {kind!r} is built in")
    _GOALS.pop(kind, None)


def goal_spec(kind: str) -> GoalSpec:
    """The spec of a goal kind (KeyError naming the known kinds when unknown)."""
    try:
        return _GOALS[str(kind)]
    except KeyError:
        raise KeyError(f"goal {kind!r} is not one of {goal_names()}") from None


def goal_specs() -> Iterator[GoalSpec]:
    """Every goal, the built-in ones first in ``GoalKind`` order."""
    return iter(tuple(_GOALS.values()))


def goal_names() -> tuple[str, ...]:
    """Every goal kind's name, in registry order."""
    return tuple(str(k) for k in _GOALS)


def is_goal(kind: object) -> bool:
    """Whether ``kind`` names a registered goal."""
    return isinstance(kind, str) and kind in _GOALS


def goal_kind(kind: str) -> GoalKind | str:
    """The ``GoalKind`` member of a built-in kind, the name itself for a registered one."""
    return GoalKind(kind) if kind in tuple(GoalKind) else str(kind)


def bounded_goal(objectives) -> GoalSpec | None:
    """The goal an epsilon-constraint result was bounded on, among its ``objectives``
    (the sweep's pair): the last one whose spec labels a bound."""
    found = [goal_spec(k) for k in objectives if is_goal(k) and goal_spec(k).bound_format]
    return found[-1] if found else None


for _spec in (
    GoalSpec(
        GoalKind.MIN_ELECTRIC_POWER,
        "Electric power",
        "Least electric power",
        "least electric power",
        "electric power",
        "W",
        "{:9.1f} W",
        result_format="{:,.1f} W",
    ),
    GoalSpec(
        GoalKind.MAX_LIGHT_POWER,
        "Reflected light power",
        "Most reflected light power",
        "most light power",
        "light power",
        "lm",
        "{:12.0f} lm",
        bound_format="{:,.0f} lm",
        maximise=True,
    ),
    GoalSpec(
        GoalKind.MATCH,
        "Match error e",
        "Match a target lighting",
        "match a target lighting",
        "match error e",
    ),
    GoalSpec(
        GoalKind.MIN_INSTALLED_POWER,
        "Installed power",
        "Least installed power",
        "least installed power",
        "installed power",
        "W",
        "{:9.1f} W",
    ),
    GoalSpec(
        GoalKind.MIN_LUMINAIRE_COUNT,
        "Luminaire count",
        "Fewest luminaires",
        "fewest luminaires",
        "luminaires",
    ),
    GoalSpec(
        GoalKind.MIN_ANNUAL_ENERGY,
        "Annual lighting energy",
        "Least annual lighting energy (dimming with daylight)",
        "least annual energy",
        "annual energy",
        "kWh",
        "{:8.1f} kWh",
        annual=True,
    ),
    GoalSpec(
        GoalKind.MAX_SDA,
        "sDA300/50%",
        "Most daylight: sDA300/50% of the control work plane",
        "most daylight (sDA)",
        "sDA300/50% (fraction)",
        "",
        "sDA {:5.1f}%",
        text_factor=100.0,
        maximise=True,
        annual=True,
    ),
    GoalSpec(
        GoalKind.MIN_GLAZING_AREA,
        "Glazing area",
        "Least glazing area",
        "least glazing area",
        "glazing area",
        "m²",
        "{:6.2f} m²",
        bound_format="{:,.2f} m²",
    ),
):
    register_goal(_spec)
