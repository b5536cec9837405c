"""How a project's optimisation runs: the method, its stopping rule and the settings of
every built-in method, as one flat object the project file declares. A method reads
its own settings dataclass from it (``MethodSpec.settings_from``)."""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.fields import (
    Field,
    ObjectSpec,
    _choice,
    _count,
    _integer,
    _list,
    _number,
    _optional,
)
from lightinv_core.optimize.catalogue import method_names


def _method(v, path: str) -> str:
    """A method name the catalogue knows (built in or registered), looked up when a
    file is read."""
    return _choice(v, path, method_names())


_opt_count = _optional(_count)
_opt_number = _optional(_number)

OPTIMIZER = ObjectSpec(
    "optimizer",
    (
        Field(
            "method",
            _method,
            "auto",
            "string",
            "`auto` (default): NSGA-II when the design has both power goals, else CMA-ES "
            "then VNS (docs/design.md); `vns`: one VNS on all patches; `multilevel`: VNS on "
            "the `divisors` levels, each warm-started from the previous; `cmaes`: CMA-ES "
            "with IPOP restarts; `epsilon`: epsilon-constraint sweep; `two_step`: "
            "skylights first, then luminaires (paper 5.5); `nsga2`: NSGA-II front of the "
            "design's two goals (any pair; refused with the reason where there is none)",
        ),
        Field(
            "seed",
            lambda v, p: _integer(v, p, lo=0),
            0,
            "integer >= 0",
            "random seed; the same seed gives the same result",
        ),
        Field(
            "max_evals",
            _opt_count,
            20000,
            "integer >= 1",
            "stop after this many evaluations (shared by all levels); null: no limit",
        ),
        Field(
            "time_limit",
            _optional(lambda v, p: _number(v, p, gt=0.0)),
            None,
            "number > 0",
            "stop after this many seconds (shared by all levels)",
        ),
        Field(
            "target",
            _opt_number,
            None,
            "number",
            "stop when the primary goal reaches this value with every rule and intention "
            "met (W, lm or e)",
        ),
        Field(
            "stall",
            _opt_count,
            None,
            "integer >= 1",
            "stop after this many evaluations without improvement",
        ),
        Field(
            "trials",
            _count,
            32,
            "integer >= 1",
            "neighbours drawn (and evaluated as one batch) per local search",
        ),
        Field(
            "divisors",
            lambda v, p: _list(v, p, _count, "divisors (integers >= 1)", 1),
            (64, 16, 1),
            "list of integers >= 1",
            "multilevel: levels on about n/d representative patches; a final level on "
            "all patches (1) is added when missing, and keeps at least a quarter of the "
            "budgets",
        ),
        Field(
            "level_max_evals",
            _opt_count,
            None,
            "integer >= 1",
            "multilevel: evaluation limit of each coarse level",
        ),
        Field(
            "level_target",
            _opt_number,
            None,
            "number",
            "multilevel: target of the coarse levels (e.g. 0.03 for a match error)",
        ),
        Field(
            "runs",
            _count,
            10,
            "integer >= 1",
            "`two_step`: repetitions with seeds `seed`, `seed` + 1, ...",
        ),
        Field(
            "population",
            lambda v, p: _integer(v, p, lo=4),
            100,
            "integer >= 4",
            "`nsga2`: population size (and the most points of its front)",
        ),
        Field(
            "epsilons",
            _optional(lambda v, p: _list(v, p, lambda x, q: _number(x, q, lo=0.0), "bounds", 1)),
            None,
            "list of numbers >= 0",
            "`epsilon`: the light-power bounds (lm) to sweep, or the glazing-area bounds (m²) "
            "for the climate pair `min_annual_energy`, `min_glazing_area`; null: automatic",
        ),
        Field(
            "epsilon_count",
            _count,
            12,
            "integer >= 1",
            "`epsilon`: number of automatic bounds, evenly spread between the light power "
            "of the least-power layout and the largest feasible light power (climate pair: "
            "between the least glazing area and the glazing of the least-energy layout)",
        ),
    ),
    write_defaults=True,  # a saved file shows every setting of its run
)
"""Every run setting, declared once: checks, file reading and writing, and docs."""


@dataclass(frozen=True)
class OptimizerSettings:
    """How the optimiser runs (see docs/project-file.md for every field).

    ``method``: a registry name (optimize/registry.py; "auto" by default). Stopping:
    ``max_evals``, ``time_limit`` (s), ``target`` (primary goal's units, counts only
    when feasible), ``stall`` (evaluations without improvement); None disables each.
    """

    method: str = OPTIMIZER.field("method").default
    seed: int = OPTIMIZER.field("seed").default
    max_evals: int | None = OPTIMIZER.field("max_evals").default
    time_limit: float | None = OPTIMIZER.field("time_limit").default
    target: float | None = OPTIMIZER.field("target").default
    stall: int | None = OPTIMIZER.field("stall").default
    trials: int = OPTIMIZER.field("trials").default
    divisors: tuple[int, ...] = OPTIMIZER.field("divisors").default
    level_max_evals: int | None = OPTIMIZER.field("level_max_evals").default
    level_target: float | None = OPTIMIZER.field("level_target").default
    runs: int = OPTIMIZER.field("runs").default
    population: int = OPTIMIZER.field("population").default
    epsilons: tuple[float, ...] | None = OPTIMIZER.field("epsilons").default
    epsilon_count: int = OPTIMIZER.field("epsilon_count").default

    def __post_init__(self) -> None:
        OPTIMIZER.check_object(self)
