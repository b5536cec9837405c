"""What ``simulate`` prints: a ``SimulationResult`` as one JSON object (its keys are
documented in docs/cli.md and used by scripts: they stay) and as text."""

from __future__ import annotations

import numpy as np

from lightinv_core.cli.output import peak_rss_mb
from lightinv_core.climate.control_modes import control_text
from lightinv_core.quantities import quantity_spec
from lightinv_core.study import SimulationResult, SimulationSpec
from lightinv_core.study.simulation import installed_watts, luminaire_watts
from lightinv_core.transport.annual import panes
from lightinv_core.value_text import u0_text


def group_lines(groups: list[dict]) -> list[str]:
    """The table of min / average / max lux per group."""
    lines = [f"{'group':<14} {'min lux':>10} {'avg lux':>10} {'max lux':>10}"]
    lines += [
        f"{s['group']:<14} {s['min_lux']:10.1f} {s['avg_lux']:10.1f} {s['max_lux']:10.1f}"
        for s in groups
    ]
    return lines


def lrr_payload(res: SimulationResult) -> tuple[dict, list[str]]:
    """(JSON, text lines) of a simulation by the low-rank operator."""
    op, t = res.operator, res.timings
    payload = {
        "scene": res.scene.name,
        "patches": res.patches.n,
        "method": "lrr",
        "k": op["k"],
        "from_cache": op["from_cache"],
        "cache_path": op["cache_path"],
        "precompute_seconds": t["precompute_seconds"],
        "solve_seconds": t["solve_seconds"],
        "estimated_rel_error": op["estimated_rel_error"],
        "emitted_lm": op["emitted_lm"],
        "emitted_outside_zones_lm": op["emitted_outside_zones_lm"],
        "groups": res.groups,
        "peak_rss_mb": peak_rss_mb(),
    }
    lines = [
        f"{res.scene.name}: {res.patches.n:,} patches, operator k = {op['k']} "
        f"({'cache' if op['from_cache'] else 'built'} in {t['precompute_seconds']:.2f} s), "
        f"evaluation {1e3 * t['solve_seconds']:.2f} ms",
        *group_lines(res.groups),
    ]
    outside, emitted = op["emitted_outside_zones_lm"], op["emitted_lm"]
    if outside > 1e-9 * max(emitted, 1.0):
        lines.append(
            "note: light emitted outside the emitter zones goes through the plain "
            "low-rank operator, which blurs it over clusters (see docs/operator.md)"
        )
    return payload, lines


def reference_payload(res: SimulationResult, spec: SimulationSpec) -> tuple[dict, list[str]]:
    """(JSON, text lines) of a simulation by the reference solver."""
    light, t = res.light, res.timings
    bal = {
        "emitted_lm": light.emitted_lm,
        "absorbed_lm": light.absorbed_lm,
        "lost_lm": light.emitted_lm - light.absorbed_lm,
        "imbalance": light.imbalance,
    }
    payload = {
        "scene": res.scene.name,
        "patches": res.patches.n,
        "method": "reference",
        "rays_per_patch": spec.rays,
        "formfactor_seconds": t["formfactor_seconds"],
        "solve_seconds": t["solve_seconds"],
        "lost_fraction": res.lost_fraction,
        "energy": bal,
        "warnings": res.warnings + res.photometry_warnings,
        "groups": res.groups,
        "peak_rss_mb": peak_rss_mb(),
    }
    lines = [
        f"{res.scene.name}: {res.patches.n:,} patches, form factors "
        f"{t['formfactor_seconds']:.2f} s ({spec.rays} rays/patch), solve "
        f"{t['solve_seconds']:.2f} s",
        f"emitted {bal['emitted_lm']:.0f} lm, absorbed {bal['absorbed_lm']:.0f} lm "
        f"(imbalance {100 * bal['imbalance']:+.2f}%)",
    ]
    if spec.luminaires:
        payload["luminaires"] = luminaire_summary(spec.luminaires)
        lines.append(luminaire_line(payload["luminaires"]))
    lines += group_lines(res.groups)
    if res.grid is not None:
        payload["grid"] = grid_payload(res, spec)
        lines += grid_lines(payload["grid"], spec)
    if res.points_lux is not None:
        payload["points"] = points_payload(res, spec)
        lines += points_lines(payload["points"])
    if res.clear_year is not None:
        payload["annual"] = clear_payload(res, spec)
        lines += clear_lines(payload["annual"])
    elif res.annual is not None:
        payload["annual"] = annual_payload(res, spec)
        lines += annual_lines(payload["annual"])
    if res.control_groups is not None:
        groups = [g.as_dict() for g in res.control_groups]
        payload["annual"]["control_groups"] = {"groups": groups, "total": res.control_total}
        lines += [
            f"control group {g['name']} "
            f"({control_text(g['mode'], g['target_lux'], g['dead_band'])}): "
            f"{g['luminaires']} luminaire(s), {g['installed_w']:.0f} W, "
            f"sensor {g['sensor_points']} points, mean level {g['mean_level']:.2f}, "
            f"{g['energy_kwh']:.0f} kWh a year, LENI {g['leni']:.2f} kWh/m² a"
            for g in groups
        ]
        t = res.control_total
        lines.append(
            f"control groups in total: {t['energy_kwh']:.0f} kWh a year, LENI "
            f"{t['leni_kwh_m2']:.2f} kWh/m² a"
        )
    if res.sky_label is not None:
        payload["moment_sky"] = res.sky_label
        lines.append(f"sky: {res.sky_label}")
    if res.df_patches is not None:
        payload["sky"] = {
            "model": spec.sky,
            "exterior_lux": spec.exterior_lux,
            "ground_reflectance": spec.ground_reflectance,
            "glazing": dict(spec.glazing),
        }
    return payload, lines


def grid_payload(res: SimulationResult, spec: SimulationSpec) -> dict:
    """The work plane's statistics, layout and daylight factor."""
    plane, grid = spec.workplane, res.grid
    out = {
        **res.grid_stats,
        "height_m": plane.height,
        "border_m": plane.border,
        "group": plane.group,
        "edition": str(spec.edition),
        "spacing_m": list(grid.spacing),
        "rule_spacing_m": grid.rule_spacing,
        "counts": list(grid.counts),
        "dropped": grid.dropped,
    }
    if res.df_grid is not None:
        d = res.df_grid
        out["df"] = {"mean": float(d.mean()), "median": float(np.median(d)), "min": float(d.min())}
    return out


def grid_lines(g: dict, spec: SimulationSpec) -> list[str]:
    """The work plane's lines: layout, EN 12464-1 values, daylight factor."""
    lines = [
        f"work plane {g['height_m']:g} m over {g['group']!r}, border {g['border_m']:g} m: "
        f"{g['points']} points ({g['spacing_m'][0]:.2f} x {g['spacing_m'][1]:.2f} m; "
        f"{g['edition']} p = {g['rule_spacing_m']:.2f} m)",
        f"Em {g['Em']:.1f} lux, Emin {g['Emin']:.1f} lux, Emax {g['Emax']:.1f} lux, "
        f"U0 {u0_text(g['U0'])}",
    ]
    if "df" in g:
        d = g["df"]
        lines.append(
            f"daylight factor (CIE overcast, {spec.exterior_lux:g} lux outside): mean "
            f"{d['mean']:.2f}%, median {d['median']:.2f}%, min {d['min']:.2f}%"
        )
    return lines


def points_payload(res: SimulationResult, spec: SimulationSpec) -> dict:
    """The free points' illuminance (lux), each with its place and normal, and their
    statistics (mean, min, max, U0 = min / mean)."""
    ps, lux = spec.points, res.points_lux
    mean = float(lux.mean())
    return {
        "count": len(lux),
        "Em": mean,
        "Emin": float(lux.min()),
        "Emax": float(lux.max()),
        "U0": float(lux.min() / mean) if mean > 0 else 0.0,
        "points": [
            {"x": float(p[0]), "y": float(p[1]), "z": float(p[2]), "normal": n.tolist(), "lux": e}
            for p, n, e in zip(ps.points, ps.normals, lux.tolist(), strict=True)
        ],
    }


def points_lines(g: dict) -> list[str]:
    """One line per free point, then their statistics."""
    lines = [f"points: {g['count']}"]
    for k, p in enumerate(g["points"], 1):
        n = ", ".join(f"{v:.3g}" for v in p["normal"])
        lines.append(
            f"  {k}: ({p['x']:g}, {p['y']:g}, {p['z']:g}) facing ({n}): {p['lux']:.1f} lux"
        )
    lines.append(
        f"points: mean {g['Em']:.1f} lux, min {g['Emin']:.1f} lux, max {g['Emax']:.1f} lux, "
        f"U0 {u0_text(g['U0'])}"
    )
    return lines


def year_header(res: SimulationResult, spec: SimulationSpec, weather: dict, hours: int) -> dict:
    """What both years' JSON opens with: the weather, the occupied hours, the schedule,
    the north bearing and the glazing's panes."""
    daylight = spec.annual
    return {
        "weather": weather,
        "occupied_hours": hours,
        "occupancy": list(daylight.occupancy),
        "weekdays_only": daylight.weekdays,
        "north_deg": daylight.north_deg,
        "panes": [
            {"group": q.group, "outward": q.outward.round(4).tolist(), "patches": len(q.idx)}
            for q in panes(res.patches, dict(spec.glazing))
        ],
    }


def annual_payload(res: SimulationResult, spec: SimulationSpec) -> dict:
    """The weather year on the work plane: metrics, panes and dimming."""
    a = res.annual
    out = {
        **year_header(res, spec, a.year.weather, a.year.hours),
        **a.metrics.summary(),
        "metrics": {
            name: {"label": quantity_spec(name).metric, "mean": float(values.mean())}
            for name, values in a.annual.items()
        },
    }
    if a.dimming is not None:
        out["dimming"] = dimming_payload(
            a.dimming, spec.annual, a.electric_em, a.installed_w, a.floor_m2
        )
    return out


def dimming_payload(d, dim, electric_em: float, installed_w: float, floor_m2: float) -> dict:
    """The dimming figures for JSON (``climate.metrics.Dimming`` ``d``, ``Daylight`` ``dim``)."""
    return {
        "target_lux": dim.target_lux,
        "electric_em_lux": electric_em,
        "installed_w": installed_w,
        "min_level": dim.min_level,
        "standby_w": dim.standby_w,
        "mean_level": float(d.levels.mean()),
        "energy_kwh": d.energy_kwh,
        "undimmed_kwh": d.full_power_kwh,
        "leni_kwh_m2": d.leni,
        "floor_m2": floor_m2,
    }


def clear_payload(res: SimulationResult, spec: SimulationSpec) -> dict:
    """The weather year through clear (and diffusing) glazing on the work plane."""
    cy, daylight = res.clear_year, spec.annual
    out = {
        **year_header(res, spec, cy.year.weather, int(cy.occupied.sum())),
        "glazing_kinds": {g: spec.glazing_kinds.get(g, "diffusing") for g in spec.glazing},
        **res.clear_annual,
    }
    if res.clear_dimming is not None:
        d, em = res.clear_dimming
        watts = installed_watts(spec.luminaires)
        out["dimming"] = dimming_payload(d, daylight, em, watts, _floor(res, spec))
    return out


def _floor(res: SimulationResult, spec: SimulationSpec) -> float:
    return float(res.patches.area[res.patches.group_index(spec.workplane.group)].sum())


def grid_columns(res: SimulationResult) -> dict[str, np.ndarray]:
    """The grid CSV's columns after x, y, z, lux: df (%), then DA300 and the UDI bands,
    then every annual daylight metric of the quantity registry by its name."""
    columns = {"df": res.df_grid} if res.df_grid is not None else {}
    if res.annual is not None:
        m = res.annual.metrics
        columns.update(
            da300=m.da, udi_n=m.udi[:, 0], udi_s=m.udi[:, 1], udi_a=m.udi[:, 2], udi_x=m.udi[:, 3]
        )
        columns.update(res.annual.annual)
    if res.clear_columns is not None:
        columns.update(res.clear_columns)
    return columns


def clear_lines(a: dict) -> list[str]:
    """The year through clear glazing: weather, DA, UDI, blinds, ASE, continuous DA,
    EN 17037, glare, dimming."""
    w = a["weather"]
    days = "weekdays" if a["weekdays_only"] else "every day"
    lines = [
        f"weather: {w['format']}, {w['hours']} hours ({w['time_convention']}); "
        f"illuminance {w['illuminance']}",
        f"annual daylight ({w['site']}, {a['occupied_hours']} occupied hours, {days} "
        f"{a['occupancy'][0]:g}-{a['occupancy'][1]:g} h): DA300 mean "
        f"{100 * a['da300_mean']:.0f}%, UDI <100 {100 * a['udi_n']:.0f}%, 100-3000 "
        f"{100 * a['udi_100_3000']:.0f}%, >3000 {100 * a['udi_x']:.0f}%",
        f"through clear glazing: ASE1000,250 {100 * a['ase1000_250']:.0f}% of the points; "
        f"sDA300/50% {100 * a['sda300_50']:.0f}% with LM-83 blinds "
        f"({100 * a['sda300_50_open']:.0f}% with them open); continuous DA300 mean "
        f"{100 * a['cda300_mean']:.0f}%",
        "blinds closed: " + ", ".join(f"{g} {h} h" for g, h in a["blinds_closed_hours"].items()),
    ]
    p = a.get("en17037_provision")
    if p:
        lines.append(f"EN 17037 daylight provision: {p['level']}")
    s = a.get("en17037_sunlight")
    if s:
        lines.append(f"EN 17037 sunlight exposure: {s['hours']:.2f} h, {s['level']}")
    for v in a.get("views", []):
        lines.append(
            f"view {v['view'][:3]}: DGPs max {v['dgp_max']:.2f}, above 0.40 in "
            f"{100 * v['dgp_over_0.40']:.1f}% of occupied hours"
        )
    lines += dimming_lines(a)
    lines += [
        f"{'PASS' if c['passed'] else 'FAIL'}  {c['text']}: {c['value']} (needs {c['required']})"
        for c in a.get("criteria", [])
    ]
    return lines


def dimming_lines(a: dict) -> list[str]:
    """The dimming energy's line, when the year has luminaires to dim."""
    if "dimming" not in a:
        return []
    d = a["dimming"]
    return [
        f"daylight-linked dimming to {d['target_lux']:g} lux: {d['energy_kwh']:.0f} kWh a year "
        f"(undimmed {d['undimmed_kwh']:.0f} kWh), LENI {d['leni_kwh_m2']:.2f} kWh/m² a"
    ]


def annual_lines(a: dict) -> list[str]:
    """The weather, the annual metrics and the dimming energy."""
    w = a["weather"]
    lines = [
        f"weather: {w['format']}, {w['hours']} hours ({w['time_convention']}); "
        f"illuminance {w['illuminance']}",
        f"annual daylight ({w['site']}, {a['occupied_hours']} occupied hours, "
        f"{'weekdays' if a['weekdays_only'] else 'every day'} "
        f"{a['occupancy'][0]:g}-{a['occupancy'][1]:g} h): DA300 mean "
        f"{100 * a['da300_mean']:.0f}%, sDA300/50% {100 * a['sda300_50']:.0f}%",
        f"UDI <100 {100 * a['udi_n']:.0f}%, 100-300 {100 * a['udi_s']:.0f}%, 300-3000 "
        f"{100 * a['udi_a']:.0f}%, >3000 {100 * a['udi_x']:.0f}% of occupied hours",
        "annual metrics (means over the grid): "
        + ", ".join(f"{m['label']} {m['mean']:.3f}" for m in a["metrics"].values()),
    ]
    lines += dimming_lines(a)
    return lines


def luminaire_summary(luminaires) -> list[dict]:
    """Each luminaire for ``--json``: ``lumens`` and ``watts_at_dimming`` at its set
    dimming, ``lumens_rated`` and ``watts`` (the file's input watts, or None) at full
    output (``study.simulation.luminaire_watts``); ``warnings`` of its photometric file."""
    return [
        {
            "name": x.name,
            "position_m": x.position.tolist(),
            "file": x.photometry.source,
            "lumens": x.lumens,
            "watts": x.photometry.input_watts,
            "dimming": x.dimming,
            "lumens_rated": x.photometry.flux(),
            "watts_at_dimming": luminaire_watts(x),
            "warnings": list(x.photometry.warnings),
        }
        for x in luminaires
    ]


def luminaire_line(summary: list[dict]) -> str:
    """The luminaires' flux and power, both at the set dimming, then both at full output
    (unless nothing is dimmed); luminaires whose file gives no input watts are counted."""
    lm = sum(x["lumens"] for x in summary)
    lm_rated = sum(x["lumens_rated"] for x in summary)
    watts = sum(x["watts_at_dimming"] or 0.0 for x in summary)
    rated = sum(x["watts"] or 0.0 for x in summary)
    if all(x["dimming"] == 1.0 for x in summary):
        text = f"{lm:.0f} lm, {watts:.1f} W at full output"
    else:
        text = (
            f"{lm:.0f} lm, {watts:.1f} W at the set dimming "
            f"(rated {lm_rated:.0f} lm, {rated:.1f} W)"
        )
    unknown = sum(x["watts"] is None for x in summary)
    if unknown:
        text += f"; {unknown} with no input watts in the file, not counted in W"
    return f"{len(summary)} luminaire(s): {text}"
