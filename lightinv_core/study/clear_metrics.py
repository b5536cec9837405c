"""The annual figures of a year through clear glazing (issue #30, docs/daylight.md).

Over the occupied hours, on the work plane:

- ASE1000,250 (IES LM-83): direct sun alone, blinds open;
- operable blinds per clear glazing group by LM-83's rule, then DA300, continuous DA,
  the UDI bands and sDA300/50% with the blinds as they would be (``sda300_50``) and,
  for comparison, with them always open (``sda300_50_open``);
- EN 17037 daylight provision over its daylight hours (blinds open, as the standard's
  calculation of the daylight available);
- EN 17037 sunlight exposure at a reference point on a chosen day;
- simplified DGP at view points (vertical eye illuminance, sun included, blinds as
  they would be) and the share of occupied hours above each glare class.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.climate.metrics import daylight_metrics


def blinds(year, occupied: np.ndarray | None = None) -> np.ndarray:
    """(G, T) whether each clear group's blinds are closed, every hour of the file (by
    the LM-83 rule on the ``occupied`` hours, default the schedule's; open outside)."""
    from lightinv_core.climate.sun_metrics import blinds_schedule

    if occupied is None:
        occupied = year.occupied
    closed = np.zeros((year.open.shape[0], year.open.shape[2]), bool)
    if occupied.any():
        # LM-83: the groups close in the fewest combination that leaves at most 2% of
        # the points in direct sun, judged on every group's sun together.
        closed[:, occupied] = blinds_schedule(year.direct_sun[:, :, occupied])
    return closed


def work_plane_metrics(year) -> tuple[dict, dict[str, np.ndarray]]:
    """(summary for JSON, per-point columns) of a ``ClearYear`` on a work plane."""
    from lightinv_core.climate.en17037 import daylight_hours, daylight_provision
    from lightinv_core.climate.sun_metrics import ase, continuous_da

    occ = year.occupied
    closed = blinds(year, occ)
    lux = year.total(closed)[:, occ]
    m = daylight_metrics(lux)
    open_m = daylight_metrics(year.total()[:, occ])
    cda = continuous_da(lux)
    sun = year.direct_sun.sum(axis=0)[:, occ]
    a = ase(sun)
    summary = {
        **m.summary(),
        "cda300_mean": float(np.mean(cda)),
        "sda300_50_open": open_m.sda,
        "ase1000_250": float(a.share),
        "ase_hours_mean": float(np.mean(a.hours)),
        "blinds_closed_hours": {g: int(closed[i, occ].sum()) for i, g in enumerate(year.groups)},
    }
    mask = daylight_hours(year.weather.dh_lux)
    horizontal = year.horizontal_openings
    provision = daylight_provision(year.total()[:, mask], horizontal_openings=horizontal)
    summary["en17037_provision"] = {
        "level": provision.level,
        "horizontal_openings": horizontal,
        "daylight_hours": int(mask.sum()),
        **{k: v for k, v in provision.summary().items() if k != "en17037_provision"},
    }
    summary["lm83"] = lm83_figures(year)
    columns = {
        "da300": m.da,
        "cda300": cda,
        "udi_n": m.udi[:, 0],
        "udi_s": m.udi[:, 1],
        "udi_a": m.udi[:, 2],
        "udi_x": m.udi[:, 3],
        "ase_hours": np.asarray(a.hours, dtype=float),
    }
    return summary, columns


LM83_HOURS = (8.0, 18.0)
"""IES LM-83's analysis period: 8:00 to 18:00 local standard time, every day of the
year, whatever the project's own occupancy."""


def lm83_figures(year) -> dict:
    """sDA300/50% (with the LM-83 blinds) and ASE1000,250 over LM-83's own period
    (``LM83_HOURS``, every day): the figures LEED judges."""
    from lightinv_core.climate.sun_metrics import ase

    mask = np.asarray(year.weather.occupied(*LM83_HOURS, weekdays=False))
    closed = blinds(year, mask)
    m = daylight_metrics(year.total(closed)[:, mask])
    a = ase(year.direct_sun.sum(axis=0)[:, mask])
    return {"hours": int(mask.sum()), "sda300_50": m.sda, "ase1000_250": float(a.share)}


def view_metrics(views_year, work_plane_year) -> list[dict]:
    """Per view point: simplified DGP over the occupied hours (blinds as the work
    plane's rule sets them), its classes and the EN 17037 glare-protection level."""
    from lightinv_core.climate.sun_metrics import dgp_exceedance, dgp_simplified, glare_protection

    occ = views_year.occupied
    closed = blinds(work_plane_year, occ)
    ev = views_year.total(closed)[:, occ]
    dgp = dgp_simplified(ev)
    levels = glare_protection(ev).level
    out = []
    for v in range(ev.shape[0]):
        row = {"dgp_max": float(dgp[v].max()), "ev_max_lux": float(ev[v].max())}
        for limit in (0.35, 0.40, 0.45):
            row[f"dgp_over_{limit:.2f}"] = float(dgp_exceedance(ev[v : v + 1], limit)[0])
        row["en17037_glare"] = str(levels[v])
        out.append(row)
    return out


def sunlight(point, clear, year, date: tuple[int, int], min_altitude_deg: float) -> dict:
    """EN 17037 sunlight exposure at ``point`` (scene, m) through ``clear``'s glass on
    ``date`` (month, day) of the weather's site, counting the sun above
    ``min_altitude_deg`` (the standard's value for the site)."""
    import datetime

    from lightinv_core.climate.en17037 import sunlight_exposure
    from lightinv_core.transport.clear_glazing import exit_pane, to_scene

    w = year.weather
    north = year.north_deg
    p = np.asarray(point, dtype=float)

    def visible(directions):
        d = to_scene(np.asarray(directions, float).reshape(-1, 3), north)
        o = np.broadcast_to(p, d.shape)
        j, _ = exit_pane(o, d, clear.lit, clear.glass, clear.caster)
        return j >= 0

    day = datetime.date(2001, *date)
    got = sunlight_exposure(
        visible,
        w.latitude,
        w.longitude,
        day,
        min_altitude_deg=min_altitude_deg,
        utc_offset_h=w.utc_offset_h,
    )
    return {
        "hours": float(got.hours),
        "level": got.level,
        "sun_hours": float(got.sun_hours),
        "date": got.date.isoformat(),
        "min_altitude_deg": got.min_altitude_deg,
        "point": list(point),
    }
