"""What a model import made of the file: each element (IFC) or group (OBJ, glTF, PLY)
and what it became, a lighting group, an emitter zone, part of another element's group,
or nothing, with the reason.

Importers build an ``ImportReport`` and keep it as plain data in
``scene.info["import_report"]`` (``to_dict``), so it survives the scene's edits and goes
into JSON as it is; ``report_of(scene)`` reads it back. The command line prints
``lines()`` and the window shows ``summary()`` with ``lines()`` as its details.
"""

from __future__ import annotations

from dataclasses import dataclass

OUTCOMES = ("zone", "group", "kept", "dropped")
"""What an item became: an emitter zone (and the lighting group around it); a lighting
group of surfaces; surfaces kept in another item's group (a window's frames and pane);
nothing (``reason`` says why)."""
KEY = "import_report"
"""The key of the report in ``Scene.info``."""
EXPECTED = "not a surface"
"""Reasons starting so are drops every import makes (spaces, openings): no cause for
attention."""
SHOWN = 200
"""Lines listed per section in ``lines()`` before "... N more"."""
NAMES = 6
"""Names listed on one line of alike items."""


@dataclass(frozen=True)
class ImportItem:
    """One element or group of the file and what it became.

    ``kind`` is the IFC class (``IfcCovering``) or what the item is in its format
    (``group``, ``glTF primitive``); ``becomes`` names the lighting group or zone
    (None when dropped); ``reason`` says why an item was dropped, kept in another group
    or is a plain group though it could have been a zone; ``area_m2`` is the surface area
    it left in the scene."""

    kind: str
    name: str
    outcome: str
    becomes: str | None = None
    reason: str = ""
    area_m2: float = 0.0

    def __post_init__(self):
        if self.outcome not in OUTCOMES:
            raise ValueError(f"outcome {self.outcome!r} is not one of {', '.join(OUTCOMES)}")

    def to_dict(self) -> dict:
        return {
            "kind": self.kind,
            "name": self.name,
            "outcome": self.outcome,
            "becomes": self.becomes,
            "reason": self.reason,
            "area_m2": round(float(self.area_m2), 4),
        }


@dataclass(frozen=True)
class ImportReport:
    """The items of one imported file (``source``: its name), in file order."""

    source: str
    items: tuple[ImportItem, ...] = ()
    skipped: tuple[str, ...] = ()
    """What was skipped within items that stay (faces dropped, cuts not made), one line
    each."""
    notes: tuple[str, ...] = ()
    """What the import assumed that the file did not say (a default reflectance where
    the file has no materials), one line each."""

    def counts(self) -> dict[str, dict[str, int]]:
        """Kind -> outcome -> number of items, kinds in order of first appearance."""
        out: dict[str, dict[str, int]] = {}
        for it in self.items:
            row = out.setdefault(it.kind, dict.fromkeys(OUTCOMES, 0))
            row[it.outcome] += 1
        return out

    def of(self, outcome: str) -> list[ImportItem]:
        return [it for it in self.items if it.outcome == outcome]

    @property
    def dropped(self) -> list[ImportItem]:
        return self.of("dropped")

    @property
    def not_zoned(self) -> list[ImportItem]:
        """Groups that are plain surfaces though their kind makes zones (a reason given)."""
        return [it for it in self.items if it.outcome == "group" and it.reason]

    @property
    def needs_attention(self) -> bool:
        """Whether something was dropped (besides spaces, openings and the like),
        skipped, or did not become the zone it could have been."""
        unexpected = [it for it in self.dropped if not it.reason.startswith(EXPECTED)]
        return bool(self.skipped or self.not_zoned or unexpected or self.notes)

    def summary(self) -> str:
        """One line: ``"room.ifc: 12 elements: 3 zones, 8 groups, 1 dropped"``."""
        n = {o: len(self.of(o)) for o in OUTCOMES}
        parts = [
            f"{n['zone']} zone{'s' * (n['zone'] != 1)}",
            f"{n['group']} group{'s' * (n['group'] != 1)}",
        ]
        if n["kept"]:
            parts.append(f"{n['kept']} kept in other groups")
        parts.append(f"{n['dropped']} dropped")
        if self.skipped:
            parts.append(f"{len(self.skipped)} skipped within them")
        unit = "element" if any(it.kind.startswith("Ifc") for it in self.items) else "item"
        total = len(self.items)
        return f"{self.source}: {total} {unit}{'s' * (total != 1)}: {', '.join(parts)}"

    def lines(self) -> list[str]:
        """The summary, a table of kinds by outcome, then the items dropped, left
        without their zone or kept in another group (alike ones on one line, with their
        reason), what was skipped and what was assumed."""
        head = f"  {'kind':<28} {'zone':>5} {'group':>6} {'kept':>5} {'dropped':>8}"
        out = [self.summary(), head]
        for kind, row in self.counts().items():
            out.append(
                f"  {kind:<28} {row['zone']:>5} {row['group']:>6} {row['kept']:>5} "
                f"{row['dropped']:>8}"
            )
        for title, items in (
            ("dropped", self.dropped),
            ("not a zone", self.not_zoned),
            ("kept in another group", self.of("kept")),
        ):
            if items:
                out.append(f"{title} ({len(items)}):")
                out += [f"  {line}" for line in _alike(items)]
        if self.skipped:
            out.append(f"skipped ({len(self.skipped)}):")
            out += [f"  {line}" for line in self.skipped[:SHOWN]]
            if len(self.skipped) > SHOWN:
                out.append(f"  ... {len(self.skipped) - SHOWN} more (--json lists them all)")
        if self.notes:
            out.append(f"assumed ({len(self.notes)}):")
            out += [f"  {line}" for line in self.notes]
        return out

    def to_dict(self) -> dict:
        return {
            "source": self.source,
            "summary": self.summary(),
            "counts": self.counts(),
            "items": [it.to_dict() for it in self.items],
            "skipped": list(self.skipped),
            "notes": list(self.notes),
        }

    @classmethod
    def from_dict(cls, data: dict) -> ImportReport:
        items = tuple(
            ImportItem(
                str(d["kind"]),
                str(d["name"]),
                str(d["outcome"]),
                d.get("becomes"),
                str(d.get("reason", "")),
                float(d.get("area_m2", 0.0)),
            )
            for d in data.get("items", ())
        )
        skipped = tuple(str(s) for s in data.get("skipped", ()))
        notes = tuple(str(s) for s in data.get("notes", ()))
        return cls(str(data.get("source", "")), items, skipped, notes)


def _alike(items: list[ImportItem]) -> list[str]:
    """One line per kind, target and reason: ``"36 IfcCovering: reason: a #1, b #2"``."""
    by: dict[tuple, list[str]] = {}
    for it in items:
        target = it.becomes if it.outcome != "dropped" else None
        by.setdefault((it.kind, target, it.reason), []).append(it.name)
    out = []
    for (kind, target, reason), names in by.items():
        into = f" -> {target}" if target else ""
        more = f", ... ({len(names) - NAMES} more)" if len(names) > NAMES else ""
        why = f": {reason}" if reason else ""
        out.append(f"{len(names)} {kind}{into}{why}: {', '.join(names[:NAMES])}{more}")
    if len(out) > SHOWN:
        out = [*out[:SHOWN], f"... {len(out) - SHOWN} more lines (--json lists them all)"]
    return out


def report_of(scene) -> ImportReport | None:
    """The import report kept in ``scene.info`` (None for built-in scenes)."""
    data = scene.info.get(KEY) if isinstance(scene.info, dict) else None
    return ImportReport.from_dict(data) if isinstance(data, dict) else None
