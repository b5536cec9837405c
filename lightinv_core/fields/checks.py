"""Project-file values: the ``ProjectError`` a bad one raises and the low-level checks.

Each checker takes a parsed JSON value and the JSON path it came from, and returns the
value normalised (``_number`` gives a float, ``_list`` a tuple, ...) or raises a
``ProjectError`` naming that path. The leading underscores mark helpers private to the
modules that declare fields; the typed checks of ``fields.types`` word their messages
with them, so a value read from a file and one given in code fail alike.
"""

from __future__ import annotations

import difflib
import math
import numbers
import os
from collections.abc import Callable
from typing import Any, NoReturn

import numpy as np

from lightinv_core.errors import DesignError, LightInvError

MAX_INT = 2**53  # integers beyond this are not exact in every JSON reader
NONFINITE = {"inf": math.inf, "-inf": -math.inf, "nan": math.nan}


class ProjectError(LightInvError):
    """A project file or project value is invalid.

    ``detail`` says what is wrong, ``path`` is the JSON path of the value ("" for the
    whole document) and ``file`` the file name when loading or saving a file; the message
    is ``"file: path: detail"`` without the empty parts.
    """

    def __init__(self, detail: str, path: str = "", file: str | None = None):
        self.detail, self.path, self.file = detail, path, file
        super().__init__(": ".join(p for p in (file, path, detail) if p))

    def within(self, prefix: str) -> ProjectError:
        """The same error with ``prefix`` put before its path."""
        return ProjectError(self.detail, _join(prefix, self.path), self.file)


# -- low-level checks ---------------------------------------------------------------------


def _join(prefix: str, sub: str | int) -> str:
    if isinstance(sub, int):
        return f"{prefix}[{sub}]"
    if not prefix:
        return sub
    if not sub:
        return prefix
    return prefix + sub if sub.startswith("[") else f"{prefix}.{sub}"


def _fail(path: str, detail: str) -> NoReturn:
    raise ProjectError(detail, path)


class _within:
    """Context manager: prefix the path of a ProjectError; wrap a DesignError at ``path``."""

    def __init__(self, path: str):
        self.path = path

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind, err, tb) -> bool:
        if isinstance(err, ProjectError):
            raise err.within(self.path) from None
        if isinstance(err, DesignError):
            raise ProjectError(str(err), self.path) from None
        return False


def _fmt(x: float) -> str:
    """A number as the user would write it (2 not 2.0)."""
    if isinstance(x, float) and x.is_integer() and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


def _describe(v: Any) -> str:
    """A JSON value for an error message: its type, and the value when it is short."""
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return f"number {int(v)}" if abs(v) < 10**15 else "a very large number"
    if isinstance(v, numbers.Real):
        return f"number {float(v)!r}"
    if isinstance(v, str):
        return f"string {(v if len(v) <= 40 else v[:37] + '...')!r}"
    if isinstance(v, list | tuple):
        return "an empty list" if not v else f"a list of {len(v)} item" + "s" * (len(v) > 1)
    if isinstance(v, dict):
        return "an object"
    return f"a {type(v).__name__}"


def _is_int(v: Any) -> bool:
    return isinstance(v, numbers.Integral) and not isinstance(v, bool | np.bool_)


def _is_number(v: Any) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, bool | np.bool_)


def _number(
    v: Any,
    path: str,
    lo: float | None = None,
    hi: float | None = None,
    gt: float | None = None,
    lt: float | None = None,
    finite: bool = True,
) -> float:
    """A JSON number as a float. ``finite=False`` also takes inf/nan and their strings."""
    if not finite and isinstance(v, str) and v in NONFINITE:
        return NONFINITE[v]
    cond = " and ".join(
        f"{op} {_fmt(b)}"
        for op, b in ((">=", lo), (">", gt), ("<=", hi), ("<", lt))
        if b is not None
    )
    what = f"a number {cond}" if cond else "a number"
    if not _is_number(v):
        _fail(path, f"expected {what}, got {_describe(v)}")
    try:
        x = float(v)
    except OverflowError:
        _fail(path, f"expected {what}, got a number too large to use")
    if not finite and not math.isfinite(x):
        return x
    if not math.isfinite(x):
        _fail(path, f"expected {'a finite number ' + cond if cond else 'a finite number'}, got {x}")
    if (
        (lo is not None and x < lo)
        or (gt is not None and x <= gt)
        or (hi is not None and x > hi)
        or (lt is not None and x >= lt)
    ):
        _fail(path, f"expected {what}, got {_fmt(x)}")
    return x


def _integer(v: Any, path: str, lo: int | None = None, hi: int | None = None) -> int:
    if hi is not None:
        what = f"an integer from {lo} to {hi:,}"
    else:
        what = f"an integer >= {lo}" if lo is not None else "an integer"
    if not _is_int(v):
        _fail(path, f"expected {what}, got {_describe(v)}")
    if abs(v) > MAX_INT:
        _fail(path, f"expected {what} of at most 2**53, got a larger one")
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        _fail(path, f"expected {what}, got {int(v)}")
    return int(v)


def _string(v: Any, path: str, empty: bool = False) -> str:
    if not isinstance(v, str):
        _fail(path, f"expected a string, got {_describe(v)}")
    if not empty and not v.strip():
        _fail(path, "expected a non-empty string")
    return v


def _choice(v: Any, path: str, choices: tuple[str, ...]) -> str:
    listed = ", ".join(repr(c) for c in choices)
    if not isinstance(v, str) or v not in choices:
        _fail(path, f"expected one of {listed}, got {_describe(v)}")
    return v


def _optional(check: Callable[[Any, str], Any]) -> Callable[[Any, str], Any]:
    """``check`` that also takes null (None)."""
    return lambda v, path: None if v is None else check(v, path)


def _list(v: Any, path: str, item: Callable[[Any, str], Any], what: str, min_len: int = 0) -> tuple:
    if not isinstance(v, list | tuple):
        _fail(path, f"expected a list of {what}, got {_describe(v)}")
    if len(v) < min_len:
        _fail(path, f"expected at least {min_len} {what}, got {len(v)}")
    return tuple(item(x, _join(path, i)) for i, x in enumerate(v))


def _numbers(v: Any, path: str, count: int, **limits) -> tuple[float, ...]:
    """Exactly ``count`` numbers."""
    if not isinstance(v, list | tuple):
        _fail(path, f"expected a list of {count} numbers, got {_describe(v)}")
    if len(v) != count:
        _fail(path, f"expected {count} numbers, got {len(v)}")
    return tuple(_number(x, _join(path, i), **limits) for i, x in enumerate(v))


def _unique(items: tuple[str, ...], path: str) -> tuple[str, ...]:
    seen: dict[str, int] = {}
    for i, s in enumerate(items):
        if s in seen:
            _fail(_join(path, i), f"{s!r} is listed twice")
        seen[s] = i
    return items


def _object(v: Any, path: str, known: tuple[str, ...], required: tuple[str, ...] = ()) -> dict:
    """A JSON object with only ``known`` keys and every ``required`` key."""
    if not isinstance(v, dict):
        _fail(path, f"expected an object, got {_describe(v)}")
    for key in getattr(v, "duplicates", ()):
        _fail(path, f"field {key!r} is given twice")
    for key in v:
        if not isinstance(key, str) or key not in known:
            detail = f"unknown field {key!r} (known: {', '.join(known)})"
            close = difflib.get_close_matches(str(key), known, n=1)
            _fail(path, detail + (f"; did you mean {close[0]!r}?" if close else ""))
    for key in required:
        if key not in v:
            _fail(path, f"missing required field {key!r}")
    return v


def _count(v: Any, path: str) -> int:
    return _integer(v, path, lo=1)


def _boolean(v: Any, path: str) -> bool:
    if not isinstance(v, bool | np.bool_):
        _fail(path, f"expected true or false, got {_describe(v)}")
    return bool(v)


def _path_string(v: Any, path: str) -> str:
    return _string(os.fspath(v) if isinstance(v, os.PathLike) else v, path)
