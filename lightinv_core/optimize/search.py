"""What every single-objective search shares: its trace, a geometry-valid random start,
the feasibility-first comparison, the stop test and the answer judged on every patch.

The comparison (``better``) is the rule every method ranks by: a feasible candidate
(P = 0) beats an infeasible one; among feasible ones the smaller value wins, among
infeasible ones the smaller f + P. With a quadratic penalty, f + P alone would settle
just outside an active bound.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from lightinv_core.design.geometry import MIN_SIDE, rule_names
from lightinv_core.design.solution import SolutionInfo
from lightinv_core.errors import DesignError
from lightinv_core.goals import goal_spec
from lightinv_core.optimize.problem import DesignProblem, Evaluation, Level
from lightinv_core.optimize.progress import CancelFn, Progress
from lightinv_core.optimize.result import HistoryRow, OptimizationResult, status_of
from lightinv_core.optimize.termination import StopRule

START_TRIES = 20_000


@dataclass
class SearchResult:
    """Best x found, its scores, and the convergence history
    (evaluations, best value, best penalty, best primary goal) at each improvement."""

    x: np.ndarray
    value: float
    penalty: float
    goal: float
    evaluations: int
    iterations: int
    seconds: float
    status: str
    history: list[tuple[int, float, float, float]] = field(default_factory=list)


def check_fixed_sources(problem: DesignProblem) -> None:
    """A DesignError naming a source whose rectangle is fixed (no corner free, no tie)
    but degenerate or outside its zone: no search can move it, so say which it is."""
    tied = {s for r in problem.design.rules if r.kind in ("mirror", "centred") for s in r.sources}
    corners = {"u0", "v0", "u1", "v1"}
    for i, src in enumerate(problem.design.sources):
        if corners & set(src.free) or src.name in tied:
            continue
        u0, v0, u1, v1 = src.rect
        w, h = abs(u1 - u0), abs(v1 - v0)
        zw, zh = problem.zone_size[i]
        rect = f"({u0:g}, {v0:g}, {u1:g}, {v1:g})"
        if min(w, h) < MIN_SIDE:
            raise DesignError(
                f"source {src.name!r}: its fixed rect {rect} is {w:g} x {h:g} m, a line or a "
                f"point; give it a width and a height of at least {MIN_SIDE * 1000:g} mm"
            )
        tol = 1e-9
        if (
            min(u0, u1) < -tol
            or max(u0, u1) > zw + tol
            or min(v0, v1) < -tol
            or max(v0, v1) > zh + tol
        ):
            raise DesignError(
                f"source {src.name!r}: its fixed rect {rect} lies outside its zone "
                f"{src.zone!r}, which spans 0 to {zw:g} m by 0 to {zh:g} m; move it inside "
                "or let its position be optimised"
            )


def random_start(problem: DesignProblem, rng: np.random.Generator) -> np.ndarray:
    """A random x meeting every geometric rule (DesignError if none is found: the rules
    cannot be met together, e.g. a minimum area larger than the zone; a fixed source
    that is degenerate or outside its zone is named)."""
    check_fixed_sources(problem)
    lo, hi = problem.vars.lo, problem.vars.hi
    failing = np.zeros(len(rule_names(problem.design)), np.int64)
    for _ in range(START_TRIES // 500):
        X = lo + rng.random((500, len(lo))) * (hi - lo)
        broken = problem.rule_violations(X) > 0
        ok = np.flatnonzero(~np.any(broken, axis=1))
        if len(ok):
            return X[ok[0]]
        failing += broken.sum(axis=0)
    # Name the rule most layouts break: the one to relax first.
    k = int(np.argmax(failing))
    worst = rule_names(problem.design)[k]
    hint = "check area, aspect and spacing bounds against the zone sizes"
    if k == 0 and problem.outlines:
        hint = (
            "sources must lie inside their zone's polygon outline; a source too large "
            "for the polygon, or a mirrored or centred copy (tied across the polygon's "
            "bounding rectangle) that falls outside it, cannot"
        )
    raise DesignError(
        f"no random layout out of {START_TRIES:,} meets the geometric rules; "
        f"most break {worst!r}: {hint}"
    )


def random_layouts(problem: DesignProblem, rng: np.random.Generator, count: int) -> np.ndarray:
    """``count`` random x (count, nvar) meeting every geometric rule (see ``random_start``)."""
    lo, hi = problem.vars.lo, problem.vars.hi
    found: list[np.ndarray] = []
    total = 0
    while total < count:
        X = lo + rng.random((500, len(lo))) * (hi - lo)
        ok = ~np.any(problem.rule_violations(X) > 0, axis=1)
        if not ok.any():
            found.append(random_start(problem, rng)[None])  # raises when the rules clash
            total += 1
            continue
        found.append(X[ok])
        total += int(ok.sum())
    return np.vstack(found)[:count]


def better(value: float, penalty: float, best_value: float, best_penalty: float) -> bool:
    """Paper Algorithm 1's test f + P < best, except that feasibility is never given up:
    a feasible trial beats an infeasible incumbent, an infeasible one never beats a
    feasible incumbent."""
    if (penalty == 0.0) != (best_penalty == 0.0):
        return penalty == 0.0
    return value < best_value


def best_of(ev: Evaluation) -> int:
    """Index of the best candidate of a batch by ``better``: feasible ones (P = 0) first,
    then by f + P."""
    rank = np.where(ev.penalty == 0.0, ev.value, np.inf)
    return int(np.argmin(rank)) if np.isfinite(rank).any() else int(np.argmin(ev.value))


def goal_of(problem: DesignProblem, ev: Evaluation, j: int) -> float:
    """Candidate j's primary goal in its units (W, lm or e)."""
    return float(ev.goals[problem.primary][j])


def reached(problem: DesignProblem, goal: float, target: float) -> bool:
    """Whether the primary goal value ``goal`` meets ``target`` (at least, for light power)."""
    if goal_spec(problem.primary).maximise:
        return goal >= target
    return goal <= target


class Budget:
    """The stop test of one search: ``why()`` names the reason to stop, or None.

    ``evals`` and ``best`` (value, penalty, goal) are updated by the search; ``gain()``
    marks an improvement (for the stall rule), ``improve`` records a better candidate
    in ``best`` and ``history``.
    """

    def __init__(self, problem: DesignProblem, stop: StopRule, cancel: CancelFn | None):
        self.problem, self.stop, self.cancel = problem, stop, cancel
        self.t0 = time.perf_counter()
        self.evals = 0
        self.last_gain = 0
        self.best = (np.inf, np.inf, np.nan)
        self.history: list[tuple[int, float, float, float]] = []

    def improve(self, ev: Evaluation, j: int) -> None:
        """Candidate j of ``ev`` is the new best (the evaluations already counted)."""
        self.best = (float(ev.value[j]), float(ev.penalty[j]), goal_of(self.problem, ev, j))
        self.history.append((self.evals, *self.best))
        self.gain()

    def result(self, x: np.ndarray, iterations: int, status: str) -> SearchResult:
        """The search's outcome, ``x`` its best layout."""
        return SearchResult(
            x, *self.best, self.evals, iterations, self.elapsed(), status, self.history
        )

    def elapsed(self) -> float:
        """Seconds since the search began."""
        return time.perf_counter() - self.t0

    def gain(self) -> None:
        """The best just improved."""
        self.last_gain = self.evals

    def target_met(self) -> bool:
        """The best is feasible and meets the stop rule's target."""
        t = self.stop.target
        return t is not None and self.best[1] == 0.0 and reached(self.problem, self.best[2], t)

    def snapshot(self, iteration: int, divisor: int, x: np.ndarray) -> Progress:
        """The progress report of the search now, ``x`` its best layout."""
        return Progress(
            iteration,
            self.evals,
            self.elapsed(),
            *self.best,
            divisor,
            tuple(float(c) for c in x),
        )

    def why(self) -> str | None:
        """ "cancelled", "max_evals", "time_limit", "target", "stall", or None to go on."""
        stop = self.stop
        if self.cancel is not None and self.cancel():
            return "cancelled"
        if stop.max_evals is not None and self.evals >= stop.max_evals:
            return "max_evals"
        if stop.time_limit is not None and self.elapsed() >= stop.time_limit:
            return "time_limit"
        if self.target_met():
            return "target"
        if stop.stall is not None and self.evals - self.last_gain >= stop.stall:
            return "stall"
        return None


def first_point(
    problem: DesignProblem,
    x0: np.ndarray | None,
    rng: np.random.Generator,
    level: Level,
    stop: StopRule,
    cancel: CancelFn | None,
) -> tuple[np.ndarray, Budget]:
    """A search's start and its budget: ``x0`` clipped to the bounds, or a random layout
    meeting the geometric rules when ``x0`` is None or breaks one; evaluated once, which
    is the first best, the first history row and the first evaluations counted."""
    if problem.vars.n == 0:
        raise DesignError("nothing to optimise: no source has a free variable")
    lo, hi = problem.vars.lo, problem.vars.hi
    x = np.clip(np.asarray(x0, float), lo, hi) if x0 is not None else random_start(problem, rng)
    budget = Budget(problem, stop, cancel)
    ev = problem.evaluate(x[None], level)
    if not ev.ok[0]:
        x = random_start(problem, rng)
        ev = problem.evaluate(x[None], level)
    budget.evals = ev.evaluated
    budget.improve(ev, 0)
    return x, budget


def history_rows(history) -> tuple[HistoryRow, ...]:
    """A run's convergence history as plain rows (evaluations, f + P, P, goal)."""
    return tuple((int(e), float(v), float(p), float(g)) for e, v, p, g in history)


def judged(
    problem: DesignProblem, res: SearchResult, method: str, seed: int, **info
) -> OptimizationResult:
    """A search's answer judged on every patch, with its typed info. The result's
    evaluations are the search's: judging an answer (one evaluation on every patch,
    ``DesignProblem.solution``) is not a search step and is not counted."""
    history = history_rows(res.history)
    best = problem.solution(
        res.x,
        SolutionInfo(
            method=method,
            seed=seed,
            evaluations=res.evaluations,
            seconds=res.seconds,
            status=res.status,
            history=history,
            **info,
        ),
    )
    status = status_of(best, res.status == "cancelled")
    return OptimizationResult(status, best, None, res.evaluations, res.seconds, history)
