"""What a method returns: the best solution or the Pareto front, with its history."""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.design.solution import ParetoFront, Solution

HistoryRow = tuple[int, float, float, float]
"""(evaluations, best f + P, best P, best primary goal) at an improvement."""


@dataclass(frozen=True)
class OptimizationResult:
    """The outcome of one method run.

    ``status``: "feasible", "infeasible" (judged on every patch) or "cancelled" (the best
    found so far is kept); ``best``: the best solution (for a front, its first point);
    ``front``: the Pareto front of a multi-objective method, else None; ``evaluations``
    of the light; ``seconds`` of wall time; ``history`` of the best (single-objective
    runs; a front's runs keep theirs in each solution's info).
    """

    status: str
    best: Solution | None
    front: ParetoFront | None
    evaluations: int
    seconds: float
    history: tuple[HistoryRow, ...] = ()


def status_of(best: Solution | None, cancelled: bool) -> str:
    """ "cancelled", else "feasible" when ``best`` meets every constraint on every patch."""
    if cancelled:
        return "cancelled"
    return "feasible" if best is not None and best.feasible else "infeasible"
