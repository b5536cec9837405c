"""Several daylight-linked control groups, each dimmed by its own sensor region.

Each luminaire belongs to a control group (the schedule's ``control`` column; one
group for all by default). A group's sensor reads the work-plane points inside its
region (a rectangle in plan, ``--sensor GROUP=X0,Y0,X1,Y1``; the whole grid when none
is given). Each occupied hour the group's control mode (``climate.control_modes``,
``dimming`` unless it names another) sets its level from the region's mean daylight, its
target (its own, else the settings') and the group's own luminaires' light on that
region at full output (the light of the other groups is not counted: each sensor is
calibrated with its own group alone, as a commissioning engineer does at night):
``dimming`` tops the daylight up to the target by the one rule of ``climate.metrics``;
``switching`` is off while the daylight alone meets the target, else full (with a dead
band: off from target x (1 + band), on again below the target, the hours of each day
in order). Outside the
schedule the luminaires are off; standby is counted once, in the total.

Energy (kWh a year) per group and in total; LENI per group is the group's energy over
the whole floor area, so the groups' LENIs add up to the total's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.control_modes import DIMMING, control_mode, mode_levels
from lightinv_core.climate.metrics import lighting_kwh
from lightinv_core.errors import LightInvError
from lightinv_core.light.control_groups import sensor_mask

__all__ = ["DEFAULT_GROUP", "GroupDimming", "group_dimming", "sensor_mask"]

DEFAULT_GROUP = "all"
"""The control group of luminaires whose schedule names none."""


@dataclass(frozen=True)
class GroupDimming:
    """One control group's year: its ``luminaires``, ``installed_w`` (W at the set
    dimming), ``sensor_points`` read, ``electric_lux`` (its own light on the region at
    full output), ``mean_level`` over the occupied hours, ``energy_kwh``, ``leni``
    (kWh/m² a over the whole floor), its control ``mode`` and ``target_lux``."""

    name: str
    luminaires: int
    installed_w: float
    sensor_points: int
    electric_lux: float
    mean_level: float
    energy_kwh: float
    leni: float
    mode: str = DIMMING
    target_lux: float = 500.0
    dead_band: float = 0.0

    def as_dict(self) -> dict:
        """JSON-ready."""
        return dict(self.__dict__)


def group_dimming(
    daylight: np.ndarray,
    points: np.ndarray,
    electric: dict[str, np.ndarray],
    watts: dict[str, float],
    counts: dict[str, int],
    sensors: dict[str, tuple[float, float, float, float]],
    settings,
    floor_m2: float,
    hours_per_year: float,
    modes: dict[str, str] | None = None,
    targets: dict[str, float] | None = None,
    bands: dict[str, float] | None = None,
    starts: np.ndarray | None = None,
) -> tuple[list[GroupDimming], dict]:
    """Each group's year and the total: ``daylight`` (q, T) lux per work-plane point
    and occupied hour, ``electric[g]`` (q,) group g's lux at full output, ``watts[g]``
    its power (W), ``counts[g]`` its luminaires, ``sensors[g]`` its region (or the
    whole grid), ``settings`` a ``Daylight`` (target lux, minimum level, standby W),
    ``modes[g]`` its control mode (default dimming), ``targets[g]`` its own target
    (lux; default the settings'), ``bands[g]`` its dead band (fraction of the target;
    default 0) and ``starts`` (T,) True at each hour that begins a day (the hours in
    order; None: one day)."""
    modes, targets, bands = dict(modes or {}), dict(targets or {}), dict(bands or {})
    given_all = (("--sensor", sensors), ("a control mode", modes), ("a target", targets))
    for what, given in (*given_all, ("a dead band", bands)):
        unknown = sorted(set(given) - set(electric))
        if unknown:
            raise LightInvError(
                f"{what} names control group(s) {unknown} that no luminaire belongs to; "
                f"the groups are {sorted(electric)}"
            )
    if not floor_m2 > 0:
        raise LightInvError("LENI needs a floor area above 0 m²")
    groups = []
    for name in sorted(electric):
        mask = sensor_mask(points, sensors.get(name))
        if not mask.any():
            raise LightInvError(
                f"control group {name!r}: its sensor region holds no work-plane point; "
                "draw it over the work plane"
            )
        full = float(electric[name][mask].mean())
        if not full > 0:
            raise LightInvError(
                f"control group {name!r}: its luminaires give no light on its sensor region"
            )
        day = daylight[mask].mean(axis=0)
        mode = control_mode(modes.get(name, DIMMING))
        target = float(targets.get(name, settings.target_lux))
        band = float(bands.get(name, 0.0))
        try:
            levels = mode_levels(mode, day, full, target, settings.min_level, band, starts)
        except LightInvError as e:
            raise LightInvError(f"control group {name!r}: {e}") from None
        kwh = float(lighting_kwh(watts[name], levels.sum(), 0.0, hours_per_year))
        groups.append(
            GroupDimming(
                name,
                counts[name],
                float(watts[name]),
                int(mask.sum()),
                full,
                float(levels.mean()),
                kwh,
                kwh / floor_m2,
                mode.name,
                target,
                band,
            )
        )
    standby = float(lighting_kwh(0.0, 0.0, settings.standby_w, hours_per_year))
    energy = sum(g.energy_kwh for g in groups) + standby
    total = {"energy_kwh": energy, "leni_kwh_m2": energy / floor_m2, "standby_kwh": standby}
    return groups, total
