"""Autosave and crash recovery.

While a project has unsaved changes or an optimisation runs, the window writes the
project — with the best result of the running optimisation — to
``<autosave dir>/autosave-<pid>-<token>.json`` every ``interval`` seconds (atomically: a
crash mid-write leaves the previous autosave). A clean exit, or a save with nothing
running, removes the file. At start-up, autosaves whose session is gone are offered
for recovery (``offer_recovery``, ``recover``).

A session is alive while it holds an exclusive ``flock`` on its ``.lock`` file beside
the autosave; the kernel drops the lock when the process dies, however it dies. The
process id alone cannot tell: in a container every new window gets the crashed
one's id, and an id check deleted the crashed session's work within seconds.

The directory is ``$LIGHTINV_AUTOSAVE_DIR`` or the user data folder
(``platformdirs.user_data_dir("LightInv")/autosave``); the interval is
``$LIGHTINV_AUTOSAVE_SECONDS`` or ``lightinv --autosave-interval`` (default 30 s).
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import secrets
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

from PySide6 import QtCore

from lightinv_core.atomic import remove_stale_temporaries
from lightinv_core.errors import LightInvError
from lightinv_core.project import Project, project_from_dict, project_to_dict
from lightinv_core.project.write import write_json

FORMAT = 1
LOCK_SUFFIX = ".lock"
DEFAULT_INTERVAL = 30.0


def autosave_dir() -> Path:
    """Where autosaves go (created on first use)."""
    env = os.environ.get("LIGHTINV_AUTOSAVE_DIR")
    if env:
        return Path(env)
    from platformdirs import user_data_dir

    return Path(user_data_dir("LightInv", appauthor=False)) / "autosave"


def autosave_interval() -> float:
    """Seconds between autosaves ($LIGHTINV_AUTOSAVE_SECONDS, default 30)."""
    try:
        value = float(os.environ.get("LIGHTINV_AUTOSAVE_SECONDS", DEFAULT_INTERVAL))
    except ValueError:
        return DEFAULT_INTERVAL
    return value if value > 0 else DEFAULT_INTERVAL


def write_autosave(path: Path, project: Project, original: Path | None, note: str = "") -> None:
    """Write ``project`` (scene paths absolute) as an autosave, atomically."""
    data = {
        "lightinv_autosave": FORMAT,
        "pid": os.getpid(),
        "saved_at": time.strftime("%Y-%m-%d %H:%M:%S"),
        "original": None if original is None else str(Path(original).resolve()),
        "note": note,
        "project": project_to_dict(project),
    }
    path.parent.mkdir(parents=True, exist_ok=True)
    write_json(data, path)


def session_alive(autosave: Path) -> bool:
    """Whether the session that writes ``autosave`` is still running: its lock file is
    held. Autosaves from before lock files fall back to the process id."""
    lock = autosave.with_suffix(LOCK_SUFFIX)
    try:
        fd = os.open(lock, os.O_RDONLY)
    except FileNotFoundError:
        parts = autosave.stem.split("-")
        try:
            pid = int(parts[1])
        except (IndexError, ValueError):
            return False
        # Sessions with a token always have a lock file; only old ones go by pid, and
        # this process never writes such a name, so its own pid means a dead session.
        return len(parts) == 2 and pid != os.getpid() and pid_alive(pid)
    except OSError:
        return True  # cannot tell: leave it alone
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return True  # held by a live session
    finally:
        os.close(fd)  # also releases the probe's own lock
    return False


def pid_alive(pid: int) -> bool:
    """Whether a process with this id exists (its autosave is not orphaned)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True
    return True


@dataclass(frozen=True)
class Recoverable:
    """An orphaned autosave: its project (None if unreadable, with ``error``)."""

    path: Path
    project: Project | None
    original: Path | None
    saved_at: str
    note: str
    error: str = ""


def read_autosave(path: Path) -> Recoverable:
    """Read one autosave; a broken one comes back with ``error`` set, never raises."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        if data.get("lightinv_autosave") != FORMAT:
            raise LightInvError(f"unknown autosave format {data.get('lightinv_autosave')!r}")
        original = Path(data["original"]) if data.get("original") else None
        project = project_from_dict(data["project"], None)
        return Recoverable(
            path, project, original, str(data.get("saved_at", "")), str(data.get("note", ""))
        )
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        return Recoverable(path, None, None, "", "", f"{type(exc).__name__}: {exc}")


def orphaned_autosaves(directory: Path | None = None) -> list[Recoverable]:
    """Autosaves left by LightInv processes that are gone (a crash or a kill)."""
    directory = directory or autosave_dir()
    remove_stale_temporaries(directory)  # autosaves killed while being written
    found = []
    for path in sorted(Path(directory).glob("autosave-*.json")):
        if not session_alive(path):
            found.append(read_autosave(path))
    for lock in Path(directory).glob(f"autosave-*{LOCK_SUFFIX}"):
        # A session that ended without an autosave to recover leaves only its lock.
        if not lock.with_suffix(".json").exists() and not session_alive(lock):
            lock.unlink(missing_ok=True)
    return found


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
    doc.mark_dirty()
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
