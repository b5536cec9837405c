"""Annual daylight metrics and daylight-linked dimming, from hourly illuminance.

All inputs are illuminance (lux) per point and hour (q, h) over the *occupied* hours
only. Definitions (stated, as codes and tools differ in details):

- DA300 (daylight autonomy): per point, the share of occupied hours with daylight
  >= 300 lux; sDA300/50% (spatial DA, as IES LM-83 / LEED): the share of points whose
  DA300 is at least 50%;
- UDI (useful daylight illuminance, Mardaljevic and Nabil): per point, the shares of
  occupied hours below 100 lux (UDI-n, too dark), 100-300 (UDI-s, useful with
  supplementary light), 300-3000 (UDI-a, autonomous) and above 3000 (UDI-x, likely
  glare or overheating); UDI 100-3000 = UDI-s + UDI-a;
- daylight-linked dimming (continuous): one control group of luminaires dims each
  occupied hour to the level that keeps the grid's mean illuminance at the target,
  daylight plus electric light, between a minimum level and full output; it is off
  outside the occupancy schedule; power is proportional to the level; a standby
  power is drawn all year. Annual energy (kWh) and LENI = energy / floor area
  (kWh/m² a), a simplified EN 15193-1 with occupancy factor 1 in the schedule and 0
  outside it and constant-illuminance factor 1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import LightInvError

UDI_BANDS = (100.0, 300.0, 3000.0)
DA_THRESHOLD = 300.0


@dataclass(frozen=True)
class DaylightMetrics:
    """Per point: ``da`` (DA300) and ``udi`` (q, 4): shares of occupied hours in the
    bands <100, 100-300, 300-3000, >3000 lux; ``sda`` the share of points with DA300
    >= 50%."""

    da: np.ndarray
    udi: np.ndarray
    sda: float

    def summary(self) -> dict[str, float]:
        """Means over the points, as fractions (0-1)."""
        u = self.udi.mean(axis=0)
        return {
            "da300_mean": float(self.da.mean()),
            "sda300_50": self.sda,
            "udi_n": float(u[0]),
            "udi_s": float(u[1]),
            "udi_a": float(u[2]),
            "udi_x": float(u[3]),
            "udi_100_3000": float(u[1] + u[2]),
        }


def daylight_metrics(lux: np.ndarray) -> DaylightMetrics:
    """DA300, UDI bands and sDA300/50% of hourly illuminance ``lux`` (q, h)."""
    lux = np.asarray(lux, dtype=float)
    if lux.ndim != 2 or lux.shape[1] == 0:
        raise LightInvError("annual metrics need at least one occupied hour")
    da = (lux >= DA_THRESHOLD).mean(axis=1)
    lo, mid, hi = UDI_BANDS
    udi = np.stack(
        [
            (lux < lo).mean(axis=1),
            ((lux >= lo) & (lux < mid)).mean(axis=1),
            ((lux >= mid) & (lux <= hi)).mean(axis=1),
            (lux > hi).mean(axis=1),
        ],
        axis=1,
    )
    return DaylightMetrics(da, udi, float((da >= 0.5).mean()))


def dimming_level(daylight, electric_full, target_lux: float, min_level: float):
    """The one dimming rule (continuous, daylight-linked): the level (0-1) that tops
    ``daylight`` (lux) up to ``target_lux`` with luminaires giving ``electric_full``
    (lux, > 0) at full output, between ``min_level`` and 1. Arrays broadcast."""
    return np.clip((target_lux - daylight) / electric_full, min_level, 1.0)


def lighting_kwh(watts, level_hours, standby_w: float, standby_hours: float):
    """Energy (kWh) of luminaires drawing ``watts`` (W) at full output for
    ``level_hours`` (their dimming level summed over the hours they are on), plus
    ``standby_w`` (W) drawn for ``standby_hours``: power proportional to the level."""
    return (watts * level_hours + standby_w * standby_hours) / 1000.0


@dataclass(frozen=True)
class Dimming:
    """Daylight-linked dimming over a year: the level (0-1) per occupied hour, the
    annual lighting energy (kWh) and LENI (kWh/m² a)."""

    levels: np.ndarray
    energy_kwh: float
    leni: float
    full_power_kwh: float


def dimming_energy(
    daylight_mean: np.ndarray,
    electric_mean: float,
    target_lux: float,
    installed_w: float,
    floor_area_m2: float,
    min_level: float = 0.1,
    standby_w: float = 0.0,
    hours_per_year: float = 8760.0,
) -> Dimming:
    """Energy of one dimmed control group (see the module): ``daylight_mean`` is the
    grid's mean daylight per occupied hour (lux), ``electric_mean`` the grid's mean
    from the luminaires at full output (lux)."""
    if not electric_mean > 0:
        raise LightInvError("the luminaires give no light on the work plane: nothing to dim")
    if not 0 <= min_level <= 1:
        raise LightInvError(f"minimum dimming level must be from 0 to 1, got {min_level}")
    if not floor_area_m2 > 0:
        raise LightInvError("LENI needs a floor area above 0 m²")
    levels = dimming_level(
        np.asarray(daylight_mean, dtype=float), electric_mean, target_lux, min_level
    )
    energy = lighting_kwh(installed_w, levels.sum(), standby_w, hours_per_year)
    full = lighting_kwh(installed_w, len(levels), standby_w, hours_per_year)
    return Dimming(levels, float(energy), float(energy / floor_area_m2), float(full))
