"""The report's tables as data: sources, geometric rules, lighting intentions, groups.

Each table is a ``Table`` of already formatted strings (what the PDF shows), so the
numbers in the report can be checked against these functions' output. Units are in
the column headers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightinv_core.design.geometry import rule_names, rule_violations
from lightinv_core.design.model import Design, Source
from lightinv_core.design.solution import Solution
from lightinv_core.design.variables import array_layout
from lightinv_core.kinds import Bound, Quantity, SourceKind
from lightinv_core.light.arrays import array_shapes
from lightinv_core.light.field import LightField
from lightinv_core.scene.patches import Patches
from lightinv_core.scene.zone_grid import zone_grid
from lightinv_core.sources.emission import source_electric_power, source_flux

PASS, FAIL = "pass", "FAIL"

OBJECTIVES = {
    "min_electric_power": ("Electric power", "W"),
    "max_light_power": ("Reflected light power", "lm"),
    "match": ("Match error e", ""),
}


@dataclass(frozen=True)
class Table:
    """A titled table of strings; ``flags`` marks rows "pass", "fail" or "" (colouring)."""

    title: str
    columns: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    flags: tuple[str, ...] = ()
    note: str = ""

    def __post_init__(self) -> None:
        if not self.flags:
            object.__setattr__(self, "flags", ("",) * len(self.rows))


def fmt(value: float | None, digits: int = 4) -> str:
    """A number for the tables: ``digits`` significant digits below 1,000, whole numbers
    with thousands separators above, "—" for a missing or undefined value."""
    if value is None or math.isnan(float(value)):
        return "—"
    v = float(value)
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    if abs(float(f"{v:.{digits}g}")) >= 10 ** (digits - 1):
        return f"{v:,.0f}"
    return f"{v:.{digits}g}"


def fmt_corners(s: Source) -> str:
    """The rectangle's lower and upper corners in zone (u, v) metres: "(u0, v0)–(u1, v1)"."""
    (a, b), (c, d) = s.u_range, s.v_range
    return f"({a:.2f}, {c:.2f})–({b:.2f}, {d:.2f})"


def objective_text(kind: str, value: float) -> str:
    """ "Electric power: 123.4 W" and the like."""
    name, units = OBJECTIVES.get(kind, (kind, ""))
    return f"{name}: {fmt(value)}{' ' + units if units else ''}"


def source_table(solution: Solution, design: Design) -> Table:
    """One row per source: zone, corners, size and area, flux or filter, electric power."""
    rows = []
    total_w = 0.0
    for s in solution.sources:
        w, h = s.size
        if s.kind == SourceKind.SKYLIGHT:
            setting = f"filter {s.filter:.3f}"
            power = "—"
        else:
            setting = f"{fmt(s.flux)} lm" if s.flux is not None else f"{fmt(s.exitance)} lm/m²"
            watts = source_electric_power(s)
            total_w += watts
            power = fmt(watts)
        rows.append(
            (
                s.name,
                s.kind,
                s.zone,
                fmt_corners(s),
                f"{w:.2f} x {h:.2f}",
                f"{s.area:.2f}",
                setting,
                fmt(source_flux(s, design.daylight)),
                power,
            )
        )
    note = (
        f"Total electric power {fmt(total_w)} W."
        if any(s.kind == SourceKind.LUMINAIRE for s in solution.sources)
        else ""
    )
    return Table(
        "Sources",
        (
            "source",
            "kind",
            "zone",
            "corners (u, v) m",
            "size m",
            "area m²",
            "flux / filter",
            "emitted lm",
            "electric W",
        ),
        tuple(rows),
        note=note,
    )


def rules_table(solution: Solution, design: Design, patches: Patches) -> Table | None:
    """Every checked geometric rule (and epsilon bound) with pass/fail; None when the
    design has no rule and the solution no epsilon bound."""
    rows, flags = [], []
    names = [s.name for s in design.sources]
    by_name = {s.name: s for s in solution.sources}
    arrays_ok = len(solution.arrays) == len(design.arrays)
    if design.rules and all(n in by_name for n in names) and arrays_ok:
        rect = np.array([[by_name[n].rect for n in names]], dtype=float).reshape(1, -1, 4)
        size = np.array([zone_grid(patches, s.zone).size for s in design.sources])
        arrays = None
        if design.arrays:
            arrays = (
                array_layout(solution.arrays),
                array_shapes(patches, solution.arrays, design.workplanes),
            )
        outlines = [patches.zone_outline(s.zone) for s in design.sources]
        amounts = rule_violations(design, rect, size.reshape(-1, 2), arrays, outlines)[0]
        for name, amount in zip(rule_names(design), amounts, strict=True):
            ok = amount <= 0
            rows.append((name, "geometry", PASS if ok else f"{FAIL} ({fmt(amount, 3)})"))
            flags.append("pass" if ok else "fail")
        for r in design.rules:
            if r.kind in ("mirror", "centred"):
                rows.append((f"{r.kind} {','.join(r.sources)}", "tie", "holds (tied)"))
                flags.append("pass")
    else:
        for v in solution.violations:
            if v.constraint == "geometry":
                rows.append((v.name, "geometry", f"{FAIL} ({fmt(v.amount, 3)})"))
                flags.append("fail")
    for v in solution.violations:
        if v.constraint == "epsilon":
            sign = "≥" if "light" in v.name else "≤"
            rows.append(
                (
                    f"{v.name} {sign} {fmt(v.bound)} {v.units}",
                    "epsilon",
                    f"{FAIL} ({fmt(v.value)} {v.units})",
                )
            )
            flags.append("fail")
    eps = solution.info.epsilon
    if eps is not None and not any(v.constraint == "epsilon" for v in solution.violations):
        rows.append((f"light power ≥ {fmt(eps)} lm", "epsilon", PASS))
        flags.append("pass")
    if not rows:
        return None
    return Table("Geometric rules", ("rule", "type", "result"), tuple(rows), tuple(flags))


def intention_table(solution: Solution, design: Design, field: LightField) -> Table | None:
    """One row per bound of every lighting intention: required vs achieved and pass/fail.

    The achieved values come from the solution's light ``field``; pass/fail is the
    solution's own verdict (its violations) when its intentions were judged (finite
    penalty), else the verdict of the field, with the same 0.1% tolerance. Intentions on
    work-plane grids have their own table (``report/luminaires.py``).
    """
    patch_intentions = [it for it in design.intentions if it.grid is None]
    if not patch_intentions:
        return None
    judged = math.isfinite(solution.penalty)
    failed = {(v.name, v.constraint) for v in solution.violations}
    rows, flags = [], []
    for it in patch_intentions:
        res = field.intention(it)
        st = res.stats
        u0 = float(st.uniformity[0]) if st.average[0] > 0 else float("nan")
        units = "lux" if it.quantity == Quantity.LUX else "lm/m²"
        where = {None: f"{len(res.patches)} picked", "*": "all"}.get(it.group, it.group)
        stats = f"{fmt(st.min[0])} / {fmt(st.average[0])} / {fmt(st.max[0])}"
        for chk in res.checks:
            bad = (it.name, chk.bound) in failed if judged else not chk.met[0]
            c = float(chk.c[0])
            u = "" if chk.bound == Bound.UNIFORMITY else f" {units}"
            label = "U0" if chk.bound == Bound.UNIFORMITY else str(chk.bound)
            sign = "≤" if chk.bound == Bound.MAX else "≥"
            rows.append(
                (
                    it.name,
                    where,
                    f"{label} {sign} {fmt(chk.limit)}{u}",
                    f"{fmt(chk.value[0])}{u}",
                    stats + f" {units}",
                    fmt(u0, 3),
                    f"{FAIL} ({100 * max(c, 0):.1f}%)" if bad else PASS,
                )
            )
            flags.append("fail" if bad else "pass")
    return Table(
        "Lighting intentions",
        ("intention", "patches", "required", "achieved", "min / avg / max", "U0", "result"),
        tuple(rows),
        tuple(flags),
        note="Averages are area-weighted; U0 = min / average. FAIL gives how far past the "
        "bound, relative to it; a bound met to within 0.1% passes.",
    )


def group_table(field: LightField) -> Table:
    """Illuminance (lux) per lighting group: area, min, area-weighted average, max, U0."""
    rows = []
    patches = field.patches
    for gid, name in enumerate(patches.group_names):
        idx = np.flatnonzero(patches.group_id == gid)
        if len(idx) == 0:
            continue
        st = field.group_stats(name)
        avg = float(st.average[0])
        rows.append(
            (
                name,
                str(len(idx)),
                f"{patches.area[idx].sum():.1f}",
                fmt(st.min[0]),
                fmt(avg),
                fmt(st.max[0]),
                fmt(st.uniformity[0], 3) if avg > 0 else "—",
            )
        )
    return Table(
        "Illuminance per group",
        ("group", "patches", "area m²", "min lux", "average lux", "max lux", "U0"),
        tuple(rows),
    )
