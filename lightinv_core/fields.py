"""Project-file fields: value checks, the ``ProjectError`` they raise, and field specs.

Each checker takes a parsed JSON value and the JSON path it came from, and returns the
value normalised (``_number`` gives a float, ``_list`` a tuple, ...) or raises a
``ProjectError`` naming that path. The leading underscores mark helpers private to the
modules that declare fields.

``Field`` and ``ObjectSpec`` declare each field of a JSON object once (its check,
default, the kinds of object that take it, its docs); reading, the error messages,
writing and the field tables of docs/project-file.md are all derived from them. The
specs themselves live beside the classes they describe: ``OPERATOR`` in
``operator/settings.py``, ``OPTIMIZER`` in ``optimize/settings.py``, the scene and the
top level in ``project/model.py``, the design in ``project/specs.py`` and the results
in ``project/results.py``.
"""

from __future__ import annotations

import difflib
import math
import numbers
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
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


# -- field specs: each field of a JSON object declared once ---------------------------------

REQUIRED = object()
"""The default of a field that must be given."""


@dataclass(frozen=True)
class Field:
    """One field of a JSON object, declared once.

    ``check`` turns the JSON value at a JSON path into the model's value (a
    ``ProjectError`` on a bad one); with ``needs``, it also gets the values of those
    earlier fields of the same object as keyword arguments (a rule's source names).
    ``default`` is taken when the field is missing (``REQUIRED``: it must be given;
    ``doc_default`` shows a default that is not a plain JSON value in the docs).
    ``type`` and ``meaning`` (units included) are what the docs say of it. ``kinds``
    lists the kinds of object that take the field (empty: every kind). On writing, a
    field is left out at its default unless ``always``; ``of`` is the spec of the
    object(s) it holds, ``encode`` turns any other value into plain data. ``nullable``:
    a null means "not given". ``optional``: left out at its default even in an object
    that writes its defaults (a field later versions added, so older files stay as
    they were).
    """

    name: str
    check: Callable[..., Any]
    default: Any = REQUIRED
    type: str = ""
    meaning: str = ""
    kinds: tuple[str, ...] = ()
    always: bool = False
    nullable: bool = False
    needs: tuple[str, ...] = ()
    of: ObjectSpec | None = None
    encode: Callable[[Any], Any] | None = None
    doc_default: str | None = None
    optional: bool = False

    @property
    def required(self) -> bool:
        """Whether the field must be given."""
        return self.default is REQUIRED


@dataclass(frozen=True)
class ObjectSpec:
    """The fields of one kind of JSON object, in the order they are written.

    ``kind_field`` names the field that says which kinds' fields apply (a source's
    ``kind``), or an attribute of the data class when the kind is implied (a scene's
    ``kind``: builtin or obj; then the class calls ``check_kinds``). ``not_taken(kind,
    field)`` words the error for a field the kind does not take; it is checked after
    the values unless ``kinds_first``, and with ``default_anywhere`` a field at its
    default passes whatever the kind (a built-in scene's ``"scale": 1``).
    ``write_defaults``: every field is written, defaults included (settings, results).
    ``kinds_doc`` words the docs' note on a field only some kinds take.
    """

    name: str
    fields: tuple[Field, ...]
    kind_field: str | None = None
    not_taken: Callable[[str, str], str] | None = None
    kinds_first: bool = False
    default_anywhere: bool = False
    write_defaults: bool = False
    kinds_doc: str = "{} only"

    @property
    def names(self) -> tuple[str, ...]:
        """Every field name, in order."""
        return tuple(f.name for f in self.fields)

    def field(self, name: str) -> Field:
        """The field called ``name``."""
        return next(f for f in self.fields if f.name == name)

    def defaults(self) -> dict[str, Any]:
        """The default of every field that need not be given."""
        return {f.name: f.default for f in self.fields if not f.required}

    def read(self, v: Any, path: str) -> dict[str, Any]:
        """The checked values of the object ``v`` at ``path`` (fields not given are left
        out): unknown, repeated and missing fields, each value's check in field order,
        then fields its kind does not take (a null counts as not given where the field
        is ``nullable``)."""
        required = tuple(f.name for f in self.fields if f.required)
        d = _object(v, path, self.names, required)
        kind = None
        if self.kind_field in self.names:
            kind = self.field(self.kind_field).check(d[self.kind_field], _join(path, "kind"))
        out: dict[str, Any] = {}
        for f in self.fields:
            if f.name not in d or (d[f.name] is None and f.nullable):
                continue
            if self.kinds_first:
                self._taken(kind, f, d[f.name], path)
            given = {n: out.get(n, self.field(n).default) for n in f.needs}
            out[f.name] = f.check(d[f.name], _join(path, f.name), **given)
        for f in self.fields:
            if f.name in out:
                self._taken(kind, f, out[f.name], path)
        return out

    def build(self, cls: type, v: Any, path: str) -> Any:
        """``cls(**values)`` of the object ``v`` at ``path``, an error of the model class
        (``DesignError``) reported at ``path``."""
        values = self.read(v, path)
        with _within(path):
            return cls(**values)

    def check_object(self, obj: Any) -> None:
        """Check and normalise, in place, the fields of the frozen dataclass ``obj`` (a
        settings object made in code or read from a file)."""
        for f in self.fields:
            object.__setattr__(obj, f.name, f.check(getattr(obj, f.name), f.name))

    def check_kinds(self, obj: Any, path: str = "") -> None:
        """Fail on a field of the data class ``obj`` that its kind does not take."""
        kind = getattr(obj, self.kind_field)
        for f in self.fields:
            value = getattr(obj, f.name)
            if not (f.nullable and value is None):
                self._taken(kind, f, value, path)

    def _taken(self, kind: str | None, f: Field, value: Any, path: str) -> None:
        if kind is None or not f.kinds or kind in f.kinds:
            return
        if self.default_anywhere and value == f.default:
            return
        _fail(_join(path, f.name), self.not_taken(kind, f.name))

    def write(self, obj: Any) -> dict[str, Any]:
        """The fields of ``obj`` (a mapping, or attributes of the same names) as they are
        saved: the fields its kind takes that are required, ``always`` written or not at
        their default (all of them with ``write_defaults``), nested objects by their own
        spec, tuples as lists."""
        get = obj.__getitem__ if isinstance(obj, Mapping) else lambda n: getattr(obj, n)
        kind = get(self.kind_field) if self.kind_field else None
        out: dict[str, Any] = {}
        for f in self.fields:
            value = get(f.name)
            if f.kinds and kind not in f.kinds:
                continue
            written = self.write_defaults and not f.optional
            if f.required or f.always or written or value != f.default:
                out[f.name] = _encode(f, value)
        return out

    def markdown(self) -> str:
        """The fields as a Markdown table: key, required, type, default, meaning (the
        kinds that take it, then what it is, with its units)."""
        rows = ["| key | required | type | default | meaning |", "|---|---|---|---|---|"]
        for f in self.fields:
            need = "yes" if f.required else "no"
            if f.doc_default is not None:
                default = f.doc_default
            elif f.required:
                default = ""
            elif f.default is None:
                default = "none"
            else:
                default = f"`{_doc_value(f.default)}`"
            kinds = ", ".join(f"`{k}`" for k in f.kinds)
            only = self.kinds_doc.format(kinds) + ": " if f.kinds else ""
            rows.append(f"| `{f.name}` | {need} | {f.type} | {default} | {only}{f.meaning} |")
        return "\n".join(rows)


def _encode(f: Field, value: Any) -> Any:
    """A field's value as it is written (before ``_jsonable`` makes it plain JSON)."""
    if f.encode is not None:
        return f.encode(value)
    if f.of is not None and value is not None:
        if isinstance(value, tuple | list):
            return [f.of.write(x) for x in value]
        return f.of.write(value)
    return list(value) if isinstance(value, tuple) else value


def _doc_value(v: Any) -> str:
    """A default value as JSON text for the docs."""
    if isinstance(v, tuple):
        return "[" + ", ".join(_doc_value(x) for x in v) + "]"
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, bool):
        return "true" if v else "false"
    return _fmt(v)
