"""NSGA-II (package ``pymoo``, Apache-2.0) for the front of the design's own two goals
(``fronts.design_pair``): electric power (W) against reflected light power (lm), annual
energy (kWh) against glazing area (m²), or any other pair (sDA, installed power,
luminaire count, a registered goal), each minimised or maximised as its ``GoalSpec``
says. A design with fewer than two goals, or a goal that cannot change, is refused with
the reason (``fronts.front_refusal``).

Constraints reach pymoo as G (every geometric rule, intention bound), not as a penalty:
its constrained tournament and survival prefer feasible candidates, then smaller summed
violation (Deb's rules, the same feasibility-first order as the other methods). Each
generation is one batch for ``DesignProblem.evaluate`` on every patch.

The first population is made of random layouts that meet the geometric rules (uniform
samples mostly break the area and aspect rules). Every feasible candidate evaluated
enters an archive of non-dominated points; the answer is that archive, thinned to at
most ``population`` points by dropping the point of least hypervolume contribution, each
point judged on every patch. Randomness: pymoo's per-algorithm generator seeded with
the run's seed, and ``np.random.default_rng(seed)`` for the first population.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from lightinv_core.design.model import Goal
from lightinv_core.design.solution import SolutionInfo
from lightinv_core.errors import DesignError
from lightinv_core.goals import goal_spec
from lightinv_core.kinds import GoalKind
from lightinv_core.optimize.fronts import design_goal, design_pair, front_of, front_refusal
from lightinv_core.optimize.method import MethodSpec, RunContext, SolutionFn, always_front
from lightinv_core.optimize.pareto import hypervolume_2d, non_dominated
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.progress import Progress
from lightinv_core.optimize.quality import front_scales
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import random_layouts

_BIG = 1e12  # stands for +inf (not lit) in F and G: pymoo needs finite numbers


def thin(F: np.ndarray, keep: int) -> np.ndarray:
    """Indices of at most ``keep`` rows of the non-dominated 2-D points F (minimised),
    dropping one at a time the point of least exclusive hypervolume (extremes stay)."""
    idx = np.argsort(F[:, 0], kind="stable")
    while len(idx) > max(keep, 2):
        P = F[idx]
        contrib = (P[2:, 0] - P[1:-1, 0]) * (P[:-2, 1] - P[1:-1, 1])
        idx = np.delete(idx, 1 + int(np.argmin(contrib)))
    return idx


@dataclass(frozen=True)
class NSGA2Run:
    """An NSGA-II run: the archive's x (k, nvar) and normalised F (k, 2), the light
    evaluations, why it stopped, seconds, and the candidate of least summed violation
    seen (the answer to explain when nothing was feasible)."""

    X: np.ndarray
    F: np.ndarray
    evaluations: int
    status: str
    seconds: float
    closest: np.ndarray


def reference_point(pair) -> tuple[float, float]:
    """The hypervolume's reference in minimised normalised objectives: 1 for a
    minimised goal (its scale), 0 for a maximised one (none of it, -0 minimised)."""
    return tuple(-0.0 if goal_spec(k).maximise else 1.0 for k in pair)


class _Archive:
    """Feasible non-dominated (x, F) seen so far, F as minimised normalised objectives,
    measured from the reference point ``ref``."""

    def __init__(self, nvar: int, ref: tuple[float, float]):
        self.X, self.F = np.zeros((0, nvar)), np.zeros((0, 2))
        self.ref = ref

    def add(self, X: np.ndarray, F: np.ndarray) -> None:
        X, F = np.vstack([self.X, X]), np.vstack([self.F, F])
        _, first = np.unique(F, axis=0, return_index=True)
        first = np.sort(first)
        X, F = X[first], F[first]
        keep = non_dominated(F)
        self.X, self.F = X[keep], F[keep]

    def hypervolume(self) -> float:
        return hypervolume_2d(self.F, self.ref)


def nsga2(
    problem: DesignProblem, scales: tuple[float, float], population: int, context: RunContext
) -> NSGA2Run:
    """Run NSGA-II on ``problem``'s two goals (``problem.objectives``, divided by
    ``scales``, their units) with the context's seed, stop rule, ``progress`` and
    ``cancel``."""
    from pymoo.algorithms.moo.nsga2 import NSGA2 as PymooNSGA2  # lazily: only front runs need pymoo
    from pymoo.core.problem import Problem

    seed, stop = context.seed, context.stop
    progress, cancel = context.progress, context.cancel
    n = problem.vars.n
    if n == 0:
        raise DesignError("nothing to optimise: no source has a free variable")
    lo, hi = problem.vars.lo, problem.vars.hi
    span = np.where(hi > lo, hi - lo, 1.0)
    norm = np.array(scales)  # ev.F, e.g. (P, -L) -> (P/Pmax, -L/Lmax)
    archive = _Archive(n, reference_point(problem.objectives))
    count = {"evals": 0}
    ncon = len(problem.constraints)

    class _Lit(Problem):
        def __init__(self):
            super().__init__(n_var=n, n_obj=2, n_ieq_constr=max(ncon, 1), xl=0.0, xu=1.0)

        def _evaluate(self, Z, out, *args, **kwargs):
            X = lo + np.clip(Z, 0.0, 1.0) * span
            ev = problem.evaluate(X)
            count["evals"] += ev.evaluated
            F = ev.F / norm
            F = np.nan_to_num(F, nan=_BIG, posinf=_BIG, neginf=-_BIG)
            G = ev.G if ncon else np.zeros((len(X), 1))
            G = np.nan_to_num(G, nan=_BIG, posinf=_BIG)
            ok = np.all(G <= 0, axis=1)
            if ok.any():
                archive.add(Z[ok], F[ok])
            out["F"], out["G"] = F, G

    rng = np.random.default_rng(seed)
    start = (random_layouts(problem, rng, population) - lo) / span
    algo = PymooNSGA2(pop_size=population, sampling=start, eliminate_duplicates=True)
    lit = _Lit()
    algo.setup(lit, termination=("n_gen", 10**9), seed=int(seed) % 2**32, verbose=False)
    t0 = time.perf_counter()
    best_hv, last_gain, gen = 0.0, 0, 0
    least_cv, closest = np.inf, lo + start[0] * span
    why = None
    while True:
        if cancel is not None and cancel():
            why = "cancelled"
        elif stop.max_evals is not None and count["evals"] >= stop.max_evals:
            why = "max_evals"
        elif stop.time_limit is not None and time.perf_counter() - t0 >= stop.time_limit:
            why = "time_limit"
        elif stop.stall is not None and count["evals"] - last_gain >= stop.stall:
            why = "stall"
        if why is not None:
            break
        pop = algo.ask()
        algo.evaluator.eval(lit, pop)
        algo.tell(infills=pop)
        gen += 1
        hv = archive.hypervolume()
        cv = pop.get("CV").ravel()
        j = int(np.argmin(cv))
        # Before the first feasible point, less violation is progress (for ``stall``).
        if hv > best_hv or (hv == 0.0 and cv[j] < least_cv):
            best_hv, last_gain = hv, count["evals"]
        if cv[j] < least_cv:
            least_cv, closest = float(cv[j]), lo + pop[j].X * span
        if progress is not None:
            least = 0.0 if len(archive.F) else least_cv
            progress(Progress(gen, count["evals"], time.perf_counter() - t0, -hv, least, hv, 1))
    X = lo + archive.X * span
    return NSGA2Run(X, archive.F, count["evals"], why, time.perf_counter() - t0, closest)


@dataclass(frozen=True)
class NSGA2Settings:
    """``population``: the population size (and the most points of the front)."""

    population: int = 100


def run_nsga2(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """One NSGA-II run within ``context.stop``; the front's points go to
    ``context.on_solution`` once judged."""
    pop, c = context.options(NSGA2Settings).population, context
    mop = front_problem(problem)
    scales = front_scales(mop.design, mop.light, mop.objectives)
    run = nsga2(mop, scales, pop, c)
    return judged_front(mop, run, pop, NSGA2.name, c.seed, c.on_solution)


NSGA2 = MethodSpec(
    "nsga2",
    "NSGA-II front",
    run_nsga2,
    NSGA2Settings,
    always_front,
    count_setting=("Population", "population"),
    progress_label="front hypervolume",
    refusal=lambda design: front_refusal(design, "NSGA-II"),
)
"""NSGA-II front of the design's two goals (pymoo)."""


def front_problem(problem: DesignProblem) -> DesignProblem:
    """``problem``'s design with its front's two goals (``design_pair``) in that order;
    DesignError with the reason when it has no front (``front_refusal``)."""
    design = problem.design
    why = front_refusal(design, "NSGA-II")
    if why is not None:
        raise DesignError(why)
    a, b = design_pair(design)
    # Electric power as a plain goal, as before goals were the design's: same runs.
    first = Goal(a) if a == GoalKind.MIN_ELECTRIC_POWER else design_goal(design, a)
    goals = (first, design_goal(design, b))
    if goals == tuple(design.goals):
        return problem
    return DesignProblem(replace(design, goals=goals), problem.light)


def judged_front(
    mop: DesignProblem,
    run: NSGA2Run,
    population: int,
    method: str,
    seed: int,
    on_solution: SolutionFn | None = None,
) -> OptimizationResult:
    """The archive thinned to ``population`` points, each judged on every patch (sent to
    ``on_solution``), as the run's front; the least-violating candidate when nothing was
    feasible, to say what stands in the way."""
    info = SolutionInfo(method=method, seed=seed, evaluations=run.evaluations, status=run.status)
    picks = [run.X[i] for i in thin(run.F, population)] if len(run.F) else []
    solutions = [mop.solution(x, info) for x in picks or [run.closest]]
    for sol in solutions:
        if on_solution is not None and sol.feasible:
            on_solution(sol)
    front = front_of(solutions, method, tuple(map(str, mop.objectives)))
    best = front.solutions[0] if front.solutions else None
    if run.status == "cancelled":
        status = "cancelled"
    else:
        status = "feasible" if best is not None else "infeasible"
    return OptimizationResult(status, best, front, run.evaluations, run.seconds)
