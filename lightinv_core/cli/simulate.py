"""``simulate``: a forward simulation. The arguments become a ``SimulationSpec``,
``study.simulate`` runs it, and the result is printed as text or JSON, with the patch
and grid values written to CSV files when asked."""

from __future__ import annotations

from lightinv_core.atomic import check_writable
from lightinv_core.cli.output import failed, out, progress_printer, warn, write_or_rescue
from lightinv_core.cli.scenes import scene_of
from lightinv_core.cli.simulate_text import grid_columns, lrr_payload, reference_payload
from lightinv_core.design.model import Daylight
from lightinv_core.errors import LightInvError
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.sources.luminaire_csv import read_luminaire_csv
from lightinv_core.study import SimulationResult, SimulationSpec, simulate
from lightinv_core.transport.photometry import write_patch_csv
from lightinv_core.transport.point_sets import UP, PointSet, read_points_csv
from lightinv_core.transport.scene_light import write_grid_csv
from lightinv_core.transport.workplane import DEFAULT_BORDER, WorkPlane


def check_args(args) -> None:
    """LightInvError naming the options to give when the arguments do not make a
    simulation (nothing emits, a sky without glazing, a year without a work plane)."""
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
    if args.weather is not None and args.workplane is None and args.hour is None:
        raise LightInvError("annual daylight is measured on a work plane: add --workplane 0.8")
    if args.hour is not None and args.weather is None:
        raise LightInvError("--hour is an hour of a weather file: give --weather FILE")
    if args.sky == "cie-clear" and args.sun is None:
        raise LightInvError("the CIE clear sky needs the sun: give --sun ALTITUDE,AZIMUTH")
    if args.sun is not None and args.sky != "cie-clear":
        raise LightInvError("--sun places the CIE clear sky's sun: give --sky cie-clear")
    clear = [g for g, _, kind in args.glazing if kind == "clear"]
    annual_only = (args.view or args.sunlight_point) and args.weather is None
    if annual_only:
        raise LightInvError("--view and --sunlight-point are studied over a year: give --weather")
    if (args.view or args.sunlight_point) and args.hour is not None:
        raise LightInvError(
            "--view and --sunlight-point are studied over the whole year: leave out --hour"
        )
    if (args.sensor or args.group_control) and not args.luminaires:
        what = "--sensor" if args.sensor else "--group-control"
        raise LightInvError(f"{what} controls a group of luminaires: give --luminaires")
    if args.sunlight_point and args.sunlight_min_altitude is None:
        raise LightInvError(
            "EN 17037 counts the sun above a minimum altitude set for the site (the "
            "standard's national values): give --sunlight-min-altitude DEG"
        )
    if (args.view or args.sunlight_point) and not clear:
        raise LightInvError(
            "glare and sunlight exposure need clear glazing: give --glazing GROUP=TAU:clear"
        )
    if args.points and any(kind == "clear" for _, _, kind in args.glazing):
        raise LightInvError(
            "--points reads the light of luminaires, emitting groups and diffusing glazing; "
            "clear glazing's view of the sky at free points is not done: use a work plane"
        )
    if args.workplane is None and (args.grid_csv or args.border is not None):
        raise LightInvError("--grid-csv and --border describe a work plane: add --workplane 0.8")


def spec_of(args) -> SimulationSpec:
    """The simulation the arguments describe (luminaire schedule and scene read)."""
    luminaires = read_luminaire_csv(args.luminaires) if args.luminaires else []
    scene = scene_of(args)
    plane = None
    if args.workplane is not None:
        border = DEFAULT_BORDER if args.border is None else args.border
        plane = WorkPlane(args.workplane, border, args.workplane_group)
    points = None
    if args.points:
        pts, normals = read_points_csv(args.points)
        points = PointSet(pts, UP if normals is None else normals)
    annual = None
    if args.weather is not None:
        annual = Daylight(
            weather=args.weather,
            north_deg=args.north,
            occupancy=args.occupancy,
            weekdays=not args.all_days,
            ground_reflectance=args.ground_reflectance,
            target_lux=args.target_lux,
            min_level=args.min_dimming,
            standby_w=args.standby_w,
        )
    return SimulationSpec(
        scene,
        emit=dict(args.emit),
        luminaires=tuple(luminaires),
        glazing={g: t for g, t, _ in args.glazing},
        glazing_kinds={g: kind for g, _, kind in args.glazing},
        sky=args.sky,
        sun=args.sun,
        sun_lux=args.sun_lux,
        hour=args.hour,
        north_deg=args.north,
        views=tuple(args.view),
        sunlight_point=args.sunlight_point,
        sunlight_date=args.sunlight_date,
        sunlight_min_altitude=args.sunlight_min_altitude,
        sky_mf=args.sky_subdivision,
        sensors=dict(args.sensor),
        group_modes={g: m for g, m, _, _ in args.group_control},
        group_targets={g: t for g, _, t, _ in args.group_control if t is not None},
        group_bands={g: b for g, _, _, b in args.group_control if b > 0},
        exterior_lux=args.exterior_lux,
        ground_reflectance=args.ground_reflectance,
        workplane=plane,
        edition=f"EN 12464-1:{args.edition}",
        points=points,
        annual=annual,
        rays=args.rays,
        seed=args.seed,
        method=args.method,
        operator=OperatorSettings(tol=args.tol, rank=args.rank, rays=args.rays, seed=args.seed),
        use_cache=not args.no_cache,
        scheduler=args.scheduler,
    )


def cmd_simulate(args) -> int:
    """Forward simulation: groups emit given fluxes, photometric luminaires shine, a sky
    lights the glazing; report illuminance per group and on a work-plane grid."""
    check_args(args)
    for path in (args.patches_csv, args.grid_csv):
        if path:
            check_writable(path)
    spec = spec_of(args)
    res = simulate(
        spec,
        formfactor_progress=progress_printer("form factors"),
        operator_progress=progress_printer("precompute"),
        warn=warn,
    )
    for note in res.weather_notes:
        warn(note)
    for w in res.warnings:
        warn(w)
    for w in res.photometry_warnings:
        warn(f"warning: {w}")
    if res.method == "lrr":
        payload, lines = lrr_payload(res)
    else:
        payload, lines = reference_payload(res, spec)
    problems = _write_csvs(args, res, payload, lines)
    out(args, payload, "\n".join(lines))
    return failed("; ".join(m for m in problems if m))


def _write_csvs(args, res: SimulationResult, payload: dict, lines: list[str]) -> list[str]:
    """Write the patch and grid CSVs asked for (rescued elsewhere when the place fails);
    where they went goes into ``payload`` and ``lines``. Returns the failure messages."""
    problems = []
    if args.patches_csv:
        where, msg = write_or_rescue(
            "patch values",
            args.patches_csv,
            lambda f: write_patch_csv(f, res.lit, res.E, res.B, res.H, res.df_patches),
        )
        problems.append(msg)
        payload["patches_csv"] = str(where)
        lines.append(f"patch values written to {where}")
    if args.grid_csv:
        columns = grid_columns(res)
        where, msg = write_or_rescue(
            "grid values",
            args.grid_csv,
            lambda f: write_grid_csv(f, res.grid.points, res.grid_lux, columns),
        )
        problems.append(msg)
        payload["grid_csv"] = str(where)
        lines.append(f"grid values written to {where}")
    return problems
