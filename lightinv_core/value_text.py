"""How values are written for people: one place for the CLI, the report and the window.

A goal's value, a quantity with its unit, a bound of a lighting intention and a
source's setting are written from the registries (``goals.goal_spec``,
``quantities.quantity_spec``, ``sources.types.source_type``), never by branching on a
kind, so a registered goal, quantity or source kind reads right everywhere at once.
"""

from __future__ import annotations

import math

from lightinv_core.design.model import Daylight, Intention, Source
from lightinv_core.goals import goal_spec, is_goal
from lightinv_core.kinds import Bound, bound_sign
from lightinv_core.light.intentions import bounds_set
from lightinv_core.quantities import level_name, quantity_spec
from lightinv_core.sources.emission import source_electric_power, source_flux
from lightinv_core.sources.types import source_type

SETTING_UNITS = {"flux": "lm", "exitance": "lm/m²"}
"""Units of the ``Source`` fields that set how much a source emits; a field not listed
(``filter``) is a fraction, written with its name."""


def fmt(value: float | None, digits: int = 4) -> str:
    """A number for tables: ``digits`` significant digits below 1,000, whole numbers with
    thousands separators above, "—" for a missing or undefined value."""
    if value is None or math.isnan(float(value)):
        return "—"
    v = float(value)
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    if abs(float(f"{v:.{digits}g}")) >= 10 ** (digits - 1):
        return f"{v:,.0f}"
    return f"{v:.{digits}g}"


def u0_text(value: float | None) -> str:
    """A uniformity U0 = Emin / Em: three decimals everywhere (a 0.712 against a bound of
    0.7 reads apart; "—" when missing or undefined)."""
    if value is None or not math.isfinite(float(value)):
        return "—"
    return f"{float(value):.3f}"


# -- goals ------------------------------------------------------------------------------------


def goal_name(kind: str) -> tuple[str, str]:
    """(name, unit) of a goal as the report shows it (the kind itself and no unit when it
    is not registered: a file from another version)."""
    if not is_goal(kind):
        return str(kind), ""
    spec = goal_spec(kind)
    return spec.label, spec.unit


def goal_value(kind: str, value: float) -> str:
    """A goal's value with its unit as a line of the CLI's front writes it ("  12.3 W")."""
    return goal_spec(kind).value_text(value)


def objective_text(kind: str, value: float) -> str:
    """ "Electric power: 123.4 W" and the like."""
    name, unit = goal_name(kind)
    return f"{name}: {fmt(value)}{' ' + unit if unit else ''}"


def goal_label(kind: str) -> str:
    """A goal as an axis label: "electric power (W)", "glazing area (m²)", "sDA300/50%"."""
    name, unit = goal_name(kind)
    name = name[:1].lower() + name[1:] if name[1:2].islower() else name
    return f"{name} ({unit})" if unit else name


# -- quantities and intentions ----------------------------------------------------------------


def quantity_value(quantity: str, value: float | None, digits: int = 4) -> str:
    """A value of an intention quantity with its unit: "312.5 lux", "2.13 %", "0.52";
    a quantity with named levels adds the level reached: "2.4 (medium)"."""
    spec = quantity_spec(quantity)
    unit = spec.unit
    text = f"{fmt(value, digits)} {unit}" if unit else fmt(value, digits)
    if spec.levels and value is not None and math.isfinite(float(value)):
        text += f" ({level_name(spec, float(value))})"  # "2.4 (medium)"
    return text


def bound_value(bound: str, quantity: str, value: float | None) -> str:
    """A value of one bound: in the quantity's unit, U0 (a ratio) without one."""
    return u0_text(value) if bound == Bound.UNIFORMITY else quantity_value(quantity, value)


BOUND_LABELS = {Bound.UNIFORMITY: "U0", Bound.MAX_AVERAGE: "average"}
"""How a bound is named beside its sign: "U0 ≥ 0.600", "average ≤ 0.1"."""


def bound_text(bound: str, quantity: str, limit: float) -> str:
    """One bound of an intention: "min ≥ 300 lux", "max ≤ 2,000 lux", "U0 ≥ 0.600"."""
    label = BOUND_LABELS.get(bound, str(bound))
    sign = bound_sign(bound)
    return f"{label} {sign} {bound_value(bound, quantity, limit)}"


def intention_target(intention: Intention) -> str:
    """Every bound an intention sets, joined: "min ≥ 300 lux, U0 ≥ 0.600"."""
    it = intention
    return ", ".join(bound_text(b, it.quantity, getattr(it, b)) for b in bounds_set(it))


# -- sources ----------------------------------------------------------------------------------


def source_setting(s: Source) -> str:
    """How much a source emits, as set: "1,200 lm", "400 lm/m²" (a luminous panel's fixed
    exitance), "filter 0.500"."""
    field = source_type(s.kind).strength
    if getattr(s, field, None) is None and getattr(s, "exitance", None) is not None:
        field = "exitance"  # a luminous panel: no flux, a fixed exitance
    value = getattr(s, field)
    unit = SETTING_UNITS.get(field)
    return f"{fmt(value)} {unit}" if unit else f"{field} {value:.3f}"


def source_summary(s: Source, daylight: Daylight) -> dict:
    """A placed source as data (the CLI's ``--json``): its rectangle in zone metres
    (``corners`` u0, v0, u1, v1 ordered), area (m²) and, for a source drawing power, its
    emitted flux (lm) and electric power (W), else its setting field and value."""
    u0, v0, u1, v1 = s.rect
    row = {
        "name": s.name,
        "zone": s.zone,
        "kind": s.kind,
        "corners": [min(u0, u1), min(v0, v1), max(u0, u1), max(v0, v1)],
        "area_m2": s.area,
    }
    t = source_type(s.kind)
    if t.electric:
        row.update(flux_lm=source_flux(s, daylight), electric_w=source_electric_power(s))
    else:
        row[t.strength] = getattr(s, t.strength)
    return row


def source_line(row: dict) -> str:
    """One line of a ``source_summary``: name, zone, corners (m), area and what it emits."""
    t = source_type(row["kind"])
    corners = ", ".join(f"{x:.3f}" for x in row["corners"])
    if t.electric:
        emits = f"{row['flux_lm']:.0f} lm, {row['electric_w']:.1f} W"
    else:
        emits = f"{t.strength} {row[t.strength]:.3f}"
    return f"{row['name']:<10} {row['zone']:<10} ({corners}) m  {row['area_m2']:.2f} m²  {emits}"
