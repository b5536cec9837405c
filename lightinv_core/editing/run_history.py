"""The results of the open project as the user browses them: runs kept, the run browsed,
a result loaded into the design, pins, the front and its quality.

``RunHistory`` is the document's concern for results (a mixin over
``state.DocumentState``); the bookkeeping is pure functions of the project in
results.py.
"""

from __future__ import annotations

from dataclasses import replace
from datetime import datetime

from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.editing import results as _results
from lightinv_core.editing.state import DocumentState
from lightinv_core.errors import DesignError, LightInvError
from lightinv_core.optimize.fronts import front_pair
from lightinv_core.optimize.quality import FrontQuality, front_quality, front_scales
from lightinv_core.project import OptimizerSettings
from lightinv_core.project.results import RunRecord


class RunHistory(DocumentState):
    """Keep, browse, delete, pin and load the results of optimisation runs."""

    def apply_solution(self, solution: Solution) -> None:
        """Load a result into the design: each source takes the result's rectangle, flux
        and filter (which variables are free, the rules and the intentions stay), and the
        result becomes the shown one. DesignError if it was found for other sources."""
        found = {s.name: s for s in solution.sources}
        if set(found) != {s.name for s in self.design.sources}:
            raise DesignError(
                "this solution was found for other sources "
                f"({', '.join(found)}); it cannot be loaded"
            )
        sources = tuple(
            replace(
                s, rect=found[s.name].rect, flux=found[s.name].flux, filter=found[s.name].filter
            )
            for s in self.design.sources
        )
        # Arrays take the result's layout (rows, columns, rectangle, rotation, dimming);
        # product, ranges and which variables are free stay the design's.
        laid = {a.name: a for a in solution.arrays}
        arrays = tuple(
            replace(
                a,
                rect=laid[a.name].rect,
                rows=laid[a.name].rows,
                columns=laid[a.name].columns,
                rotation=laid[a.name].rotation,
                dimming=laid[a.name].dimming,
            )
            if a.name in laid
            else a
            for a in self.design.arrays
        )
        self._preview = None
        self._set_design(replace(self.design, sources=sources, arrays=arrays), "load a result")
        self.shown = solution
        self._emit_results()

    @property
    def browsed_run(self) -> int | None:
        """The run whose results are listed: its number, ``results.SAVED`` (the saved
        results) or ``results.ALL`` (every run's); ALL once the run chosen is gone (an
        undo, a redo of its deletion)."""
        return _results.browsed(self._project, self._browsed)

    @property
    def runs(self) -> tuple[RunRecord, ...]:
        """The project's optimisation runs, oldest first."""
        return self._project.runs

    def add_run(
        self,
        solutions: tuple[Solution, ...],
        pareto: ParetoFront | None,
        *,
        settings: OptimizerSettings,
        seeds=(),
        status: str = "",
        evaluations: int = 0,
        seconds: float = 0.0,
        time: str | None = None,
    ) -> RunRecord:
        """Keep a finished run's results as the next run of the history (earlier runs
        stay); its results are then the ones browsed. ``time``: when it ended (ISO 8601;
        default now). Not an edit (undo leaves it)."""
        number = _results.next_run_number(self._project, self._run_mark)
        run = RunRecord(
            number=number,
            method=settings.method,
            time=time or datetime.now().isoformat(timespec="seconds"),
            settings=settings,
            seeds=tuple(seeds),
            goals=tuple(g.kind for g in self.design.goals),
            status=status,
            evaluations=int(evaluations),
            seconds=float(seconds),
            solutions=tuple(solutions),
            pareto=pareto,
        )
        self._project = _results.with_run(self._project, run)
        self._run_mark = number + 1
        self._browsed = number
        self.mark_dirty()
        self._emit_results()
        return run

    def delete_run(self, number: int) -> None:
        """Delete run ``number`` and its results (its pinned ones are kept as saved
        results); an edit, so Edit > Undo brings it back. DesignError if there is none."""
        before = self._project
        self._project = _results.without_run(self._project, number)
        if self.browsed_run == number:
            self._browsed = _results.ALL
        self.mark_dirty()
        self._emit_results()
        self._edited(f"delete run {number}", before)

    def browse_run(self, number: int | None) -> None:
        """List run ``number``'s results (``results.SAVED``: the saved ones; None: every
        run's); DesignError for a run the project does not have."""
        if number is not _results.ALL and number != _results.SAVED:
            _results.find_run(self._project, number)
        self._browsed = number
        self._emit_results()

    def run_summary(self, number: int) -> str:
        """One line on what run ``number`` was asked and did."""
        return _results.run_summary(_results.find_run(self._project, number))

    def results(self) -> list[_results.Entry]:
        """The results browsed, labelled (see ``results.browse``)."""
        return _results.browse(self._project, self.browsed_run)

    def front(self) -> ParetoFront | None:
        """The Pareto front of the results browsed (see ``results.front_of``)."""
        return _results.front_of(self._project, self.browsed_run)

    def front_quality(self) -> FrontQuality | None:
        """Hypervolume and spacing of the front browsed (None without a front or a light
        model, or when the design's goals no longer make that front: its scales are the
        design's, e.g. power and light or annual energy and glazing area)."""
        front = self.front() if self._project is not None else None
        if front is None or not front.solutions or self.light is None:
            return None
        pair = tuple(map(str, front.objectives))
        if pair != front_pair(self.design):
            return None
        try:
            scales = front_scales(self._project.design, self.light, pair)
        except LightInvError:  # the climate scales read the weather file
            return None
        return front_quality(front.solutions, scales, pair)

    def on_front(self, solution: Solution) -> bool:
        """Whether ``solution`` is on one of the project's Pareto fronts."""
        return _results.on_front(self._project, solution)

    def pin(self, solution: Solution, pinned: bool = True) -> Solution:
        """Pin (offer for comparison, keep when its run is deleted; saved with the
        project) or unpin a result; returns the pinned copy."""
        self._project, new = _results.with_pin(self._project, solution, pinned)
        if self.shown is not None and self.shown.x == solution.x:
            self.shown = new
        self.mark_dirty()
        self._emit_results()
        return new

    def pinned(self) -> list[Solution]:
        """The pinned results, each layout once."""
        return _results.pinned_results(self._project)
