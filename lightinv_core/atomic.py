"""Atomic file writes: a reader never sees a half-written file, a crash leaves the old one.

What each kind of output path gets:

- a regular file, or a new name: a temporary file beside it, fsynced, then renamed over
  it (all or nothing);
- a symbolic link: the same, on the file the link points to, so the link stays a link
  and its target gets the new content;
- a pipe, FIFO, terminal or device (``/dev/stdout``, ``/dev/null``, ``-o >(gzip ...)``):
  written through directly, in order. Renaming over one would replace the device or
  the link with a regular file and the reader would get nothing.

Temporary files are named ``.NAME.tmp-RANDOM`` and held under an exclusive ``flock``
while written. A process killed mid-write (``kill -9``) leaves its temporary behind;
the next write to the same folder removes every such file that no live writer holds
(``remove_stale_temporaries``), and the operator cache and the autosave folder are
swept when they are opened. Locks die with their process, so a reused process id
cannot keep a leftover alive.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import stat
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import IO

from lightinv_core.errors import OutputError

TEMP_MARK = ".tmp-"
STALE_AGE_S = 2.0
"""A temporary younger than this is left alone: its writer may be between creating it
and locking it."""


def _write_target(path: Path) -> tuple[Path, bool]:
    """(the file to write, whether to write through instead of renaming)."""
    try:
        st = os.stat(path)  # follows links
    except FileNotFoundError:
        # A new file; a dangling link gets its target created.
        return (Path(os.path.realpath(path)) if path.is_symlink() else path), False
    if not stat.S_ISREG(st.st_mode):
        return path, True
    return Path(os.path.realpath(path)), False


def remove_stale_temporaries(folder: str | Path) -> list[Path]:
    """Delete the temporaries of killed writers in ``folder`` (see the module); returns
    what was removed. Never raises: a folder that cannot be read or written is left."""
    removed: list[Path] = []
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    now = time.time()
    for entry in entries:
        name = entry.name
        if not (name.startswith(".") and TEMP_MARK in name):
            continue
        try:
            if not entry.is_file(follow_symlinks=False):
                continue
            if now - entry.stat(follow_symlinks=False).st_mtime < STALE_AGE_S:
                continue
            fd = os.open(entry.path, os.O_RDONLY)
        except OSError:
            continue
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            continue  # a live writer holds it
        else:
            with contextlib.suppress(OSError):
                os.unlink(entry.path)
                removed.append(Path(entry.path))
        finally:
            os.close(fd)
    return removed


@contextlib.contextmanager
def atomic_writer(path: str | Path, mode: str = "w", **kwargs) -> Iterator[IO]:
    """Open ``path`` for writing all or nothing (see the module for links, pipes and
    devices). On any exception the temporary file is removed and ``path`` is left
    untouched."""
    target, through = _write_target(Path(path))
    if through:
        with open(target, mode, **kwargs) as fh:
            yield fh
        return
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target.parent)
    # mkstemp creates the file 0600; keep an existing file's mode, else the usual 0644.
    try:
        perms = target.stat().st_mode & 0o777
    except FileNotFoundError:
        perms = 0o644
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}{TEMP_MARK}", dir=target.parent)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # ours while written: not stale
        with os.fdopen(fd, mode, **kwargs) as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
            os.chmod(tmp, perms)
            os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def check_writable(path: str | Path) -> None:
    """Raise OutputError now if ``path`` cannot be written later: a folder in the way, a
    folder that cannot be created or written (read-only, no permission). A device or
    pipe passes. Long work calls this first, so a typo in ``-o`` costs nothing."""
    p = Path(path)
    try:
        target, through = _write_target(p)
    except OSError as exc:  # a file where a folder should be, a loop of links
        reason = exc.strerror or type(exc).__name__
        raise OutputError(f"cannot write {p}: {reason}; choose another path") from None
    if through:
        if p.is_dir():
            raise OutputError(f"cannot write {p}: it is a folder; give a file name")
        return
    folder = Path(os.path.abspath(target)).parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    if not folder.is_dir():
        raise OutputError(f"cannot write {p}: {folder} is not a folder; choose another path")
    try:
        fd, probe = tempfile.mkstemp(prefix=f".{target.name}{TEMP_MARK}", dir=folder)
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise OutputError(f"cannot write {p}: {reason} in {folder}; choose another path") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)


def rescue_paths(path: str | Path) -> list[Path]:
    """Where to put an output that could not be written to ``path``, best first: beside
    it with ``.unsaved-TIME`` in its name, in the user's data folder, in the temp folder."""
    p = Path(path)
    stamp = time.strftime("%Y%m%d-%H%M%S")
    name = f"{p.stem}.unsaved-{stamp}{p.suffix}"
    out = [p.parent / name]
    try:
        from platformdirs import user_data_dir

        out.append(Path(user_data_dir("lightinv")) / "unsaved" / name)
    except ImportError:  # pragma: no cover - platformdirs is a dependency
        pass
    out.append(Path(tempfile.gettempdir()) / name)
    return out
