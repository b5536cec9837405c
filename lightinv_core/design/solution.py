"""Results of an optimisation: solutions, their violations, and Pareto fronts."""

from __future__ import annotations

from dataclasses import dataclass, field

from lightinv_core.design.model import Source


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
class Solution:
    """A source layout with its objective values (in their units), penalty and violations.

    ``objectives`` maps goal kinds to values: "min_electric_power" in W,
    "max_light_power" in lm, "match" as the relative error e(E). ``x`` is the
    variable vector it was decoded from.
    """

    sources: tuple[Source, ...]
    objectives: dict[str, float]
    penalty: float
    violations: tuple[Violation, ...] = ()
    x: tuple[float, ...] = ()
    info: dict = field(default_factory=dict)

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
