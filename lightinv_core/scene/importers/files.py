"""Reading a model's files: a regular file, checked first, with errors that say what to do."""

from __future__ import annotations

import os
import stat
from collections.abc import Callable
from pathlib import Path

from lightinv_core.errors import ObjImportError
from lightinv_core.textcodec import decode_text


def check_file(path: Path, what: str) -> None:
    """ObjImportError unless ``path`` is a regular file (``what``: "glTF file", ...)."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise ObjImportError(f"{what} '{path}' does not exist; check the path") from None
    except (OSError, ValueError) as exc:
        raise ObjImportError(f"cannot read {what} '{path}': {exc}") from None
    if not stat.S_ISREG(mode):
        raise ObjImportError(
            f"{what} '{path}' is not a file (a folder or device); give the path of the file"
        )


def read_text(path: Path, what: str, guard: Callable[[Path, str], object] | None = None) -> str:
    """Read a regular file as text (``decode_text``); ObjImportError if impossible.

    ``guard(path, name)`` runs once the path is known to be a regular file and before
    it is read, to refuse files too big to import.
    """
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise ObjImportError(f"{what} '{path}' does not exist; check the path") from None
    except (OSError, ValueError) as exc:
        raise ObjImportError(f"cannot read {what} '{path}': {reason(exc)}") from None
    if not stat.S_ISREG(mode):
        raise ObjImportError(
            f"{what} '{path}' is not a file (a folder or device); give the path of the file"
        )
    if guard is not None:
        guard(Path(path), Path(path).name)
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise ObjImportError(
            f"cannot read {what} '{path}': {reason(exc)}; check that it is readable"
        ) from None
    return decode_text(data)[0]


def reason(exc: Exception) -> str:
    return getattr(exc, "strerror", None) or str(exc) or type(exc).__name__
