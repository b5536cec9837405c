"""Editing rules of a design as pure functions: each takes a ``Design`` (and what it
needs of the scene) and returns the edited design, never changing anything in place.

The cascades live here: removing a source removes the rules that name it; keeping only
the sources of some zones (a drawn zone deleted) keeps only the rules whose sources all
stay.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from lightinv_core.design.model import CORNERS, Design, Goal, Rule, Source
from lightinv_core.errors import DesignError
from lightinv_core.kinds import RuleKind
from lightinv_core.scene.zone_outline import inner_square, kept_inside
from lightinv_core.sources.types import source_type

NEW_SOURCE_SIZE = 1.0
"""m: a new source is a square this wide (or the zone's width or height if smaller)."""
NEW_LUMINAIRE_FLUX = 3000.0
"""lm: a typical luminaire's flux; a new skylight starts with filter 1."""
NEW_STRENGTH = {"flux": NEW_LUMINAIRE_FLUX}
"""The setting a new source starts with, by the ``Source`` field that sets how much it
emits (its type's ``strength``); a field not listed starts at the model's default
(filter 1)."""


def free_name(stem: str, taken: set[str]) -> str:
    """The first of ``stem``1, ``stem``2, ... not in ``taken``."""
    return next(f"{stem}{i}" for i in range(1, 10_000) if f"{stem}{i}" not in taken)


def new_source(
    design: Design,
    zone: str,
    kind: str,
    size: tuple[float, float],
    name: str | None = None,
    outline: np.ndarray | None = None,
) -> Source:
    """A source centred in ``zone`` (``size`` (w, h) m): a 1 x 1 m (or smaller)
    rectangle, a 3,000 lm luminaire or a skylight with filter 1, whose corners and flux
    (or filter) the optimiser may change: a fixed flux would leave a least-power run
    unable to reach its targets. In a zone with a polygon ``outline``, the square
    (smaller if need be) lies inside it, near its centroid. Unnamed, it takes the first
    free name of its type's stem: L1, L2, ... (luminaires), S1, ... (skylights)."""
    w, h = size
    sw, sh = min(NEW_SOURCE_SIZE, w), min(NEW_SOURCE_SIZE, h)
    rect = ((w - sw) / 2, (h - sh) / 2, (w + sw) / 2, (h + sh) / 2)
    if outline is not None:
        rect = inner_square(outline, NEW_SOURCE_SIZE)
    t = source_type(kind)  # DesignError for an unknown kind
    if name is None:
        name = free_name(t.stem, {s.name for s in design.sources})
    start = {t.strength: NEW_STRENGTH[t.strength]} if t.strength in NEW_STRENGTH else {}
    return Source(name, zone, kind, rect, free=(*CORNERS, t.strength), **start)


def with_source(design: Design, source: Source) -> Design:
    """``design`` with ``source`` appended (DesignError if its name is taken)."""
    return replace(design, sources=(*design.sources, source))


def with_source_fields(design: Design, name: str, **fields) -> Design:
    """``design`` with fields of source ``name`` changed (rect, flux, filter, free, ...);
    the model validates them (DesignError)."""
    design.source(name)  # DesignError naming the source if there is none
    sources = tuple(replace(s, **fields) if s.name == name else s for s in design.sources)
    return replace(design, sources=sources)


def moved_rect(
    source: Source,
    du: float,
    dv: float,
    size: tuple[float, float],
    outline: np.ndarray | None = None,
) -> tuple:
    """``source``'s rectangle shifted by (du, dv) m, the shift clipped so that it stays
    inside its zone of ``size`` (w, h) m and, if it has one, inside its polygon
    ``outline`` (the move stops at the edge)."""
    w, h = size
    (a, b), (c, d) = source.u_range, source.v_range
    du = float(np.clip(du, -a, w - b))
    dv = float(np.clip(dv, -c, h - d))
    return kept_inside(outline, (a, c, b, d), (a + du, c + dv, b + du, d + dv))


def without_source(design: Design, name: str) -> Design:
    """``design`` without source ``name`` and without the rules that name it."""
    rules = tuple(r for r in design.rules if name not in r.sources)
    sources = tuple(s for s in design.sources if s.name != name)
    return replace(design, sources=sources, rules=rules)


def only_in_zones(design: Design, zones: set[str]) -> Design:
    """``design`` keeping only the sources placed in ``zones`` and the rules whose
    sources all stay (a drawn zone was deleted or renamed)."""
    kept = tuple(s for s in design.sources if s.zone in zones)
    names = {s.name for s in kept}
    rules = tuple(r for r in design.rules if set(r.sources) <= names)
    return replace(design, sources=kept, rules=rules)


def is_centred(design: Design, name: str) -> bool:
    """Whether a centred rule ties source ``name`` to the centre of its zone."""
    return any(r.kind == RuleKind.CENTRED and name in r.sources for r in design.rules)


def with_centred(design: Design, name: str, centred: bool) -> Design:
    """``design`` with source ``name`` tied to (or freed from) the centre of its zone."""
    rules = tuple(r for r in design.rules if not (r.kind == RuleKind.CENTRED and name in r.sources))
    if centred:
        rules += (Rule(RuleKind.CENTRED, (name,)),)
    return replace(design, rules=rules)


def mirror_of(design: Design, name: str) -> tuple[str, str] | None:
    """(original, axis) if source ``name`` mirrors another one, else None."""
    for r in design.rules:
        if r.kind == RuleKind.MIRROR and r.sources[0] == name:
            return r.sources[1], r.axis
    return None


def with_mirror(design: Design, name: str, original: str | None, axis: str = "u") -> Design:
    """``design`` with source ``name`` the mirror image of ``original`` along a zone axis
    ("u" or "v"); None frees it. Its zone may be another one (the symmetric zone across
    a hall)."""
    rules = tuple(
        r for r in design.rules if not (r.kind == RuleKind.MIRROR and r.sources[0] == name)
    )
    if original is not None:
        rules += (Rule(RuleKind.MIRROR, (name, original), axis=axis),)
    return replace(design, rules=rules)


def with_primary_goal(design: Design, kind: str) -> Design:
    """``design`` with goal ``kind`` first (what a single-objective run optimises); the
    other goals stay, as secondary objectives reported with each solution."""
    goals = design.goals
    first = next((g for g in goals if g.kind == kind), None) or Goal(kind)
    if goals and goals[0] == first:
        return design
    return replace(design, goals=(first, *(g for g in goals if g != first)))


def with_goal(design: Design, kind: str, on: bool) -> Design:
    """``design`` with goal ``kind`` added (after the others) or removed; DesignError
    when that would leave no goal."""
    goals = tuple(g for g in design.goals if g.kind != kind)
    if on:
        goals = (*goals, next((g for g in design.goals if g.kind == kind), None) or Goal(kind))
    if not goals:
        raise DesignError("a design needs at least one goal")
    return replace(design, goals=goals)


def _bounds(unit: str):
    """The bounds of a rule on a size: "at least 0.5 m² and at most 4 m²"."""

    def text(rule) -> str:
        lo = f"at least {rule.min:g}{unit}" if rule.min is not None else ""
        hi = f"at most {rule.max:g}{unit}" if rule.max is not None else ""
        return " and ".join(x for x in (lo, hi) if x)

    return text


RULE_TEXT = {
    RuleKind.AREA: (lambda r, names: f"area {names}", _bounds(" m²")),
    RuleKind.ASPECT: (lambda r, names: f"aspect {names}", _bounds("")),
    RuleKind.SPACING: (lambda r, names: f"spacing {names}", _bounds(" m")),
    RuleKind.MIRROR: (
        lambda r, names: f"mirror {r.sources[0]}",
        lambda r: f"of {r.sources[1]} along {r.axis}",
    ),
    RuleKind.ALIGN: (lambda r, names: f"align {names}", lambda r: f"along {r.axis}"),
    RuleKind.CENTRED: (lambda r, names: f"centred {names}", lambda r: "in their zones"),
    RuleKind.SHR: (lambda r, names: f"spacing/height {names}", lambda r: f"at most {r.max:g}"),
    RuleKind.CLEARANCE: (
        lambda r, names: f"clearance {names}",
        lambda r: f"at least {r.min:g} m from the zone's edges",
    ),
}
"""Per rule kind: (what it ties, given the rule and its sources' names; its bounds)."""


def rule_text(rule) -> tuple[str, str]:
    """(what, bounds) of a rule for a list: ("area L1, L2", "0.5 to 4 m²") and so on."""
    what, bounds = RULE_TEXT[rule.kind]
    return what(rule, ", ".join(rule.sources)), bounds(rule)
