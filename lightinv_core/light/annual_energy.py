"""A layout's daylight-linked dimming over the weather year: its annual energy (kWh),
LENI (kWh/m² a) and monthly energy, from the light at the control plane's points
(``light.daylight.ScenarioLight``) and the rules of ``climate.metrics``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.metrics import lighting_kwh
from lightinv_core.light.daylight_year import dimming_levels


@dataclass(frozen=True)
class AnnualEnergy:
    """Daylight-linked dimming of a layout over the weather year: ``energy_kwh`` (a
    year, standby included), ``leni`` (kWh/m² a over ``floor_m2``), ``full_kwh`` (the
    same hours at full output), ``monthly_kwh`` (12,) and the mean dimming level."""

    energy_kwh: float
    leni: float
    full_kwh: float
    monthly_kwh: tuple[float, ...]
    mean_level: float
    floor_m2: float
    groups: tuple = ()  # ``light.control_groups.GroupEnergy`` each, with control groups


def annual_energy(light, grid_idx, installed_w: float, floor_m2: float) -> AnnualEnergy:
    """Dimming energy of the first layout of ``light`` controlled on the work-plane points
    ``grid_idx`` (their mean): see ``climate.metrics`` for the rules."""
    d = light.daylight
    y = light.year()
    full = float(light.electric[grid_idx, 0].mean())
    # Without skylights there are no sky groups: b is empty and the daylight zero.
    b = light.sky[:, grid_idx, 0].mean(axis=1)
    clear = light.clear_hours(grid_idx)
    fixed = None if clear is None else clear.mean(axis=0)
    levels = dimming_levels(y, b, full, d.target_lux, d.min_level, fixed)
    hours_year = y.every.shape[1]
    energy = lighting_kwh(installed_w, levels.sum(), d.standby_w, hours_year)
    full_kwh = lighting_kwh(installed_w, y.hours, d.standby_w, hours_year)
    per_month = np.bincount(np.asarray(y.midpoints.month) - 1, minlength=12)
    monthly = [
        float(
            lighting_kwh(
                installed_w, levels[y.months == mth].sum(), d.standby_w, per_month[mth - 1]
            )
        )
        for mth in range(1, 13)
    ]
    floor = max(float(floor_m2), 1e-9)
    return AnnualEnergy(
        float(energy),
        float(energy / floor),
        float(full_kwh),
        tuple(monthly),
        float(levels.mean()),
        float(floor_m2),
    )
