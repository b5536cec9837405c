"""Autosave and crash recovery.

While a project has unsaved changes or an optimisation runs, the window writes the
project — with the best result of the running optimisation — to
``<autosave dir>/autosave-<pid>-<token>.json`` every ``interval`` seconds (atomically: a
crash mid-write leaves the previous autosave). A clean exit, or a save with nothing
running, removes the file. At start-up, autosaves whose session is gone are offered
for recovery (``app.window.recovery``). This module is the files alone, Qt-free: what
an autosave holds, where it goes, whose session is alive.

A session is alive while it holds an exclusive ``flock`` on its ``.lock`` file beside
the autosave; the kernel drops the lock when the process dies, however it dies. The
process id alone cannot tell: in a container every new window gets the crashed
one's id, and an id check deleted the crashed session's work within seconds.

The directory is ``$LIGHTINV_AUTOSAVE_DIR`` or the user data folder
(``platformdirs.user_data_dir("LightInv")/autosave``); the interval is
``$LIGHTINV_AUTOSAVE_SECONDS`` or ``lightinv --autosave-interval`` (default 30 s).
"""

from __future__ import annotations

import fcntl
import json
import os
import time
from dataclasses import dataclass
from pathlib import Path

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
