"""Saved results in a project file: solutions, their violations, Pareto fronts and the
history of optimisation runs.

Each object's fields are declared once here (``VIOLATION``, ``SOLUTION``, ``PARETO``,
``RUN``, ``RESULTS``); reading, the messages, writing and the tables of
docs/project-file.md come from them. A ``RunRecord`` is one optimisation run of the
window's history (its method, when it ended, its settings and what it found); the
results' own ``solutions`` and ``pareto`` hold results outside any recorded run (those of
``lightinv-cli solve``, of files written before runs were recorded, pinned results of a
deleted run). Results may hold infinities and NaN (a penalty of infinity, a violation whose
value is not defined), written as the strings "inf", "-inf" and "nan". A solution's
``info`` is free-form: its values are read as JSON values and typed by ``SolutionInfo``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import partial
from typing import Any

from lightinv_core.design.solution import ParetoFront, Solution, SolutionInfo, Violation
from lightinv_core.errors import DesignError
from lightinv_core.fields import (
    NONFINITE,
    Choice,
    Custom,
    Field,
    Integer,
    ListOf,
    Number,
    ObjectSpec,
    String,
    _describe,
    _fail,
    _is_int,
    _is_number,
    _join,
    _list,
)
from lightinv_core.goals import goal_names
from lightinv_core.optimize.settings import OPTIMIZER, OptimizerSettings
from lightinv_core.project.specs import ARRAY, SOURCE, read_arrays, read_sources


class Info(dict):
    """A solution's free-form info: its numbers are written exactly as they are."""


_result_number = Number(finite=False)
"""A result's number: inf and nan too (written as strings)."""
_text = String(empty=True)


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
        for k in getattr(v, "duplicates", ()):
            _fail(path, f"field {k!r} is given twice")
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


_goal_kind = Choice(goal_names, name="goal kind")


def _objectives(v: Any, path: str) -> dict[str, float]:
    if not isinstance(v, dict):
        _fail(path, f"expected an object, got {_describe(v)}")
    for key in getattr(v, "duplicates", ()):
        _fail(path, f"objective {key!r} is given twice")
    out = {}
    for key, value in v.items():
        if key not in goal_names():
            _fail(path, f"unknown goal {key!r} (goals: {', '.join(goal_names())})")
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
            many=True,
        ),
        Field(
            "objectives",
            Custom(
                _objectives,
                schema_={"type": "object", "additionalProperties": _result_number.schema()},
            ),
            type="object",
            meaning="goal kind -> value: `min_electric_power` in W, `max_light_power` in lm, "
            "`match` as e, `min_installed_power` in W, `min_luminaire_count`, "
            "`min_annual_energy` in kWh, `max_sda` as a fraction, `min_glazing_area` in m²",
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
            many=True,
        ),
        Field(
            "x",
            ListOf(_result_number, "numbers"),
            (),
            "list of numbers",
            "the variable vector the layout was decoded from",
        ),
        Field(
            "info",
            Custom(_info, schema_={"type": "object"}),
            SolutionInfo(),
            "object",
            "free-form run information (seed, evaluations, seconds, status, ...)",
            encode=lambda info: Info(info.to_dict()),
            doc_default="`{}`",
        ),
        Field(
            "arrays",
            read_arrays,
            (),
            "list of arrays",
            "the luminaire arrays as laid out, in the format of `arrays`",
            of=ARRAY,
            many=True,
            optional=True,
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
            ListOf(_goal_kind, "goal kinds", unique=True),
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
            many=True,
        ),
        Field(
            "candidates",
            read_solutions,
            (),
            "list of solutions",
            "every solution the front was chosen from",
            of=SOLUTION,
            many=True,
        ),
    ),
    write_defaults=True,
)


@dataclass(frozen=True)
class RunRecord:
    """One optimisation run of a project's history.

    ``number``: 1, 2, ... in the order the runs were made (a deleted run's number is not
    reused); ``method``: the registry name it ran with; ``time``: when it ended (ISO 8601
    local date and time, e.g. "2026-11-25T14:03:12"); ``settings``: the run settings it
    used; ``seeds``: the seeds of a several-seed run (empty: the settings' seed);
    ``goals``: the design's goal kinds at the time, primary first; ``status``: "feasible",
    "infeasible" or "cancelled"; ``evaluations`` of the light and wall time ``seconds``
    over all its sub-runs; ``solutions``: each seed's best; ``pareto``: the front of a
    multi-objective run (or None).
    """

    number: int
    method: str
    time: str = ""
    settings: OptimizerSettings = field(default_factory=OptimizerSettings)
    seeds: tuple[int, ...] = ()
    goals: tuple[str, ...] = ()
    status: str = ""
    evaluations: int = 0
    seconds: float = 0.0
    solutions: tuple[Solution, ...] = ()
    pareto: ParetoFront | None = None

    def __post_init__(self) -> None:
        for name in ("seeds", "goals", "solutions"):
            object.__setattr__(self, name, tuple(getattr(self, name)))

    def results(self) -> tuple[Solution, ...]:
        """Every result of the run: each seed's best, then its front's candidates (or the
        front itself when it kept no candidates)."""
        front = () if self.pareto is None else (self.pareto.candidates or self.pareto.solutions)
        return self.solutions + tuple(front)


RUN = ObjectSpec(
    "run",
    (
        Field("number", Integer(lo=1), type="integer", meaning="1, 2, ..."),
        Field("method", String(), meaning="the method it ran with"),
        Field(
            "time",
            _text,
            "",
            "string",
            'when it ended, ISO 8601 local time ("2026-11-25T14:03:12")',
        ),
        Field(
            "settings",
            partial(OPTIMIZER.build, OptimizerSettings),
            OptimizerSettings(),
            "object",
            "the run settings it used, as `optimizer`",
            of=OPTIMIZER,
            doc_default="see `optimizer`",
        ),
        Field(
            "seeds",
            ListOf(Integer(), "integers"),
            (),
            "list of integers",
            "the seeds of a several-seed run (empty: the settings' seed)",
        ),
        Field(
            "goals",
            ListOf(_goal_kind, "goal kinds"),
            (),
            "list of goal kinds",
            "the design's goals when it ran, primary first",
        ),
        Field("status", _text, "", "string", "`feasible`, `infeasible` or `cancelled`"),
        Field(
            "evaluations",
            Integer(lo=0),
            0,
            "integer",
            "light evaluations, all its sub-runs",
        ),
        Field("seconds", Number(lo=0), 0, "number", "wall time, s"),
        Field(
            "solutions",
            read_solutions,
            (),
            "list of solutions",
            "each seed's best",
            of=SOLUTION,
            many=True,
        ),
        Field(
            "pareto",
            partial(PARETO.build, ParetoFront),
            None,
            "object or null",
            "its front, for a multi-objective run",
            nullable=True,
            of=PARETO,
        ),
    ),
    write_defaults=True,
)


def read_runs(v: Any, path: str) -> tuple[RunRecord, ...]:
    """The runs listed at ``path`` (each number once)."""
    runs = _list(v, path, partial(RUN.build, RunRecord), "runs")
    seen: set[int] = set()
    for i, run in enumerate(runs):
        if run.number in seen:
            _fail(_join(_join(path, i), "number"), f"run {run.number} is listed twice")
        seen.add(run.number)
    return runs


# ``solutions`` and ``pareto`` are always written (files from before the run history read
# the same); ``runs`` only when there are some.
RESULTS = ObjectSpec(
    "results",
    (
        Field(
            "solutions",
            read_solutions,
            (),
            "list of solutions",
            "saved solutions outside the run history (`lightinv-cli solve`, older files, "
            "pinned results of a deleted run)",
            always=True,
            of=SOLUTION,
            many=True,
        ),
        Field(
            "pareto",
            partial(PARETO.build, ParetoFront),
            None,
            "object or null",
            "a multi-objective front outside the run history",
            nullable=True,
            always=True,
            of=PARETO,
        ),
        Field(
            "runs",
            read_runs,
            (),
            "list of runs",
            "the optimisation runs made in the window, oldest first (below)",
            of=RUN,
            many=True,
        ),
    ),
)


def read_results(v: Any, path: str) -> dict[str, Any]:
    """The results object at ``path``: ``solutions`` (a tuple), ``pareto`` (a
    ``ParetoFront`` or None) and ``runs`` (a tuple of ``RunRecord``)."""
    return {**RESULTS.defaults(), **RESULTS.read(v, path)}
