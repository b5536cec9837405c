"""The design's criteria, one row each: required, achieved and pass/fail.

- ``workplane_criteria``: each work plane's EN 12464-1 criteria (Em, U0, Emin, Emax as
  its intentions ask, each in its own scenario; UGR_L and Ra for an intention made
  from a preset, stated as not calculated / product data: LightInv computes neither);
- ``status_table``: the title page's summary: every criterion of the work planes, every
  other intention's bounds and the geometric rules, each pass or FAIL with its value.

Pass/fail is the solution's own verdict (its violations) when its intentions were
judged (finite penalty), else the verdict of the values, with the same 0.1% tolerance
the optimiser uses (as ``tables.intention_table``).
"""

from __future__ import annotations

import math

from lightinv_core.design.en12464 import Requirement, requirement
from lightinv_core.design.model import Design, Intention
from lightinv_core.design.solution import Solution
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Bound, Scenario
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.intentions import bounds_set
from lightinv_core.quantities import quantity_spec
from lightinv_core.report.glare import observer_rows
from lightinv_core.report.tables import FAIL, PASS, Table
from lightinv_core.value_text import bound_value, fmt

EN_LABELS = {Bound.AVERAGE: "Em", Bound.MIN: "Emin", Bound.MAX: "Emax", Bound.UNIFORMITY: "U0"}
NOT_CALCULATED = "not calculated"


def preset_of(it: Intention) -> Requirement | None:
    """The EN 12464-1 preset an intention was made from (its name is the preset's key,
    perhaps with a "-2" suffix, and its Em and U0 are the preset's), else None."""
    key = it.name.split("-")[0]
    try:
        r = requirement(key)
    except LightInvError:
        return None
    if it.grid is None or it.average != r.em or it.uniformity != r.u0:
        return None
    return r


def _criterion(it: Intention, bound: Bound) -> str:
    q = quantity_spec(it.quantity)
    if q.metric is None and it.grid is not None:
        name = EN_LABELS[bound]
    elif bound == Bound.UNIFORMITY:
        name = "U0"
    else:
        name = f"{bound} {q.metric or q.noun}"
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
        sign = "≤" if bound == Bound.MAX else "≥"
        required = f"{sign} {bound_value(bound, it.quantity, limit)}"
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
        for it in (i for i in design.intentions if i.grid == plane.name):
            for crit, req, got, res in intention_rows(it, solution, daylight):
                rows.append((plane.name, it.name, crit, req, got, res))
                flags.append(_flag(res))
            preset = preset_of(it)
            if preset is not None:
                rows.append((plane.name, it.name, "UGR_L", "see note", NOT_CALCULATED, "—"))
                rows.append((plane.name, it.name, "Ra", f"≥ {preset.ra}", "product data", "check"))
                flags += ["", ""]
    if not rows:
        return None
    refs = sorted(
        {
            f"{p.activity} (ref. {p.reference}: Em {p.em:.0f} lux, U0 {p.u0:g}, Ra {p.ra})"
            for it in design.intentions
            if (p := preset_of(it)) is not None
        }
    )
    note = (
        "Em = mean of the grid points, U0 = Emin / Em, maintained values (each luminaire "
        "array's maintenance factor applied), each criterion in its scenario (night: "
        "luminaires only). A bound met to within 0.1% passes."
    )
    if refs:
        note += (
            " EN 12464-1:2011 requirements: "
            + "; ".join(refs)
            + ". UGR_L is not calculated by LightInv: check it with the luminaire "
            "manufacturer's UGR table for the room (limit in the standard's schedule "
            "for the activity). Ra is a property of the lamps: check the product's data."
        )
    return Table(
        "Work planes: EN 12464-1 criteria",
        ("work plane", "intention", "criterion", "required", "achieved", "result"),
        tuple(rows),
        tuple(flags),
        note=note,
    )


def status_table(
    design: Design,
    solution: Solution,
    daylight: LayoutDaylight | None,
    rules: Table | None,
) -> Table:
    """Every criterion of the design with its verdict: the work planes' and the other
    intentions' bounds, and the geometric rules in one row."""
    rows, flags = [], []
    for it in design.intentions:
        where = f"work plane {it.grid}" if it.grid is not None else it.name
        if it.grid is None and it.group is not None:
            where = f"{it.name} ({'every surface' if it.group == '*' else 'group ' + it.group})"
        if it.weight == 0:
            where += ", not optimised"
        if it.observers is not None:  # one row per eye (report/glare.py)
            for row in observer_rows(it, solution, daylight):
                rows.append(row)
                flags.append(_flag(row[-1]))
            continue
        for crit, req, got, res in intention_rows(it, solution, daylight):
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
