"""Long work off the GUI thread: each worker is a QThread that reports through signals.

A worker never touches widgets or VTK; it calls the core with a progress callback
(emitted as a signal, drawn by the GUI thread) and a cancel flag it checks
between steps. Cancelling makes the core raise CancelledError, which becomes the
``cancelled`` signal; any other error becomes ``failed`` with its message, never
a silent thread death.
"""

from __future__ import annotations

import threading
import traceback
import weakref
from typing import ClassVar

from PySide6 import QtCore

from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.io.operator_cache import get_operator
from lightinv_core.scene.patches import Patches


class Worker(QtCore.QThread):
    """Base worker: ``progress(float)``, ``succeeded(object)``, ``failed(str)``, ``cancelled()``."""

    progress = QtCore.Signal(float)
    succeeded = QtCore.Signal(object)
    failed = QtCore.Signal(str)
    cancelled = QtCore.Signal()

    _live: ClassVar[weakref.WeakSet] = weakref.WeakSet()

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
            if self.is_cancelled():
                self.cancelled.emit()
            else:
                self.succeeded.emit(result)


class PrecomputeWorker(Worker):
    """Builds (or loads from the cache) the radiosity operator of some patches."""

    def __init__(self, patches: Patches, settings, parent: QtCore.QObject | None = None):
        super().__init__(parent)
        self.patches, self.settings = patches, settings
        self.warnings: list[str] = []

    def work(self):
        s = self.settings
        got = get_operator(
            self.patches,
            rank=s.rank,
            tol=s.tol,
            rays=s.rays,
            seed=s.seed,
            progress=self.progress.emit,
            cancel=self.is_cancelled,
            warn=self.warnings.append,
        )
        self.progress.emit(1.0)
        return got


class ReportWorker(Worker):
    """Writes the PDF report of the open project (its saved solution) off the GUI thread."""

    def __init__(self, project, prepared, path, parent: QtCore.QObject | None = None):
        super().__init__(parent)
        self.project, self.prepared, self.path = project, prepared, path

    def work(self):
        from lightinv_core.report import write_report

        return write_report(
            self.project,
            self.prepared,
            self.path,
            progress=self.progress.emit,
            cancel=self.is_cancelled,
        )
