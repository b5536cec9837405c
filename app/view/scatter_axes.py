"""The axes a result can be plotted on: every registered goal's value, each source type's
area and strength, and the penalty.

The lists are read from the registries when asked (``axes``), so a goal or a source type
registered at run time is an axis too; a key is the goal's kind, ``area:<kind>`` or
``strength:<kind>`` of a source kind, or ``penalty``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lightinv_core.goals import goal_spec, goal_specs, is_goal
from lightinv_core.sources.types import SourceType, source_types

PENALTY = "penalty"


class Axis(NamedTuple):
    """One scatter axis: its label with units, and a solution's value on it (None when
    the solution has none)."""

    label: str
    value: Callable[[object], float | None]


def _goal_value(kind: str):
    return lambda s: s.objectives.get(kind)


def _of(t: SourceType, s) -> list:
    return [x for x in s.sources if x.kind == t.kind]


def _area(t: SourceType) -> Axis:
    return Axis(f"{t.label.lower()} area (m²)", lambda s: sum(x.area for x in _of(t, s)))


def _strength(t: SourceType) -> Axis:
    """The sources' strength: a luminaire's flux adds up over the sources (the light they
    add), a daylit source's filter is averaged (a share of the sky's light)."""
    name = f"{t.label.lower()} {t.strength_label.lower()}"
    if t.electric:
        return Axis(name, lambda s: sum(getattr(x, t.strength) or 0.0 for x in _of(t, s)))
    return Axis(f"mean {name}", lambda s: _mean([getattr(x, t.strength) for x in _of(t, s)]))


def _mean(values) -> float | None:
    values = [v for v in values if v is not None]
    return float(np.mean(values)) if values else None


def goal_axis_label(kind: str) -> str:
    """A goal's value on a plot axis, with its units: "annual energy (kWh)"."""
    spec = goal_spec(kind)
    return spec.with_units(spec.axis)


def axis(key: str) -> Axis:
    """The axis ``key`` (KeyError when no goal or source type gives it)."""
    if key == PENALTY:
        return Axis("penalty P", lambda s: s.penalty)
    what, _, kind = key.partition(":")
    if kind:
        t = next((t for t in source_types() if t.kind == kind), None)
        if t is None or what not in ("area", "strength"):
            raise KeyError(key)
        return _area(t) if what == "area" else _strength(t)
    if not is_goal(key):
        raise KeyError(key)
    return Axis(goal_axis_label(key), _goal_value(key))


def axes() -> dict[str, Axis]:
    """Every scatter axis by key: the goals first, then each source type's area and
    strength, then the penalty."""
    keys = [str(g.kind) for g in goal_specs()]
    keys += [f"{what}:{t.kind}" for t in source_types() for what in ("area", "strength")]
    return {k: axis(k) for k in (*keys, PENALTY)}


def axis_label(key: str) -> str:
    """The label of axis ``key``."""
    return axis(key).label


def axis_value(solution, key: str) -> float:
    """A solution's value on axis ``key`` (NaN when it has none)."""
    v = axis(key).value(solution)
    return float("nan") if v is None else float(v)


def front_axes(objectives) -> tuple[str, str]:
    """The (x, y) axes of a front of two goals: the first across, the second up, except
    that a goal the weather year does not decide goes across when the other is an annual
    one (energy or daylight against glazing area). KeyError for an unknown goal."""
    a, b = (str(k) for k in tuple(objectives)[:2])
    if not (is_goal(a) and is_goal(b)):
        raise KeyError(f"not goals: {a!r}, {b!r}")
    if goal_spec(a).annual and not goal_spec(b).annual:
        return b, a
    return a, b
