"""The report's table of calculation objects: each object's values against its criteria.

One row per object (task area, wall or ceiling surface, cylindrical or semi-cylindrical
points, free points): what it reads (E, Ez, Esc), its points, mean, min, max and U0 in
the design scenario (maintained, the luminaires placed exactly), and the bounds of the
intentions that name it with their verdicts, each judged in its own scenario
(``LayoutDaylight.checks``).
"""

from __future__ import annotations

from lightinv_core.design.model import Design
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import bound_sign
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.grids import DesignGrids
from lightinv_core.report.tables import EN_LABELS, FAIL, PASS, Table
from lightinv_core.transport.workplane import grid_statistics
from lightinv_core.value_text import fmt, u0_text


def calc_table(
    design: Design, grids: DesignGrids, lux, daylight: LayoutDaylight | None = None
) -> Table | None:
    """The calculation objects' values (``lux``: at ``grids.points``, design scenario)
    and their intentions' verdicts (None without objects)."""
    if not design.calc_objects:
        return None
    rows, flags = [], []
    for obj in design.calc_objects:
        st = grid_statistics(lux[grids.calc_spans[obj.name]])
        asks = [it for it in design.intentions if it.grid == obj.name]
        required, verdicts = [], []
        for it in asks:
            try:
                checks = daylight.checks(it) if daylight is not None else []
            except LightInvError:
                checks = []
            for chk in checks:
                label = EN_LABELS.get(chk.bound, str(chk.bound))
                if label.startswith("E"):
                    label = obj.spec.symbol + label[1:]
                text = f"{label} {bound_sign(chk.bound)} {fmt(chk.limit)}"
                if str(it.scenario) != "design":
                    text += f" ({it.scenario})"
                required.append(text)
                verdicts.append(bool(chk.met[0]))
        verdict = "—" if not verdicts else PASS if all(verdicts) else FAIL
        sym = obj.spec.symbol
        rows.append(
            (
                obj.name,
                f"{obj.spec.label} ({sym})",
                str(st["points"]),
                fmt(st["Em"]),
                fmt(st["Emin"]),
                fmt(st["Emax"]),
                u0_text(st["U0"]),
                ", ".join(required) or "—",
                verdict,
            )
        )
        flags.append({PASS: "pass", FAIL: "fail"}.get(verdict, ""))
    note = (
        "Illuminance in lux at each object's points, maintained, the luminaires placed "
        "exactly, in the design scenario: E on the object's front (horizontal on a task "
        "area), Ez the mean vertical illuminance around a point (32 directions), Esc = Ez "
        "+ (Ev facing - Ev behind) / pi. Criteria are judged in their own scenario; a "
        "bound met to within 0.1% passes."
    )
    return Table(
        "Calculation objects",
        ("object", "kind", "points", "mean", "min", "max", "U0", "required", "result"),
        tuple(rows),
        tuple(flags),
        note=note,
    )
