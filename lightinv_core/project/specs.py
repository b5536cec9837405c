"""The design's JSON objects: their specs, taken from the model classes' declarations,
and the readers of their lists.

Each object's fields are declared once, in its class in ``design/model/``; here the
source spec learns which fields each kind takes from the source types
(``sources.types.source_type(kind).fields``, a layer the model cannot see), and the
readers (``read_sources``, ``read_rules``, ...: JSON data -> design objects) add the checks
that span a list: unique names, rules naming sources that exist, each goal kind once.
"""

from __future__ import annotations

from dataclasses import replace
from functools import partial
from typing import Any

from lightinv_core.design.model import (
    ARRAY_FIELDS,
    ARRAY_RULES,
    CALC_FIELDS,
    CONTROL_GROUP_FIELDS,
    DAYLIGHT_FIELDS,
    GOAL_FIELDS,
    INTENTION_FIELDS,
    OBSERVER_FIELDS,
    RULE_FIELDS,
    SOURCE_FIELDS,
    WORKPLANE_FIELDS,
    CalcObject,
    ControlGroup,
    Daylight,
    Goal,
    Intention,
    LuminaireArray,
    Observer,
    Rule,
    Source,
    Workplane,
)
from lightinv_core.fields import _fail, _join, _list, _within
from lightinv_core.kinds import GoalKind, RuleKind
from lightinv_core.project.source_kinds import kind_fields, source_kind_problem, source_not_taken

SOURCE = replace(
    SOURCE_FIELDS, kind_field="kind", kind_fields=kind_fields, not_taken=source_not_taken
)
"""A source's fields; those of one kind only come from its source type."""
RULE = replace(RULE_FIELDS, kinds_first=True)
"""A rule's fields; a field its kind does not take is refused before the values."""
INTENTION = INTENTION_FIELDS
GOAL = GOAL_FIELDS
DAYLIGHT = DAYLIGHT_FIELDS
ARRAY = ARRAY_FIELDS
WORKPLANE = WORKPLANE_FIELDS
OBSERVER = OBSERVER_FIELDS
CONTROL_GROUP = CONTROL_GROUP_FIELDS
CALC = CALC_FIELDS


def _source(v: Any, path: str) -> Source:
    """A source read at ``path``, the kind's own checks included."""
    source = SOURCE.build(Source, v, path)
    problem = source_kind_problem(source)
    if problem is not None:
        field, detail = problem
        _fail(_join(path, field), detail) if field else _fail(
            path, f"source {source.name!r}: {detail}"
        )
    return source


def read_arrays(v: Any, path: str) -> tuple[LuminaireArray, ...]:
    """The luminaire arrays listed at ``path``, names unique."""
    return _unique_names(_list(v, path, partial(ARRAY.build, LuminaireArray), "arrays"), path)


def read_workplanes(v: Any, path: str) -> tuple[Workplane, ...]:
    """The work planes listed at ``path``, names unique."""
    return _unique_names(_list(v, path, partial(WORKPLANE.build, Workplane), "work planes"), path)


def read_observers(v: Any, path: str) -> tuple[Observer, ...]:
    """The observers listed at ``path``, names unique."""
    return _unique_names(_list(v, path, partial(OBSERVER.build, Observer), "observers"), path)


def read_control_groups(v: Any, path: str) -> tuple[ControlGroup, ...]:
    """The daylight-linked control groups listed at ``path``, names unique."""
    items = _list(v, path, partial(CONTROL_GROUP.build, ControlGroup), "control groups")
    return _unique_names(items, path)


def read_calc_objects(v: Any, path: str) -> tuple[CalcObject, ...]:
    """The calculation objects listed at ``path``, names unique."""
    items = _list(v, path, partial(CALC.build, CalcObject), "calculation objects")
    return _unique_names(items, path)


def _unique_names(items: tuple, path: str) -> tuple:
    """``items`` (with a ``name``), failing at the second use of a name."""
    seen: dict[str, int] = {}
    for i, x in enumerate(items):
        if x.name in seen:
            where = f"{path}[{seen[x.name]}]"
            _fail(_join(_join(path, i), "name"), f"{x.name!r} is already used by {where}")
        seen[x.name] = i
    return items


def read_sources(v: Any, path: str) -> tuple[Source, ...]:
    """The sources (or target sources) listed at ``path``, names unique."""
    return _unique_names(_list(v, path, _source, "sources"), path)


def _rule(v: Any, path: str, names: tuple[str, ...], arrays: tuple[str, ...] = ()) -> Rule:
    values = RULE.read(v, path)
    on_arrays = values["kind"] in ARRAY_RULES
    what, pool = ("luminaire array", arrays) if on_arrays else ("source", names)
    for i, s in enumerate(values["sources"]):
        if s not in pool:
            known = ", ".join(pool) or "none"
            _fail(_join(_join(path, "sources"), i), f"no {what} {s!r} ({what}s: {known})")
    with _within(path):
        return Rule(**values)


def read_rules(
    v: Any,
    path: str,
    sources: tuple[Source, ...] = (),
    arrays: tuple[LuminaireArray, ...] = (),
) -> tuple[Rule, ...]:
    """The rules listed at ``path``; each names some of ``sources`` (``shr`` and
    ``clearance``: of ``arrays``), and a source mirrors at most one other."""
    names = tuple(s.name for s in sources)
    array_names = tuple(a.name for a in arrays)
    rules = _list(v, path, lambda x, p: _rule(x, p, names, array_names), "rules")
    mirrored: dict[str, int] = {}
    for i, r in enumerate(rules):
        if r.kind == RuleKind.MIRROR:
            derived = r.sources[0]
            if derived in mirrored:
                _fail(
                    _join(_join(path, i), "sources[0]"),
                    f"{derived!r} already mirrors another source ({path}[{mirrored[derived]}])",
                )
            mirrored[derived] = i
    return rules


def read_intentions(v: Any, path: str) -> tuple[Intention, ...]:
    """The intentions listed at ``path``, names unique."""
    items = _list(v, path, partial(INTENTION.build, Intention), "intentions")
    return _unique_names(items, path)


def read_goals(v: Any, path: str, target_sources: tuple[Source, ...] = ()) -> tuple[Goal, ...]:
    """The goals listed at ``path``: at least one, each kind once, a match goal only with
    ``target_sources``."""
    goals = _list(v, path, partial(GOAL.build, Goal), "goals", 1)
    seen: dict[str, int] = {}
    for i, g in enumerate(goals):
        if g.kind in seen:
            _fail(
                _join(_join(path, i), "kind"),
                f"{g.kind!r} is already a goal ({path}[{seen[g.kind]}])",
            )
        seen[g.kind] = i
    for i, g in enumerate(goals):
        if g.kind == GoalKind.MATCH and not target_sources:
            _fail(_join(path, i), "a match goal needs target_sources (the light to reproduce)")
    return goals


def read_daylight(v: Any, path: str) -> Daylight:
    """The daylight object at ``path``."""
    return DAYLIGHT.build(Daylight, v, path)
