"""Geometric rules on sources and luminaire arrays (no radiosity needed; paper eq. 4).

What each rule kind takes and needs is a table (``RULE_TAKES``, ``RULE_SOURCES``,
``RULE_NEEDS``), so a new kind is one entry in each and its check in
``design/geometry.py``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from lightinv_core.errors import DesignError
from lightinv_core.fields import Choice, ListOf, Number, ObjectSpec, String, choice_of, declare
from lightinv_core.kinds import RuleKind

AXES = ("u", "v")
"""A zone's two axes, as mirror and align rules name them."""
RULE_SOURCES = {RuleKind.MIRROR: 2, RuleKind.SPACING: 2}
"""Rule kinds that take an exact number of sources."""
ARRAY_RULES = (str(RuleKind.SHR), str(RuleKind.CLEARANCE))
"""Rule kinds that name luminaire arrays (the others name sources)."""
RULE_TAKES = {
    RuleKind.AREA: ("min", "max"),
    RuleKind.ASPECT: ("max",),
    RuleKind.MIRROR: ("axis",),
    RuleKind.CENTRED: (),
    RuleKind.SPACING: ("min",),
    RuleKind.ALIGN: ("axis",),
    RuleKind.SHR: ("max",),
    RuleKind.CLEARANCE: ("min",),
}
"""Which of min, max and axis each rule kind takes."""


def _taking(key: str) -> tuple[str, ...]:
    return tuple(str(k) for k, takes in RULE_TAKES.items() if key in takes)


def rule_not_taken(kind: str, field: str) -> str:
    """The message for a field rule ``kind`` does not take."""
    also = ", ".join(("sources", *RULE_TAKES[RuleKind(kind)]))
    return f"{kind} rules do not take {field!r} (they take: {also})"


def _at_least_one(r: Rule) -> str | None:
    return "give min and/or max area (m²)" if r.min is None and r.max is None else None


def _aspect(r: Rule) -> str | None:
    if r.max is None or r.max < 1:
        got = "none" if r.max is None else f"{r.max:g}"
        return f"max aspect ratio must be at least 1, got {got}"
    return None


RULE_NEEDS: dict[str, Callable[[Rule], str | None]] = {
    RuleKind.AREA: _at_least_one,
    RuleKind.ASPECT: _aspect,
    RuleKind.SPACING: lambda r: "give the min gap (m)" if r.min is None else None,
    RuleKind.ALIGN: lambda r: "needs at least two sources" if len(r.sources) < 2 else None,
    RuleKind.SHR: lambda r: (
        None
        if r.max is not None and r.max > 0
        else "give the largest spacing-to-height ratio as max (e.g. 1.5)"
    ),
    RuleKind.CLEARANCE: lambda r: (
        "give the least clearance to the zone's edges (m) as min" if r.min is None else None
    ),
}
"""What a rule of each kind needs beyond its fields' own checks: a message, or None."""


@dataclass(frozen=True)
class Rule:
    """A geometric rule (no radiosity needed; paper eq. 4).

    kinds and their fields:
    - ``area``: ``sources``, ``min`` and/or ``max`` (m²) for each source;
    - ``aspect``: ``sources``, ``max`` (long side / short side);
    - ``mirror``: ``sources`` = (derived, original), ``axis`` "u" or "v": the
      derived source is the original's rectangle flipped along that axis (in
      the same or another zone; coordinates scale with the zones' sizes along
      the axis when they differ) and copies its flux or filter — it has no
      variables;
    - ``centred``: ``sources``: each rectangle is centred in its zone (the
      second corner is the first mirrored through the zone centre);
    - ``spacing``: ``sources`` (two, same zone), ``min`` (m) gap between them;
    - ``align``: ``sources`` (two or more), ``axis`` "u" or "v": they lie on one
      line parallel to that axis (their centres share the other coordinate,
      within 1 cm);
    - ``shr`` and ``clearance``: luminaire arrays (``sources`` are array names), ``max``
      spacing-to-height ratio and ``min`` clearance to the zone's edges (m).
    """

    kind: RuleKind = field(
        metadata=declare(
            Choice(lambda: tuple(RuleKind), RuleKind, name="rule kind"),
            "see the table of rule kinds",
        )
    )
    sources: tuple[str, ...] = field(
        metadata=declare(
            ListOf(String(), "source names", 1, unique=True, name="list of names"),
            "the sources it constrains, each once (`shr`, `clearance`: luminaire arrays)",
        )
    )
    min: float | None = field(
        default=None,
        metadata=declare(Number(lo=0.0), "lower bound", kinds=_taking("min"), nullable=True),
    )
    max: float | None = field(
        default=None,
        metadata=declare(Number(lo=0.0), "upper bound", kinds=_taking("max"), nullable=True),
    )
    axis: str | None = field(
        default=None,
        metadata=declare(choice_of(*AXES), "the zone axis", kinds=_taking("axis"), nullable=True),
    )

    KINDS = tuple(str(k) for k in RuleKind)

    def __post_init__(self) -> None:
        RULE_FIELDS.check_fields(self, f"rule {self.kind!r}")
        where = f"rule {self.kind!r} on {list(self.sources)}"
        need = RULE_SOURCES.get(self.kind)
        if need and len(self.sources) != need:
            raise DesignError(f"{where}: needs exactly {need} sources")
        if "axis" in RULE_TAKES[self.kind] and self.axis is None:
            raise DesignError(f"{where}: axis must be 'u' or 'v'")
        if self.min is not None and self.max is not None and self.min > self.max:
            raise DesignError(f"{where}: min {self.min} is larger than max {self.max}")
        needs = RULE_NEEDS.get(self.kind)
        problem = needs(self) if needs is not None else None
        if problem:
            raise DesignError(f"{where}: {problem}")


RULE_FIELDS = ObjectSpec.of(Rule, "rule", kind_field="kind", not_taken=rule_not_taken)
"""The rule's fields (the project file checks which kinds take them first)."""
