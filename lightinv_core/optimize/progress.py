"""What a running optimisation reports: immutable snapshots, and the callback types."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Progress:
    """An immutable snapshot for progress callbacks (GUI plots, CLI, autosave).

    ``iteration`` counts the method's own steps (a VNS local search, a CMA-ES generation);
    ``evaluations`` the light evaluations so far; ``elapsed`` seconds; ``best_value`` the
    best minimised value f + P, ``best_penalty`` its penalty P and ``best_goal`` its
    primary goal in its units (NSGA-II: ``best_goal`` is the front's normalised
    hypervolume, ``best_value`` its negative, ``best_penalty`` the least summed
    violation until a feasible point exists, then 0). ``level`` is the divisor of the
    patches evaluated (about n / level representatives; 1 = every patch). ``best_x`` is
    the best variable vector so far (the problem's own variables; a multi-objective
    driver's sub-problems may have other variables than the design's; empty for
    NSGA-II). ``run``/``runs`` say which of several runs of a driver (epsilon values,
    two-step runs, seeds, auto's front and its two end searches) this is, from 0.
    """

    iteration: int
    evaluations: int
    elapsed: float
    best_value: float
    best_penalty: float
    best_goal: float
    level: int
    best_x: tuple[float, ...] = ()
    run: int = 0
    runs: int = 1


ProgressFn = Callable[[Progress], None]
CancelFn = Callable[[], bool]
