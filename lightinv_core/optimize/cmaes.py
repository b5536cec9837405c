"""CMA-ES with IPOP restarts (package ``cma``, BSD-3) over the design's variables.

The search runs in the unit cube: each variable scaled by its bounds, so one step size
fits all (metres of a corner, lumens of a flux, a filter). ``cma``'s ``BoundTransform``
keeps every sampled candidate inside the bounds. A generation is one batch for
``DesignProblem.evaluate``.

Ranking is the feasibility-first rule every method uses (search.better): candidates
breaking a geometric rule rank last (ordered by how far they break it, so the
distribution is pulled back to valid layouts), then those breaking an intention or
epsilon bound (by f + P), then the feasible ones (by f). CMA-ES uses only the ranks of
a generation, so the fitness handed to ``cma`` is the class offset plus the key.

IPOP (Auger and Hansen 2005): when ``cma`` reports convergence or stagnation the search
restarts from a new random layout with twice the population. The best over all
restarts is the answer. Randomness comes from ``np.random.default_rng(seed)`` through
``cma``'s ``randn`` option (never numpy's global state), so the same seed gives the
same result even with other runs in other threads.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from lightinv_core.optimize.method import MethodSpec, RunContext, context_of
from lightinv_core.optimize.problem import DesignProblem, Evaluation, Level
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import (
    SearchResult,
    best_of,
    better,
    first_point,
    judged,
    random_start,
)

SIGMA0 = 0.3
"""Initial step size in the unit cube (a third of each range: wide enough to leave a
poor start, the usual choice for a box-bounded problem)."""
TOLX = 1e-5
"""Restart when steps are below 1e-5 of each range (0.1 mm of a 10 m zone): finer
moves do not change the light measurably (``cma``'s default, 1e-11, spends thousands
of evaluations there)."""
TOLFUN = 1e-9
"""Restart when a generation's values differ by less than this (goals are scaled to
about [0, 1])."""
MAX_POPSIZE_FACTOR = 32
"""IPOP doubles the population at each restart up to this multiple of the default."""
_INFEASIBLE, _REJECTED = 1e6, 1e9


def ranking_fitness(ev: Evaluation) -> np.ndarray:
    """Values whose order is the feasibility-first rule: feasible by f, then infeasible
    by f + P, then geometry-rejected by their summed rule violation."""
    fit = np.where(ev.penalty == 0.0, ev.value, _INFEASIBLE + np.minimum(ev.value, 1e5))
    broken = ~ev.ok
    if broken.any():
        excess = np.maximum(ev.geometry[broken], 0.0).sum(axis=1)
        fit[broken] = _REJECTED + np.minimum(excess, 1e8)
    return fit


class CMAESRun:
    """A CMA-ES search taken one generation at a time (``step``), for a driver that
    interleaves it with other searches (``auto``); ``cmaes`` runs one to its stop.

    ``budget`` holds its evaluations, best (value, penalty, goal) and history; ``best_x``
    its best layout; ``restarts`` the IPOP restarts begun so far."""

    def __init__(
        self,
        problem: DesignProblem,
        context: RunContext,
        level: Level | None = None,
        popsize: int | None = None,
    ):
        self.problem, self.context = problem, context
        self.rng = np.random.default_rng(context.seed)
        self.level = level or problem.level(1)
        x, self.budget = first_point(
            problem, context.x0, self.rng, self.level, context.stop, context.cancel
        )
        self.x0, self.best_x = x, x.copy()
        lo, hi = problem.vars.lo, problem.vars.hi
        self.lo, self.span = lo, np.where(hi > lo, hi - lo, 1.0)
        self.lam0 = popsize or 4 + int(3 * math.log(problem.vars.n))
        self.lam, self.iterations, self.restarts = self.lam0, 0, 0
        self.es = None

    def _new_run(self):
        import cma  # lazily: only CMA-ES runs need it

        if self.es is not None:  # IPOP: each restart doubles the population
            self.restarts += 1
            self.lam = min(2 * self.lam, MAX_POPSIZE_FACTOR * self.lam0)
        start = self.x0 if self.restarts == 0 else random_start(self.problem, self.rng)
        z0 = (start - self.lo) / self.span
        if len(z0) == 1:
            # cma refuses one dimension: a second coordinate that no layout reads (step
            # drops it) keeps a design with one free variable searchable.
            z0 = np.append(z0, 0.5)
        rng = self.rng
        return cma.CMAEvolutionStrategy(
            z0,
            SIGMA0,
            {
                "bounds": [0.0, 1.0],
                "popsize": self.lam,
                "randn": lambda *shape: rng.standard_normal(shape),
                "seed": np.nan,  # never touch numpy's global random state
                "tolx": TOLX,
                "tolfun": TOLFUN,
                "verbose": -10,  # silent; no signals file read from the working folder
                "verb_log": 0,  # no output files
                "verb_disp": 0,
                "maxiter": np.inf,
            },
        )

    def step(self) -> int:
        """One generation (a new IPOP run first when the last one has converged or
        stagnated); returns the candidates evaluated."""
        if self.es is None or self.es.stop():
            self.es = self._new_run()
        es, budget, problem = self.es, self.budget, self.problem
        Z = np.asarray(es.ask())
        X = self.lo + np.clip(Z[:, : len(self.lo)], 0.0, 1.0) * self.span
        ev = problem.evaluate(X, self.level)
        es.tell(list(Z), ranking_fitness(ev).tolist())
        budget.evals += ev.evaluated
        self.iterations += 1
        j = best_of(ev)
        if ev.ok[j] and better(ev.value[j], ev.penalty[j], *budget.best[:2]):
            self.best_x = X[j].copy()
            budget.improve(ev, j)
        if self.context.progress is not None:
            self.context.progress(budget.snapshot(self.iterations, self.level.divisor, self.best_x))
        return ev.evaluated


def cmaes(
    problem: DesignProblem,
    context: RunContext | None = None,
    level: Level | None = None,
    popsize: int | None = None,
    **given: Any,
) -> SearchResult:
    """Minimise f + P by CMA-ES with IPOP restarts at ``level`` (default: every patch),
    with the context's seed, stop rule and hooks (or those fields ``given`` as
    keywords); returns the best solution found.

    ``context.x0`` starts the first run (later restarts start at random layouts);
    ``popsize`` is the first run's population (default ``cma``'s 4 + 3 ln n).
    """
    run = CMAESRun(problem, context_of(context, given), level, popsize)
    while (why := run.budget.why()) is None:
        run.step()
    return run.budget.result(run.best_x, run.iterations, why)


def run_cmaes(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """One CMA-ES run (restarts included) within ``context.stop``."""
    return judged(problem, cmaes(problem, context), CMAES.name, context.seed)


CMAES = MethodSpec("cmaes", "CMA-ES (IPOP restarts)", run_cmaes)
"""CMA-ES with IPOP restarts on every patch."""
