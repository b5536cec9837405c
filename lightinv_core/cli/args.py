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
altitude = number_in(0.0, 90.0, "an altitude from 0 to 90 degrees")


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


def group_transmittance(text: str) -> tuple[str, float, str]:
    """``GROUP=TRANSMITTANCE[:KIND]`` -> (group, 0-1, kind): the kind of glazing
    (``kinds.GlazingKind``: diffusing, the default, or clear)."""
    from lightinv_core.kinds import GlazingKind

    group, sep, value = text.partition("=")
    value, _, kind = value.partition(":")
    kinds = [str(k) for k in GlazingKind]
    try:
        t = float(value)
        if not sep or not group or not 0 <= t <= 1 or (kind and kind not in kinds):
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected GROUP=TRANSMITTANCE[:KIND] with a transmittance from 0 to 1 and a kind "
            f"{' or '.join(kinds)}, got {text!r}"
        ) from None
    return group, t, kind or str(GlazingKind.DIFFUSING)


def sun_position(text: str) -> tuple[float, float]:
    """``ALTITUDE,AZIMUTH`` degrees (compass azimuth, clockwise from north)."""
    alt, sep, az = text.partition(",")
    try:
        a, z = float(alt), float(az)
        if not sep or not 0 < a <= 90 or not -360 <= z <= 360:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected ALTITUDE,AZIMUTH in degrees (altitude above 0 up to 90, azimuth "
            f"clockwise from north), got {text!r}"
        ) from None
    return a, z % 360.0


def vector6(text: str) -> tuple[float, ...]:
    """``X,Y,Z,DX,DY,DZ``: a point (m) and a direction."""
    try:
        v = tuple(float(x) for x in text.split(","))
        if len(v) != 6 or not all(map(math.isfinite, v)) or not any(v[3:]):
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected X,Y,Z,DX,DY,DZ (a point in m and a view direction), got {text!r}"
        ) from None
    return v


def group_rect(text: str) -> tuple[str, tuple[float, float, float, float]]:
    """``GROUP=X0,Y0,X1,Y1``: a control group's sensor rectangle in plan (m)."""
    group, sep, value = text.partition("=")
    try:
        v = tuple(float(x) for x in value.split(","))
        if not sep or not group or len(v) != 4 or not all(map(math.isfinite, v)):
            raise ValueError
        if v[0] == v[2] or v[1] == v[3]:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected GROUP=X0,Y0,X1,Y1 (a rectangle in plan, m, of non-zero size), got {text!r}"
        ) from None
    return group, v


def group_control(text: str) -> tuple[str, str, float | None, float]:
    """``GROUP=MODE``, ``GROUP=MODE:LUX`` or ``GROUP=MODE:LUX:BAND``: a control group's
    mode (a registered control mode: dimming, switching), its own target (lux; default
    ``--target-lux``) and its dead band (a fraction of the target, 0-2; default 0)."""
    from lightinv_core.climate.control_modes import control_mode, control_mode_names

    group, sep, value = text.partition("=")
    mode, colon, rest = value.partition(":")
    lux, colon2, band_text = rest.partition(":")
    names = control_mode_names()
    try:
        target = float(lux) if colon else None
        band = float(band_text) if colon2 else 0.0
        if not sep or not group or mode not in names:
            raise ValueError
        if target is not None and not (math.isfinite(target) and target > 0):
            raise ValueError
        if not 0.0 <= band <= 2.0:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected GROUP=MODE, GROUP=MODE:LUX or GROUP=MODE:LUX:BAND (MODE one of "
            f"{', '.join(names)}, LUX a target above 0, BAND a dead band 0-2, a fraction "
            f"of the target), got {text!r}"
        ) from None
    if band > 0 and control_mode(mode).banded is None:
        raise argparse.ArgumentTypeError(
            f"a dead band applies to switching; mode {mode!r} takes none, got {text!r}"
        )
    return group, mode, target, band


def point3(text: str) -> tuple[float, float, float]:
    """``X,Y,Z`` metres."""
    try:
        v = tuple(float(x) for x in text.split(","))
        if len(v) != 3 or not all(map(math.isfinite, v)):
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected X,Y,Z in metres, got {text!r}") from None
    return v


def month_day(text: str) -> tuple[int, int]:
    """``MM-DD``: a day of the year."""
    m, sep, d = text.partition("-")
    try:
        month, day = int(m), int(d)
        if not sep:
            raise ValueError
        import datetime

        datetime.date(2001, month, day)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a date MM-DD, got {text!r}") from None
    return month, day


def hour_of_year(text: str) -> int:
    """An hour of the weather file, 0 to 8783 (0: the hour ending 01:00 on 1 January)."""
    try:
        h = int(text)
        if not 0 <= h < 8784:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected an hour of the weather file from 0 (the hour ending 01:00 on 1 "
            f"January) to 8759 (8783 in a leap year), got {text!r}"
        ) from None
    return h


def scheduler(text: str) -> str:
    """A Dask scheduler address ``tcp://HOST:PORT`` (checked, not connected)."""
    from lightinv_core.operator.distributed import check_scheduler

    try:
        return check_scheduler(text)
    except LightInvError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
