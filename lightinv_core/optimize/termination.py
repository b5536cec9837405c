"""When a run stops: evaluations, wall time, a target, stall, or the caller's cancel."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class StopRule:
    """When to stop; ``None`` disables a criterion. ``max_evals`` counts light
    evaluations, ``time_limit`` is in seconds, ``target`` is in the primary goal's units
    (W, lm, or the match error e) and counts only when feasible (P = 0), ``stall`` is the
    number of evaluations without improvement. Rules are checked between batches, so a
    run may pass ``max_evals`` by one batch (VNS: ``trials``; CMA-ES: a generation,
    which IPOP restarts double; NSGA-II: a population)."""

    max_evals: int | None = 20_000
    time_limit: float | None = None
    target: float | None = None
    stall: int | None = None
