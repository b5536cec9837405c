"""Reading a project: parsed JSON data -> a checked ``Project``.

``read_project`` builds the design (sources, rules, intentions, goals, daylight), the
settings and the saved results from the data of a project file, checking every value
with ``project_checks`` and raising a ``ProjectError`` at the JSON path of the first
problem. ``object_pairs_hook`` is the ``json.loads`` hook that lets it report keys given
twice.
"""

from __future__ import annotations

from dataclasses import replace
from functools import partial
from pathlib import Path
from typing import Any

from lightinv_core.design.model import (
    GOALS,
    Daylight,
    Design,
    Goal,
    Intention,
    Rule,
    Source,
)
from lightinv_core.design.solution import ParetoFront, Solution, SolutionInfo, Violation
from lightinv_core.errors import DesignError
from lightinv_core.fields import (
    NONFINITE,
    _choice,
    _describe,
    _fail,
    _integer,
    _is_int,
    _is_number,
    _join,
    _list,
    _number,
    _object,
    _string,
    _unique,
    _within,
)
from lightinv_core.kinds import GoalKind
from lightinv_core.project.model import (
    OPERATOR_FIELDS,
    OPTIMIZER_FIELDS,
    PARETO_FIELDS,
    RESULTS_FIELDS,
    SCENE_FIELDS,
    SCHEMA,
    SOLUTION_FIELDS,
    TOP_FIELDS,
    VIOLATION_FIELDS,
    OperatorSettings,
    OptimizerSettings,
    Project,
    SceneSpec,
    resolve_path,
)
from lightinv_core.project.specs import DAYLIGHT, GOAL, INTENTION, RULE, SOURCE

# -- JSON parsing ---------------------------------------------------------------------------


class _JSONObject(dict):
    """A parsed JSON object that remembers keys given more than once."""

    duplicates: tuple[str, ...] = ()


def object_pairs_hook(pairs: list[tuple[str, Any]]) -> dict:
    """Build a JSON object, noting its repeated keys for ``_object``."""
    out = _JSONObject(pairs)
    if len(out) != len(pairs):
        seen: set[str] = set()
        out.duplicates = tuple(k for k, _ in pairs if k in seen or seen.add(k))
    return out


# -- the design -----------------------------------------------------------------------------


def _source(v: Any, path: str) -> Source:
    kw = SOURCE.read(v, path)
    with _within(path):
        return Source(**kw)


def _sources(v: Any, path: str) -> tuple[Source, ...]:
    out = _list(v, path, _source, "sources")
    seen: dict[str, int] = {}
    for i, s in enumerate(out):
        if s.name in seen:
            _fail(
                _join(_join(path, i), "name"),
                f"{s.name!r} is already used by {path}[{seen[s.name]}]",
            )
        seen[s.name] = i
    return out


def _rule(v: Any, path: str, names: tuple[str, ...]) -> Rule:
    kw = RULE.read(v, path)
    for i, s in enumerate(kw["sources"]):
        if s not in names:
            known = ", ".join(names) or "none"
            _fail(_join(_join(path, "sources"), i), f"no source {s!r} (sources: {known})")
    with _within(path):
        return Rule(**kw)


def _rules(v: Any, path: str, names: tuple[str, ...]) -> tuple[Rule, ...]:
    rules = _list(v, path, lambda x, p: _rule(x, p, names), "rules")
    mirrored: dict[str, int] = {}
    for i, r in enumerate(rules):
        if r.kind == "mirror":
            derived = r.sources[0]
            if derived in mirrored:
                _fail(
                    _join(_join(path, i), "sources[0]"),
                    f"{derived!r} already mirrors another source ({path}[{mirrored[derived]}])",
                )
            mirrored[derived] = i
    return rules


def _intention(v: Any, path: str) -> Intention:
    kw = INTENTION.read(v, path)
    with _within(path):
        return Intention(**kw)


def _intentions(v: Any, path: str) -> tuple[Intention, ...]:
    out = _list(v, path, _intention, "intentions")
    seen: dict[str, int] = {}
    for i, it in enumerate(out):
        if it.name in seen:
            where = f"{path}[{seen[it.name]}]"
            _fail(_join(_join(path, i), "name"), f"{it.name!r} is already used by {where}")
        seen[it.name] = i
    return out


def _goal(v: Any, path: str) -> Goal:
    kw = GOAL.read(v, path)
    if kw.get("kinds") and kw["kind"] != GoalKind.MAX_LIGHT_POWER:
        _fail(_join(path, "kinds"), "only a max_light_power goal takes source kinds")
    with _within(path):
        return Goal(**kw)


def _goals(v: Any, path: str) -> tuple[Goal, ...]:
    goals = _list(v, path, _goal, "goals", 1)
    seen: dict[str, int] = {}
    for i, g in enumerate(goals):
        if g.kind in seen:
            _fail(
                _join(_join(path, i), "kind"),
                f"{g.kind!r} is already a goal ({path}[{seen[g.kind]}])",
            )
        seen[g.kind] = i
    return goals


def _daylight(v: Any, path: str) -> Daylight:
    return Daylight(**DAYLIGHT.read(v, path))


def _design(d: dict) -> Design:
    sources = _sources(d["sources"], "sources")
    targets = _sources(d.get("target_sources", []), "target_sources")
    names = tuple(s.name for s in sources)
    rules = _rules(d.get("rules", []), "rules", names)
    intentions = _intentions(d.get("intentions", []), "intentions")
    goals = _goals(d["goals"], "goals")
    for i, g in enumerate(goals):
        if g.kind == GoalKind.MATCH and not targets:
            _fail(f"goals[{i}]", "a match goal needs target_sources (the light to reproduce)")
    daylight = _daylight(d["daylight"], "daylight") if "daylight" in d else Daylight()
    power = 2
    if "penalty_power" in d:
        power = _integer(d["penalty_power"], "penalty_power", lo=2)
        if power % 2:
            _fail("penalty_power", f"expected an even integer >= 2, got {power}")
    with _within(""):
        return Design(sources, goals, rules, intentions, targets, daylight, power)


def _settings(cls: type, v: Any, path: str, known: tuple[str, ...]):
    d = _object(v, path, known)
    with _within(path):
        return cls(**d)


# -- results --------------------------------------------------------------------------------


def _result_number(v: Any, path: str) -> float:
    return _number(v, path, finite=False)


def _info_value(v: Any, path: str) -> Any:
    if isinstance(v, str):
        return NONFINITE.get(v, v)
    if v is None or isinstance(v, bool):
        return v
    if _is_int(v):
        return int(v)
    if _is_number(v):
        return float(v)
    if isinstance(v, list | tuple):
        return [_info_value(x, _join(path, i)) for i, x in enumerate(v)]
    if isinstance(v, dict):
        for k in v:
            if not isinstance(k, str):
                _fail(path, f"expected string keys, got {_describe(k)}")
        return {k: _info_value(x, _join(path, k)) for k, x in v.items()}
    _fail(path, f"expected a JSON value, got {_describe(v)}")


def _violation(v: Any, path: str) -> Violation:
    d = _object(v, path, VIOLATION_FIELDS, VIOLATION_FIELDS)
    at = partial(_join, path)
    return Violation(
        _string(d["name"], at("name"), empty=True),
        _string(d["constraint"], at("constraint"), empty=True),
        _result_number(d["amount"], at("amount")),
        _result_number(d["value"], at("value")),
        _result_number(d["bound"], at("bound")),
        _string(d["units"], at("units"), empty=True),
    )


def _solution(v: Any, path: str) -> Solution:
    d = _object(v, path, SOLUTION_FIELDS, ("sources", "objectives", "penalty"))
    at = partial(_join, path)
    sources = _sources(d["sources"], at("sources"))
    obj = d["objectives"]
    if not isinstance(obj, dict):
        _fail(at("objectives"), f"expected an object, got {_describe(obj)}")
    objectives = {}
    for key, value in obj.items():
        if key not in GOALS:
            _fail(at("objectives"), f"unknown goal {key!r} (goals: {', '.join(GOALS)})")
        objectives[key] = _result_number(value, _join(at("objectives"), key))
    info = _info_value(d.get("info", {}), at("info"))
    if not isinstance(info, dict):
        _fail(at("info"), f"expected an object, got {_describe(d['info'])}")
    try:
        typed = SolutionInfo.from_dict(info)
    except DesignError as err:
        _fail(at("info"), str(err))
    return Solution(
        sources,
        objectives,
        _result_number(d["penalty"], at("penalty")),
        _list(d.get("violations", []), at("violations"), _violation, "violations"),
        _list(d.get("x", []), at("x"), _result_number, "numbers"),
        typed,
    )


def _pareto(v: Any, path: str) -> ParetoFront:
    d = _object(v, path, PARETO_FIELDS, ("objectives", "solutions"))
    at = partial(_join, path)
    objectives = _list(
        d["objectives"], at("objectives"), lambda x, p: _choice(x, p, GOALS), "goal kinds"
    )
    return ParetoFront(
        _unique(objectives, at("objectives")),
        _list(d["solutions"], at("solutions"), _solution, "solutions"),
        _string(d.get("method", ""), at("method"), empty=True),
        _list(d.get("candidates", []), at("candidates"), _solution, "solutions"),
    )


# -- the project ----------------------------------------------------------------------------


def read_project(data: Any, base_dir: Path | None) -> Project:
    """The project described by parsed JSON ``data``; relative scene paths are made
    absolute against ``base_dir`` when it is given."""
    if not isinstance(data, dict):
        _fail("", f"expected a JSON object at the top level, got {_describe(data)}")
    if "schema" not in data:
        _fail("", "missing required field 'schema' (is this a LightInv project file?)")
    schema = _integer(data["schema"], "schema")
    if schema != SCHEMA:
        _fail(
            "", f"unknown project schema {schema}; this version of LightInv reads schema {SCHEMA}"
        )
    d = _object(data, "", TOP_FIELDS, ("name", "scene", "sources", "goals"))
    name = _string(d["name"], "name")
    description = _string(d.get("description", ""), "description", empty=True)
    scene = _settings(SceneSpec, d["scene"], "scene", SCENE_FIELDS)
    if base_dir is not None and scene.obj is not None:
        scene = replace(
            scene,
            obj=resolve_path(scene.obj, base_dir),
            materials=resolve_path(scene.materials, base_dir),
        )
    operator = _settings(OperatorSettings, d.get("operator", {}), "operator", OPERATOR_FIELDS)
    design = _design(d)
    optimizer = _settings(OptimizerSettings, d.get("optimizer", {}), "optimizer", OPTIMIZER_FIELDS)
    solutions: tuple[Solution, ...] = ()
    pareto = None
    if "results" in d:
        r = _object(d["results"], "results", RESULTS_FIELDS)
        solutions = _list(r.get("solutions", []), "results.solutions", _solution, "solutions")
        if r.get("pareto") is not None:
            pareto = _pareto(r["pareto"], "results.pareto")
    return Project(name, scene, design, operator, optimizer, description, solutions, pareto)
