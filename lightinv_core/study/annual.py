"""Annual daylight on a work plane lit through glazing groups: the simulation's year.

The coefficients come from the reference solver (``transport.annual``: one solve per
orientation of the glazing); the year, its occupied hours and the statistics are the
optimiser's (``light.daylight_year``: sky groups, sorted exterior illuminance, counts by
``searchsorted``), and the dimming is ``climate.metrics.dimming_energy``. So the command
line, the window, the report and the optimiser measure DA300, UDI and sDA one way.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.metrics import (
    DA_THRESHOLD,
    UDI_BANDS,
    DaylightMetrics,
    Dimming,
    dimming_energy,
)
from lightinv_core.climate.sky import overcast_plane_illuminance
from lightinv_core.design.model import Daylight
from lightinv_core.light.daylight import SDA_SHARE
from lightinv_core.light.daylight_year import (
    DaylightYear,
    SkyGroups,
    band_values,
    daylight_year,
    hours_from,
    hours_within,
    reaches_share,
)
from lightinv_core.quantities import annual_metrics
from lightinv_core.transport.annual import Orientation


def glazing_groups(orients: list[Orientation], daylight: Daylight) -> SkyGroups:
    """The orientations of the glazing as the optimiser's sky groups: ``zones[g]`` the
    glazing groups facing way g (no zone columns: the glazing is no emitter zone)."""
    outward = np.array([o.outward for o in orients], dtype=float).reshape(-1, 3)
    over = (
        overcast_plane_illuminance(outward, 1.0, daylight.ground_reflectance)
        if len(outward)
        else np.zeros(0)
    )
    return SkyGroups(
        tuple(tuple(q.group for q in o.panes) for o in orients),
        outward,
        tuple(np.zeros(0, dtype=np.int64) for _ in orients),
        np.asarray(over, float),
    )


def occupied_metrics(year: DaylightYear, coefficients: np.ndarray) -> DaylightMetrics:
    """DA300, the four UDI bands and sDA300/50% over the occupied hours at receivers of
    daylight ``coefficients`` (q, G), counted as the optimiser counts them."""
    a = np.asarray(coefficients, dtype=float)
    T = year.hours
    lo, mid, hi = UDI_BANDS
    above_lo = hours_from(year, a, lo)
    above_mid = hours_from(year, a, mid)
    useful = hours_within(year, a, mid, hi)
    da = hours_from(year, a, DA_THRESHOLD) / T
    udi = np.stack([T - above_lo, above_lo - above_mid, useful, above_mid - useful], axis=1) / T
    sda = float(reaches_share(year, a, DA_THRESHOLD, SDA_SHARE).mean())
    return DaylightMetrics(da, udi, sda)


@dataclass(frozen=True)
class GridYear:
    """The year on a grid: the ``year`` (occupied hours, exterior lux per sky group),
    its ``groups``, the glazing ``orientations``, ``coefficients`` (q, G) lux per
    exterior lux, the ``metrics`` per point (DA300, the UDI bands, sDA), ``annual``: every
    annual daylight metric of the quantity registry per point, by name, and, with
    luminaires, the ``dimming`` of luminaires drawing ``installed_w`` (W) giving
    ``electric_em`` (lux) at full output over ``floor_m2``."""

    year: DaylightYear
    groups: SkyGroups
    orientations: list[Orientation]
    coefficients: np.ndarray
    metrics: DaylightMetrics
    annual: dict[str, np.ndarray]
    dimming: Dimming | None = None
    electric_em: float | None = None
    installed_w: float | None = None
    floor_m2: float | None = None

    @property
    def lux(self) -> np.ndarray:
        """(q, T) daylight per point and occupied hour (the oracle's view; large)."""
        return self.coefficients @ self.year.exterior


def grid_year(daylight: Daylight, orients: list[Orientation], coefficients: np.ndarray) -> GridYear:
    """The year of ``daylight``'s weather, orientation and schedule on a grid whose
    daylight ``coefficients`` (q, G) belong to the glazing ``orients``."""
    groups = glazing_groups(orients, daylight)
    year = daylight_year(groups, daylight)
    metrics = occupied_metrics(year, coefficients)
    annual = {str(q.name): band_values(year, coefficients, q.hours) for q in annual_metrics()}
    return GridYear(year, groups, orients, coefficients, metrics, annual)


def with_dimming(
    got: GridYear, electric: np.ndarray, installed_w: float, floor_m2: float, daylight: Daylight
) -> GridYear:
    """``got`` with the dimming energy of luminaires giving ``electric`` (q,) lux at full
    output and drawing ``installed_w`` (W) in all: the grid's mean daylight per occupied
    hour is topped up to ``daylight.target_lux`` between ``min_level`` and full output,
    ``standby_w`` drawn all year (``climate.metrics``)."""
    d = daylight
    em = float(np.mean(electric))
    daylight_mean = got.coefficients.mean(axis=0) @ got.year.exterior
    dim = dimming_energy(
        daylight_mean, em, d.target_lux, installed_w, floor_m2, d.min_level, d.standby_w
    )
    return GridYear(
        got.year,
        got.groups,
        got.orientations,
        got.coefficients,
        got.metrics,
        got.annual,
        dim,
        em,
        installed_w,
        floor_m2,
    )
