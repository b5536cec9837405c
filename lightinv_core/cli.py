"""``lightinv-cli``: the headless command line.

Every subcommand prints human-readable text, or one JSON object with ``--json``.
User errors (bad names, bad files, bad numbers) exit with status 2 and a one-line
message on stderr, never a traceback.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import resource
import sys
import time
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from lightinv_core.atomic import check_writable, rescue_paths
from lightinv_core.climate.metrics import daylight_metrics, dimming_energy
from lightinv_core.climate.weather import read_weather
from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.kinds import SourceKind
from lightinv_core.light.model import LightModel
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.registry import method_names
from lightinv_core.scene.builtin import BUILTIN_SCENES, builtin_scene
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.patches import count_patches, mesh_patches
from lightinv_core.sources.emission import source_electric_power, source_flux
from lightinv_core.sources.luminaire_csv import read_luminaire_csv
from lightinv_core.transport.annual import annual_daylight
from lightinv_core.transport.escape import luminaire_escape_warnings
from lightinv_core.transport.formfactors import (
    DEFAULT_RAYS,
    MAX_RAYS,
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
    DEFAULT_HEIGHT,
    WorkPlane,
    grid_statistics,
    work_plane_grid,
)


def peak_rss_mb() -> float:
    """Peak resident memory of this process so far, in MB."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _emit(text: str) -> tuple[str, float]:
    group, sep, value = text.partition("=")
    try:
        if not sep or not group:
            raise ValueError
        return group, float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected GROUP=LUMENS, got {text!r}") from None


MAX_SEED = 2**63 - 1


def _integer(text: str, lo: int, hi: int, what: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}") from None
    if not lo <= v <= hi:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text}")
    return v


def _seed(text: str) -> int:
    return _integer(text, 0, MAX_SEED, "an integer seed from 0 to 2**63 - 1")


"""Most rays per patch the command line accepts: 64 times the default, already far past
where the form factors' error stops mattering (docs/operator.md), and about an hour of
ray casting on the patio scene."""


def _rays(text: str) -> int:
    return _integer(text, 1, MAX_RAYS, f"an integer from 1 to {MAX_RAYS:,} rays per patch")


def _count(text: str) -> int:
    return _integer(text, 1, 2**53, "an integer >= 1")


def _number_in(lo: float, hi: float, what: str, open_lo: bool = False, open_hi: bool = False):
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


_positive = _number_in(0.0, 1e12, "a positive number", open_lo=True)
_non_negative = _number_in(0.0, 1e4, "a length from 0 to 10,000 m")
_lux = _number_in(0.0, 2e5, "from 0 to 200,000 lux", open_lo=True)
_fraction = _number_in(0.0, 1.0, "a number from 0 to below 1", open_hi=True)
_angle = _number_in(-360.0, 360.0, "an angle from -360 to 360 degrees")


def _hours(text: str) -> tuple[float, float]:
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


def _transmittance(text: str) -> tuple[str, float]:
    group, sep, value = text.partition("=")
    try:
        t = float(value)
        if not sep or not group or not 0 <= t <= 1:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected GROUP=TRANSMITTANCE with a transmittance from 0 to 1, got {text!r}"
        ) from None
    return group, t


def _out(args, payload: dict, text: str) -> None:
    print(json.dumps(payload, indent=2) if args.json else text)


def cmd_scenes(args) -> int:
    """List the built-in scenes with their default patch counts."""
    scenes = []
    for name in BUILTIN_SCENES:
        s = builtin_scene(name)
        scenes.append(
            {
                "name": name,
                "patches": count_patches(s),
                "resolution": s.resolution,
                "description": s.description,
            }
        )
    lines = [f"{s['name']:<10} {s['patches']:>7,} patches  {s['description']}" for s in scenes]
    _out(args, {"scenes": scenes}, "\n".join(lines))
    return 0


def _scene(args):
    return load_scene(
        args.scene,
        args.resolution,
        args.materials,
        args.scale,
        args.up,
        args.skip_degenerate,
        group_by=args.group_by,
    )


def cmd_scene_info(args) -> int:
    """Patch count, area, groups and emitter zones of a scene, and for a model file its
    import report (what each element or group became, what was dropped and why)."""
    from lightinv_core.scene.importers.report import report_of

    scene = _scene(args)
    p = mesh_patches(scene)
    groups = [
        {
            "name": g,
            "patches": int((p.group_id == k).sum()),
            "area_m2": float(p.area[p.group_id == k].sum()),
        }
        for k, g in enumerate(p.group_names)
    ]
    zones = []
    for z in scene.zones:
        r = scene.zone_rect(z.name)
        zones.append(
            {
                "name": z.name,
                "kind": z.kind,
                "size_m": list(r.size),
                "grid": list(p.grid_shape[z.surface]),
                "origin": r.origin.tolist(),
                "u_axis": (r.u / r.size[0]).tolist(),
                "v_axis": (r.v / r.size[1]).tolist(),
                "normal": r.normal.tolist(),
                "outline": None if z.outline is None else z.outline.tolist(),
            }
        )
    info = {
        "name": scene.name,
        "patches": p.n,
        "area_m2": float(p.area.sum()),
        "resolution": scene.resolution,
        "groups": groups,
        "zones": zones,
        "warnings": list(scene.info.get("warnings", [])),
    }
    report = report_of(scene)
    if report is not None:
        info["import_report"] = report.to_dict()
    lines = [
        f"{scene.name}: {p.n:,} patches, {info['area_m2']:.1f} m² "
        f"(resolution {scene.resolution} m)",
        "groups:",
    ]
    lines += [
        f"  {g['name']:<14} {g['patches']:>7,} patches {g['area_m2']:9.2f} m²" for g in groups
    ]
    lines.append("emitter zones:" if zones else "emitter zones: none")
    lines += [
        f"  {z['name']:<10} {z['kind']:<9} {z['size_m'][0]:.2f} x {z['size_m'][1]:.2f} m, "
        f"grid {z['grid'][0]} x {z['grid'][1]}"
        + (f", polygon of {len(z['outline'])} corners" if z["outline"] else "")
        for z in zones
    ]
    if report is not None:
        lines += ["import report:", *(f"  {line}" for line in report.lines())]
    lines += [f"warning: {w}" for w in info["warnings"]]
    _out(args, info, "\n".join(lines))
    return 0


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
    for out in (args.patches_csv, args.grid_csv):
        if out:
            check_writable(out)
    luminaires = read_luminaire_csv(args.luminaires) if args.luminaires else []
    scene = _scene(args)
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
        p, args.rays, seed=args.seed, progress=_progress_printer("form factors"), caster=caster
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
        _warn(w)
    failed = []
    if args.patches_csv:
        patch_df = df(light.H) if df else None
        csv_path, msg = _write_or_rescue(
            "patch values",
            args.patches_csv,
            lambda f: write_patch_csv(f, lit, E, light.B, light.H, patch_df),
        )
        failed.append(msg)
    if args.grid_csv:
        grid_path, msg = _write_or_rescue(
            "grid values",
            args.grid_csv,
            lambda f: write_grid_csv(f, grid_light.points, grid_light.lux, columns),
        )
        failed.append(msg)
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
        result["luminaires"] = _luminaire_summary(luminaires)
        lines.append(_luminaire_line(result["luminaires"]))
        from lightinv_core.luminaires.photometry import light_warnings

        for w in light_warnings(x.photometry for x in luminaires):
            _warn(f"warning: {w}")
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
        lines += _annual_lines(annual)
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
    _out(args, result, "\n".join(lines))
    return _failed("; ".join(m for m in failed if m))


def _annual(args, lit, F, caster, grid, factors, luminaires, plane, electric=None) -> dict:
    """Annual daylight metrics on the grid (and dimming energy with luminaires);
    ``electric`` is the grid's light from the luminaires alone when already solved."""
    weather = read_weather(args.weather)
    for note in weather.notes:
        _warn(f"weather {Path(weather.source).name}: {note}")
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


def _annual_lines(a: dict) -> list[str]:
    w = a["weather"]
    lines = [
        f"weather: {w['format']}, {w['hours']} hours ({w['time_convention']}); "
        f"illuminance {w['illuminance']}",
        f"annual daylight ({w['site']}, {a['occupied_hours']} occupied hours, "
        f"weekdays {a['occupancy'][0]:g}-{a['occupancy'][1]:g} h): DA300 mean "
        f"{100 * a['da300_mean']:.0f}%, sDA300/50% {100 * a['sda300_50']:.0f}%",
        f"UDI <100 {100 * a['udi_n']:.0f}%, 100-300 {100 * a['udi_s']:.0f}%, 300-3000 "
        f"{100 * a['udi_a']:.0f}%, >3000 {100 * a['udi_x']:.0f}% of occupied hours",
    ]
    if "dimming" in a:
        d = a["dimming"]
        lines.append(
            f"daylight-linked dimming to {d['target_lux']:g} lux: {d['energy_kwh']:.0f} kWh a year "
            f"(undimmed {d['undimmed_kwh']:.0f} kWh), LENI {d['leni_kwh_m2']:.2f} kWh/m² a"
        )
    return lines


def _luminaire_summary(luminaires) -> list[dict]:
    """Each luminaire for ``--json``: ``lumens`` and ``watts_at_dimming`` at its set
    dimming, ``lumens_rated`` and ``watts`` (the file's input watts, or None) at full
    output; power taken as proportional to output (a linear-dimming driver), as the
    optimiser's electric power is; ``warnings`` of its photometric file."""
    out = []
    for x in luminaires:
        rated = x.photometry.input_watts
        out.append(
            {
                "name": x.name,
                "position_m": x.position.tolist(),
                "file": x.photometry.source,
                "lumens": x.lumens,
                "watts": rated,
                "dimming": x.dimming,
                "lumens_rated": x.photometry.flux(),
                "watts_at_dimming": None if rated is None else rated * x.dimming,
                "warnings": list(x.photometry.warnings),
            }
        )
    return out


def _luminaire_line(summary: list[dict]) -> str:
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


def _failed(message: str) -> int:
    """Exit status 2 with the message when an output could not be written where asked."""
    if not message:
        return 0
    print(f"lightinv-cli: error: {message}", file=sys.stderr)
    return 2


AUTO_LRR_PATCHES = 3000


def _write_or_rescue(label: str, path: str, write: Callable[[Path], object]) -> tuple[Path, str]:
    """Write an output with ``write(path)``; if that fails (disk full, folder gone), write
    it to the first of ``rescue_paths`` that works. Returns (where it went, the failure
    message or ""), so computed results are never thrown away."""
    try:
        write(Path(path))
        return Path(path), ""
    except (OSError, LightInvError) as exc:
        first = str(exc)
    for other in rescue_paths(path):
        try:
            write(other)
        except (OSError, LightInvError):
            continue
        return other, f"could not write {label} {path}: {first}; it was written to {other} instead"
    return Path(path), f"could not write {label} {path}: {first}, nor anywhere else"


def _progress_printer(label: str):
    """A progress callback that redraws a percentage on stderr when it is a terminal."""
    if not sys.stderr.isatty():
        return None
    last = [-1]

    def report(frac: float) -> None:
        pct = int(100 * frac)
        if pct != last[0]:
            last[0] = pct
            print(f"\r{label}: {pct:3d}%", end="" if pct < 100 else "\n", file=sys.stderr)

    return report


def _warn(msg: str) -> None:
    print(f"lightinv-cli: {msg}", file=sys.stderr)


def _operator(args, patches):
    settings = OperatorSettings(tol=args.tol, rank=args.rank, rays=args.rays, seed=args.seed)
    return get_operator(
        patches,
        settings,
        use_cache=not args.no_cache,
        progress=_progress_printer("precompute"),
        warn=_warn,
        scheduler=args.scheduler,
    )


def _simulate_lrr(args, scene, p, E) -> int:
    t0 = time.perf_counter()
    got = _operator(args, p)
    t1 = time.perf_counter()
    field = LightModel(scene, p, got.operator).emission_field(E)
    t2 = time.perf_counter()
    H, B = field.illuminance, field.radiosity
    failed = ""
    if args.patches_csv:
        csv_path, failed = _write_or_rescue(
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
    _out(args, result, "\n".join(lines + lines_csv))
    return _failed(failed)


def cmd_precompute(args) -> int:
    """Build (or load from the cache) the radiosity operator of a scene."""
    scene = _scene(args)
    p = mesh_patches(scene)
    got = _operator(args, p)
    info = got.operator.info
    result = {
        "scene": scene.name,
        "n": p.n,
        "k": got.operator.k,
        "nz": info["nz"],
        "seconds": got.seconds,
        "from_cache": got.from_cache,
        "cache_path": str(got.path) if got.path else None,
        "estimated_rel_error": info["estimated_rel_error"],
        "estimated_max_rel_error": info["estimated_max_rel_error"],
        "tol_met": info["tol_met"],
        "build_seconds": info["build_seconds"],
        "operator_mb": got.operator.nbytes() / 2**20,
        "peak_rss_mb": peak_rss_mb(),
    }
    lines = [
        f"{scene.name}: n = {p.n:,} patches, k = {got.operator.k}, {info['nz']:,} zone patches",
        f"{'loaded from cache' if got.from_cache else 'built'} in {got.seconds:.2f} s"
        f" ({result['operator_mb']:.0f} MB)",
        f"estimated relative error of C: {100 * info['estimated_rel_error']:.2f}% "
        f"(max {100 * info['estimated_max_rel_error']:.2f}%)",
        f"cache: {result['cache_path'] or 'disabled'}",
    ]
    _out(args, result, "\n".join(lines))
    return 0


def _source_summary(src, daylight) -> dict:
    u0, v0, u1, v1 = src.rect
    out = {
        "name": src.name,
        "zone": src.zone,
        "kind": src.kind,
        "corners": [min(u0, u1), min(v0, v1), max(u0, u1), max(v0, v1)],
        "area_m2": src.area,
    }
    if src.kind == SourceKind.SKYLIGHT:
        out["filter"] = src.filter
    else:
        out.update(flux_lm=source_flux(src, daylight), electric_w=source_electric_power(src))
    return out


def _solution_summary(sol, daylight) -> dict:
    out = {
        "objectives": dict(sol.objectives),
        "penalty": sol.penalty,
        "feasible": sol.feasible,
        "sources": [_source_summary(s, daylight) for s in sol.sources],
        "violations": [dataclasses.asdict(v) for v in sol.violations],
    }
    if sol.arrays:
        out["arrays"] = [_array_summary(a) for a in sol.arrays]
    return out


def _array_summary(a) -> dict:
    from lightinv_core.light.arrays import resolve_product

    prod = resolve_product(a.product, a.watts)
    return {
        "name": a.name,
        "zone": a.zone,
        "product": prod.name,
        "rows": a.rows,
        "columns": a.columns,
        "count": a.count,
        "spacing_m": list(a.spacing),
        "rotation": a.rotation,
        "dimming": a.dimming,
        "lumens_each": prod.lumens,
        "watts_each": prod.watts,
        "electric_w": a.count * prod.watts * a.dimming,
    }


def _daylight_summary(light, design, sol) -> dict:
    """The solution's daylight on the control work plane: DF (overcast), DA300, sDA, UDI
    and the dimming energy over the weather year (or why the year could not be read)."""
    from lightinv_core.light.daylight import layout_daylight

    lay = layout_daylight(light, design, sol.sources, sol.arrays)
    span = lay.grids.spans[lay.control]
    df = 100 * lay.points.overcast_daylight(span)[:, 0]
    out = {
        "workplane": lay.control,
        "df_mean": float(df.mean()),
        "df_median": float(np.median(df)),
        "df_min": float(df.min()),
    }
    try:
        da = lay.points.da(span)[:, 0]
        energy = lay.energy()
    except LightInvError as exc:
        out["annual_error"] = str(exc)
        return out
    year = lay.patches.year()
    for note in year.weather.get("notes", []):
        _warn(f"weather {Path(year.source).name}: {note}")
    out.update(
        site=year.site,
        weather=year.weather,
        da300_mean=float(da.mean()),
        sda300_50=float((da >= 0.5).mean()),
        udi_100_3000_mean=float(lay.points.udi(span)[:, 0].mean()),
        energy_kwh=energy.energy_kwh,
        full_output_kwh=energy.full_kwh,
        leni_kwh_m2=energy.leni,
        monthly_kwh=list(energy.monthly_kwh),
    )
    return out


def cmd_solve(args) -> int:
    """Optimise a project file; optionally save it with the results."""
    from dataclasses import replace

    from lightinv_core.optimize.quality import front_quality, front_scales
    from lightinv_core.project import load_project, save_project
    from lightinv_core.study import prepare, solve

    if args.output:
        check_writable(args.output)
    project = load_project(args.project)
    if args.resolution is not None:
        project = replace(project, scene=replace(project.scene, resolution=args.resolution))
    if args.method is not None:
        project = replace(project, optimizer=replace(project.optimizer, method=args.method))
    prepared = prepare(
        project, progress=_progress_printer("precompute"), warn=_warn, scheduler=args.scheduler
    )
    result = solve(
        project,
        prepared,
        seed=args.seed,
        max_evals=args.max_evals,
        time_limit=args.time_limit,
        progress=_vns_printer(),
        precompute=_progress_printer("luminaire responses") if project.design.arrays else None,
    )
    out = {
        "project": project.name,
        "status": result.status,
        "method": project.optimizer.method,
        "evaluations": result.evaluations,
        "seconds": result.seconds,
        "precompute_seconds": result.precompute_seconds,
        "operator_from_cache": prepared.from_cache,
        "patches": prepared.patches.n,
    }
    best = result.best
    if best is not None:
        primary = project.design.goals[0].kind
        out.update(
            objective=best.objectives.get(primary),
            objective_kind=primary,
            **_solution_summary(best, project.design.daylight),
        )
        if "match" in best.objectives:
            out["error"] = best.objectives["match"]
        if project.design.workplanes:
            from lightinv_core.light.grids import design_grids, grid_results

            grids = design_grids(prepared.light, project.design.workplanes)
            out["workplanes"] = grid_results(
                prepared.light, grids, best.sources, best.arrays, project.design.daylight
            )
            if any(s.kind == SourceKind.SKYLIGHT for s in best.sources):
                out["daylight"] = _daylight_summary(prepared.light, project.design, best)
    if result.pareto is not None:
        out["pareto"] = [
            _solution_summary(s, project.design.daylight) for s in result.pareto.solutions
        ]
        out["candidates"] = len(result.pareto.candidates)
        scales = front_scales(project.design, prepared.light)
        out["front_quality"] = front_quality(result.pareto.solutions, scales).to_dict()
    failed = ""
    if args.output:
        sols = (best,) if best is not None and result.pareto is None else ()
        solved = replace(project, solutions=sols, pareto=result.pareto)
        saved, failed = _write_or_rescue(
            "the project", args.output, lambda f: save_project(solved, f)
        )
        if not failed or saved != Path(args.output):
            out["saved"] = str(saved)
    _out(args, out, _solve_text(out))
    if failed:
        return _failed(failed)
    return 0 if result.status != "cancelled" else 130


def _solve_text(out: dict) -> str:
    lines = [
        f"{out['project']}: {out['status']} ({out['method']}, {out['evaluations']:,} "
        f"evaluations in {out['seconds']:.2f} s; operator {out['precompute_seconds']:.2f} s)"
    ]
    if out.get("objective") is not None:
        lines.append(
            f"{out['objective_kind']}: {out['objective']:.6g}   penalty {out['penalty']:.3g}"
        )
    for s in out.get("sources", []):
        c = ", ".join(f"{x:.3f}" for x in s["corners"])
        extra = (
            f"filter {s['filter']:.3f}"
            if s["kind"] == SourceKind.SKYLIGHT
            else f"{s['flux_lm']:.0f} lm, {s['electric_w']:.1f} W"
        )
        lines.append(f"  {s['name']:<10} {s['zone']:<10} ({c}) m  {s['area_m2']:.2f} m²  {extra}")
    for a in out.get("arrays", []):
        lines.append(
            f"  {a['name']:<10} {a['zone']:<10} {a['rows']} x {a['columns']} {a['product']} "
            f"(spacing {a['spacing_m'][0]:.2f} x {a['spacing_m'][1]:.2f} m, rotation "
            f"{a['rotation']}, dimming {a['dimming']:.2f})  {a['electric_w']:.1f} W"
        )
    for name, g in out.get("workplanes", {}).items():
        lines.append(
            f"  work plane {name}: Em {g['Em']:.0f} lux, Emin {g['Emin']:.0f} lux, "
            f"Emax {g['Emax']:.0f} lux, U0 {g['U0']:.2f} ({g['points']} points; luminaires "
            "placed exactly; skylights at the design exterior lux)"
        )
    if "daylight" in out:
        d = out["daylight"]
        lines.append(
            f"  daylight on {d['workplane']}: DF mean {d['df_mean']:.2f}%, median "
            f"{d['df_median']:.2f}%, min {d['df_min']:.2f}% (CIE overcast)"
        )
        if "annual_error" in d:
            lines.append(f"  annual daylight not computed: {d['annual_error']}")
        else:
            lines.append(
                f"  {d['site']}: DA300 mean {100 * d['da300_mean']:.0f}%, sDA300/50% "
                f"{100 * d['sda300_50']:.0f}%, UDI 100-3000 {100 * d['udi_100_3000_mean']:.0f}%; "
                f"dimmed lighting {d['energy_kwh']:.0f} kWh a year (full output "
                f"{d['full_output_kwh']:.0f} kWh), LENI {d['leni_kwh_m2']:.2f} kWh/m² a"
            )
    for v in out.get("violations", []):
        lines.append(
            f"  violated: {v['name']} {v['constraint']} by {100 * v['amount']:.1f}% "
            f"({v['value']:.4g} vs {v['bound']:.4g} {v['units']})"
        )
    if "pareto" in out:
        q = out["front_quality"]
        spread = "–" if q["spacing"] is None else f"{q['spacing']:.4f}"
        lines.append(
            f"Pareto front: {len(out['pareto'])} non-dominated of {out['candidates']} "
            f"candidates; hypervolume {q['hypervolume']:.4f}, spacing {spread} "
            "(normalised, docs/design.md)"
        )
        for s in out["pareto"]:
            o = s["objectives"]
            lines.append("  " + "   ".join(_goal_text(k, o.get(k, 0.0)) for k in q["objectives"]))
    if "saved" in out:
        lines.append(f"saved to {out['saved']}")
    return "\n".join(lines)


def _goal_text(kind: str, value: float) -> str:
    """A goal's value with its unit, as the front's lines show it."""
    from lightinv_core.goals import goal_spec

    return goal_spec(kind).value_text(value)


def _vns_printer():
    """A progress callback printing the best value on stderr (terminals only, 5 Hz)."""
    if not sys.stderr.isatty():
        return None
    last = [0.0]

    def report(p) -> None:
        if p.elapsed - last[0] >= 0.2:
            last[0] = p.elapsed
            print(
                f"\rlevel n/{p.level}: {p.evaluations:,} evaluations, best {p.best_goal:.6g}, "
                f"penalty {p.best_penalty:.3g}   ",
                end="",
                file=sys.stderr,
            )

    return report


def cmd_report(args) -> int:
    """Write a PDF report of a project's solution."""
    from lightinv_core.project import load_project
    from lightinv_core.report import write_report
    from lightinv_core.study import prepare

    check_writable(args.output)
    if args.png_dir:
        check_writable(Path(args.png_dir) / "page-1.png")
    project = load_project(args.project)
    prepared = prepare(project, progress=_progress_printer("precompute"), warn=_warn)
    info = write_report(
        project, prepared, args.output, png_dir=args.png_dir, progress=_progress_printer("report")
    )
    out = {
        "project": project.name,
        "report": str(info.path),
        "pages": list(info.pages),
        "png_files": [str(p) for p in info.png_files],
        "solution": info.solution,
        "feasible": info.feasible,
        "seconds": info.seconds,
        "operator_from_cache": prepared.from_cache,
    }
    state = "feasible" if info.feasible else "infeasible"
    text = (
        f"{info.path}: {len(info.pages)} pages ({info.solution}, {state}) in {info.seconds:.1f} s"
    )
    if info.png_files:
        text += f"\n{len(info.png_files)} PNG pages in {args.png_dir}"
    _out(args, out, text)
    return 0


class _Parser(argparse.ArgumentParser):
    """Usage errors as one line on stderr and exit status 2, like every other user error."""

    def error(self, message: str):
        self.exit(2, f"lightinv-cli: error: {self.prog}: {message} (see --help)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``lightinv-cli``."""
    ap = _Parser(prog="lightinv-cli", description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def add(name: str, fn, help_text: str) -> argparse.ArgumentParser:
        p = sub.add_parser(name, help=help_text, description=help_text)
        p.add_argument("--json", action="store_true", help="print one JSON object")
        p.set_defaults(func=fn)
        return p

    add("scenes", cmd_scenes, "list the built-in scenes")

    def scene_args(p: argparse.ArgumentParser) -> None:
        p.add_argument(
            "scene",
            help="built-in scene name or path to a model file (.obj, .gltf, .glb, .ply, .ifc)",
        )
        p.add_argument("--resolution", type=_positive, help="target patch size in metres")
        p.add_argument(
            "--materials", help="model files only: materials JSON (reflectance per group)"
        )
        p.add_argument(
            "--scale",
            type=_positive,
            default=1.0,
            help="model files only: metres per model unit (0.001 for millimetres)",
        )
        p.add_argument(
            "--up",
            choices=("z", "y"),
            default=None,
            help="model files only: up axis (default: y for glTF, z for the others)",
        )
        p.add_argument(
            "--skip-degenerate",
            action="store_true",
            help="model files only: drop zero-area faces (with a warning) instead of failing",
        )
        p.add_argument(
            "--group-by",
            choices=("node", "material"),
            default="node",
            help="glTF only: lighting groups named after nodes (default) or materials",
        )

    scene_args(add("scene-info", cmd_scene_info, "patches, groups and zones of a scene"))
    sim = add("simulate", cmd_simulate, "forward radiosity simulation")
    scene_args(sim)
    sim.add_argument(
        "--emit",
        type=_emit,
        action="append",
        default=[],
        metavar="GROUP=LUMENS",
        help="a group emitting this luminous flux (lm), uniformly over its area",
    )
    sim.add_argument(
        "--luminaires",
        metavar="CSV",
        help="photometric luminaires, one per row: name,x,y,z,ies,aim_x,aim_y,aim_z,"
        "c0_x,c0_y,c0_z[,dimming] (IES/LDT paths relative to the CSV; docs/photometry.md)",
    )
    sim.add_argument(
        "--workplane",
        type=_non_negative,
        nargs="?",
        const=DEFAULT_HEIGHT,
        metavar="HEIGHT",
        help=f"an EN 12464-1 grid this high above the floor (m; {DEFAULT_HEIGHT} if no value)",
    )
    sim.add_argument(
        "--border",
        type=_non_negative,
        help=f"work plane: band left out along the walls (m, default {DEFAULT_BORDER})",
    )
    sim.add_argument(
        "--workplane-group", default="floor", help="work plane: the floor group it lies over"
    )
    sim.add_argument("--grid-csv", metavar="FILE", help="work plane: write x,y,z,lux per point")
    sim.add_argument(
        "--sky",
        choices=("cie-overcast",),
        help="light the glazing groups with this sky (docs/daylight.md); adds df (%%) outputs",
    )
    sim.add_argument(
        "--exterior-lux",
        type=_lux,
        default=10000.0,
        help="unobstructed horizontal illuminance outside (lux, default 10000)",
    )
    sim.add_argument(
        "--glazing",
        type=_transmittance,
        action="append",
        default=[],
        metavar="GROUP=TRANSMITTANCE",
        help="a group of diffusing glazing and its visible transmittance (0 to 1)",
    )
    sim.add_argument(
        "--weather",
        metavar="FILE",
        help="EPW or TMY3 weather file ('builtin': Greensboro NC) for annual daylight on the "
        "work plane through the glazing (DA300, sDA, UDI; dimming energy with luminaires)",
    )
    sim.add_argument(
        "--north",
        type=_angle,
        default=0.0,
        help="compass bearing of the scene's +y axis (deg; 0: +y is north, 90: +y is east)",
    )
    sim.add_argument(
        "--occupancy",
        type=_hours,
        default=(8.0, 18.0),
        metavar="START-END",
        help="occupied hours on weekdays, local time (default 8-18)",
    )
    sim.add_argument(
        "--target-lux",
        type=_lux,
        default=500.0,
        help="dimming: the grid's mean illuminance to keep (lux, default 500)",
    )
    sim.add_argument(
        "--min-dimming",
        type=_fraction,
        default=0.1,
        help="dimming: lowest level of the luminaires (default 0.1)",
    )
    sim.add_argument(
        "--standby-w",
        type=_non_negative,
        default=0.0,
        help="dimming: standby power of the controls, drawn all year (W, default 0)",
    )
    sim.add_argument(
        "--ground-reflectance",
        type=_fraction,
        default=0.2,
        help="reflectance of the ground outside (default 0.2)",
    )
    sim.add_argument("--patches-csv", metavar="FILE", help="write one CSV row per patch")
    sim.add_argument(
        "--method",
        choices=("auto", "reference", "lrr"),
        default="auto",
        help=f"solver: reference (exact, sparse F) or lrr (the low-rank operator); "
        f"auto uses lrr above {AUTO_LRR_PATCHES} patches",
    )
    sol = add("solve", cmd_solve, "optimise a project file (inverse design)")
    sol.add_argument("project", help="project file (JSON, schema 1)")
    sol.add_argument("--seed", type=_seed, help="random seed (default: the project's)")
    sol.add_argument(
        "--method",
        choices=method_names(),
        help="optimisation method (default: the project's; docs/design.md compares them)",
    )
    sol.add_argument("--max-evals", type=_count, help="radiosity evaluations at most")
    sol.add_argument("--time-limit", type=_positive, help="seconds of optimisation at most")
    sol.add_argument("--resolution", type=_positive, help="override the scene's patch size (m)")
    sol.add_argument("-o", "--output", help="save the project with its results to this file")
    _scheduler_arg(sol)
    rep = add("report", cmd_report, "write a PDF report of a project's solution")
    rep.add_argument("project", help="project file holding results (lightinv-cli solve ... -o)")
    rep.add_argument("-o", "--output", required=True, help="PDF file to write")
    rep.add_argument("--png-dir", help="also save every page as a PNG in this folder")
    pre = add("precompute", cmd_precompute, "build or load the radiosity operator of a scene")
    scene_args(pre)
    for p in (sim, pre):
        p.add_argument(
            "--rays", type=_rays, default=DEFAULT_RAYS, help=f"rays per patch (1 to {MAX_RAYS:,})"
        )
        p.add_argument("--seed", type=_seed, default=0, help="random seed of the form factors")
        group = p.add_mutually_exclusive_group()
        group.add_argument("--rank", type=int, help="fix the low-rank operator's rank k")
        group.add_argument(
            "--tol",
            type=float,
            default=0.01,
            help="target relative error of C that chooses k (default 0.01)",
        )
        p.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
        _scheduler_arg(p)
    return ap


def _scheduler_arg(p: argparse.ArgumentParser) -> None:
    """--scheduler: build the operator on a Dask cluster (docs/cluster.md)."""
    p.add_argument(
        "--scheduler",
        type=_scheduler,
        metavar="tcp://HOST:PORT",
        help="build the radiosity operator on this Dask cluster (the cluster extra; "
        "docs/cluster.md): the same operator as a local build",
    )


def _scheduler(text: str) -> str:
    from lightinv_core.operator.distributed import check_scheduler

    try:
        return check_scheduler(text)
    except LightInvError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """Any Python warning (numpy's RuntimeWarning on a bad number) as one line on
    stderr, never the source line of a library: a number the engine did not catch."""
    _warn(f"warning: {category.__name__}: {message} (please report it with the input used)")


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the process exit status."""
    try:
        args = build_parser().parse_args(argv)
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            return args.func(args)
    except (LightInvError, OSError) as exc:
        print(f"lightinv-cli: error: {exc}", file=sys.stderr)
        return 2
    except (KeyboardInterrupt, CancelledError):
        print("lightinv-cli: cancelled", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
