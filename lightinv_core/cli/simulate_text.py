"""The text ``simulate`` prints beyond the tables: the luminaires and the annual
daylight."""

from __future__ import annotations


def annual_lines(a: dict) -> list[str]:
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


def luminaire_summary(luminaires) -> list[dict]:
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
