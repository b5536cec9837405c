"""The report's tables as data: sources, geometric rules, lighting intentions, groups.

Each table is a ``Table`` of already formatted strings (what the PDF shows), so the
numbers in the report can be checked against these functions' output. Units are in
the column headers; values are written by ``lightinv_core.value_text``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lightinv_core.design.geometry import rule_names, rule_violations
from lightinv_core.design.model import Design, Source
from lightinv_core.design.solution import Solution
from lightinv_core.design.variables import array_layout
from lightinv_core.errors import LightInvError
from lightinv_core.goals import bounded_goal, goal_spec, goal_specs
from lightinv_core.kinds import Bound, Scenario
from lightinv_core.light.arrays import Product, array_shapes, resolve_product
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.field import LightField
from lightinv_core.light.intentions import (
    BoundCheck,
    bounds_set,
    intention_stats,
)
from lightinv_core.quantities import quantity_spec
from lightinv_core.scenarios import scenario_specs
from lightinv_core.scene.patches import Patches
from lightinv_core.scene.zone_grid import zone_grid
from lightinv_core.sources.emission import source_electric_power, source_flux
from lightinv_core.sources.types import electric, source_type
from lightinv_core.value_text import (
    bound_text,
    bound_value,
    fmt,
    source_setting,
    u0_text,
)

# Written in value_text, still importable from here (tests/core/test_extension_points.py).
from lightinv_core.value_text import goal_label as goal_label
from lightinv_core.value_text import objective_text as objective_text

PASS, FAIL = "pass", "FAIL"

EN_LABELS = {
    Bound.AVERAGE: "Em",
    Bound.MIN: "Emin",
    Bound.MAX: "Emax",
    Bound.UNIFORMITY: "U0",
    Bound.MAX_AVERAGE: "Em",
}
"""EN 12464-1's name of each bound of a lux intention on a work plane's grid."""


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


SHORT_NAME = 36
"""A product name longer than this (an IES file's luminaire description) is replaced by
its catalogue number or file name where space is short."""


def product_title(p: Product) -> str:
    """A product's name for tables and headings: its name, or when that is a long
    description, the manufacturer's catalogue number (else the file's name)."""
    if len(p.name) <= SHORT_NAME:
        return p.name
    ph = p.photometry
    return ph.catalogue_number or (Path(ph.source).stem if ph.source else p.name[:SHORT_NAME])


def fmt_corners(s: Source) -> str:
    """The rectangle's lower and upper corners in zone (u, v) metres: "(u0, v0)–(u1, v1)"."""
    (a, b), (c, d) = s.u_range, s.v_range
    return f"({a:.2f}, {c:.2f})–({b:.2f}, {d:.2f})"


def source_table(solution: Solution, design: Design) -> Table:
    """One row per source and per luminaire array: zone, corners, size and area, flux or
    filter (an array: its rows x columns of which product), emitted flux, electric
    power."""
    rows = []
    total_w = 0.0
    for s in solution.sources:
        w, h = s.size
        power = "—"
        if source_type(s.kind).electric:
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
                source_setting(s),
                fmt(source_flux(s, design.daylight)),
                power,
            )
        )
    for a in solution.arrays:
        p = resolve_product(a.product, a.watts)
        u0, v0, u1, v1 = a.rect
        watts = a.count * p.watts * a.dimming
        total_w += watts
        rows.append(
            (
                a.name,
                "luminaire array",
                a.zone,
                f"({u0:.2f}, {v0:.2f})–({u1:.2f}, {v1:.2f})",
                f"{abs(u1 - u0):.2f} x {abs(v1 - v0):.2f}",
                f"{abs(u1 - u0) * abs(v1 - v0):.2f}",
                f"{a.rows} x {a.columns} {product_title(p)}"
                + (f" at {100 * a.dimming:.0f}%" if a.dimming < 1 else ""),
                fmt(a.count * p.lumens * a.dimming),
                fmt(watts),
            )
        )
    note = (
        f"Total electric power {fmt(total_w)} W."
        if electric(solution.sources) or solution.arrays
        else ""
    )
    if solution.arrays:
        note += " An array's row is the rectangle its luminaires fill evenly."
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


def _epsilon_maximised(name: str) -> bool:
    """Whether the goal an epsilon bound named ``name`` is on is maximised: the judge
    names it by the goal's label ("epsilon reflected light power"); files saved before
    named it by the goal's kind ("epsilon max_light_power")."""
    for g in goal_specs():
        if name in (f"epsilon {g.label.lower()}", f"epsilon {g.kind}"):
            return g.maximise
    return False


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
            sign = "≥" if _epsilon_maximised(v.name) else "≤"
            rows.append(
                (
                    f"{v.name} {sign} {fmt(v.bound)} {v.units}",
                    "epsilon",
                    f"{FAIL} ({fmt(v.value)} {v.units})",
                )
            )
            flags.append("fail")
    eps = solution.info.epsilon
    bounded = bounded_goal(solution.objectives)
    if eps is not None and not any(v.constraint == "epsilon" for v in solution.violations):
        bounded = bounded or goal_spec("max_light_power")
        sign = "≥" if bounded.maximise else "≤"
        rows.append((f"{bounded.axis} {sign} {fmt(eps)} {bounded.unit}", "epsilon", PASS))
        flags.append("pass")
    if not rows:
        return None
    return Table("Geometric rules", ("rule", "type", "result"), tuple(rows), tuple(flags))


def intention_table(
    solution: Solution,
    design: Design,
    field: LightField,
    daylight: LayoutDaylight | None = None,
) -> Table | None:
    """One row per bound of every lighting intention: its scenario, required vs
    achieved and pass/fail.

    Intentions on patches in the design scenario take their values from the solution's
    light ``field``. With ``daylight`` (the solution's ``LayoutDaylight``) every other
    intention, work-plane grids included, is measured in its own scenario and units
    (``LayoutDaylight.checks``); without it, only the intentions on patches are listed
    and those in another scenario show no value. Pass/fail is the solution's own
    verdict (its violations) when its intentions were judged (finite penalty), else the
    verdict of the values, with the same 0.1% tolerance. An annual intention whose
    weather file cannot be read shows no value (the note says why).
    """
    listed = [it for it in design.intentions if daylight is not None or it.grid is None]
    if not listed:
        return None
    judged = math.isfinite(solution.penalty)
    failed = {(v.name, v.constraint) for v in solution.violations}
    rows, flags = [], []
    problems: dict[str, list[str]] = {}
    for it in listed:
        q = quantity_spec(it.quantity)
        units = q.unit
        where, stats, checks = _measured(it, field, daylight, problems)
        scenario = str(it.scenario) + (f", {q.metric}" if q.metric else "")
        u0 = float("nan")
        if stats is not None and stats.average[0] > 0 and q.uniformity:
            u0 = float(stats.uniformity[0])
        summary = "—"
        if stats is not None:
            summary = f"{fmt(stats.min[0])} / {fmt(stats.average[0])} / {fmt(stats.max[0])}"
            summary += f" {units}" if units else ""
        for bound, limit, chk in checks:
            met = chk is None or bool(chk.met[0])
            bad = (it.name, bound) in failed if judged else not met
            c = float(chk.c[0]) if chk is not None else float("nan")
            if chk is None and not judged:
                result, flag = "—", ""
            elif bad:
                result = f"{FAIL} ({100 * max(c, 0):.1f}%)" if chk is not None else FAIL
                flag = "fail"
            else:
                result, flag = PASS, "pass"
            rows.append(
                (
                    it.name,
                    where,
                    bound_text(bound, it.quantity, limit),
                    scenario,
                    bound_value(bound, it.quantity, chk.value[0]) if chk is not None else "—",
                    summary,
                    u0_text(u0),
                    result,
                )
            )
            flags.append(flag)
    used = {it.scenario for it in listed}
    scenarios = [
        f"{sc.name} ({sc.describe(design.daylight)})" for sc in scenario_specs() if sc.name in used
    ]
    note = (
        "Averages are area-weighted (grid points: plain means); U0 = min / average. "
        f"Each intention is judged in its scenario: {', '.join(scenarios)}. FAIL gives how "
        "far past the bound, relative to it; a bound met to within 0.1% passes."
    )
    for why, names in problems.items():
        note += f" Not measured ({', '.join(names)}): {why}."
    return Table(
        "Lighting intentions",
        (
            "intention",
            "patches",
            "required",
            "scenario",
            "achieved",
            "min / avg / max",
            "U0",
            "result",
        ),
        tuple(rows),
        tuple(flags),
        note=note,
    )


def _measured(
    it, field: LightField, daylight: LayoutDaylight | None, problems: dict[str, list[str]]
):
    """(where, stats or None, [(bound, limit, BoundCheck or None)]) of one intention."""
    design_patch = it.grid is None and it.observers is None and it.scenario == Scenario.DESIGN
    stats, checks = None, None
    if design_patch:
        res = field.intention(it)
        where = {None: f"{len(res.patches)} picked", "*": "all"}.get(it.group, it.group)
        stats, checks = res.stats, list(res.checks)
    else:
        if it.grid is not None:
            grids = daylight.grids
            span = grids.span(it.grid) if grids is not None and grids.has(it.grid) else None
            n = "?" if span is None else str(len(daylight.grids.points[span]))
            where = f"grid {it.grid} ({n} points)"
            calc = {o.name: o for o in daylight.design.calc_objects}.get(it.grid)
            if calc is not None:  # a calculation object: what it reads, where
                where = f"{calc.spec.symbol} at {it.grid} ({n} points)"
        elif it.observers is not None:
            where = "observers " + ", ".join(it.observers)
        else:
            picked = f"{len(set(it.patches or ()))} picked"
            where = {None: picked, "*": "all"}.get(it.group, it.group)
        if daylight is not None:
            try:
                q, w = daylight.quantity(it)
                stats = intention_stats(q[:, None], w)
                checks = daylight.checks(it)
            except LightInvError as exc:
                problems.setdefault(str(exc).rstrip("."), []).append(it.name)
        else:
            why = f"the {it.scenario} scenario was not computed"
            problems.setdefault(why, []).append(it.name)
    by_bound: dict[Bound, BoundCheck] = {c.bound: c for c in checks or ()}
    out = [(b, getattr(it, b), by_bound.get(b)) for b in bounds_set(it)]
    return where, stats, out


MERGED = 3
"""Groups of one IFC class (``IfcMember:Sparren-1``, ``-2``, ...) alike in reflectance,
at least this many, share a row of the per-group tables: the rafters of an IFC house
filled four pages of surfaces and three of illuminances, a row each."""


def alike_groups(patches: Patches, key=lambda name: None) -> list[tuple[str, list[int]]]:
    """(row title, group ids) for a per-group table, in the scene's order, empty groups
    left out: ``MERGED`` or more groups of one class (the name's text before ":") with one
    area-weighted reflectance (2 decimals) and one ``key(name)`` share a row titled
    "CLASS: N groups"; every other group has its own."""
    buckets: dict[tuple, list[int]] = {}
    for gid, name in enumerate(patches.group_names):
        idx = patches.group_id == gid
        if not idx.any():
            continue
        rho = float(patches.rho[idx] @ patches.area[idx] / patches.area[idx].sum())
        kind = name.split(":", 1)[0] if ":" in name else None
        buckets.setdefault((kind, round(rho, 2), key(name)) if kind else (name,), []).append(gid)
    out: list[tuple[str, list[int]]] = []
    for k, gids in buckets.items():
        if len(gids) >= MERGED:
            out.append((f"{k[0]}: {len(gids)} groups", gids))
        else:
            out += [(patches.group_names[g], [g]) for g in gids]
    return out


def group_table(field: LightField) -> Table:
    """Illuminance (lux) per lighting group: area, min, area-weighted average, max, U0
    (alike groups of one class in one row, ``alike_groups``)."""
    rows = []
    patches = field.patches
    for title, gids in alike_groups(patches):
        idx = np.flatnonzero(np.isin(patches.group_id, gids))
        stats = [field.group_stats(patches.group_names[g]) for g in gids]
        areas = np.array([patches.area[patches.group_id == g].sum() for g in gids])
        lo = min(float(st.min[0]) for st in stats)
        hi = max(float(st.max[0]) for st in stats)
        avg = float(np.array([float(st.average[0]) for st in stats]) @ areas / areas.sum())
        u0 = float(stats[0].uniformity[0]) if len(stats) == 1 else lo / avg if avg > 0 else 0.0
        rows.append(
            (
                title,
                str(len(idx)),
                f"{patches.area[idx].sum():.1f}",
                fmt(lo),
                fmt(avg),
                fmt(hi),
                u0_text(u0) if avg > 0 else "—",
            )
        )
    return Table(
        "Illuminance per group",
        ("group", "patches", "area m²", "min lux", "average lux", "max lux", "U0"),
        tuple(rows),
    )
