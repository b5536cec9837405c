"""The quantities a lighting intention bounds: one ``QuantitySpec`` each, in one registry.

A spec says what the views and the light model ask of a quantity: its names and unit,
the values it can take and the bounds the window offers, whether it is a daylight metric
(then the scenario it is measured in and how it is read from the light of the
scenarios) or derived from illuminance (then how, and whether it needs the receivers'
reflectance). The light model, the report, the design checks and the window look
quantities up here (``quantity_spec``); a new quantity is one ``register_quantity``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from lightinv_core.kinds import MAX_LUX, Bound, Quantity, Scenario


def _reflected(lux, rho):
    """C = rho x H at receivers of reflectance rho (p,), lux (p,) or (p, m)."""
    return lux * (rho[:, None] if lux.ndim == 2 else rho)


@dataclass(frozen=True)
class HourBand:
    """The rule of an annual daylight metric, over the occupied hours of the weather
    year: an hour counts at a point when ``lo`` <= its daylight <= ``hi`` (lux); the
    point's value is the share of hours that count (0-1), or, with ``point_share``, 1
    when at least that share counts and 0 otherwise (so the metric's average over a
    grid is the share of its area: sDA300/50%). ``direct_sun``: the rule reads the
    direct sun through clear glazing alone, blinds open (ASE); ``above``: an hour counts
    when its light exceeds ``lo`` (not equals); ``point_hours``: a point's value is 1
    when more than that many hours count (ASE1000,250: more than 250 hours above 1000 lux).

    The light model evaluates a band from its sky-group coefficients without the
    hour-by-hour illuminance (``light.daylight.ScenarioLight.band``); ``of_hours`` is
    the hour-by-hour definition the tests compare it with.
    """

    lo: float
    hi: float = math.inf
    point_share: float | None = None
    direct_sun: bool = False
    above: bool = False
    point_hours: int | None = None

    def of_hours(self, lux: np.ndarray) -> np.ndarray:
        """The metric per point from hourly daylight ``lux`` (q, h) lux: (q,)."""
        lux = np.asarray(lux, dtype=float)
        low = lux > self.lo if self.above else lux >= self.lo
        counted = (low & (lux <= self.hi)).sum(axis=1)
        if self.point_hours is not None:
            return (counted > self.point_hours).astype(float)
        hours = lux.shape[1]
        if self.point_share is None:
            return counted / max(hours, 1)
        need = math.ceil(self.point_share * hours - 1e-9)
        return (counted >= need).astype(float)


@dataclass(frozen=True)
class QuantitySpec:
    """One intention quantity.

    ``name``: its name in project files; ``noun`` ("reflected exitance") and ``label``
    (the window's list entry, with its unit); ``unit`` as messages and tables show it
    ("" for fractions); ``range_text``: its unit as the range error says it.
    ``low``..``high``: the values it can take (a bound outside can never be met);
    ``decimals`` and ``defaults`` (min, max, average, U0): the bounds the window offers;
    ``average_only``: only the average bound tells (sDA's 0/1 mark).
    ``metric``: the report's name of a daylight metric ("DA300"), None for a light
    quantity; ``scenario``: the scenario a daylight metric is always measured in (None:
    the intention's own, default ``design``); ``hours``: an annual daylight metric's
    rule over the weather year's hours (``HourBand``): the CLI's annual output, the
    report's daylight table and the window's daylight maps list every quantity that
    has one (``annual_metrics``); ``from_scenarios(light, idx)``: another daylight
    metric's values from a ``light.daylight.ScenarioLight`` at receivers idx.
    ``from_lux(lux, rho)``: a light quantity from illuminance (and the receivers'
    reflectance when ``needs_reflectance``: not on work-plane grid points).
    ``uniformity``: U0 = min / mean means something (the report shows it).
    ``average_bound``: the bound the window offers on the mean (``max_average`` for a
    quantity to keep low, ASE).
    ``at_observers``: measured at the design's observers, not at patches or grid points
    (an intention on it names ``observers`` and sets ``max`` only); ``from_glare(total,
    background)``: its value from the glare sum ``sum L² omega / p²`` (cd²/m⁴ sr) and
    the background luminance (cd/m²) at each eye, arrays broadcast like numpy;
    ``from_eyes(eyes, lit)``: its value from the daylight at the eyes over the year
    (``light.dgp_observers.EyeDaylight``) for a batch's light ``lit``, (observers, m).
    An observer quantity with neither is a figure of the fixed glazing (EN 17037
    sunlight exposure).
    """

    name: str
    noun: str
    label: str
    unit: str
    range_text: str
    low: float = 0.0
    high: float = MAX_LUX
    decimals: int = 1
    defaults: tuple[float, float, float, float] = (300.0, 1000.0, 500.0, 0.6)
    average_only: bool = False
    metric: str | None = None
    scenario: Scenario | None = None
    hours: HourBand | None = None
    from_scenarios: Callable[[Any, Any], Any] | None = None
    from_lux: Callable[[Any, Any], Any] | None = None
    needs_reflectance: bool = False
    uniformity: bool = True
    average_bound: Bound = Bound.AVERAGE
    at_observers: bool = False
    from_glare: Callable[[Any, Any], Any] | None = None
    plane: bool = False
    levels: tuple[tuple[str, float], ...] = ()
    point_maps: tuple[tuple[str, str, Callable[[Any, Any], Any]], ...] = ()
    from_eyes: Callable[[Any, Any], Any] | None = None

    @property
    def daylight(self) -> bool:
        """A daylight metric (measured in its own scenario), not a light quantity."""
        return self.scenario is not None

    @property
    def default_scenario(self) -> Scenario:
        """The scenario an intention on it is judged in unless it names one."""
        return self.scenario or Scenario.DESIGN


_QUANTITIES: dict[str, QuantitySpec] = {}


def register_quantity(spec: QuantitySpec) -> QuantitySpec:
    """Add a quantity (ValueError when its name is taken); returns the spec."""
    if spec.name in _QUANTITIES:
        raise ValueError(f"quantity {spec.name!r} is already registered")
    _QUANTITIES[spec.name] = spec
    return spec


def unregister_quantity(name: str) -> None:
    """Remove a quantity added by ``register_quantity`` (the built-in ones stay)."""
    if name in tuple(Quantity):
        raise ValueError(f"quantity {name!r} is built in")
    _QUANTITIES.pop(name, None)


def quantity_spec(name: str) -> QuantitySpec:
    """The spec of a quantity (KeyError naming the known ones when unknown)."""
    try:
        return _QUANTITIES[str(name)]
    except KeyError:
        raise KeyError(f"quantity {name!r} is not one of {quantity_names()}") from None


def quantity_specs() -> Iterator[QuantitySpec]:
    """Every quantity, the built-in ones first in ``Quantity`` order."""
    return iter(tuple(_QUANTITIES.values()))


def quantity_names() -> tuple[str, ...]:
    """Every quantity's name, in registry order."""
    return tuple(str(q) for q in _QUANTITIES)


def is_quantity(name: object) -> bool:
    """Whether ``name`` names a registered quantity."""
    return isinstance(name, str) and name in _QUANTITIES


def annual_metrics() -> tuple[QuantitySpec, ...]:
    """The annual daylight metrics (quantities with an ``HourBand``), in registry order."""
    return tuple(q for q in _QUANTITIES.values() if q.hours is not None)


def level_name(spec: QuantitySpec, value: float) -> str:
    """The highest of ``spec.levels`` that ``value`` reaches ("none" below the first)."""
    name = "none"
    for level, need in spec.levels:
        if value >= need - 1e-9:
            name = level
    return name


def quantity_kind(name: str) -> Quantity | str:
    """The ``Quantity`` member of a built-in name, the name itself for a registered one."""
    return Quantity(name) if name in tuple(Quantity) else str(name)


UGR_FLOOR = 0.0
"""The least UGR a layout reads: a luminaire out of view (a glare sum of 0) gives -inf,
read as this (CIE 117's scale runs from 10, no glare, to 30)."""


def _ugr(total, background):
    """CIE 117: UGR = 8 log10(0.25 / Lb * total), floored at ``UGR_FLOOR``."""
    t = np.asarray(total, dtype=float)
    lb = np.maximum(np.asarray(background, dtype=float), 1e-12)
    with np.errstate(divide="ignore"):
        u = 8.0 * np.log10(0.25 * t / lb)
    return np.maximum(u, UGR_FLOOR)


_FRACTION = (0.0, 1.0)
for _spec in (
    QuantitySpec(
        Quantity.LUX,
        "illuminance",
        "illuminance (lux)",
        "lux",
        "illuminance, lux",
        from_lux=lambda lux, rho: lux,
    ),
    QuantitySpec(
        Quantity.C,
        "reflected exitance",
        "reflected exitance C (lm/m²)",
        "lm/m²",
        "reflected exitance, lm/m²",
        from_lux=_reflected,
        needs_reflectance=True,
    ),
    QuantitySpec(
        Quantity.DF,
        "daylight factor",
        "daylight factor DF (%)",
        "%",
        "daylight factor, %",
        0.0,
        100.0,
        2,
        (1.0, 10.0, 2.0, 0.3),
        metric="DF",
        scenario=Scenario.OVERCAST,
        from_scenarios=lambda light, idx: 100.0 * light.overcast_daylight(idx),
    ),
    QuantitySpec(
        Quantity.DA,
        "daylight autonomy",
        "daylight autonomy DA300 (share of occupied hours, 0-1)",
        "",
        "DA300, a fraction of the occupied hours",
        *_FRACTION,
        3,
        (0.3, 1.0, 0.5, 0.3),
        metric="DA300",
        scenario=Scenario.ANNUAL,
        hours=HourBand(300.0),
        uniformity=False,
    ),
    QuantitySpec(
        Quantity.UDI,
        "useful daylight",
        "useful daylight UDI 100-3000 lux (share of hours, 0-1)",
        "",
        "UDI 100-3000, a fraction of the occupied hours",
        *_FRACTION,
        3,
        (0.3, 1.0, 0.5, 0.3),
        metric="UDI 100-3000",
        scenario=Scenario.ANNUAL,
        hours=HourBand(100.0, 3000.0),
        uniformity=False,
    ),
    QuantitySpec(
        Quantity.SDA,
        "spatial daylight autonomy",
        "sDA300/50%: the average is the share of the area",
        "",
        "1 or 0 per point, its average a fraction",
        *_FRACTION,
        3,
        (0.0, 1.0, 0.55, 0.3),
        average_only=True,
        metric="sDA300/50%",
        scenario=Scenario.ANNUAL,
        hours=HourBand(300.0, point_share=0.5),
        uniformity=False,
    ),
    QuantitySpec(
        Quantity.ASE,
        "annual sunlight exposure",
        "ASE1000,250: the average is the share of the area",
        "",
        "1 or 0 per point, its average a fraction",
        *_FRACTION,
        3,
        (0.0, 1.0, 0.1, 0.3),
        average_only=True,
        average_bound=Bound.MAX_AVERAGE,
        metric="ASE1000,250",
        scenario=Scenario.ANNUAL,
        hours=HourBand(1000.0, direct_sun=True, above=True, point_hours=250),
        uniformity=False,
    ),
    QuantitySpec(
        Quantity.UGR,
        "unified glare rating",
        "unified glare rating UGR (CIE 117) at observers",
        "",
        "UGR, CIE 117's scale",
        0.0,
        40.0,
        1,
        (10.0, 19.0, 16.0, 0.0),
        metric="UGR",
        uniformity=False,
        at_observers=True,
        from_glare=_ugr,
    ),
    QuantitySpec(
        Quantity.EN17037,
        "EN 17037 daylight provision",
        "EN 17037 daylight provision (level: 1 minimum, 2 medium, 3 high)",
        "",
        "a level score, 0 (none) to 3 (high)",
        0.0,
        3.0,
        2,
        (1.0, 3.0, 1.0, 0.0),
        metric="EN 17037 provision",
        scenario=Scenario.ANNUAL,
        from_scenarios=lambda light, idx: light.en17037_score(idx),
        uniformity=False,
        plane=True,
        levels=(("minimum", 1.0), ("medium", 2.0), ("high", 3.0)),
        point_maps=tuple(
            (
                f"en17037_{lux:.0f}",
                f"EN 17037: share of the daylight hours with {lux:.0f} lux or more "
                f"(E_T, {level} level)",
                lambda light, idx, lux=lux: light.en17037_reach(idx, lux),
            )
            for level, lux in (("minimum", 300.0), ("medium", 500.0), ("high", 750.0))
        ),
    ),
    QuantitySpec(
        Quantity.SUNLIGHT,
        "EN 17037 sunlight exposure",
        "EN 17037 sunlight exposure at observers (hours of sun on the day)",
        "h",
        "hours of sun on the day",
        0.0,
        24.0,
        2,
        (1.5, 24.0, 1.5, 0.0),
        metric="EN 17037 sunlight",
        scenario=Scenario.ANNUAL,
        uniformity=False,
        at_observers=True,
        levels=(("minimum", 1.5), ("medium", 3.0), ("high", 4.0)),
    ),
    QuantitySpec(
        Quantity.CDA,
        "continuous daylight autonomy",
        "continuous daylight autonomy cDA300 (0-1)",
        "",
        "cDA300, a fraction",
        *_FRACTION,
        3,
        (0.3, 1.0, 0.5, 0.3),
        metric="cDA300",
        scenario=Scenario.ANNUAL,
        from_scenarios=lambda light, idx: light.cda(idx),
        uniformity=False,
    ),
    QuantitySpec(
        Quantity.DGP,
        "simplified DGP exceedance",
        "simplified DGP at observers: share of occupied hours above the limit (0-1)",
        "",
        "a fraction of the occupied hours",
        *_FRACTION,
        3,
        (0.0, 0.05, 0.05, 0.0),
        metric="DGPs exceedance",
        scenario=Scenario.ANNUAL,
        uniformity=False,
        at_observers=True,
        from_eyes=lambda eyes, lit: eyes.values_of(lit),
    ),
):
    register_quantity(_spec)
