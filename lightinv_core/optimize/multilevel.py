"""Multilevel VNS (paper 5.2): optimise on n/64, then n/16 representative patches,
then all patches, each level warm-started from the previous one's best.

The answer is always judged on every patch: a level list that does not end with 1
gets a final all-patch level, so a layout that is feasible only at a coarse level is
never returned as the answer: it goes on at full resolution with at least a quarter
of the budget (``FULL_LEVEL_SHARE``), and is reported infeasible if it is still
infeasible when that runs out.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from lightinv_core.optimize.method import MethodSpec, RunContext, context_of
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import SearchResult, judged
from lightinv_core.optimize.termination import StopRule
from lightinv_core.optimize.vns import vns

DEFAULT_DIVISORS = (64, 16, 1)
FULL_LEVEL_SHARE = 0.25
"""Part of the evaluation and time budgets the coarse levels leave to the full level: a
coarse answer can break bounds by several times on patches no representative sees."""


def full_resolution(divisors: tuple[int, ...]) -> tuple[int, ...]:
    """``divisors`` ending at 1 (every patch): a final level is added when missing."""
    divisors = tuple(int(d) for d in divisors) or (1,)
    return divisors if divisors[-1] <= 1 else (*divisors, 1)


def multilevel(
    problem: DesignProblem,
    context: RunContext | None = None,
    divisors: tuple[int, ...] = DEFAULT_DIVISORS,
    level_stop: StopRule | None = None,
    trials: int = 32,
    **given: Any,
) -> tuple[SearchResult, list[SearchResult]]:
    """Run VNS level by level from ``context.x0``, with the context's seed, stop rule and
    hooks (or those fields ``given`` as keywords); returns the result of the last level
    (every patch: see ``full_resolution``) and every level's result.

    ``level_stop`` bounds the coarse levels (default: the context's stop); the
    evaluation and time budgets of that stop are shared by all levels, the coarse ones
    using at most 1 - ``FULL_LEVEL_SHARE`` of them. A cancelled level ends the run.
    """
    c = context_of(context, given)
    stop = c.stop
    divisors = full_resolution(divisors)
    results: list[SearchResult] = []
    x = c.x0
    used_evals, used_time = 0, 0.0
    for i, d in enumerate(divisors):
        last = i == len(divisors) - 1
        rule = stop if last or level_stop is None else level_stop
        # The coarse levels leave the full level at least FULL_LEVEL_SHARE of each budget.
        keep = 0.0 if last else FULL_LEVEL_SHARE
        if stop.max_evals is not None:
            left = int(stop.max_evals * (1 - keep)) - used_evals
            rule = replace(rule, max_evals=max(1, min(rule.max_evals or left, left)))
        if stop.time_limit is not None:
            left_t = stop.time_limit * (1 - keep) - used_time
            rule = replace(rule, time_limit=max(0.0, min(rule.time_limit or left_t, left_t)))
        res = vns(problem, c.but(x0=x, seed=c.seed + 7919 * i, stop=rule), problem.level(d), trials)
        results.append(res)
        x = res.x
        used_evals += res.evaluations
        used_time += res.seconds
        if res.status == "cancelled":
            break
    final = results[-1]
    total = SearchResult(
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


@dataclass(frozen=True)
class MultilevelSettings:
    """``divisors``: the levels (about n/d representative patches each); the coarse
    levels stop at ``level_max_evals``, ``level_target`` or the run's ``stall``;
    ``trials`` as VNS's."""

    divisors: tuple[int, ...] = DEFAULT_DIVISORS
    level_max_evals: int | None = None
    level_target: float | None = None
    trials: int = 32


def run_multilevel(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """Levels ``divisors``, each warm-started from the previous (the first from
    ``context.x0``)."""
    s, c = context.options(MultilevelSettings), context
    level_stop = StopRule(max_evals=s.level_max_evals, target=s.level_target, stall=c.stop.stall)
    res, levels = multilevel(problem, c, tuple(s.divisors), level_stop, s.trials)
    per_level = tuple(r.evaluations for r in levels)
    return judged(problem, res, MULTILEVEL.name, c.seed, level_evaluations=per_level)


MULTILEVEL = MethodSpec("multilevel", "Multilevel VNS", run_multilevel, MultilevelSettings)
"""VNS on coarse representative patches first, then on every patch (paper 5.2)."""
