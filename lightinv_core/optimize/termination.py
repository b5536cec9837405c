"""When a run stops: evaluations, wall time, a target, stall, or the caller's cancel."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class StopRule:
    """When to stop; ``None`` disables a criterion. ``max_evals`` counts light
    evaluations, ``time_limit`` is in seconds, ``target`` is in the primary goal's units
    (W, lm, or the match error e) and counts only when feasible (P = 0), ``stall`` is the
    number of evaluations without improvement."""

    max_evals: int | None = 20_000
    time_limit: float | None = None
    target: float | None = None
    stall: int | None = None
