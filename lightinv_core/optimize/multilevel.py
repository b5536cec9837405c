"""Multilevel VNS (paper 5.2): optimise on n/64, then n/16 representative patches,
then all patches, each level warm-started from the previous one's best."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.vns import Progress, StopRule, VNSResult, vns

DEFAULT_DIVISORS = (64, 16, 1)


def multilevel(
    problem: DesignProblem,
    divisors: tuple[int, ...] = DEFAULT_DIVISORS,
    seed: int = 0,
    stop: StopRule | None = None,
    level_stop: StopRule | None = None,
    x0: np.ndarray | None = None,
    trials: int = 32,
    progress: Callable[[Progress], None] | None = None,
    cancel: Callable[[], bool] | None = None,
) -> tuple[VNSResult, list[VNSResult]]:
    """Run VNS level by level; returns the last level's result (judged on all patches
    when the last divisor is 1) and every level's result.

    ``level_stop`` bounds the coarse levels (default: ``stop``); the evaluation and
    time budgets of ``stop`` are shared by all levels. A cancelled level ends the run.
    """
    stop = stop or StopRule()
    results: list[VNSResult] = []
    x = x0
    used_evals, used_time = 0, 0.0
    for i, d in enumerate(divisors):
        rule = stop if i == len(divisors) - 1 or level_stop is None else level_stop
        if stop.max_evals is not None:
            left = stop.max_evals - used_evals
            rule = replace(rule, max_evals=max(1, min(rule.max_evals or left, left)))
        if stop.time_limit is not None:
            left_t = stop.time_limit - used_time
            rule = replace(rule, time_limit=max(0.0, min(rule.time_limit or left_t, left_t)))
        res = vns(
            problem,
            x0=x,
            seed=seed + 7919 * i,
            stop=rule,
            level=problem.level(d),
            trials=trials,
            progress=progress,
            cancel=cancel,
        )
        results.append(res)
        x = res.x
        used_evals += res.evaluations
        used_time += res.seconds
        if res.status == "cancelled":
            break
    final = results[-1]
    total = VNSResult(
        final.x,
        final.value,
        final.penalty,
        final.goal,
        used_evals,
        sum(r.iterations for r in results),
        used_time,
        final.status,
        [h for r in results for h in r.history],
    )
    return total, results
