"""The report's glare rows: UGR or the simplified DGP's exceedance at each observer of
an intention, its bound and verdict."""

from __future__ import annotations

from lightinv_core.design.model import Intention
from lightinv_core.design.solution import Solution
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.intentions import JUDGED_TOL
from lightinv_core.quantities import quantity_spec
from lightinv_core.report.tables import FAIL, PASS


def observer_rows(
    it: Intention, solution: Solution, daylight: LayoutDaylight | None
) -> list[tuple[str, str, str, str, str]]:
    """(where, criterion, required, achieved, result) for each observer of an intention
    at observers: UGR at that eye (CIE 117, luminaires placed exactly, as new) against
    the intention's max, pass within the optimiser's 0.1%. The intention's verdict is
    its worst observer's, as the solution's violations say."""
    if quantity_spec(it.quantity).from_eyes is not None:
        return dgp_rows(it, daylight)
    values = (daylight.observed or {}) if daylight is not None else {}
    rows = []
    for name in it.observers:
        got = values.get(name)
        if got is None:
            achieved, result = "—", "—"
        else:
            achieved = f"{got:.1f}"
            over = (got - it.max) / max(it.max, 1e-12)
            result = PASS if over <= JUDGED_TOL else FAIL
        where = f"observer {name} ({it.name})"
        rows.append((where, "UGR (CIE 117)", f"≤ {it.max:g}", achieved, result))
    return rows


def dgp_rows(it: Intention, daylight: LayoutDaylight | None) -> list[tuple[str, ...]]:
    """(where, criterion, required, achieved, result) for each observer of a ``dgp``
    intention: the share of the occupied hours whose simplified DGP exceeds the
    design's limit (``light.dgp_observers``) against the intention's max."""
    figures = (daylight.glared or {}) if daylight is not None else {}
    rows = []
    for name in it.observers:
        got = figures.get(name)
        limit = it.max
        if got is None:
            criterion, achieved, result = "simplified DGP", "—", "—"
        else:
            criterion = f"DGPs > {got['limit']:.2f} (share of occupied hours)"
            achieved = f"{100 * got['exceedance']:.1f}% (max DGPs {got['dgp_max']:.2f})"
            over = got["exceedance"] - limit
            result = PASS if over <= JUDGED_TOL * max(limit, 1e-12) else FAIL
        where = f"observer {name} ({it.name})"
        rows.append((where, criterion, f"≤ {100 * limit:g}%", achieved, result))
    return rows
