"""Results of an optimisation: solutions, their violations, and Pareto fronts."""

from __future__ import annotations

import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from typing import Any

from lightinv_core.design.model import LuminaireArray, Source
from lightinv_core.errors import DesignError


@dataclass(frozen=True)
class Violation:
    """One violated constraint: ``amount`` is the relative violation (0.05 = 5% past
    the bound); ``value`` and ``bound`` are in ``units``."""

    name: str
    constraint: str
    amount: float
    value: float
    bound: float
    units: str


@dataclass(frozen=True)
class SolutionInfo:
    """How a solution was found: the typed metadata a method attaches to its answer,
    saved as the solution's ``"info"`` object in project files.

    ``method``: the optimisation method's registry name; ``seed``; ``evaluations``
    (light evaluations used); ``seconds`` (wall time); ``status``: why the run stopped
    ("max_evals", "time_limit", "target", "stall", "cancelled"; "running" for the best
    so far of a run still going); ``history``: rows (evaluations, best f + P, best P, best
    primary goal) at each improvement; ``level_evaluations``: the evaluations each
    multilevel stage used; ``epsilon``: the light-power bound (lm) of an
    epsilon-constraint run; ``step1_light_power``: the skylights' light power (lm) of a
    two-step run's first step; ``pinned``: kept across runs by the user. ``extra`` holds
    keys this version does not know, so that a file round-trips unchanged.
    """

    method: str = ""
    seed: int | None = None
    evaluations: int | None = None
    seconds: float | None = None
    status: str = ""
    history: tuple[tuple[int, float, float, float], ...] = ()
    level_evaluations: tuple[int, ...] = ()
    epsilon: float | None = None
    step1_light_power: float | None = None
    pinned: bool = False
    extra: Mapping[str, Any] = field(default_factory=dict)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> SolutionInfo:
        """The info of a saved solution (DesignError naming a key whose value is wrong)."""
        known = {f.name for f in fields(cls)} - {"extra"}
        kw: dict[str, Any] = {"extra": {k: v for k, v in data.items() if k not in known}}
        for key in known & set(data):
            kw[key] = _info_field(key, data[key])
        return cls(**kw)

    def to_dict(self) -> dict[str, Any]:
        """The info as plain data: the fields that are set, then ``extra``."""
        out: dict[str, Any] = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name != "extra" and value != f.default and value != ():
                out[f.name] = [list(r) for r in value] if f.name == "history" else value
        out.update(self.extra)
        return out

    def but(self, **changes: Any) -> SolutionInfo:
        """A copy with ``changes``."""
        return replace(self, **changes)


def _info_field(key: str, v: Any) -> Any:
    """One known info value, type-checked (None allowed where the field is optional)."""
    whole = isinstance(v, numbers.Integral) and not isinstance(v, bool)
    real = isinstance(v, numbers.Real) and not isinstance(v, bool)
    if key in ("method", "status") and isinstance(v, str):
        return v
    if key == "pinned" and isinstance(v, bool):
        return v
    if key in ("seed", "evaluations") and (v is None or whole):
        return None if v is None else int(v)
    if key in ("seconds", "epsilon", "step1_light_power") and (v is None or real):
        return None if v is None else float(v)
    if (
        key == "level_evaluations"
        and isinstance(v, list | tuple)
        and all(isinstance(x, numbers.Integral) and not isinstance(x, bool) for x in v)
    ):
        return tuple(int(x) for x in v)
    if key == "history" and isinstance(v, list | tuple):
        rows = tuple(tuple(r) for r in v if isinstance(r, list | tuple))
        if len(rows) == len(v) and all(
            len(r) == 4 and all(isinstance(x, numbers.Real) and not isinstance(x, bool) for x in r)
            for r in rows
        ):
            return tuple((int(r[0]), *(float(x) for x in r[1:])) for r in rows)
    expected = {
        "method": "a string",
        "status": "a string",
        "pinned": "true or false",
        "seed": "an integer",
        "evaluations": "an integer",
        "level_evaluations": "a list of integers",
        "history": "a list of [evaluations, value, penalty, goal] rows",
    }.get(key, "a number")
    raise DesignError(f"{key}: expected {expected}")


@dataclass(frozen=True)
class Solution:
    """A source layout with its objective values (in their units), penalty and violations.

    ``objectives`` maps goal kinds to values: "min_electric_power" in W,
    "max_light_power" in lm, "match" as the relative error e(E),
    "min_installed_power" in W, "min_luminaire_count" a count. ``x`` is the variable
    vector it was decoded from; ``arrays`` the design's luminaire arrays as laid out.
    """

    sources: tuple[Source, ...]
    objectives: dict[str, float]
    penalty: float
    violations: tuple[Violation, ...] = ()
    x: tuple[float, ...] = ()
    info: SolutionInfo = field(default_factory=SolutionInfo)
    arrays: tuple[LuminaireArray, ...] = ()

    def __post_init__(self) -> None:
        if isinstance(self.info, Mapping):
            object.__setattr__(self, "info", SolutionInfo.from_dict(self.info))
        elif not isinstance(self.info, SolutionInfo):
            raise DesignError(f"a solution's info must be a SolutionInfo, got {self.info!r:.40}")

    @property
    def feasible(self) -> bool:
        """True when every geometric rule and lighting intention is met."""
        return self.penalty == 0.0 and not self.violations


@dataclass(frozen=True)
class ParetoFront:
    """Non-dominated solutions of a multi-objective run; ``objectives`` names the goal
    kinds in the order the values are compared (each minimised after its sign)."""

    objectives: tuple[str, ...]
    solutions: tuple[Solution, ...]
    method: str = ""
    candidates: tuple[Solution, ...] = ()
