"""Long work off the GUI thread: each worker is a QThread that reports through signals.

A worker never touches widgets or VTK; it calls the core with a progress callback
(emitted as a signal, drawn by the GUI thread) and a cancel flag it checks
between steps. Cancelling makes the core raise CancelledError, which becomes the
``cancelled`` signal; any other error becomes ``failed`` with its message, never
a silent thread death.
"""

from __future__ import annotations

import threading
import time
import traceback
import weakref
from dataclasses import dataclass
from typing import ClassVar

from PySide6 import QtCore, QtWidgets

from lightinv_core.editing import load_scene_of
from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.operator.cache import CachedOperator, get_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.progress import Progress
from lightinv_core.scene.patches import Patches


class Worker(QtCore.QThread):
    """Base worker: ``progress(float)``, ``succeeded(object)``, ``failed(str)``, ``cancelled()``."""

    progress = QtCore.Signal(float)
    succeeded = QtCore.Signal(object)
    failed = QtCore.Signal(str)
    cancelled = QtCore.Signal()

    _live: ClassVar[weakref.WeakSet] = weakref.WeakSet()
    result_survives_cancel: ClassVar[bool] = False
    """True for work whose partial result is worth keeping (an optimisation's best)."""

    def __init__(self, parent: QtCore.QObject | None = None):
        super().__init__(parent)
        self._cancel = threading.Event()
        Worker._live.add(self)

    @classmethod
    def live(cls) -> list[Worker]:
        """Workers whose Qt object still exists (tests check none is still running)."""
        from shiboken6 import isValid

        return [w for w in list(cls._live) if isValid(w)]

    def cancel(self) -> None:
        """Ask the work to stop at its next check (within a batch of rays or a step)."""
        self._cancel.set()

    def is_cancelled(self) -> bool:
        """Whether ``cancel`` was called."""
        return self._cancel.is_set()

    def work(self):  # pragma: no cover - overridden
        raise NotImplementedError

    def run(self) -> None:
        try:
            result = self.work()
        except CancelledError:
            self.cancelled.emit()
        except LightInvError as exc:
            self.failed.emit(str(exc))
        except Exception as exc:  # a bug: show it, with the traceback for the report
            self.failed.emit(f"{type(exc).__name__}: {exc}\n\n{traceback.format_exc()}")
        else:
            if self.is_cancelled() and not self.result_survives_cancel:
                self.cancelled.emit()
            else:
                self.succeeded.emit(result)


class LoadWorker(Worker):
    """Loads a project's scene and meshes it: an imported building takes seconds."""

    def __init__(self, project, path, parent: QtCore.QObject | None = None):
        super().__init__(parent)
        self.project, self.path = project, path

    def work(self):
        return load_scene_of(self.project, self.path)


WINDOW_REMEDY = (
    "import the model again with a larger patch size (File > Import model..., Patch size)"
)
"""What a user of the window can do about a missed accuracy target (it has no --rank)."""


@dataclass(frozen=True)
class Precomputed:
    """What a ``PrecomputeWorker`` hands the window: the operator (``CachedOperator``:
    ``operator``, ``from_cache``, ``seconds``), the design's light laid out on it
    (``shown``, a ``ShownLight``; None when it could not be, ``layout_error`` says why),
    the design's light in every scenario (``daylight``; None when its clear glazing
    still needs its trace, or without intentions) and the layout's seconds."""

    cached: CachedOperator
    shown: object | None = None
    daylight: object | None = None
    layout_s: float = 0.0
    layout_error: str = ""

    @property
    def operator(self):
        return self.cached.operator

    @property
    def from_cache(self) -> bool:
        return self.cached.from_cache

    @property
    def seconds(self) -> float:
        return self.cached.seconds


class PrecomputeWorker(Worker):
    """Builds (or loads from the cache) the radiosity operator of some patches, then,
    given the ``scene`` and ``design``, lays out the design's light on it
    (``phase`` "layout": the work planes' grids, the arrays placed exactly, the light
    in every scenario; 3.5 s on the GUI thread on the flagship office before issue #30).
    ``progress`` restarts from 0 for the layout."""

    def __init__(
        self,
        patches: Patches,
        settings: OperatorSettings,
        parent: QtCore.QObject | None = None,
        scene=None,
        design=None,
    ):
        super().__init__(parent)
        self.patches, self.settings = patches, settings
        self.scene, self.design = scene, design
        self.warnings: list[str] = []
        self.phase = "operator"  # then "layout" (read by the GUI thread for its words)
        self.announced = False  # the GUI thread said the layout began

    def _step(self, fraction: float) -> None:
        if self.is_cancelled():
            raise CancelledError("the layout of the light was cancelled")
        self.progress.emit(fraction)

    def work(self) -> Precomputed:
        got = get_operator(
            self.patches,
            self.settings,
            progress=self.progress.emit,
            cancel=self.is_cancelled,
            warn=self.warnings.append,
            remedy=WINDOW_REMEDY,
        )
        self.progress.emit(1.0)
        if self.scene is None or self.design is None:
            return Precomputed(got)
        self.phase = "layout"
        self._step(0.0)
        t0 = time.perf_counter()
        try:
            shown, daylight = lay_out(
                self.scene, self.patches, got.operator, self.design, self._step
            )
        except (CancelledError, MemoryError):
            raise
        except LightInvError as exc:  # the window lights it itself and says why
            return Precomputed(got, layout_error=str(exc))
        except Exception as exc:  # a bug: the window goes on without it; the traceback
            traceback.print_exc()  # on stderr, the message in the status bar
            return Precomputed(got, layout_error=f"{type(exc).__name__}: {exc}")
        self.progress.emit(1.0)
        return Precomputed(got, shown, daylight, time.perf_counter() - t0)


def lay_out(scene, patches, operator, design, progress) -> tuple:
    """(``ShownLight`` of ``design`` lit on ``operator``, its ``LayoutDaylight`` or None)
    made off the GUI thread: the work planes' grids (kept per operator), the arrays'
    light, then the light in every scenario unless the design's clear glazing waits for
    its trace (``ClearLightWorker`` makes it then) or nothing reads it (no intention).
    ``progress(fraction)`` between the steps (it raises CancelledError to stop)."""
    from threadpoolctl import threadpool_limits

    from lightinv_core.editing import ShownLight
    from lightinv_core.light.clear_build import clear_light_ready
    from lightinv_core.light.daylight import layout_daylight
    from lightinv_core.light.grids import design_receivers
    from lightinv_core.light.model import LightModel

    # One BLAS thread: a second one spins against the GUI thread (see RunWorker).
    with threadpool_limits(limits=1, user_api="blas"):
        light = LightModel(scene, patches, operator)
        design_receivers(light, design)  # the grids, remembered per operator
        progress(0.3)
        shown = ShownLight(light)
        shown.defer_clear = True  # the window traces clear glazing in its own worker
        shown.relight(design)  # the arrays placed exactly (kept while they stay)
        progress(0.5)
        daylight = None
        if design.intentions and clear_light_ready(light, design):
            try:
                daylight = layout_daylight(
                    light, design, progress=lambda f: progress(0.5 + 0.5 * f)
                )
            except LightInvError:  # no weather year, a bad sensor: the views say why
                daylight = None
    return shown, daylight


class ReportWorker(Worker):
    """Writes the PDF report of ``solution`` (the design on screen) off the GUI thread."""

    def __init__(
        self, project, prepared, path, solution=None, parent: QtCore.QObject | None = None
    ):
        super().__init__(parent)
        self.project, self.prepared, self.path = project, prepared, path
        self.solution = solution

    def work(self):
        from lightinv_core.report import write_report

        return write_report(
            self.project,
            self.prepared,
            self.path,
            solution=self.solution,
            label="the design on screen",
            progress=self.progress.emit,
            cancel=self.is_cancelled,
        )


class ExportWorker(Worker):
    """Writes the design on screen (``solution``) in one export format off the GUI
    thread (``lightinv_core.export``); succeeds with the ``ExportedFile``."""

    def __init__(self, project, prepared, name, path, solution, parent=None):
        super().__init__(parent)
        self.project, self.prepared, self.name, self.path = project, prepared, name, path
        self.solution = solution

    def work(self):
        from lightinv_core.export import export_design, exporter

        ex = export_design(self.project, self.prepared, self.solution)
        ex.label = "the design on screen"
        self.progress.emit(0.5)
        return exporter(self.name).write(ex, self.path)


class ClearLightWorker(Worker):
    """Traces the clear glazing's light of ``design`` (``light.clear_build.clear_light``:
    sky patches, the sun hour by hour, their reflections; about 20 s on the flagship
    office) on the document's operator, off the GUI thread: once it succeeds the
    document finds it built. Then the design's light in every scenario
    (``layout_daylight``: its arrays placed exactly, its groups' and observers' light, as
    long again on the flagship), which the views would otherwise build on the GUI thread
    next. Cancel stops it at its next progress call (between blocks of the reflections'
    columns and between luminaires: a fraction of a second, bench/open_cancel.py) and
    leaves nothing built; succeeds with (seconds, the ``LayoutDaylight`` or None when it
    could not be made here)."""

    def __init__(self, prepared, design, parent: QtCore.QObject | None = None):
        from lightinv_core.light.clear_build import clear_light_key

        super().__init__(parent)
        self.prepared, self.design = prepared, design
        self.key = clear_light_key(design)

    def _step(self, fraction: float) -> None:
        if self.is_cancelled():
            raise CancelledError("the clear glazing's trace was cancelled")
        self.progress.emit(fraction)

    def work(self) -> tuple:
        from threadpoolctl import threadpool_limits

        from lightinv_core.light.clear_build import clear_light
        from lightinv_core.light.daylight import layout_daylight
        from lightinv_core.light.model import LightModel

        p = self.prepared
        t0 = time.perf_counter()
        ld = None
        try:
            # One BLAS thread: a second one spins against the GUI thread (see RunWorker).
            with threadpool_limits(limits=1, user_api="blas"):
                light = LightModel(p.scene, p.patches, p.operator)
                # The trace, then the light in every scenario: about as long again.
                clear_light(light, self.design, lambda f: self._step(0.6 * f))
                self._step(0.6)
                try:
                    ld = layout_daylight(
                        light, self.design, progress=lambda f: self._step(0.6 + 0.4 * f)
                    )
                except LightInvError:
                    ld = None  # the views build it and say why
        except (LightInvError, MemoryError):
            raise
        except Exception as exc:  # a bug: a message for people, the traceback on stderr
            traceback.print_exc()
            raise LightInvError(
                f"the clear glazing's light could not be traced ({type(exc).__name__}: {exc})"
            ) from exc
        self.progress.emit(1.0)
        return time.perf_counter() - t0, ld


@dataclass(frozen=True)
class RunSnapshot:
    """What the GUI draws of a running optimisation, taken at its redraw rate.

            ``points`` are new (run, cumulative evaluations, best goal, best penalty) rows since
            the last snapshot; ``latest`` the newest core ``Progress`` (None before the first);
            ``solutions`` new points of a multi-objective sweep; ``evaluations`` counts all runs
        (every sub-run and level; once the run has ended, the count the core reports);
            ``precompute`` the fraction done of the luminaire arrays' responses (None: none) and
    ``precompute_seconds`` the time it took (s, part of ``elapsed``; known once the search
    reports).
    """

    latest: Progress | None
    points: tuple[tuple[int, int, float, float], ...]
    solutions: tuple
    evaluations: int
    elapsed: float
    precompute: float | None = None
    precompute_seconds: float = 0.0


class RunWorker(Worker):
    """Runs a project's optimisation (one seed, or one run per seed) off the GUI thread.

    The optimizer calls back thousands of times a second: the worker only records
    (under a lock) and the GUI takes a ``RunSnapshot`` on its own timer, so drawing is
    throttled and never floods the event loop. A cancelled run is not an error: it
    ends with ``succeeded`` and the best result found so far (status "cancelled").
    ``succeeded`` carries a list of ``RunResult`` (one per seed).
    """

    result_survives_cancel = True

    def __init__(self, project, prepared, seeds=None, parent: QtCore.QObject | None = None):
        super().__init__(parent)
        self.project, self.prepared = project, prepared
        self.seeds = list(seeds) if seeds else None
        self._lock = threading.Lock()
        self._latest: Progress | None = None
        self._points: list = []
        self._solutions: list = []
        self._offset = 0  # evaluations of finished VNS runs and levels
        self._last_evals = 0
        self._last_key = None
        self._t0 = time.perf_counter()
        self._precompute: float | None = None
        self._final: int | None = None  # the core's count of the run, once it ended
        self._final_s = 0.0  # and its seconds (the search's, as the core reports them)
        self._pre_s = 0.0  # seconds of the arrays' precompute before the search

    def _precomputed(self, fraction: float) -> None:
        with self._lock:
            self._precompute = fraction

    def _progress(self, p: Progress) -> None:
        with self._lock:
            if self._latest is None and self._precompute is not None:
                # The search's clock starts after the precompute: the rest is the latter's.
                self._pre_s = max(0.0, time.perf_counter() - self._t0 - p.elapsed)
            if p.evaluations < self._last_evals or (
                self._latest is not None and p.run != self._latest.run
            ):
                self._offset += self._last_evals  # a new VNS (level, epsilon, seed) began
            self._last_evals = p.evaluations
            key = (p.run, p.best_value, p.best_penalty)
            if key != self._last_key:
                total = self._offset + p.evaluations
                self._points.append((p.run, total, p.best_goal, p.best_penalty))
                self._last_key = key
            self._latest = p

    def _solution(self, solution) -> None:
        with self._lock:
            self._solutions.append(solution)

    def snapshot(self) -> RunSnapshot:
        """The progress since the previous snapshot (thread-safe)."""
        with self._lock:
            points, self._points = tuple(self._points), []
            sols, self._solutions = tuple(self._solutions), []
            live = self._offset + self._last_evals
            return RunSnapshot(
                self._latest,
                points,
                sols,
                live if self._final is None else self._final,
                time.perf_counter() - self._t0
                if self._final is None
                else self._final_s + self._pre_s,
                self._precompute,
                self._pre_s,
            )

    def work(self):
        from threadpoolctl import threadpool_limits

        # One BLAS thread while the window shares the two cores: OpenBLAS's second thread
        # spins against the GUI thread and the run went 3x slower (bench/gui_run.py).
        with threadpool_limits(limits=1, user_api="blas"):
            results = self._solve()
        # The last snapshot shows the core's count and time: a level's or sub-run's last
        # evaluations come after its last progress report.
        with self._lock:
            self._final = sum(r.evaluations for r in results)
            self._final_s = sum(r.seconds for r in results)
        return results

    def _solve(self):
        from lightinv_core.study import solve, solve_seeds

        self._t0 = time.perf_counter()
        if self.seeds is not None and len(self.seeds) > 1:
            return solve_seeds(
                self.project,
                self.prepared,
                self.seeds,
                progress=self._progress,
                cancel=self.is_cancelled,
                on_result=lambda r: self._solution(r.best),
                precompute=self._precomputed,
            )
        seed = self.seeds[0] if self.seeds else None
        return [
            solve(
                self.project,
                self.prepared,
                seed,
                progress=self._progress,
                cancel=self.is_cancelled,
                on_solution=self._solution,
                precompute=self._precomputed,
            )
        ]


def stop_and_wait(worker: QtCore.QThread | None) -> None:
    """Cancel ``worker`` (if any), wait for its thread and deliver its last signals
    (closing the window, switching projects)."""
    if worker is not None:
        worker.cancel()
        worker.wait()
        QtWidgets.QApplication.processEvents()
