"""The results of a project as the user browses them: the run history, labels, pinning.

Pure functions over a ``Project``. Each optimisation run is a ``RunRecord`` in
``project.runs`` (its method, when it ended, its settings and what it found), kept until
the user deletes it; ``project.solutions`` and ``project.pareto`` hold results outside
the history ("saved results": ``lightinv-cli solve``, files from before the history,
pinned results of a deleted run). A result is identified by its variable vector ``x``;
which run's results are browsed is a run number, ``SAVED`` (0) for the saved results or
``ALL`` (None) for everything.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.errors import DesignError
from lightinv_core.goals import bounded_goal, goal_spec, is_goal
from lightinv_core.kinds import GoalKind
from lightinv_core.optimize.registry import get_method, method_names
from lightinv_core.project import Project
from lightinv_core.project.results import RunRecord

ALL = None
"""Browse every run's results and the saved ones."""
SAVED = 0
"""Browse the results outside the run history."""
UNSTATED_BOUND = GoalKind.MAX_LIGHT_POWER
"""The goal an epsilon result was bounded on when its objectives do not say (files
from before they were stored, whose sweeps all bounded light power)."""
FRONT_MEMBER_METHODS = {"nsga2": "NSGA-II"}
"""Methods whose results are members of one front, and their names in its labels: a
result is labelled by the value of its first goal whose spec has a ``result_format``
("NSGA-II 123.4 W"). (Belongs in the method registry, optimize/, once it says so.)"""


@dataclass(frozen=True)
class Entry:
    """One result as listed: its label, the solution, and the run it belongs to (its
    number, or ``SAVED``)."""

    label: str
    solution: Solution
    run: int


def result_label(s: Solution) -> str:
    """A short name for a result: which run found it."""
    info = s.info
    if info.epsilon is not None:
        # The sweep's bounded goal (light power, glazing area) says how to write its bound.
        bounded = bounded_goal(s.objectives) or goal_spec(UNSTATED_BOUND)
        return f"epsilon {bounded.bound_format.format(info.epsilon)}"
    if info.method in FRONT_MEMBER_METHODS:
        by = next((k for k in s.objectives if is_goal(k) and goal_spec(k).result_format), None)
        if by is not None:
            value = goal_spec(by).result_format.format(s.objectives[by])
            return f"{FRONT_MEMBER_METHODS[info.method]} {value}"
    if info.step1_light_power is not None:
        return f"two-step seed {'?' if info.seed is None else info.seed}"
    if info.seed is not None:
        return f"seed {info.seed}"
    return "result"


def method_label(name: str) -> str:
    """A method's short name for people ("CMA-ES" for "cmaes"); the name itself when the
    registry does not know it (a file from another version)."""
    if name not in method_names():
        return name
    return get_method(name).label.split(" (")[0]


def browsed(project: Project | None, run: int | None) -> int | None:
    """The run whose results are listed when ``run`` was chosen: ``run`` itself while
    the project has it (a number, or ``SAVED`` while there are saved results), else
    ``ALL`` (an undo, a redo of its deletion took it away)."""
    if run is ALL or project is None:
        return ALL
    if run == SAVED:
        return run if project.solutions or project.pareto is not None else ALL
    return run if any(r.number == run for r in project.runs) else ALL


def run_label(run: RunRecord) -> str:
    """ "run 3: CMA-ES, 14:03" — its number, method and the time it ended."""
    when = run.time[11:16] if len(run.time) >= 16 else run.time
    return f"run {run.number}: {method_label(run.method)}" + (f", {when}" if when else "")


def goal_text(kind: str) -> str:
    """A goal's short name for people ("least electric power"), from its spec; the
    kind's words for a goal the registry does not know (a file from another version)."""
    return goal_spec(kind).short if is_goal(kind) else kind.replace("_", " ")


def run_summary(run: RunRecord) -> str:
    """What a run was asked and what it did, in one line: method, seeds, budget, goal,
    outcome, evaluations and time, when it ended."""
    o = run.settings
    parts = [method_label(run.method)]
    if len(run.seeds) > 1:
        parts.append(f"{len(run.seeds)} seeds ({', '.join(map(str, run.seeds))})")
    else:
        parts.append(f"seed {run.seeds[0] if run.seeds else o.seed}")
    if o.max_evals is not None:
        parts.append(f"at most {o.max_evals:,} evaluations")
    if o.time_limit is not None:
        parts.append(f"at most {o.time_limit:g} s")
    if run.goals:
        parts.append("goal " + " and ".join(map(goal_text, run.goals)))
    found = f"{len(run.pareto.solutions)} on its front" if run.pareto is not None else ""
    outcome = ", ".join(
        x
        for x in (run.status, found, f"{run.evaluations:,} evaluations in {run.seconds:.1f} s")
        if x
    )
    ended = f"; ended {run.time.replace('T', ' ')}" if run.time else ""
    return f"{', '.join(parts)}: {outcome}{ended}"


def next_run_number(project: Project, at_least: int = 1) -> int:
    """The number a new run takes: one more than any run's, and at least ``at_least``
    (the model's high-water mark, so a deleted run's number is not reused)."""
    return max(at_least, 1 + max((r.number for r in project.runs), default=0))


def with_run(project: Project, run: RunRecord) -> Project:
    """``project`` with ``run`` added to its history (DesignError if its number is taken)."""
    if any(r.number == run.number for r in project.runs):
        raise DesignError(f"the project already has a run {run.number}")
    return replace(project, runs=(*project.runs, run))


def find_run(project: Project, number: int) -> RunRecord:
    """The run called ``number`` (DesignError if there is none)."""
    run = next((r for r in project.runs if r.number == number), None)
    if run is None:
        raise DesignError(f"the project has no run {number}")
    return run


def without_run(project: Project, number: int) -> Project:
    """``project`` without run ``number``; its pinned results join the saved results (a
    pinned result is kept whatever happens to its run)."""
    run = find_run(project, number)
    kept = {s.x for s in project.solutions}
    pinned = []
    for s in run.results():
        if s.info.pinned and s.x not in kept:
            pinned.append(s)
            kept.add(s.x)
    return replace(
        project,
        runs=tuple(r for r in project.runs if r.number != number),
        solutions=project.solutions + tuple(pinned),
    )


def _saved_results(project: Project) -> list[Solution]:
    """The results outside the history: the saved solutions, then the saved front's
    candidates not among them (files from before the history stored a pinned front
    point in both)."""
    out = list(project.solutions)
    listed = {s.x for s in out}
    front = project.pareto
    out += [
        s
        for s in (() if front is None else front.candidates or front.solutions)
        if s.x not in listed
    ]
    return out


def browse(project: Project, run: int | None = ALL) -> list[Entry]:
    """The results to browse, labelled: run ``run``'s (each seed's best, then its front's
    candidates), the saved results (``SAVED``), or everything (``ALL``: the saved
    results, then each run's, oldest first, labels prefixed with the run)."""
    if run is not ALL and run != SAVED:
        return [Entry(result_label(s), s, run) for s in find_run(project, run).results()]
    out = [
        Entry(("saved: " if run is ALL else "") + result_label(s), s, SAVED)
        for s in _saved_results(project)
    ]
    if run is ALL:
        for r in project.runs:
            out += [Entry(f"run {r.number}: {result_label(s)}", s, r.number) for s in r.results()]
    return out


def front_of(project: Project, run: int | None) -> ParetoFront | None:
    """The front browsed: run ``run``'s, the saved one (``SAVED``), or for ``ALL`` the
    newest run's front (else the saved one)."""
    if run is ALL:
        fronts = [r.pareto for r in reversed(project.runs) if r.pareto is not None]
        return fronts[0] if fronts else project.pareto
    if run == SAVED:
        return project.pareto
    return find_run(project, run).pareto


def _fronts(project: Project) -> list[ParetoFront]:
    return [f for f in (project.pareto, *(r.pareto for r in project.runs)) if f is not None]


def on_front(project: Project, solution: Solution) -> bool:
    """Whether ``solution`` is on a Pareto front of the project (a run's or the saved one)."""
    return any(s.x == solution.x for f in _fronts(project) for s in f.solutions)


def pinned_results(project: Project) -> list[Solution]:
    """The pinned results, each layout once: saved ones first, then by run."""
    out, seen = [], set()
    for s in _saved_results(project) + [s for r in project.runs for s in r.results()]:
        if s.info.pinned and s.x not in seen:
            out.append(s)
            seen.add(s.x)
    return out


def _pin_all(solutions: tuple[Solution, ...], x, pinned: bool) -> tuple[Solution, ...]:
    return tuple(replace(s, info=s.info.but(pinned=pinned)) if s.x == x else s for s in solutions)


def _pin_front(front: ParetoFront | None, x, pinned: bool) -> ParetoFront | None:
    if front is None:
        return None
    return replace(
        front,
        solutions=_pin_all(front.solutions, x, pinned),
        candidates=_pin_all(front.candidates, x, pinned),
    )


def with_pin(project: Project, solution: Solution, pinned: bool) -> tuple[Project, Solution]:
    """``project`` with ``solution``'s layout pinned (or unpinned) wherever it is listed
    (its run, its front, the saved results), and the pinned copy."""
    x = solution.x
    runs = tuple(
        replace(
            r, solutions=_pin_all(r.solutions, x, pinned), pareto=_pin_front(r.pareto, x, pinned)
        )
        for r in project.runs
    )
    new = replace(
        project,
        solutions=_pin_all(project.solutions, x, pinned),
        pareto=_pin_front(project.pareto, x, pinned),
        runs=runs,
    )
    return new, replace(solution, info=solution.info.but(pinned=pinned))


def carried_over(current: Project, source: Project, target: Project) -> Project:
    """The results of ``current`` with the change from ``source`` to ``target`` applied to
    them (undo: source = after an edit, target = before it; redo the other way).

    Runs are matched by number, saved solutions by ``x``: what the change removed goes,
    what it added comes back, and everything else stays as it is now — a run made, or a
    result pinned, since the edit is kept. An edit of the design changes no results, so
    undoing it keeps them all. A run coming back whose number was taken meanwhile gets
    the next free one."""
    gone = {r.number for r in source.runs} - {r.number for r in target.runs}
    back = [r for r in target.runs if r.number not in {q.number for q in source.runs}]
    runs = [r for r in current.runs if r.number not in gone]
    for r in back:
        if any(q.number == r.number for q in runs):
            r = replace(r, number=1 + max(q.number for q in runs))
        runs.append(r)
    gone_x = {s.x for s in source.solutions} - {s.x for s in target.solutions}
    back_x = [s for s in target.solutions if s.x not in {q.x for q in source.solutions}]
    solutions = [s for s in current.solutions if s.x not in gone_x]
    solutions += [s for s in back_x if s.x not in {q.x for q in solutions}]
    pareto = target.pareto if source.pareto != target.pareto else current.pareto
    return replace(
        target,
        runs=tuple(sorted(runs, key=lambda r: r.number)),
        solutions=tuple(solutions),
        pareto=pareto,
    )
