"""Saved results in a project file: solutions, their violations and the Pareto front.

Each object's fields are declared once here (``VIOLATION``, ``SOLUTION``, ``PARETO``,
``RESULTS``); reading, the messages, writing and the tables of docs/project-file.md come
from them. Results may hold infinities and NaN (a penalty of infinity, a violation whose
value is not defined), written as the strings "inf", "-inf" and "nan". A solution's
``info`` is free-form: its values are read as JSON values and typed by ``SolutionInfo``.
"""

from __future__ import annotations

from functools import partial
from typing import Any

from lightinv_core.design.model import GOALS
from lightinv_core.design.solution import ParetoFront, Solution, SolutionInfo, Violation
from lightinv_core.errors import DesignError
from lightinv_core.fields import (
    NONFINITE,
    Field,
    ObjectSpec,
    _choice,
    _describe,
    _fail,
    _is_int,
    _is_number,
    _join,
    _list,
    _number,
    _string,
    _unique,
)
from lightinv_core.project.specs import SOURCE, read_sources


class Info(dict):
    """A solution's free-form info: its numbers are written exactly as they are."""


def _result_number(v: Any, path: str) -> float:
    return _number(v, path, finite=False)


def _text(v: Any, path: str) -> str:
    return _string(v, path, empty=True)


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


def _info(v: Any, path: str) -> SolutionInfo:
    info = _info_value(v, path)
    if not isinstance(info, dict):
        _fail(path, f"expected an object, got {_describe(v)}")
    try:
        return SolutionInfo.from_dict(info)
    except DesignError as err:
        _fail(path, str(err))


def _objectives(v: Any, path: str) -> dict[str, float]:
    if not isinstance(v, dict):
        _fail(path, f"expected an object, got {_describe(v)}")
    out = {}
    for key, value in v.items():
        if key not in GOALS:
            _fail(path, f"unknown goal {key!r} (goals: {', '.join(GOALS)})")
        out[key] = _result_number(value, _join(path, key))
    return out


VIOLATION = ObjectSpec(
    "violation",
    (
        Field("name", _text, type="string", meaning="the rule or intention violated"),
        Field(
            "constraint",
            _text,
            type="string",
            meaning="`geometry`, `min`, `max`, `average`, `uniformity` or `epsilon`",
        ),
        Field(
            "amount",
            _result_number,
            type="number",
            meaning="relative violation: 0.05 = 5% past the bound",
        ),
        Field(
            "value",
            _result_number,
            type="number",
            meaning='the value reached, in `units` (`"nan"` for geometric rules)',
        ),
        Field("bound", _result_number, type="number", meaning="the bound, in `units`"),
        Field("units", _text, type="string", meaning="`lux`, `lm/m²`, `lm`, `W` or empty"),
    ),
)

SOLUTION = ObjectSpec(
    "solution",
    (
        Field(
            "sources",
            read_sources,
            type="list of sources",
            meaning="the layout, in the format of `sources`",
            of=SOURCE,
        ),
        Field(
            "objectives",
            _objectives,
            type="object",
            meaning="goal kind -> value: `min_electric_power` in W, `max_light_power` in lm, "
            "`match` as e",
        ),
        Field(
            "penalty",
            _result_number,
            type="number",
            meaning='P; `"inf"` when the layout breaks a geometric rule',
        ),
        Field(
            "violations",
            lambda v, p: _list(v, p, partial(VIOLATION.build, Violation), "violations"),
            (),
            "list of violations",
            "every violated rule or intention (below)",
            of=VIOLATION,
        ),
        Field(
            "x",
            lambda v, p: _list(v, p, _result_number, "numbers"),
            (),
            "list of numbers",
            "the variable vector the layout was decoded from",
        ),
        Field(
            "info",
            _info,
            SolutionInfo(),
            "object",
            "free-form run information (seed, evaluations, seconds, status, ...)",
            encode=lambda info: Info(info.to_dict()),
            doc_default="`{}`",
        ),
    ),
    write_defaults=True,
)


def read_solutions(v: Any, path: str) -> tuple[Solution, ...]:
    """The solutions listed at ``path``."""
    return _list(v, path, partial(SOLUTION.build, Solution), "solutions")


PARETO = ObjectSpec(
    "pareto",
    (
        Field(
            "objectives",
            lambda v, p: _unique(_list(v, p, lambda x, q: _choice(x, q, GOALS), "goal kinds"), p),
            type="list of goal kinds",
            meaning="the goal kinds compared, in order",
        ),
        Field("method", _text, "", "string", "how the front was found"),
        Field(
            "solutions",
            read_solutions,
            type="list of solutions",
            meaning="the non-dominated solutions",
            of=SOLUTION,
        ),
        Field(
            "candidates",
            read_solutions,
            (),
            "list of solutions",
            "every solution the front was chosen from",
            of=SOLUTION,
        ),
    ),
    write_defaults=True,
)

RESULTS = ObjectSpec(
    "results",
    (
        Field(
            "solutions",
            read_solutions,
            (),
            "list of solutions",
            "saved solutions (the best of a run, pinned ones)",
            of=SOLUTION,
        ),
        Field(
            "pareto",
            partial(PARETO.build, ParetoFront),
            None,
            "object or null",
            "the last multi-objective front",
            nullable=True,
            of=PARETO,
        ),
    ),
    write_defaults=True,
)


def read_results(v: Any, path: str) -> dict[str, Any]:
    """The results object at ``path``: ``solutions`` (a tuple) and ``pareto`` (a
    ``ParetoFront`` or None)."""
    return {**RESULTS.defaults(), **RESULTS.read(v, path)}
