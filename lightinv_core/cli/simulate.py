"""``simulate``: a forward simulation. Groups emit given fluxes, photometric luminaires
shine, a design sky or a weather year lights the glazing; illuminance per group and on a
work-plane grid, daylight factor, annual daylight and dimming energy."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from lightinv_core.atomic import check_writable
from lightinv_core.cli.output import (
    failed,
    out,
    peak_rss_mb,
    progress_printer,
    warn,
    write_or_rescue,
)
from lightinv_core.cli.precompute import operator_of
from lightinv_core.cli.scenes import scene_of
from lightinv_core.cli.simulate_text import annual_lines, luminaire_line, luminaire_summary
from lightinv_core.climate.metrics import daylight_metrics, dimming_energy
from lightinv_core.climate.weather import read_weather
from lightinv_core.errors import LightInvError
from lightinv_core.light.model import LightModel
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.sources.luminaire_csv import read_luminaire_csv
from lightinv_core.transport.annual import annual_daylight
from lightinv_core.transport.escape import luminaire_escape_warnings
from lightinv_core.transport.formfactors import (
    check_formfactor_memory,
    escape_warning,
    form_factor_matrix,
    lost_fraction,
)
from lightinv_core.transport.glazing import glazing_emission
from lightinv_core.transport.photometry import group_illuminance, write_patch_csv
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors
from lightinv_core.transport.scene_light import light_grid, light_scene, write_grid_csv
from lightinv_core.transport.solver import group_emission
from lightinv_core.transport.workplane import (
    DEFAULT_BORDER,
    WorkPlane,
    grid_statistics,
    work_plane_grid,
)

AUTO_LRR_PATCHES = 3000
"""Above this many patches, ``--method auto`` simulates plain group emission with the
low-rank operator instead of the reference solver."""


def cmd_simulate(args) -> int:
    """Forward simulation: groups emit given fluxes, photometric luminaires shine; report
    illuminance per group and on a work-plane grid."""
    if not args.emit and not args.luminaires and not args.sky and args.weather is None:
        raise LightInvError(
            "nothing emits: give --emit GROUP=LUMENS, --luminaires SCHEDULE.csv, or "
            "--sky cie-overcast or --weather FILE with --glazing GROUP=TRANSMITTANCE"
        )
    daylit = bool(args.sky) or args.weather is not None
    if daylit != bool(args.glazing):
        raise LightInvError(
            "a sky lights the room through glazing: give both --sky cie-overcast (or "
            "--weather FILE) and --glazing GROUP=TRANSMITTANCE (the glazing's patches emit "
            "what they let in)"
        )
    if args.weather is not None and args.workplane is None:
        raise LightInvError("annual daylight is measured on a work plane: add --workplane 0.8")
    if args.workplane is None and (args.grid_csv or args.border is not None):
        raise LightInvError("--grid-csv and --border describe a work plane: add --workplane 0.8")
    for path in (args.patches_csv, args.grid_csv):
        if path:
            check_writable(path)
    luminaires = read_luminaire_csv(args.luminaires) if args.luminaires else []
    scene = scene_of(args)
    p = mesh_patches(scene)
    E = group_emission(p, dict(args.emit))
    method = args.method
    plain = not luminaires and args.workplane is None and not daylit
    if method == "lrr" and not plain:
        raise LightInvError(
            "luminaires, skies and work planes are simulated with the reference solver; "
            "leave out --method lrr (or use --method reference)"
        )
    if method == "auto":
        method = "lrr" if plain and p.n > AUTO_LRR_PATCHES else "reference"
    if method == "lrr":
        return _simulate_lrr(args, scene, p, E)
    return _simulate_reference(args, scene, p, E, luminaires)


def _simulate_reference(args, scene, p, E, luminaires) -> int:
    check_formfactor_memory(p, args.rays)
    t0 = time.perf_counter()
    caster = RayCaster(p)
    F = form_factor_matrix(
        p, args.rays, seed=args.seed, progress=progress_printer("form factors"), caster=caster
    )
    t1 = time.perf_counter()
    lit = p
    if args.glazing:  # black inside; it emits only under a design sky
        glass, lit = glazing_emission(
            p, dict(args.glazing), args.exterior_lux if args.sky else 0.0, args.ground_reflectance
        )
        E = E + glass
    light = light_scene(lit, F, caster, E, luminaires, seed=args.seed)
    # Daylight factor (%): illuminance over the unobstructed exterior horizontal one.
    df = (lambda lux: 100.0 * lux / args.exterior_lux) if args.sky and args.exterior_lux else None
    t2 = time.perf_counter()
    lost = lost_fraction(F, p)
    warnings = [w for w in [escape_warning(lost)] if w]
    warnings += luminaire_escape_warnings(luminaires, caster)
    grid = None
    if args.workplane is not None:
        border = DEFAULT_BORDER if args.border is None else args.border
        plane = WorkPlane(args.workplane, border, args.workplane_group)
        grid = work_plane_grid(p, caster, plane)
        factors = receiver_factors(grid.points, grid.normals, caster, p.n, args.rays, args.seed)
        grid_light = light_grid(grid, light, caster, luminaires, args.rays, factors=factors)
        columns = {"df": df(grid_light.lux)} if df else {}
        if args.weather is not None:
            # Without luminous groups or a design sky, the grid's light is the luminaires'.
            electric = grid_light.lux if not args.emit and not args.sky else None
            annual = _annual(args, lit, F, caster, grid, factors, luminaires, plane, electric)
            columns.update(annual.pop("columns"))
    for w in warnings:
        warn(w)
    problems = []
    if args.patches_csv:
        patch_df = df(light.H) if df else None
        csv_path, msg = write_or_rescue(
            "patch values",
            args.patches_csv,
            lambda f: write_patch_csv(f, lit, E, light.B, light.H, patch_df),
        )
        problems.append(msg)
    if args.grid_csv:
        grid_path, msg = write_or_rescue(
            "grid values",
            args.grid_csv,
            lambda f: write_grid_csv(f, grid_light.points, grid_light.lux, columns),
        )
        problems.append(msg)
    stats = group_illuminance(p, light.H)
    bal = {
        "emitted_lm": light.emitted_lm,
        "absorbed_lm": light.absorbed_lm,
        "lost_lm": light.emitted_lm - light.absorbed_lm,
        "imbalance": light.imbalance,
    }
    result = {
        "scene": scene.name,
        "patches": p.n,
        "method": "reference",
        "rays_per_patch": args.rays,
        "formfactor_seconds": t1 - t0,
        "solve_seconds": t2 - t1,
        "lost_fraction": lost,
        "energy": bal,
        "warnings": warnings,
        "groups": stats,
        "peak_rss_mb": peak_rss_mb(),
    }
    lines = [
        f"{scene.name}: {p.n:,} patches, form factors {t1 - t0:.2f} s "
        f"({args.rays} rays/patch), solve {t2 - t1:.2f} s",
        f"emitted {bal['emitted_lm']:.0f} lm, absorbed {bal['absorbed_lm']:.0f} lm "
        f"(imbalance {100 * bal['imbalance']:+.2f}%)",
    ]
    if luminaires:
        result["luminaires"] = luminaire_summary(luminaires)
        lines.append(luminaire_line(result["luminaires"]))
        from lightinv_core.luminaires.photometry import light_warnings

        for w in light_warnings(x.photometry for x in luminaires):
            warn(f"warning: {w}")
            warnings.append(w)  # result["warnings"] too
    lines.append(f"{'group':<14} {'min lux':>10} {'avg lux':>10} {'max lux':>10}")
    lines += [
        f"{s['group']:<14} {s['min_lux']:10.1f} {s['avg_lux']:10.1f} {s['max_lux']:10.1f}"
        for s in stats
    ]
    if grid is not None:
        g = grid_statistics(grid_light.lux)
        result["grid"] = {
            **g,
            "height_m": plane.height,
            "border_m": plane.border,
            "group": plane.group,
            "spacing_m": list(grid.spacing),
            "rule_spacing_m": grid.rule_spacing,
            "counts": list(grid.counts),
            "dropped": grid.dropped,
        }
        lines.append(
            f"work plane {plane.height:g} m over {plane.group!r}, border {plane.border:g} m: "
            f"{g['points']} points ({grid.spacing[0]:.2f} x {grid.spacing[1]:.2f} m; "
            f"EN 12464-1 p = {grid.rule_spacing:.2f} m)"
        )
        lines.append(
            f"Em {g['Em']:.1f} lux, Emin {g['Emin']:.1f} lux, Emax {g['Emax']:.1f} lux, "
            f"U0 {g['U0']:.2f}"
        )
        if df:
            d = df(grid_light.lux)
            result["grid"]["df"] = {
                "mean": float(d.mean()),
                "median": float(np.median(d)),
                "min": float(d.min()),
            }
            lines.append(
                f"daylight factor (CIE overcast, {args.exterior_lux:g} lux outside): mean "
                f"{d.mean():.2f}%, median {np.median(d):.2f}%, min {d.min():.2f}%"
            )
    if args.weather is not None:
        result["annual"] = annual
        lines += annual_lines(annual)
    if df:
        result["sky"] = {
            "model": args.sky,
            "exterior_lux": args.exterior_lux,
            "ground_reflectance": args.ground_reflectance,
            "glazing": dict(args.glazing),
        }
        for s in stats:
            s["avg_df"] = 100.0 * s["avg_lux"] / args.exterior_lux
    if args.patches_csv:
        result["patches_csv"] = str(csv_path)
        lines.append(f"patch values written to {csv_path}")
    if args.grid_csv:
        result["grid_csv"] = str(grid_path)
        lines.append(f"grid values written to {grid_path}")
    out(args, result, "\n".join(lines))
    return failed("; ".join(m for m in problems if m))


def _annual(args, lit, F, caster, grid, factors, luminaires, plane, electric=None) -> dict:
    """Annual daylight metrics on the grid (and dimming energy with luminaires);
    ``electric`` is the grid's light from the luminaires alone when already solved."""
    weather = read_weather(args.weather)
    for note in weather.notes:
        warn(f"weather {Path(weather.source).name}: {note}")
    year = annual_daylight(
        lit,
        F,
        caster,
        dict(args.glazing),
        weather,
        grid,
        factors,
        args.ground_reflectance,
        args.north,
    )
    start, end = args.occupancy
    occupied = weather.occupied(start, end)
    lux = year.lux[:, occupied]
    metrics = daylight_metrics(lux)
    out = {
        "weather": weather.describe(),
        "occupied_hours": int(occupied.sum()),
        "occupancy": [start, end],
        "north_deg": args.north,
        "panes": [
            {"group": q.group, "outward": q.outward.round(4).tolist(), "patches": len(q.idx)}
            for q in year.panes
        ],
        **metrics.summary(),
        "columns": {
            "da300": metrics.da,
            "udi_n": metrics.udi[:, 0],
            "udi_s": metrics.udi[:, 1],
            "udi_a": metrics.udi[:, 2],
            "udi_x": metrics.udi[:, 3],
        },
    }
    if luminaires:
        if electric is None:
            alone = light_scene(lit, F, caster, np.zeros(lit.n), luminaires, seed=args.seed)
            electric = light_grid(grid, alone, caster, luminaires, args.rays, factors=factors).lux
        em_elec = float(electric.mean())
        watts = sum((x.photometry.input_watts or 0.0) * x.dimming for x in luminaires)
        floor = float(lit.area[lit.group_index(plane.group)].sum())
        dim = dimming_energy(
            lux.mean(axis=0),
            em_elec,
            args.target_lux,
            watts,
            floor,
            args.min_dimming,
            args.standby_w,
        )
        out["dimming"] = {
            "target_lux": args.target_lux,
            "electric_em_lux": em_elec,
            "installed_w": watts,
            "min_level": args.min_dimming,
            "standby_w": args.standby_w,
            "mean_level": float(dim.levels.mean()),
            "energy_kwh": dim.energy_kwh,
            "undimmed_kwh": dim.full_power_kwh,
            "leni_kwh_m2": dim.leni,
            "floor_m2": floor,
        }
    return out


def _simulate_lrr(args, scene, p, E) -> int:
    t0 = time.perf_counter()
    got = operator_of(args, p)
    t1 = time.perf_counter()
    field = LightModel(scene, p, got.operator).emission_field(E)
    t2 = time.perf_counter()
    H, B = field.illuminance, field.radiosity
    problem = ""
    if args.patches_csv:
        csv_path, problem = write_or_rescue(
            "patch values", args.patches_csv, lambda f: write_patch_csv(f, p, E, B, H)
        )
        lines_csv = [f"patch values written to {csv_path}"]
    else:
        lines_csv = []
    stats = group_illuminance(p, H)
    in_zones = float(E[got.operator.zone_patches] @ p.area[got.operator.zone_patches])
    emitted = float(E @ p.area)
    info = got.operator.info
    result = {
        "scene": scene.name,
        "patches": p.n,
        "method": "lrr",
        "k": got.operator.k,
        "from_cache": got.from_cache,
        "cache_path": str(got.path) if got.path else None,
        "precompute_seconds": t1 - t0,
        "solve_seconds": t2 - t1,
        "estimated_rel_error": info["estimated_rel_error"],
        "emitted_lm": emitted,
        "emitted_outside_zones_lm": emitted - in_zones,
        "groups": stats,
        "peak_rss_mb": peak_rss_mb(),
    }
    lines = [
        f"{scene.name}: {p.n:,} patches, operator k = {got.operator.k} "
        f"({'cache' if got.from_cache else 'built'} in {t1 - t0:.2f} s), "
        f"evaluation {1e3 * (t2 - t1):.2f} ms",
        f"{'group':<14} {'min lux':>10} {'avg lux':>10} {'max lux':>10}",
    ]
    lines += [
        f"{s['group']:<14} {s['min_lux']:10.1f} {s['avg_lux']:10.1f} {s['max_lux']:10.1f}"
        for s in stats
    ]
    if emitted - in_zones > 1e-9 * max(emitted, 1.0):
        lines.append(
            "note: light emitted outside the emitter zones goes through the plain "
            "low-rank operator, which blurs it over clusters (see docs/operator.md)"
        )
    if args.patches_csv:
        result["patches_csv"] = str(csv_path)
    out(args, result, "\n".join(lines + lines_csv))
    return failed(problem)
