"""The report's EN 17037 table: each criterion of the daylight provision per work plane
(and the sunlight exposure at observers, when measured), its value, what it needs, the
level reached and pass or fail (docs/daylight.md "EN 17037 in a project").

Every figure is ``light.en17037_plane.plane_figures`` of the layout's light (the same
numbers the optimiser's score and ``lightinv-cli solve --json`` read). A plane passes
when it reaches the level an EN 17037 intention on it asks, or the minimum level when
none does.
"""

from __future__ import annotations

from lightinv_core.climate.en17037 import F_TIME
from lightinv_core.climate.sun_metrics import GLARE_LEVELS
from lightinv_core.design.model import Design
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Quantity
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.en17037_plane import level_criteria, plane_figures
from lightinv_core.quantities import level_name, quantity_spec
from lightinv_core.report.tables import FAIL, PASS, Table

ORDER = ("none", "minimum", "medium", "high")


def required_level(design: Design, plane: str) -> str:
    """The level an EN 17037 intention on work plane ``plane`` asks (the highest if
    several), "minimum" when none does."""
    spec = quantity_spec(Quantity.EN17037)
    asked = [
        level_name(spec, it.min)
        for it in design.intentions
        if it.quantity == Quantity.EN17037 and it.grid == plane and it.min is not None
    ]
    return max(asked, key=ORDER.index) if asked else "minimum"


def provision_rows(lay: LayoutDaylight) -> list[tuple[str, dict]]:
    """(work plane, ``plane_figures``) of every work plane of the layout."""
    if lay.points is None or lay.grids is None:
        return []
    return [(name, plane_figures(lay.points, span)) for name, span in lay.grids.spans.items()]


def en17037_table(lay: LayoutDaylight) -> Table | None:
    """Per work plane and level, each criterion's plane share against its requirement,
    then the level reached against the level asked; None without work planes or the
    weather year (the daylight section says why)."""
    try:
        planes = provision_rows(lay)
    except LightInvError:
        planes = []
    rows, flags = [], []
    for name, got in planes:
        for level, crits in level_criteria(got["horizontal_openings"]):
            for lux, share in crits:
                value = got[f"{level}_{int(lux)}"]
                text = f"{level}: {lux:.0f} lux in {100 * F_TIME:.0f}% of the daylight hours"
                need = share
                if got.get("basis") == "hours":  # the share of hours, not of the plane
                    text = f"{level}: {lux:.0f} lux on {100 * share:.0f}% of the plane"
                    need = F_TIME
                ok = value >= need
                rows.append(
                    (name, text, f"{100 * value:.1f}%", f"≥ {100 * need:.0f}%", _result(ok))
                )
                flags.append("pass" if ok else "fail")
        need = required_level(lay.design, name)
        ok = ORDER.index(got["level"]) >= ORDER.index(need)
        reached = f"{got['level']} (score {got['score']:.2f})"
        rows.append((name, "level reached", reached, f"{need} or better", _result(ok)))
        flags.append("pass" if ok else "fail")
    for name, got in (lay.sunlit or {}).items():
        rows.append(sunlight_row(lay.design, name, got))
        flags.append("pass" if rows[-1][-1] == PASS else "fail")
    for name, got in (lay.glared or {}).items():
        rows.append(glare_row(name, got))
        flags.append("pass" if rows[-1][-1] == PASS else "fail")
    if not rows:
        return None
    hours = planes[0][1]["daylight_hours"] if planes else 0
    basis = (
        "the 'points' basis: the share of the plane's points that reach the illuminance "
        "in at least half of"
        if lay.design.daylight.en17037_basis == "points"
        else "the 'hours' basis: the share of the hours in which the plane fraction "
        "reaches the illuminance, at least half of"
    )
    note = (
        f"EN 17037 daylight provision (Annex A, hourly illuminance; {basis} "
        f"the {hours:,} daylight hours (the year's brightest half by diffuse horizontal "
        "illuminance), every blind open. Vertical and inclined openings: E_T over 50% "
        "and E_TM over 95% of the plane; rooflights only (every pane within 10° of "
        "horizontal): E_T over 95%. The score is the level met plus the progress towards "
        "the next (what the optimiser follows). Sunlight exposure at an observer's eye: "
        "the hours of the day the sun, above the stated altitude, is seen through clear "
        "glazing (levels 1.5, 3 and 4 h). Glare protection at an observer's eye: the "
        "simplified DGP of each occupied hour's vertical eye illuminance (daylight, sun "
        "included, the LM-83 blinds), a level met when its limit (0.45, 0.40, 0.35) is "
        "exceeded in no more than 5% of the hours."
    )
    return Table(
        "EN 17037 daylight provision",
        ("work plane", "criterion", "achieved", "required", "result"),
        tuple(rows),
        tuple(flags),
        note,
    )


def sunlight_row(design: Design, name: str, got: dict) -> tuple[str, ...]:
    """One observer's sunlight exposure against the level its intentions ask (the
    highest), or the minimum level."""
    spec = quantity_spec(Quantity.SUNLIGHT)
    asked = [
        it.min
        for it in design.intentions
        if it.quantity == Quantity.SUNLIGHT and name in (it.observers or ()) and it.min
    ]
    need = max(asked) if asked else spec.levels[0][1]
    what = f"sunlight exposure on {got['date']} (sun above {got['min_altitude_deg']:g}°)"
    value = f"{got['hours']:.2f} h ({got['level']})"
    required = f"≥ {need:g} h ({level_name(spec, need)})"
    return (f"observer {name}", what, value, required, _result(got["hours"] >= need - 1e-9))


def glare_row(name: str, got: dict) -> tuple[str, ...]:
    """One observer's EN 17037 glare protection (``light.dgp_observers.observer_dgp``):
    the shares of the hours above each level's DGP limit and the level met, against
    the level of the design's ``dgp_limit`` (0.45 minimum, 0.40 medium, 0.35 high)."""
    shares = "/".join(f"{100 * got[f'dgp_over_{lim:.2f}']:.1f}" for _, lim in GLARE_LEVELS)
    limits = "/".join(f"{lim:.2f}" for _, lim in GLARE_LEVELS)
    what = f"glare protection: DGPs above {limits} in ≤ 5% of the hours"
    need = next((n for n, lim in GLARE_LEVELS if abs(lim - got["limit"]) < 1e-9), "minimum")
    ok = ORDER.index(got["en17037_glare"]) >= ORDER.index(need)
    value = f"{got['en17037_glare']} ({shares}%)"
    return (f"observer {name}", what, value, f"{need} or better", _result(ok))


def _result(ok: bool) -> str:
    return PASS if ok else FAIL
