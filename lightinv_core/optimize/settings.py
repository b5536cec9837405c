"""How an optimisation runs: the method, its stopping rule and its own settings."""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.fields import _check_fields, _choice, _count, _integer, _list, _number, _optional
from lightinv_core.optimize.registry import method_names

METHODS = method_names()
"""The method names a project may choose: the registry's (registry.py)."""


@dataclass(frozen=True)
class OptimizerSettings:
    """How the optimiser runs (see docs/project-file.md for every field).

    ``method``: "vns" (one VNS on all patches), "multilevel" (VNS on ``divisors``
    levels), "epsilon" (epsilon-constraint sweep) or "two_step" (paper 5.5). Stopping:
    ``max_evals``, ``time_limit`` (s), ``target`` (primary goal's units, counts only
    when feasible), ``stall`` (evaluations without improvement); None disables each.
    """

    method: str = "vns"
    seed: int = 0
    max_evals: int | None = 20000
    time_limit: float | None = None
    target: float | None = None
    stall: int | None = None
    trials: int = 32
    divisors: tuple[int, ...] = (64, 16, 1)
    level_max_evals: int | None = None
    level_target: float | None = None
    runs: int = 10
    epsilons: tuple[float, ...] | None = None
    epsilon_count: int = 12

    def __post_init__(self) -> None:
        count, value = _count, _number
        _check_fields(
            self,
            {
                "method": lambda v, p: _choice(v, p, METHODS),
                "seed": lambda v, p: _integer(v, p, lo=0),
                "max_evals": _optional(count),
                "time_limit": _optional(lambda v, p: _number(v, p, gt=0.0)),
                "target": _optional(value),
                "stall": _optional(count),
                "trials": count,
                "divisors": lambda v, p: _list(v, p, count, "divisors (integers >= 1)", 1),
                "level_max_evals": _optional(count),
                "level_target": _optional(value),
                "runs": count,
                "epsilons": _optional(
                    lambda v, p: _list(v, p, lambda x, q: _number(x, q, lo=0.0), "lm values", 1)
                ),
                "epsilon_count": count,
            },
        )
