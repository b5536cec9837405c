"""The text ``solve`` prints: the run, the solution's sources, arrays, work planes,
daylight, violations and front."""

from __future__ import annotations

from lightinv_core.climate.control_modes import control_text
from lightinv_core.value_text import goal_value, source_line, u0_text


def solve_text(out: dict) -> str:
    lines = [
        f"{out['project']}: {out['status']} ({out['method']}, {out['evaluations']:,} "
        f"evaluations in {out['seconds']:.2f} s; operator {out['precompute_seconds']:.2f} s)"
    ]
    if out.get("objective") is not None:
        lines.append(
            f"{out['objective_kind']}: {out['objective']:.6g}   penalty {out['penalty']:.3g}"
        )
    lines += [f"  {source_line(s)}" for s in out.get("sources", [])]
    for a in out.get("arrays", []):
        lines.append(
            f"  {a['name']:<10} {a['zone']:<10} {a['rows']} x {a['columns']} {a['product']} "
            f"(spacing {a['spacing_m'][0]:.2f} x {a['spacing_m'][1]:.2f} m, rotation "
            f"{a['rotation']}, dimming {a['dimming']:.2f})  {a['electric_w']:.1f} W"
        )
    for name, g in out.get("workplanes", {}).items():
        lines.append(
            f"  work plane {name}: Em {g['Em']:.0f} lux, Emin {g['Emin']:.0f} lux, "
            f"Emax {g['Emax']:.0f} lux, U0 {u0_text(g['U0'])} ({g['points']} points; luminaires "
            "placed exactly; skylights at the design exterior lux)"
        )
    for name, g in out.get("calc_objects", {}).items():
        s = g["symbol"]
        lines.append(
            f"  {name}: {s} mean {g['Em']:.0f} lux, min {g['Emin']:.0f} lux, max "
            f"{g['Emax']:.0f} lux, U0 {u0_text(g['U0'])} ({g['points']} points)"
        )
    if out.get("ugr"):
        each = ", ".join(f"{v:.1f} at {name}" for name, v in out["ugr"].items())
        lines.append(f"  glare: UGR {each} (CIE 117; luminaires placed exactly, as new)")
    if "daylight" in out:
        d = out["daylight"]
        lines.append(
            f"  daylight on {d['workplane']}: DF mean {d['df_mean']:.2f}%, median "
            f"{d['df_median']:.2f}%, min {d['df_min']:.2f}% (CIE overcast)"
        )
        if "annual_error" in d:
            lines.append(f"  annual daylight not computed: {d['annual_error']}")
        else:
            ase = f", ASE1000,250 {100 * d['ase1000_250']:.0f}%" if "ase1000_250" in d else ""
            if "sky_patches" in d:  # clear glazing: the sky's patches it was traced on
                ase += f" (clear glazing, sky in {d['sky_patches']:,} patches)"
            lines.append(
                f"  {d['site']}: DA300 mean {100 * d['da300_mean']:.0f}%, sDA300/50% "
                f"{100 * d['sda300_50']:.0f}%, UDI 100-3000 {100 * d['udi_100_3000_mean']:.0f}%"
                f"{ase}; "
                f"dimmed lighting {d['energy_kwh']:.0f} kWh a year (full output "
                f"{d['full_output_kwh']:.0f} kWh), LENI {d['leni_kwh_m2']:.2f} kWh/m² a"
            )
            for g in d.get("control_groups", []):
                how = ""  # results saved before modes and targets were kept say none
                if "mode" in g and "target_lux" in g:
                    how = f"; {control_text(g['mode'], g['target_lux'], g.get('dead_band', 0))}"
                lines.append(
                    f"    control group {g['name']}: {g['luminaires']} luminaires, "
                    f"{g['watts']:.0f} W, sensor {g['sensor_points']} points, mean level "
                    f"{100 * g['mean_level']:.0f}%, {g['energy_kwh']:.1f} kWh a year, "
                    f"LENI {g['leni']:.2f} kWh/m² a{how}"
                )
            p = d.get("en17037_provision")
            if p:
                where = "of the plane in half the daylight hours"
                if p.get("basis") == "hours":
                    where = "of the daylight hours on half the plane (the hours basis)"
                lines.append(
                    f"  EN 17037 daylight provision on {d['workplane']}: {p['level']} (score "
                    f"{p['score']:.2f}; E_T 300/500/750 lux reached on "
                    f"{100 * p['minimum_300']:.0f}/{100 * p['medium_500']:.0f}/"
                    f"{100 * p['high_750']:.0f}% {where})"
                )
            for name, sun in d.get("en17037_sunlight", {}).items():
                lines.append(
                    f"  EN 17037 sunlight exposure at {name} on {sun['date']}: "
                    f"{sun['hours']:.2f} h ({sun['level']})"
                )
            for name, g in d.get("dgp_observers", {}).items():
                lines.append(
                    f"  simplified DGP at {name}: above {g['limit']:.2f} in "
                    f"{100 * g['exceedance']:.1f}% of the {g['hours']:,} occupied hours "
                    f"(max {g['dgp_max']:.2f}); EN 17037 glare protection {g['en17037_glare']}"
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
            lines.append("  " + "   ".join(goal_value(k, o.get(k, 0.0)) for k in q["objectives"]))
    if "saved" in out:
        lines.append(f"saved to {out['saved']}")
    return "\n".join(lines)
