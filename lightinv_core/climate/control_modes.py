"""How a daylight-linked control group sets its luminaires from its sensor: one
``ControlModeSpec`` per mode, in one registry.

A mode turns the sensor's daylight (lux, the mean over its points) into the group's
level (0-1) each occupied hour, given its own luminaires' light on the sensor at full
output (lux), the group's target (lux) and its lowest dimming level:

- ``dimming`` (the default): continuous, ``climate.metrics.dimming_level``: the level
  that tops the daylight up to the target, between the lowest level and 1;
- ``switching`` (on/off): off (0) in the hours the daylight alone meets the target
  (daylight >= target), else full output (1); the lowest level does not apply. With a
  dead band ``band`` (a fraction of the target, as a switching photocell has to keep
  from cycling) it switches off once the daylight reaches target x (1 + band) and back
  on once it falls below the target; in between it keeps the previous hour's state, so
  its hours are scanned in order, each day starting on (the luminaires come on with the
  occupancy; ``switching_banded``). A band of 0 is the plain rule, hour by hour.

Each spec also sums its levels over a year of exterior illuminance sorted once (the
optimiser's O(log hours) path: the daylight is ``b0 x s`` with ``s`` sorted and its
prefix sums ``S``), so a mode registered later is as fast as the built-in ones. A
dead band makes the level depend on the hour before, so a banded year has no sorted
path: ``mode_levels`` scans it in order (``daylight_year.level_sum`` then goes hour by
hour; dimming keeps its sorted sum).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.metrics import dimming_level
from lightinv_core.errors import LightInvError

DIMMING = "dimming"
"""The default mode: continuous dimming to the target."""
SWITCHING = "switching"
"""On/off: off when the daylight alone meets the target."""


@dataclass(frozen=True)
class ControlModeSpec:
    """A control mode: ``name`` (the project file's), ``label`` for people,
    ``levels(daylight, full, target, min_level) -> levels`` (arrays broadcast; lux,
    lux at full output (> 0), lux, 0-1) and ``sorted_sum(s, S, b0, full, target,
    min_level) -> (m,)``: the levels summed over the hours whose exterior lux is ``s``
    (T,) sorted with prefix sums ``S`` (T + 1,), the daylight being ``b0`` (m,) x s."""

    name: str
    label: str
    levels: Callable[..., np.ndarray]
    sorted_sum: Callable[..., np.ndarray]
    banded: Callable[..., np.ndarray] | None = None
    """``banded(daylight (..., T), full, target, min_level, band, starts (T,)) -> levels``:
    the mode with a dead band ``band`` (fraction of the target) over hours in order,
    each day beginning where ``starts`` is True; None: the mode takes no dead band."""


def _dimming_sorted_sum(s, S, b0, full, target: float, min_level: float) -> np.ndarray:
    """Continuous dimming summed over a sorted year (level 1 while b0 E <= target -
    full, the lowest level once b0 E >= target - min_level full, linear between)."""
    T = len(s)
    b0 = np.asarray(b0, dtype=float)
    A = np.maximum(np.asarray(full, dtype=float), 1e-9)
    flat = b0 <= 0
    safe = np.where(flat, 1.0, b0)
    e1 = np.where(flat, np.inf, (target - A) / safe)
    e2 = np.where(flat, np.inf, (target - min_level * A) / safe)
    i1 = np.searchsorted(s, e1, side="right")
    i2 = np.maximum(np.searchsorted(s, e2, side="left"), i1)
    middle = (target * (i2 - i1) - b0 * (S[i2] - S[i1])) / A
    total = i1 + middle + min_level * (T - i2)
    # Without daylight the level is one constant all year.
    const = np.clip(target / A, min_level, 1.0) * T
    return np.where(flat, const, total)


def switching_level(daylight, full, target: float, min_level: float = 0.0):
    """On/off: 0 where ``daylight`` (lux) >= ``target`` (lux), else 1 (``full`` and
    ``min_level`` do not matter; kept for the modes' one signature)."""
    day = np.asarray(daylight, dtype=float)
    return np.broadcast_to(np.where(day >= target, 0.0, 1.0), np.broadcast(day, full).shape)


def _switching_sorted_sum(s, S, b0, full, target: float, min_level: float) -> np.ndarray:
    """Hours on over a sorted year: those with b0 E < target (all of them without
    daylight, unless the target is 0)."""
    T = len(s)
    b0 = np.asarray(b0, dtype=float)
    safe = np.where(b0 > 0, b0, 1.0)
    on = np.searchsorted(s, target / safe, side="left")
    dark = float(T) if target > 0 else 0.0
    return np.where(b0 > 0, on.astype(float), dark) * np.ones(np.shape(full))


def switching_banded(daylight, full, target: float, min_level: float, band: float, starts=None):
    """On/off with a dead band: (..., T) levels over hours in order (the last axis).
    Off (0) from the hour the daylight (lux) reaches ``target`` x (1 + ``band``), on
    (1) from the hour it falls below ``target`` (lux); between the two the previous
    hour's state holds. Each day (``starts`` (T,) True at its first hour; None: one day)
    starts on. ``full`` and ``min_level`` do not matter (the modes' one signature)."""
    day = np.atleast_1d(np.asarray(daylight, dtype=float))
    T = day.shape[-1]
    t = np.arange(T)
    first = np.zeros(T, bool) if starts is None else np.array(starts, dtype=bool)
    first[:1] = True
    off = day >= target * (1.0 + band)
    decided = off | (day < target)
    # The last hour up to each hour where the daylight left the band, and whether it
    # fell in today: without one the day's first state (on) holds.
    last = np.maximum.accumulate(np.where(decided, t, -1), axis=-1)
    today = np.maximum.accumulate(np.where(first, t, 0))
    was_off = np.take_along_axis(off, np.maximum(last, 0), axis=-1) & (last >= today)
    level = np.where(was_off, 0.0, 1.0)
    return np.broadcast_to(level, np.broadcast(level, full).shape)


def mode_levels(
    mode: ControlModeSpec,
    daylight,
    full,
    target: float,
    min_level: float,
    band: float = 0.0,
    starts=None,
) -> np.ndarray:
    """``mode``'s levels (0-1) for ``daylight`` (..., T) lux over hours in order: with a
    dead band ``band`` > 0 (fraction of the ``target``) its ``banded`` rule, each day
    beginning where ``starts`` (T,) is True; else hour by hour (``levels``)."""
    if band > 0:
        if mode.banded is None:
            raise LightInvError(f"control mode {mode.name!r} takes no dead band")
        return mode.banded(daylight, full, target, min_level, band, starts)
    return mode.levels(daylight, full, target, min_level)


def control_text(mode: str, target_lux: float, dead_band: float = 0.0) -> str:
    """A group's control for people: ``"switching to 300 lux"``, with a dead band
    ``"switching to 300 lux, off from 345 lux"`` (the CLI, the report, the window)."""
    text = f"{mode} to {target_lux:,.0f} lux"
    if dead_band > 0:
        text += f", off from {target_lux * (1.0 + dead_band):,.0f} lux"
    return text


def day_starts(midpoints) -> np.ndarray:
    """(T,) True at each hour whose date differs from the hour before (the first
    included): ``midpoints`` the middles of the hours in order (a pandas
    ``DatetimeIndex``, local time), e.g. a year's occupied hours."""
    stamps = np.asarray(midpoints, dtype="datetime64[ns]").astype("datetime64[D]")
    out = np.ones(len(stamps), bool)
    out[1:] = stamps[1:] != stamps[:-1]
    return out


_BUILT_IN = (
    ControlModeSpec(DIMMING, "dimming (continuous)", dimming_level, _dimming_sorted_sum),
    ControlModeSpec(
        SWITCHING,
        "switching (on/off)",
        switching_level,
        _switching_sorted_sum,
        switching_banded,
    ),
)
_MODES: dict[str, ControlModeSpec] = {m.name: m for m in _BUILT_IN}


def register_control_mode(spec: ControlModeSpec) -> None:
    """Add a control mode (a built-in one cannot be replaced)."""
    if spec.name in {m.name for m in _BUILT_IN}:
        raise LightInvError(f"control mode {spec.name!r} is built in")
    _MODES[spec.name] = spec


def unregister_control_mode(name: str) -> None:
    """Remove a registered control mode (the built-in ones stay)."""
    if name not in {m.name for m in _BUILT_IN}:
        _MODES.pop(name, None)


def control_mode_names() -> tuple[str, ...]:
    """The modes a control group may take, the default first."""
    return tuple(_MODES)


def control_mode(name: str) -> ControlModeSpec:
    """The spec of mode ``name`` (LightInvError naming the modes when unknown)."""
    try:
        return _MODES[name]
    except KeyError:
        raise LightInvError(
            f"unknown control mode {name!r}; the modes are {list(_MODES)}"
        ) from None
