"""Running an optimisation from the window: start, live redraws, cancel, results.

``RunController`` owns the ``RunWorker`` and a timer that takes the worker's snapshot
5 times a second: the convergence plots and counters are drawn from it, the
best layout so far lights the viewport (when the run's variables are the design's),
and the autosave reads the best so far from here. When the worker ends — finished or
cancelled — its results join the project's run history (earlier runs are kept), the
best one is loaded into the design, and an infeasible outcome opens the Violations tab
with the offending patches in red.
"""

from __future__ import annotations

import time

import numpy as np
from PySide6 import QtCore

from app.dialogs import ask
from app.view import luminaire_overlay
from app.window.workers import RunWorker, stop_and_wait
from lightinv_core.design.solution import ParetoFront, Solution, SolutionInfo
from lightinv_core.editing.results import method_label
from lightinv_core.errors import LightInvError
from lightinv_core.goals import goal_spec
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.registry import get_method

REDRAW_MS = 200
"""Plots and counters redraw at most 5 times a second. The optimizer shares the
interpreter with the GUI thread, and pyqtgraph paints in Python: measured on the
office demo (bench/gui_run.py, 2 cores), the run kept 63% of its speed at 5 Hz,
48% at 10 Hz and 25-35% at 20 Hz."""
PREVIEW_S = 0.25
"""The viewport shows a new best at most 4 times a second: a software-GL render costs
~15 ms of the GUI thread, and the optimizer shares the interpreter with it."""


class RunController(QtCore.QObject):
    """One optimisation at a time for a main window."""

    started = QtCore.Signal()
    finished = QtCore.Signal(str)  # the run's status: feasible, infeasible, cancelled, failed

    def __init__(self, window):
        super().__init__(window)
        self.win, self.doc, self.panel = window, window.doc, window.run_panel
        self.worker: RunWorker | None = None
        self.problem: DesignProblem | None = None
        self.found: list[Solution] = []  # sweep points so far (autosave)
        self.best_x: tuple[float, ...] = ()
        self.best_info = SolutionInfo()
        self.status = ""
        self.run = None  # the RunRecord of the last run that ended
        self.preview_at = 0.0
        self.preview_arrays: tuple = ()  # the luminaire arrays of the best drawn so far
        self.method = ""  # the running method's label ("NSGA-II")
        self.refused = ""  # why Run was last refused, while the run panel shows it
        self.timer = QtCore.QTimer(self)
        self.timer.setInterval(REDRAW_MS)
        self.timer.timeout.connect(self.tick)

    @property
    def running(self) -> bool:
        return self.worker is not None

    def start(self) -> bool:
        """Run the project's optimisation in a worker; False (with a message) if it cannot
        start now."""
        d = self.doc
        if self.worker is not None:
            return False
        if d.operator is None or self.win.worker is not None:
            self._say(f"Wait for {self.win.tasks.waited_for()} first.")
            return False
        why = self.panel.refusal()
        if why is not None:
            self._say(why)
            return False
        try:
            problem = d.problem()
            if problem.vars.n == 0:
                raise LightInvError(
                    "nothing to optimise: add a source (Properties > Source: Add source) "
                    "whose corners, flux or filter are free"
                )
        except LightInvError as exc:
            self._say(str(exc))
            return False
        self.problem, self.found, self.best_x, self.best_info = problem, [], (), SolutionInfo()
        self.worker = RunWorker(d.project, d.prepared(), self.panel.seeds(), self)
        self.worker.succeeded.connect(self._succeeded)
        self.worker.failed.connect(self._failed)
        self.worker.finished.connect(self._ended)
        self.panel.plot.reset(*self.panel.plot_labels())
        self.panel.set_running(True)
        self.method = method_label(d.project.optimizer.method)
        self.preview_arrays = ()
        self.panel.state.setText(f"Running {self.method}...")
        self.win.act_run.setEnabled(False)
        self.win.act_cancel_run.setEnabled(True)
        self.worker.start()
        self.timer.start()
        self.started.emit()
        return True

    def cancel(self) -> None:
        """Stop the run at its next batch; its best result is kept."""
        if self.worker is not None:
            self.panel.state.setText("Cancelling: keeping the best so far...")
            self.worker.cancel()

    def stop(self) -> None:
        """Cancel and wait (closing, switching projects); the best is still delivered."""
        stop_and_wait(self.worker)

    # -- while running ----------------------------------------------------------------------
    def tick(self) -> None:
        """Draw the worker's progress since the last tick."""
        if self.worker is None:
            return
        snap = self.worker.snapshot()
        self.found.extend(snap.solutions)
        p = snap.latest
        latest = None if p is None else (p.run, snap.evaluations)
        if snap.points or latest is not None:
            self.panel.plot.add_points(snap.points, latest)
        self.panel.show_progress(snap)
        if p is None or len(p.best_x) != self.problem.vars.n:
            return  # a sub-problem with other variables (two-step's skylight step)
        now = time.perf_counter()
        if p.best_x != self.best_x and now - self.preview_at >= PREVIEW_S:
            self.preview_at = now
            self.best_x = p.best_x
            optimizer = self.worker.project.optimizer
            seeds = self.worker.seeds or [optimizer.seed]
            self.best_info = SolutionInfo(
                method=optimizer.method,
                seed=seeds[min(p.run, len(seeds) - 1)],
                evaluations=snap.evaluations,
                seconds=snap.elapsed,
                status="running",
            )
            if self.panel.show_best.isChecked():
                self.preview(np.array(p.best_x))

    def preview(self, x: np.ndarray) -> None:
        """Show layout ``x`` (the best so far) in the view without touching the design:
        its sources lit and outlined, its luminaire arrays drawn where they are."""
        # The model lights the sources (rules applied); that relights the view and
        # redraws the outlines and the design's luminaires (ViewColouring.recolour).
        self.doc.set_preview(self.problem.sources_at(x))
        if not self.problem.design.arrays:
            return
        # Then the best's luminaires over the design's: the layout a user watches change.
        # Their exact light takes about a second a layout (the search reads a lattice
        # blend), so the colours stay those of the design's arrays until the run ends.
        arrays = self.problem.arrays_at(x)
        plotter = self.win.viewport.plotter
        plotter.remove_actor("luminaires", render=False)
        glyphs = luminaire_overlay.luminaire_glyphs(self.doc.patches, arrays)
        if glyphs is not None:
            plotter.add_mesh(
                glyphs,
                name="luminaires",
                color=luminaire_overlay.GLYPH_COLOUR,
                lighting=False,
                render=False,
            )
        self.win.viewport.request_render()
        self.preview_arrays = arrays
        layout = ", ".join(f"{a.name} {a.rows} x {a.columns}" for a in arrays)
        self.panel.state.setText(f"Running {self.method}... best layout so far: {layout}")

    def best_so_far(self) -> tuple[Solution, ...]:
        """The running optimisation's results so far, judged on all patches (autosave)."""
        if self.worker is None:
            return ()
        project = self.worker.project
        if get_method(project.optimizer.method).finds_front(project.design):
            return tuple(self.found)
        if not self.best_x:
            return ()
        return (self.problem.solution(np.array(self.best_x), self.best_info),)

    # -- when it ends -------------------------------------------------------------------------
    def _succeeded(self, results) -> None:
        self.tick()
        front: ParetoFront | None = results[0].pareto
        if front is not None:
            bests: tuple[Solution, ...] = ()
            chosen = front.solutions[0] if front.solutions else None
            if chosen is None and front.candidates:
                chosen = min(front.candidates, key=lambda s: s.penalty)
        else:
            bests = tuple(r.best for r in results if r.best is not None)
            chosen = _best_of(bests, self.problem)
        self.status = _status(results)
        evals = sum(r.evaluations for r in results)
        seconds = sum(r.seconds for r in results)
        # Each run that found something joins the project's history (earlier runs stay
        # until deleted).
        self.run = None
        if chosen is not None:
            self.run = self.doc.add_run(
                bests,
                front,
                settings=self.worker.project.optimizer,
                seeds=self.worker.seeds or (),
                status=self.status,
                evaluations=evals,
                seconds=seconds,
            )
        if chosen is None:
            self.doc.set_preview(None)
        else:
            self.doc.apply_solution(chosen)  # ends the preview, relights once
        which = "" if self.run is None else f" (run {self.run.number})"
        text = {
            "feasible": f"Done{which}: a feasible layout was found",
            "infeasible": f"Done{which}, but no layout meets every rule and intention",
            "cancelled": f"Cancelled{which}: the best layout found so far is kept",
        }[self.status]
        if front is not None:
            text += f"; {len(front.solutions)} on the front of {len(front.candidates)}"
        self.panel.state.setText(f"{text} ({self.method}: {evals:,} evaluations, {seconds:.1f} s).")
        if chosen is None:
            self.panel.state.setText(f"{text}: no result to keep.")
        elif not chosen.feasible:
            self.win.tabs.setCurrentWidget(self.win.violations_panel)
        elif front is not None or len(results) > 1:
            self.win.tabs.setCurrentWidget(self.win.solutions_panel)
        self.win.statusBar().showMessage(self.panel.state.text(), 10_000)

    def _failed(self, message: str) -> None:
        self.status = "failed"
        self.doc.set_preview(None)
        self.panel.state.setText("The run failed; nothing was changed.")
        ask.error(self.win, "optimisation failed", message)

    def _ended(self) -> None:
        self.timer.stop()
        self.worker.deleteLater()
        self.worker = None
        self.panel.set_running(False)
        self.win.act_run.setEnabled(True)
        self.win.act_cancel_run.setEnabled(False)
        self.finished.emit(self.status)

    def _say(self, message: str) -> None:
        """Why a run cannot start: in the run panel and the status bar, never a modal
        dialog (Run pressed while a project is laid out is no error to acknowledge)."""
        self.refused = message
        self.panel.state.setText(message)
        self.win.statusBar().showMessage(message, 10_000)

    def waited(self) -> None:
        """The background work a refusal waited for has ended: its words go."""
        if self.refused and self.panel.state.text() == self.refused:
            self.panel.state.setText("")
        self.refused = ""


def _status(results) -> str:
    statuses = {r.status for r in results}
    if "cancelled" in statuses:
        return "cancelled"
    return "feasible" if "feasible" in statuses else "infeasible"


def _best_of(solutions: tuple[Solution, ...], problem: DesignProblem) -> Solution | None:
    """The best of several runs' results: feasible first, then by the primary goal."""
    if not solutions:
        return None
    sign = -1.0 if goal_spec(problem.primary).maximise else 1.0

    def key(s: Solution):
        return (not s.feasible, s.penalty, sign * s.objectives.get(problem.primary, np.inf))

    return min(solutions, key=key)
