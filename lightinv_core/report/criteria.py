"""The design's criteria, one row each: required, achieved and pass/fail.

- ``workplane_criteria``: each work plane's EN 12464-1 criteria under its edition (Em,
  U0, Emin, Emax as its intentions ask, each in its own scenario; for an intention made
  from a preset of the plane's edition, UGR_L (its limit, not calculated here) and Ra
  against the Ra the chosen products state: pass, FAIL or "not stated");
- ``status_table``: the title page's summary: every criterion of the work planes, every
  other intention's bounds and the geometric rules, each pass or FAIL with its value.

Pass/fail is the solution's own verdict (its violations) when its intentions were
judged (finite penalty), else the verdict of the values, with the same 0.1% tolerance
the optimiser uses (as ``tables.intention_table``).
"""

from __future__ import annotations

import math

from lightinv_core.design.en12464 import Requirement, preset_of, ra_check
from lightinv_core.design.model import Design, Intention, Workplane
from lightinv_core.design.solution import Solution
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Bound, Scenario, bound_sign
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.intentions import bounds_set
from lightinv_core.luminaires.rendering import product_ra
from lightinv_core.quantities import quantity_spec
from lightinv_core.report.glare import observer_rows
from lightinv_core.report.tables import EN_LABELS, FAIL, PASS, Table
from lightinv_core.value_text import bound_value, fmt

NOT_CALCULATED = "not calculated"


def products_ra(design: Design) -> list[float | None]:
    """The Ra each luminaire array's product states (None: not stated)."""
    return [product_ra(a.product) for a in design.arrays]


def ra_row(preset: Requirement, design: Design) -> tuple[str, str, str]:
    """(required, achieved, result) of a preset's Ra against the products' stated Ra."""
    text, ok = ra_check(preset.ra, products_ra(design))
    return f"≥ {preset.ra}", text, "—" if ok is None else PASS if ok else FAIL


def _criterion(it: Intention, bound: Bound) -> str:
    q = quantity_spec(it.quantity)
    if q.metric is None and it.grid is not None:
        name = EN_LABELS[bound]
    elif bound == Bound.UNIFORMITY:
        name = "U0"
    else:
        label = "average" if bound == Bound.MAX_AVERAGE else bound
        name = f"{label} {q.metric or q.noun}"
    if it.scenario != Scenario.DESIGN and q.metric is None:
        name += f" ({it.scenario})"
    return name


def intention_rows(
    it: Intention, solution: Solution, daylight: LayoutDaylight | None
) -> list[tuple[str, str, str, str]]:
    """(criterion, required, achieved, result) of each bound of one intention."""
    judged = math.isfinite(solution.penalty)
    failed = {(v.name, v.constraint) for v in solution.violations}
    checks: dict = {}
    broken = daylight is None
    if daylight is not None:
        try:
            checks = {c.bound: c for c in daylight.checks(it)}
        except LightInvError:  # not measurable (an unreadable weather file)
            broken = True
    rows = []
    for bound in bounds_set(it):
        limit = getattr(it, bound)
        required = f"{bound_sign(bound)} {bound_value(bound, it.quantity, limit)}"
        chk = checks.get(bound)
        achieved = "—" if chk is None else bound_value(bound, it.quantity, float(chk.value[0]))
        if chk is None and (broken or not judged):
            result = "—"
        else:
            bad = (it.name, bound) in failed if judged else not bool(chk.met[0])
            result = FAIL if bad else PASS
        rows.append((_criterion(it, bound), required, achieved, result))
    return rows


def _flag(result: str) -> str:
    return "pass" if result == PASS else "fail" if result == FAIL else ""


def workplane_criteria(
    design: Design, solution: Solution, daylight: LayoutDaylight | None
) -> Table | None:
    """EN 12464-1 criteria of every work plane with intentions; None without."""
    rows, flags = [], []
    for plane in design.workplanes:
        where = _plane_title(plane)
        for it in (i for i in design.intentions if i.grid == plane.name):
            for crit, req, got, res in intention_rows(it, solution, daylight):
                rows.append((where, it.name, crit, req, got, res))
                flags.append(_flag(res))
            preset = preset_of(it, plane.edition)
            if preset is not None:
                ugr = f"≤ {preset.ugr_l:g}" if preset.ugr_l is not None else "see note"
                rows.append((where, it.name, "UGR_L", ugr, NOT_CALCULATED, "—"))
                rows.append((where, it.name, "Ra", *ra_row(preset, design)))
                flags += ["", _flag(rows[-1][-1])]
    if not rows:
        return None
    refs = sorted(
        {
            f"{p.edition}, {p.activity[0].lower()}{p.activity[1:]} (ref. {p.reference}): {p.values}"
            for plane in design.workplanes
            for it in design.intentions
            if it.grid == plane.name and (p := preset_of(it, plane.edition)) is not None
        }
    )
    note = (
        "Em = mean of the grid points, U0 = Emin / Em, maintained values (each luminaire "
        "array's maintenance factor applied), each criterion in its scenario (night: "
        "luminaires only). A bound met to within 0.1% passes."
    )
    if refs:
        note += (
            " Requirements: "
            + "; ".join(refs)
            + ". UGR_L is not calculated on the work plane: check it with the luminaire "
            "manufacturer's UGR table for the room (the limit is the preset's). Ra is a "
            "property of the lamps: checked against the Ra the products' data state "
            '("not stated" when a product states none).'
        )
    return Table(
        "Work planes: EN 12464-1 criteria",
        ("work plane", "intention", "criterion", "required", "achieved", "result"),
        tuple(rows),
        tuple(flags),
        note=note,
    )


def _plane_title(plane: Workplane) -> str:
    """A work plane's name with the edition it follows, e.g. "desks (EN 12464-1:2021)"."""
    return f"{plane.name} ({plane.edition})"


def status_table(
    design: Design,
    solution: Solution,
    daylight: LayoutDaylight | None,
    rules: Table | None,
) -> Table:
    """Every criterion of the design with its verdict: the work planes' and the other
    intentions' bounds, and the geometric rules in one row."""
    rows, flags = [], []
    planes = {p.name: p for p in design.workplanes}
    calcs = {c.name: c for c in design.calc_objects}
    for it in design.intentions:
        plane = planes.get(it.grid) if it.grid is not None else None
        where = f"work plane {_plane_title(plane)}" if plane is not None else it.name
        if it.grid is not None and plane is None:
            calc = calcs.get(it.grid)  # a calculation object: its kind and what it reads
            where = f"work plane {it.grid}"
            if calc is not None:
                where = f"{calc.spec.label.split(' (')[0].lower()} {it.grid} ({calc.spec.symbol})"
        if it.grid is None and it.group is not None:
            where = f"{it.name} ({'every surface' if it.group == '*' else 'group ' + it.group})"
        if it.weight == 0:
            where += ", not optimised"
        if it.observers is not None:  # one row per eye (report/glare.py)
            for row in observer_rows(it, solution, daylight):
                rows.append(row)
                flags.append(_flag(row[-1]))
            continue
        calc = calcs.get(it.grid) if it.grid is not None else None
        for crit, req, got, res in intention_rows(it, solution, daylight):
            if calc is not None and calc.spec.symbol != "E" and crit.startswith("E"):
                crit = calc.spec.symbol + crit[1:]  # Ezm, Ezmin: what the object reads
            rows.append((where, crit, req, got, res))
            flags.append(_flag(res))
    if rules is not None:
        ok = rules.flags.count("pass")
        n = len(rules.rows)
        res = PASS if ok == n else FAIL
        rows.append(("geometric rules", "rules met", f"{n} of {n}", f"{ok} of {n}", res))
        flags.append(_flag(res))
    failed = flags.count("fail")
    verdict = (
        "Every criterion is met."
        if failed == 0
        else f"{failed} of {len(rows)} criteria are not met (FAIL rows)."
    )
    if not rows:
        verdict = "The design sets no lighting criterion."
    return Table(
        "Design status",
        ("where", "criterion", "required", "achieved", "result"),
        tuple(rows),
        tuple(flags),
        note=verdict + f" Penalty P = {fmt(solution.penalty)} (0 when every criterion is met).",
    )
