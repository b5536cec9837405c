"""Variable Neighbourhood Search over source parameters (paper Algorithm 1).

Neighbourhood N(v, r): change v randomly chosen variables at once, each by a
uniform step in +-r of its range (clipped to its bounds). Neighbourhoods are
tried from small to large (r = 0.1 .. 1, and v = 1 .. min(nvar, MAX_V) within each
r); each local search draws ``trials`` neighbours and evaluates them as ONE
batch (geometric rules first, then one radiosity GEMM). If the best neighbour
improves f + P the search moves there and restarts at the first neighbourhood,
otherwise it goes on to the next; after the last it starts over.

One addition to Algorithm 1's acceptance test f(x') + P(x') < f(x) + P(x):
feasibility is never given up. A feasible trial (P = 0) beats an infeasible
incumbent, and an infeasible trial never replaces a feasible incumbent, so a
run that reaches the feasible region ends with P = 0 (with a quadratic
penalty, f + P alone settles just outside an active bound).

Stopping: evaluations, wall time, a target value of the primary goal (reached
with P = 0), stall (evaluations without improvement), or ``cancel()``; a
cancelled run returns its best solution. Everything random comes from
``np.random.default_rng(seed)``: the same seed gives the same result.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from lightinv_core.optimize.method import MethodSpec, RunContext, context_of
from lightinv_core.optimize.problem import DesignProblem, Level
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import SearchResult, best_of, better, first_point, judged

R_VALUES = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)
MAX_V = 4
"""Most variables changed at once. The paper allows v up to nvar; measured on
experiments 1 and 5, v <= 4 converges as reliably and faster (larger moves are
almost always rejected)."""


def neighbourhoods(
    nvar: int, r_values=R_VALUES, max_v: int | None = MAX_V
) -> list[tuple[int, float]]:
    """The (v, r) grid in the order it is explored."""
    top = nvar if max_v is None else min(nvar, max_v)
    return [(v, r) for r in r_values for v in range(1, top + 1)]


class VNSRun:
    """A VNS search taken one local search at a time (``step``), for a driver that
    interleaves it with other searches (``auto``); ``vns`` runs one to its stop.

    ``budget`` holds its evaluations, best (value, penalty, goal) and history, ``best_x``
    its best layout; ``stuck`` says a whole sweep of the neighbourhoods found nothing
    better than the incumbent (a local optimum for every one). ``restart(x)`` goes on
    from another layout (the best found is kept): the incumbent becomes x, evaluated,
    and the neighbourhoods start again."""

    def __init__(
        self,
        problem: DesignProblem,
        context: RunContext,
        level: Level | None = None,
        trials: int = 32,
    ):
        self.problem, self.context, self.trials = problem, context, trials
        self.rng = np.random.default_rng(context.seed)
        self.level = level or problem.level(1)
        self.x, self.budget = first_point(
            problem, context.x0, self.rng, self.level, context.stop, context.cancel
        )
        self.best_x = self.x
        self.here = self.budget.best[:2]  # the incumbent's (value, penalty)
        self.hoods = neighbourhoods(problem.vars.n)
        self.k, self.iterations = 0, 0
        self.stuck = False  # a whole sweep of the neighbourhoods found nothing better

    def restart(self, x: np.ndarray) -> int:
        """Go on from layout x (meeting the geometric rules); returns the evaluations
        (one)."""
        ev = self.problem.evaluate(x[None], self.level)
        self.budget.evals += ev.evaluated
        self.x, self.k, self.stuck = x, 0, False
        self.here = (float(ev.value[0]), float(ev.penalty[0]))
        if better(*self.here, *self.budget.best[:2]):
            self.best_x = x
            self.budget.improve(ev, 0)
        return ev.evaluated

    def step(self) -> int:
        """One local search: ``trials`` neighbours of the incumbent in the current
        neighbourhood, as one batch; returns the candidates evaluated."""
        problem, rng, budget, trials = self.problem, self.rng, self.budget, self.trials
        nvar = problem.vars.n
        lo, hi = problem.vars.lo, problem.vars.hi
        v, r = self.hoods[self.k]
        X = np.repeat(self.x[None], trials, axis=0)
        pick = np.argsort(rng.random((trials, nvar)), axis=1)[:, :v]
        step = rng.uniform(-r, r, (trials, v)) * (hi - lo)[pick]
        rows = np.repeat(np.arange(trials), v)
        X[rows, pick.ravel()] += step.ravel()
        X = np.clip(X, lo, hi)
        ev = problem.evaluate(X, self.level)
        budget.evals += ev.evaluated
        self.iterations += 1
        j = best_of(ev)
        if better(ev.value[j], ev.penalty[j], *self.here):
            self.x, self.k, self.stuck = X[j], 0, False
            self.here = (float(ev.value[j]), float(ev.penalty[j]))
            if better(*self.here, *budget.best[:2]):
                self.best_x = self.x
                budget.improve(ev, j)
        else:
            self.k = (self.k + 1) % len(self.hoods)
            self.stuck = self.stuck or self.k == 0
        if self.context.progress is not None:
            self.context.progress(budget.snapshot(self.iterations, self.level.divisor, self.best_x))
        return ev.evaluated


def vns(
    problem: DesignProblem,
    context: RunContext | None = None,
    level: Level | None = None,
    trials: int = 32,
    **given: Any,
) -> SearchResult:
    """Minimise f + P over the problem's variables at ``level`` (default: every patch)
    from ``context.x0``, with its seed, stop rule and hooks (or those fields ``given``
    as keywords); returns the best solution found."""
    run = VNSRun(problem, context_of(context, given), level, trials)
    while (why := run.budget.why()) is None:
        run.step()
    return run.budget.result(run.best_x, run.iterations, why)


@dataclass(frozen=True)
class VNSSettings:
    """``trials``: neighbours drawn (and evaluated as one batch) per local search."""

    trials: int = 32


def run_vns(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """One VNS run on every patch, from ``context.x0`` or a random layout."""
    res = vns(problem, context, trials=context.options(VNSSettings).trials)
    return judged(problem, res, VNS.name, context.seed)


VNS = MethodSpec("vns", "VNS", run_vns, VNSSettings)
"""Variable Neighbourhood Search on every patch (paper Algorithm 1)."""
