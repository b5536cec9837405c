"""``solve``: optimise a project file (inverse design), print the solution, optionally
save the project with its results."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np

from lightinv_core.atomic import check_writable
from lightinv_core.cli.output import failed, out, progress_printer, warn, write_or_rescue
from lightinv_core.cli.solve_text import solve_text
from lightinv_core.design.model import Design
from lightinv_core.design.solution import Solution
from lightinv_core.errors import LightInvError
from lightinv_core.light.en17037_plane import plane_figures
from lightinv_core.light.glare import layout_glare
from lightinv_core.light.model import LightModel
from lightinv_core.quantities import quantity_spec
from lightinv_core.sources.types import daylit
from lightinv_core.study import SolutionLight, solution_light
from lightinv_core.value_text import source_summary


def _solution_summary(sol, daylight) -> dict:
    out = {
        "objectives": dict(sol.objectives),
        "penalty": sol.penalty,
        "feasible": sol.feasible,
        "sources": [source_summary(s, daylight) for s in sol.sources],
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


def daylight_summary(light: LightModel, design: Design, sol: Solution) -> dict:
    """A solution's daylight on the control work plane: DF (overcast), DA300, sDA, UDI
    and the dimming energy over the weather year (or why the year could not be read)."""
    lay = SolutionLight(light, design, sol.sources, sol.arrays).daylight
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
        warn(f"weather {Path(year.source).name}: {note}")
    out.update(
        site=year.site,
        weather=year.weather,
        da300_mean=float(da.mean()),
        sda300_50=float((da >= 0.5).mean()),
        udi_100_3000_mean=float(lay.points.udi(span)[:, 0].mean()),
        cda300_mean=float(lay.points.cda(span)[:, 0].mean()),
        energy_kwh=energy.energy_kwh,
        full_output_kwh=energy.full_kwh,
        leni_kwh_m2=energy.leni,
        monthly_kwh=list(energy.monthly_kwh),
    )
    if energy.groups:  # several daylight-linked control groups, each on its own sensor
        out["control_groups"] = [g.as_dict() for g in energy.groups]
    out["en17037_provision"] = plane_figures(lay.points, span)
    if lay.sunlit:  # EN 17037 sunlight exposure at the observers its intentions name
        out["en17037_sunlight"] = lay.sunlit
    if lay.glared:  # simplified DGP at the observers its intentions name
        out["dgp_observers"] = lay.glared
    if lay.points.clear is not None:  # clear glazing lets the sun's beam in
        from lightinv_core.kinds import Quantity
        from lightinv_core.quantities import quantity_spec

        ase = lay.points.band(quantity_spec(Quantity.ASE).hours, span)[:, 0]
        out["ase1000_250"] = float(ase.mean())
        mf = design.daylight.sky_subdivision  # Reinhart's MF of its sky patches
        out["sky_patches"] = 144 * mf * mf + 1
    return out


def cmd_solve(args) -> int:
    """Optimise a project file; optionally save it with the results."""
    from dataclasses import replace

    from lightinv_core.optimize.quality import front_quality, front_scales
    from lightinv_core.optimize.registry import check_applies
    from lightinv_core.project import load_project, save_project
    from lightinv_core.study import prepare, solve

    if args.output:
        check_writable(args.output)
    project = load_project(args.project)
    if args.resolution is not None:
        project = replace(project, scene=replace(project.scene, resolution=args.resolution))
    if args.method is not None:
        project = replace(project, optimizer=replace(project.optimizer, method=args.method))
    # A method that cannot run on this design (NSGA-II with one goal) is refused before
    # the operator is computed, naming the methods that can.
    check_applies(project.optimizer.method, project.design)
    prepared = prepare(
        project, progress=progress_printer("precompute"), warn=warn, scheduler=args.scheduler
    )
    result = solve(
        project,
        prepared,
        seed=args.seed,
        max_evals=args.max_evals,
        time_limit=args.time_limit,
        progress=vns_printer(),
        precompute=progress_printer("luminaire responses") if project.design.arrays else None,
    )
    summary = {
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
        summary.update(
            objective=best.objectives.get(primary),
            objective_kind=primary,
            **_solution_summary(best, project.design.daylight),
        )
        if "match" in best.objectives:
            summary["error"] = best.objectives["match"]
        light = solution_light(prepared, project.design, best)
        if project.design.calc_objects:
            symbols = {c.name: c.spec.symbol for c in project.design.calc_objects}
            summary["calc_objects"] = {
                n: {**v, "symbol": symbols[n]} for n, v in light.calc_stats.items()
            }
        if project.design.workplanes:
            summary["workplanes"] = light.grid_stats
            if daylit(best.sources):
                summary["daylight"] = daylight_summary(prepared.light, project.design, best)
        rated = [i for i in project.design.intentions if i.observers]
        if any(quantity_spec(i.quantity).from_glare for i in rated):  # UGR, not DGP or sun
            summary["ugr"] = layout_glare(prepared.light, project.design, best.sources, best.arrays)
    if result.pareto is not None:
        summary["pareto"] = [
            _solution_summary(s, project.design.daylight) for s in result.pareto.solutions
        ]
        summary["candidates"] = len(result.pareto.candidates)
        pair = result.pareto.objectives
        scales = front_scales(project.design, prepared.light, pair)
        quality = front_quality(result.pareto.solutions, scales, pair)
        summary["front_quality"] = quality.to_dict()
    problem = ""
    if args.output:
        sols = (best,) if best is not None and result.pareto is None else ()
        solved = replace(project, solutions=sols, pareto=result.pareto)
        saved, problem = write_or_rescue(
            "the project", args.output, lambda f: save_project(solved, f)
        )
        if not problem or saved != Path(args.output):
            summary["saved"] = str(saved)
    out(args, summary, solve_text(summary))
    if problem:
        return failed(problem)
    return 0 if result.status != "cancelled" else 130


def vns_printer():
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
