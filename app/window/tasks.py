"""Background work of the window other than optimisation: building (or loading) the
radiosity operator and laying out the design's light on it (work-plane grids, arrays,
the light in every scenario: the window's thread only takes it), tracing the clear
glazing's light, and writing the PDF report.

One such worker at a time (``worker``), shown by the status bar's progress bar with
Compute > Cancel; the optimisation has its own controller (run_control.py). Workers
are in workers.py; this module starts them and takes their results to the document.

The clear glazing's light takes seconds to tens of seconds to trace (``light.clear_build``),
so the document never builds it on the GUI thread (``clear_elsewhere``): whenever the
design shown needs a trace not yet made (a clear-glazed project opened, its daylight or
glazing changed, an undo), a ``ClearLightWorker`` traces it while the window stays
responsive and the view shows the light without it; once done the document relights. A
cancelled (or failed) trace is not started again for the same glazing until Compute >
Precompute asks; the design itself is never changed by it.
"""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore

from app.dialogs import ask
from app.window.workers import (
    ClearLightWorker,
    ExportWorker,
    Precomputed,
    PrecomputeWorker,
    ReportWorker,
    Worker,
    stop_and_wait,
)
from lightinv_core.errors import LightInvError
from lightinv_core.light.clear_build import clear_light_key


class BackgroundTasks(QtCore.QObject):
    """Precompute and report workers of a main window."""

    def __init__(self, window):
        super().__init__(window)
        self.win, self.doc = window, window.doc
        self.worker: Worker | None = None
        self._declined = None  # the clear glazing whose trace was cancelled or failed
        window.doc.model.clear_elsewhere = True  # traced here, in a worker
        window.doc.designChanged.connect(lambda: self.start_clear_trace())
        window.doc.operatorChanged.connect(lambda: self.start_clear_trace())

    def _start(self, worker: Worker) -> None:
        win = self.win
        self.worker = worker
        worker.progress.connect(lambda f: win.progress.setValue(int(1000 * f)))
        worker.finished.connect(self._done)
        win.progress.setValue(0)
        win.progress.show()
        win.act_cancel.setEnabled(True)
        win.act_precompute.setEnabled(False)
        worker.start()

    # -- the operator --------------------------------------------------------------------------
    def start_precompute(self) -> None:
        """Build or load the operator in a worker thread (progress bar, cancel)."""
        if self.doc.patches is None or self.worker is not None:
            return
        self._declined = None  # asked for: a cancelled clear trace may run again
        d = self.doc
        worker = PrecomputeWorker(
            d.patches, d.operator_settings, self, scene=d.scene, design=d.design
        )
        worker.succeeded.connect(self._precomputed)
        worker.failed.connect(lambda msg: ask.error(self.win, "precompute failed", msg))
        worker.cancelled.connect(lambda: self._precompute_cancelled(worker))
        worker.progress.connect(lambda: self._laying_out(worker))
        self.win.statusBar().showMessage("Precomputing the radiosity operator...")
        self._start(worker)

    def _precompute_cancelled(self, worker: PrecomputeWorker) -> None:
        if worker.phase == "layout":  # the operator is in the cache: Precompute is quick
            self._say(
                "Layout cancelled: lighting unavailable until Compute > Precompute "
                "(the operator is kept in the cache)",
                8000,
            )
        else:
            self._say("Precompute cancelled: lighting unavailable until it runs", 6000)

    def _laying_out(self, worker: PrecomputeWorker) -> None:
        """Say once that the operator is there and the light is being laid out."""
        if worker.phase == "layout" and not worker.announced:
            worker.announced = True
            self.win.statusBar().showMessage(
                "Laying out the light: work-plane grids, luminaire arrays (the view shows "
                "the model meanwhile; Run waits for it; Compute > Cancel stops it)"
            )

    def _precomputed(self, got: Precomputed) -> None:
        if got.operator.digest != self.doc.patches.digest():
            return  # the scene changed while the worker ran: _done builds for the new one
        # The light laid out in the worker: the view relights at once (its grids and
        # arrays found made; a design edited meanwhile relights what changed).
        self.doc.set_operator(got.operator, shown=got.shown, daylight=got.daylight)
        info = got.operator.info
        # Without zones the error is estimated on light no source gives (cache.py).
        err = f"error {100 * info['estimated_rel_error']:.2f}%" if info.get("nz", 1) else "no zones"
        self.win.status_rank.setText(f"rank k = {got.operator.k} ({err})")
        how = "loaded from the cache" if got.from_cache else "built"
        said = f"Operator {how} in {got.seconds:.1f} s"
        if got.shown is not None and got.layout_s >= 0.05:
            said += f", the light laid out in {got.layout_s:.1f} s"
        self._say(said, 6000)
        self.win.set_warnings("operator", self.worker.warnings)
        if self.worker.warnings:
            self._say(self.worker.warnings[0], 8000)
        if got.layout_error:  # lit on this thread instead; the status bar says why
            why = got.layout_error
            self._say(f"The light could not be laid out in the background: {why}", 10000)

    def waited_for(self) -> str:
        """What work in the background the design's light waits for, in words."""
        if isinstance(self.worker, ClearLightWorker):
            return "the clear glazing's trace (the status bar shows how far)"
        if isinstance(self.worker, PrecomputeWorker) and self.worker.phase == "layout":
            return (
                "the light being laid out: work-plane grids, luminaire arrays (the status "
                "bar shows how far)"
            )
        return "the radiosity operator (Compute > Precompute)"

    # -- the clear glazing's light ---------------------------------------------------------
    def start_clear_trace(self) -> bool:
        """Trace the clear glazing's light of the design shown in a worker if it needs
        one (``Document.clear_pending``), with the progress bar and Compute > Cancel;
        whether one started. Another worker running: its end comes back here; a trace
        running for another glazing is cancelled first."""
        d = self.doc
        pending = d.project is not None and d.clear_pending()
        key = clear_light_key(d.design) if pending else None
        running = self.worker
        if isinstance(running, ClearLightWorker):
            if running.key != key:  # another glazing now, or none (an undo): not this one
                running.cancel()  # its end (_done) starts the trace needed, if any
            return False
        if not pending or running is not None or key == self._declined:
            return False
        d.model.clear_note = ""  # being traced: the document's own words say so
        worker = ClearLightWorker(d.prepared(), d.design, self)
        worker.succeeded.connect(self._clear_traced)
        worker.failed.connect(lambda msg: self._clear_missed(worker, msg))
        worker.cancelled.connect(lambda: self._clear_missed(worker, ""))
        self.win.statusBar().showMessage(
            "Tracing the clear glazing's light (sky, sun, reflections); the view shows the "
            "rest meanwhile; Compute > Cancel stops it"
        )
        self._start(worker)
        return True

    def _clear_traced(self, got: tuple) -> None:
        seconds, daylight = got
        self.win.set_warnings("clear glazing", [])
        if self.doc.light is not None:
            # Relights, and keeps the worker's light in every scenario if the design is
            # still the one traced: the views read it without building it again.
            self.doc.clear_light_changed(daylight=daylight)
        self._say(f"Clear glazing traced in {seconds:.1f} s", 6000)

    def _clear_missed(self, worker: ClearLightWorker, message: str) -> None:
        """A trace cancelled (``message`` empty) or failed: not started again for this
        glazing until Compute > Precompute; the view goes on without its light."""
        d = self.doc
        if d.project is None or clear_light_key(d.design) != worker.key:
            return  # cancelled for another glazing: _done traces that one
        self._declined = worker.key
        if message:
            note = f"the clear glazing's light could not be traced: {message}"
            self.win.set_warnings("clear glazing", [note[:1].upper() + note[1:]])
        else:
            note = (
                "the clear glazing's trace was cancelled: its light is left out until "
                "Compute > Precompute traces it"
            )
        if d.light is not None:
            d.clear_light_changed(note)  # the panels say why, not "being traced"
        self._say(note[:1].upper() + note[1:], 10000)

    def _solution_to_write(self, title: str):
        """The design on screen as a solution to report or export, or None once the
        user has been told why not (no operator yet, work running, a bad design)."""
        d = self.doc
        if d.operator is None or self.worker is not None:
            ask.inform(self.win, f"Wait for {self.waited_for()} first.")
            return None
        try:
            return d.design_solution()
        except LightInvError as exc:
            ask.error(self.win, title, str(exc))
            return None

    # -- the report ----------------------------------------------------------------------------
    def export_report(self, path: str | Path) -> bool:
        """Write the PDF report of the design on screen (as edited or as a result loaded
        into it) in a worker (progress bar, Cancel); needs the operator."""
        d = self.doc
        solution = self._solution_to_write("cannot report")
        if solution is None:
            return False
        worker = ReportWorker(d.project, d.prepared(), Path(path), solution, self)
        worker.succeeded.connect(
            lambda info: self._say(f"Report written: {info.path} ({len(info.pages)} pages)", 8000)
        )
        worker.failed.connect(lambda msg: ask.error(self.win, "report failed", msg))
        worker.cancelled.connect(lambda: self._say("Report cancelled; no file written", 6000))
        self._start(worker)
        return True

    # -- design exports ------------------------------------------------------------------------
    def export_design(self, name: str, path: str | Path) -> bool:
        """Write the design on screen in the export format ``name`` (the registry's) in a
        worker; needs the operator, as the report."""
        d = self.doc
        solution = self._solution_to_write("cannot export")
        if solution is None:
            return False
        worker = ExportWorker(d.project, d.prepared(), name, Path(path), solution, self)
        worker.succeeded.connect(lambda out: self._say(f"Design exported: {out.path}", 8000))
        worker.failed.connect(lambda msg: ask.error(self.win, "export failed", msg))
        worker.cancelled.connect(lambda: self._say("Export cancelled", 6000))
        self._start(worker)
        return True

    # -- common --------------------------------------------------------------------------------
    def cancel(self) -> None:
        """Ask the running worker to stop at its next check."""
        if self.worker is not None:
            self.worker.cancel()

    def stop(self) -> None:
        """Cancel and wait for the worker (closing, switching projects)."""
        stop_and_wait(self.worker)

    def _done(self) -> None:
        win = self.win
        win.progress.hide()
        win.act_cancel.setEnabled(False)
        win.act_precompute.setEnabled(True)
        finished = self.worker
        self.worker.deleteLater()
        self.worker = None
        win.runs.waited()  # "Wait for ... first" is over
        changed = (
            isinstance(finished, PrecomputeWorker)
            and self.doc.patches is not None
            and finished.patches is not self.doc.patches
            and self.doc.operator is None
        )
        if changed and not finished.is_cancelled():
            # The scene changed while it ran (a zone drawn, an undo): build for this one.
            self.start_precompute()
            return
        if self.start_clear_trace():  # the glazing shown (still, or since) needs its light
            return  # lightinv --run starts once it is traced
        if win.run_after_precompute and self.doc.operator is not None:
            win.run_after_precompute = False  # lightinv --run: start once the operator is there
            win.runs.start()

    def _say(self, message: str, ms: int) -> None:
        self.win.statusBar().showMessage(message, ms)
