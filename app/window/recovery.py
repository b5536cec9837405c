"""The window's autosave timer and crash recovery (the files themselves: app/autosave.py).

``Autosaver`` writes the window's unsaved work, with a running optimisation's best so
far, every ``interval`` seconds and holds the session's lock; ``offer_recovery`` and
``recover`` open the autosaves of sessions that ended without closing.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import secrets
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from PySide6 import QtCore

from app.autosave import (
    LOCK_SUFFIX,
    Recoverable,
    autosave_dir,
    autosave_interval,
    orphaned_autosaves,
    write_autosave,
)
from lightinv_core.errors import LightInvError
from lightinv_core.project import Project


class Autosaver(QtCore.QObject):
    """Writes a window's unsaved work (and a running optimisation's best) on a timer."""

    def __init__(self, window, seconds: float | None = None, folder: Path | None = None):
        super().__init__(window)
        self.win = window
        self.folder = Path(folder) if folder is not None else autosave_dir()
        token = f"{os.getpid()}-{secrets.token_hex(4)}"
        self.path = self.folder / f"autosave-{token}.json"
        self.lock_path = self.path.with_suffix(LOCK_SUFFIX)
        self._lock_fd: int | None = None
        self._hold_lock()
        self.count = 0
        self.timer = QtCore.QTimer(self)
        self.timer.setInterval(int(1000 * (seconds or autosave_interval())))
        self.timer.timeout.connect(self.save_now)
        self.timer.start()

    def content(self) -> Project | None:
        """What would be lost in a crash now: the project if it has unsaved changes, with
        the running optimisation's results so far; None when nothing would be lost."""
        doc = self.win.doc
        if doc.project is None:
            return None
        running = self.win.runs.best_so_far()
        if not running and not doc.dirty:
            return None
        return replace(doc.project, solutions=doc.project.solutions + running)

    def save_now(self) -> bool:
        """Autosave (or remove a stale autosave when nothing is unsaved). Never raises:
        a failed autosave is reported in the status bar and tried again next time."""
        try:
            project = self.content()
            if project is None:
                self.discard()
                return False
            note = "optimisation running" if self.win.runs.running else "unsaved changes"
            self._hold_lock()
            write_autosave(self.path, project, self.win.doc.path, note)
        except (OSError, LightInvError) as exc:
            self.win.statusBar().showMessage(f"Autosave failed: {exc}", 8000)
            return False
        self.count += 1
        return True

    def _hold_lock(self) -> None:
        """Take this session's lock (see the module); a folder that cannot be written
        gets no lock now, and each save tries again."""
        if self._lock_fd is not None:
            return
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
            fd = os.open(self.lock_path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError:
            return
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            return
        self._lock_fd = fd

    def discard(self) -> None:
        """Remove this window's autosave (saved or closed cleanly)."""
        with contextlib.suppress(OSError):
            self.path.unlink()

    def close(self) -> None:
        """A clean exit: remove the autosave, then the lock file, and let the lock go."""
        self.timer.stop()
        self.discard()
        if self._lock_fd is not None:
            with contextlib.suppress(OSError):
                self.lock_path.unlink()
            os.close(self._lock_fd)
            self._lock_fd = None


def offer_recovery(window, ask: Callable[[Recoverable], str]) -> bool:
    """Offer the autosaves of LightInv sessions that ended without closing (a crash, a
    kill) to ``window``: ``ask(recoverable) -> "recover" | "discard" | "keep"``. Returns
    True if a project was recovered."""
    for rec in orphaned_autosaves(window.autosaver.folder):
        answer = ask(rec)
        if answer == "recover" and rec.project is not None and recover(window, rec):
            return True
        if answer == "discard":
            rec.path.unlink(missing_ok=True)
    return False


def recover(window, rec: Recoverable) -> bool:
    """Open an autosave as ``window``'s project (unsaved; Save writes to the original
    file), with the best layout of an interrupted run loaded into the design."""
    if not window.load_project(rec.project, rec.original):
        return False
    doc = window.doc
    doc.mark_unsaved()
    running = [s for s in rec.project.solutions if s.info.status == "running"]
    if running:
        with contextlib.suppress(LightInvError):
            doc.apply_solution(running[-1])
    rec.path.unlink(missing_ok=True)
    window.autosaver.save_now()
    window.statusBar().showMessage(
        f"Recovered the work autosaved at {rec.saved_at}"
        + (" with the interrupted run's best layout" if running else ""),
        10_000,
    )
    return True
