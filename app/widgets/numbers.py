"""Numbers as the result panels write them."""

from __future__ import annotations

import math


def fmt(v: float) -> str:
    return "-" if v is None or not math.isfinite(v) else f"{v:,.1f}"


def distinct(value: float, bound: float) -> tuple[str, str]:
    """A value and its bound with as many decimals as it takes to tell them apart (a U0
    of 0.593 against 0.6 read "0.6 vs 0.6, off by 1.3%"), at most 6."""
    if value is None or bound is None or not (math.isfinite(value) and math.isfinite(bound)):
        return fmt(value), fmt(bound)
    size = max(abs(value), abs(bound))
    d = 1 if size >= 10 else (2 if size >= 1 else 3)
    while d < 6 and value != bound and f"{value:,.{d}f}" == f"{bound:,.{d}f}":
        d += 1
    return f"{value:,.{d}f}", f"{bound:,.{d}f}"
