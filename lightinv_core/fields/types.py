"""Typed value checks: what a field accepts, said once for the check, the docs and the
JSON Schema.

Each check is a callable ``check(value, path) -> normalised value`` (a ``ProjectError``
naming ``path`` on a bad value, worded by the low-level checks of ``fields.checks``) that
also knows its ``text`` (the type column of docs/project-file.md) and its ``schema()``
(JSON Schema, draft 2020-12). Valid values take a fast path: the model classes run these
checks whenever the engine builds one (``replace(source, rect=...)``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from lightinv_core.fields.checks import (
    NONFINITE,
    ProjectError,
    _boolean,
    _choice,
    _fail,
    _fmt,
    _integer,
    _list,
    _number,
    _numbers,
    _string,
    _unique,
)


def _fast_items(item: Callable[[Any, str], Any], v: tuple) -> tuple | None:
    """Each of ``v`` checked by ``item``, or None when one fails (the caller then checks
    again item by item, for the message with its path)."""
    try:
        return tuple(item(x, "") for x in v)
    except ProjectError:
        return None


class Check:
    """A value check that also says what it accepts (``text``, ``schema()``)."""

    text: str = ""

    def __call__(self, v: Any, path: str) -> Any:  # pragma: no cover - every subclass has one
        raise NotImplementedError

    def schema(self) -> dict:
        """The JSON Schema of the values it accepts."""
        return {}


def _short(x: float) -> str:
    """A bound as the docs write it: 1e10 rather than 10000000000."""
    if abs(x) >= 1e6 and float(x).is_integer():
        mantissa, exponent = f"{x:e}".split("e")
        return f"{float(mantissa):g}e{int(exponent)}"
    return _fmt(x)


def _range_text(lo, hi, gt, lt) -> str:
    """``[0, 1]``, ``(0, 1]``, ``>= 0``, ...: a range as the docs show it."""
    low = f"[{_short(lo)}" if lo is not None else (f"({_short(gt)}" if gt is not None else None)
    high = f"{_short(hi)}]" if hi is not None else (f"{_short(lt)})" if lt is not None else None)
    if low and high:
        return f" in {low}, {high}"
    if low:
        return f" >= {_short(lo)}" if lo is not None else f" > {_short(gt)}"
    if high:
        return f" <= {_short(hi)}" if hi is not None else f" < {_short(lt)}"
    return ""


@dataclass(frozen=True)
class Number(Check):
    """A number (float) within optional bounds: ``lo <= x``, ``gt < x``, ``x <= hi``,
    ``x < lt``; ``finite=False`` also takes inf and nan (and their strings); ``hint``
    says what to do about a bad one."""

    lo: float | None = None
    hi: float | None = None
    gt: float | None = None
    lt: float | None = None
    finite: bool = True
    hint: str = ""  # what to do, added to the message of a bad value

    @property
    def text(self) -> str:
        return "number" + _range_text(self.lo, self.hi, self.gt, self.lt)

    def __call__(self, v: Any, path: str) -> float:
        if type(v) is float or (type(v) is int and abs(v) <= 2**53):  # a valid plain number
            x = float(v)
            if (
                math.isfinite(x)
                and (self.lo is None or x >= self.lo)
                and (self.hi is None or x <= self.hi)
                and (self.gt is None or x > self.gt)
                and (self.lt is None or x < self.lt)
            ):
                return x
        limits = {"lo": self.lo, "hi": self.hi, "gt": self.gt, "lt": self.lt}
        try:
            return _number(v, path, finite=self.finite, **limits)
        except ProjectError as err:
            if not self.hint:
                raise
            raise ProjectError(f"{err.detail} ({self.hint})", err.path) from None

    def schema(self) -> dict:
        out: dict[str, Any] = {"type": "number"}
        for key, bound in (
            ("minimum", self.lo),
            ("maximum", self.hi),
            ("exclusiveMinimum", self.gt),
            ("exclusiveMaximum", self.lt),
        ):
            if bound is not None:
                out[key] = bound
        if not self.finite:
            return {"anyOf": [out, {"enum": list(NONFINITE)}]}
        return out


@dataclass(frozen=True)
class Integer(Check):
    """A whole number (int) in ``[lo, hi]`` (JSON integers beyond 2**53 are refused)."""

    lo: int | None = None
    hi: int | None = None

    @property
    def text(self) -> str:
        if self.hi is not None:
            return f"integer, {self.lo} to {self.hi:,}"
        return "integer" + (f" >= {self.lo}" if self.lo is not None else "")

    def __call__(self, v: Any, path: str) -> int:
        lo, hi = self.lo, self.hi
        if (
            type(v) is int
            and (lo is None or v >= lo)
            and (hi is None or v <= hi)
            and abs(v) <= 2**53
        ):
            return v
        return _integer(v, path, self.lo, self.hi)

    def schema(self) -> dict:
        out: dict[str, Any] = {"type": "integer"}
        if self.lo is not None:
            out["minimum"] = self.lo
        if self.hi is not None:
            out["maximum"] = self.hi
        return out


@dataclass(frozen=True)
class String(Check):
    """A string, not blank unless ``empty``."""

    empty: bool = False
    text = "string"

    def __call__(self, v: Any, path: str) -> str:
        if type(v) is str and (self.empty or v.strip()):
            return v
        return _string(v, path, self.empty)

    def schema(self) -> dict:
        return {"type": "string"} if self.empty else {"type": "string", "pattern": r"\S"}


@dataclass(frozen=True)
class Boolean(Check):
    """true or false."""

    text = "boolean"

    def __call__(self, v: Any, path: str) -> bool:
        return _boolean(v, path)

    def schema(self) -> dict:
        return {"type": "boolean"}


@dataclass(frozen=True)
class Choice(Check):
    """One of the strings ``values()`` (a registry: looked up at each check, so a kind
    registered later is taken), turned into the model's value by ``convert`` (a kind's
    enum member). ``name`` is what the docs call the values (listed when empty)."""

    values: Callable[[], tuple[str, ...]]
    convert: Callable[[str], Any] = str
    name: str = ""

    @property
    def text(self) -> str:
        return self.name or " or ".join(f'`"{v}"`' for v in self.values())

    def __call__(self, v: Any, path: str) -> Any:
        values = self.values()
        if isinstance(v, str) and v in values:
            return self.convert(v)
        return self.convert(_choice(v, path, tuple(str(c) for c in values)))

    def schema(self) -> dict:
        return {"enum": [str(c) for c in self.values()]}


def choice_of(*values: str, name: str = "") -> Choice:
    """A ``Choice`` of fixed ``values``."""
    return Choice(lambda: values, name=name)


@dataclass(frozen=True)
class Numbers(Check):
    """Exactly ``count`` numbers, each a ``Number`` of these bounds (a tuple)."""

    count: int
    item: Number = Number()

    @property
    def text(self) -> str:
        return f"{self.count} numbers"

    def __call__(self, v: Any, path: str) -> tuple[float, ...]:
        if type(v) is tuple and len(v) == self.count:  # the fast path of a model's value
            fast = _fast_items(self.item, v)
            if fast is not None:
                return fast
        it = self.item
        return _numbers(v, path, self.count, lo=it.lo, hi=it.hi, gt=it.gt, lt=it.lt)

    def schema(self) -> dict:
        n = self.count
        return {"type": "array", "items": self.item.schema(), "minItems": n, "maxItems": n}


@dataclass(frozen=True)
class ListOf(Check):
    """A list (a tuple) of values of ``item``: ``what`` names them in messages (``"source
    names"``), ``min_len`` the fewest, ``unique``: none listed twice."""

    item: Check
    what: str
    min_len: int = 0
    unique: bool = False
    name: str = ""

    @property
    def text(self) -> str:
        return self.name or f"list of {self.what}"

    def __call__(self, v: Any, path: str) -> tuple:
        if type(v) is tuple and len(v) >= self.min_len:  # the fast path of a model's value
            fast = _fast_items(self.item, v)
            if fast is not None and (not self.unique or len(set(fast)) == len(fast)):
                return fast
        items = _list(v, path, self.item, self.what, self.min_len)
        return _unique(items, path) if self.unique else items

    def schema(self) -> dict:
        out: dict[str, Any] = {"type": "array", "items": self.item.schema()}
        if self.min_len:
            out["minItems"] = self.min_len
        if self.unique:
            out["uniqueItems"] = True
        return out


@dataclass(frozen=True)
class Nullable(Check):
    """``item``, or null (None) where null is a value of its own (not "not given")."""

    item: Check

    @property
    def text(self) -> str:
        return self.item.text

    def __call__(self, v: Any, path: str) -> Any:
        return None if v is None else self.item(v, path)

    def schema(self) -> dict:
        return {"anyOf": [self.item.schema(), {"type": "null"}]}


@dataclass(frozen=True)
class Custom(Check):
    """A check of its own (a function) with the ``text`` and JSON ``schema_`` it accepts."""

    check: Callable[[Any, str], Any]
    text: str = ""
    schema_: dict | None = None

    def __call__(self, v: Any, path: str) -> Any:
        return self.check(v, path)

    def schema(self) -> dict:
        return dict(self.schema_ or {})


def whole_pair(lo: int, hi: int | None = None) -> Custom:
    """Two whole numbers (min, max), each at least ``lo`` (and at most ``hi``)."""
    item = Integer(lo, hi)

    def check(v: Any, p: str) -> tuple[int, int]:
        if type(v) is tuple and len(v) == 2:  # the fast path of a model's value
            fast = _fast_items(item, v)
            if fast is not None:
                return fast
        items = _list(v, p, item, "whole numbers")
        if len(items) != 2:
            _fail(p, f"expected 2 whole numbers (min, max), got {len(items)}")
        return tuple(items)

    schema = {"type": "array", "items": item.schema(), "minItems": 2, "maxItems": 2}
    return Custom(check, "2 integers", schema)
