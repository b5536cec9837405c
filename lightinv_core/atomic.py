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
