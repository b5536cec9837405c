"""The command line's argument types: each parses one option's text or raises
``argparse.ArgumentTypeError`` with a message saying what it expected."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable

from lightinv_core.errors import LightInvError
from lightinv_core.transport.formfactors import MAX_RAYS

MAX_SEED = 2**63 - 1
"""Largest seed: numpy's generators take any non-negative int, a project stores int64."""


def group_lumens(text: str) -> tuple[str, float]:
    """``GROUP=LUMENS`` -> (group, lm)."""
    group, sep, value = text.partition("=")
    try:
        if not sep or not group:
            raise ValueError
        return group, float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected GROUP=LUMENS, got {text!r}") from None


def integer(text: str, lo: int, hi: int, what: str) -> int:
    """An integer from ``lo`` to ``hi``; ``what`` says so in the message."""
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}") from None
    if not lo <= v <= hi:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text}")
    return v


def seed(text: str) -> int:
    """A random seed, 0 to 2**63 - 1."""
    return integer(text, 0, MAX_SEED, "an integer seed from 0 to 2**63 - 1")


def rays(text: str) -> int:
    """Rays per patch, 1 to ``MAX_RAYS``: 64 times the default, already far past where the
    form factors' error stops mattering (docs/operator.md), and about an hour of ray
    casting on the patio scene."""
    return integer(text, 1, MAX_RAYS, f"an integer from 1 to {MAX_RAYS:,} rays per patch")


def count(text: str) -> int:
    """A count >= 1."""
    return integer(text, 1, 2**53, "an integer >= 1")


def number_in(
    lo: float, hi: float, what: str, open_lo: bool = False, open_hi: bool = False
) -> Callable[[str], float]:
    """An argparse type: a number from ``lo`` to ``hi`` (``open_*``: that end excluded);
    ``what`` says so in the message."""

    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            v = math.nan
        above = v > lo if open_lo else v >= lo
        below = v < hi if open_hi else v <= hi
        if not (above and below):
            raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
        return v

    return parse


positive = number_in(0.0, 1e12, "a positive number", open_lo=True)
length = number_in(0.0, 1e4, "a length from 0 to 10,000 m")
lux = number_in(0.0, 2e5, "from 0 to 200,000 lux", open_lo=True)
fraction = number_in(0.0, 1.0, "a number from 0 to below 1", open_hi=True)
angle = number_in(-360.0, 360.0, "an angle from -360 to 360 degrees")


def hours(text: str) -> tuple[float, float]:
    """``START-END`` hours of the day, 0 <= START < END <= 24."""
    start, sep, end = text.partition("-")
    try:
        a, b = float(start), float(end)
        if not sep or not 0 <= a < b <= 24:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected START-END hours with 0 <= START < END <= 24 (e.g. 8-18), got {text!r}"
        ) from None
    return a, b


def group_transmittance(text: str) -> tuple[str, float]:
    """``GROUP=TRANSMITTANCE`` -> (group, 0-1)."""
    group, sep, value = text.partition("=")
    try:
        t = float(value)
        if not sep or not group or not 0 <= t <= 1:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected GROUP=TRANSMITTANCE with a transmittance from 0 to 1, got {text!r}"
        ) from None
    return group, t


def scheduler(text: str) -> str:
    """A Dask scheduler address ``tcp://HOST:PORT`` (checked, not connected)."""
    from lightinv_core.operator.distributed import check_scheduler

    try:
        return check_scheduler(text)
    except LightInvError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
