"""The design's sources and geometric rules as the user edits them.

``SourceEdits`` is the document's concern for sources, luminaire arrays and the rules
that tie them (a mixin over ``state.DocumentState``); each edit is a pure function of
the design in rules.py, applied with ``_set_design`` (an undoable edit, then a relight).
"""

from __future__ import annotations

from dataclasses import replace

from lightinv_core.design.model import ARRAY_RULES, Rule, Source
from lightinv_core.editing import rules
from lightinv_core.editing.state import DocumentState


class SourceEdits(DocumentState):
    """Add, change, move and remove sources and arrays; tie them with rules."""

    def add_source(self, zone: str, name: str | None = None) -> Source:
        """A new source centred in ``zone`` (see ``rules.new_source``); it becomes the
        current one."""
        src = rules.new_source(
            self.design,
            zone,
            self.zone_kind(zone),
            self.zone_size(zone),
            name,
            self.zone_outline(zone),
        )
        design = rules.with_source(self.design, src)
        self.current_source = src.name
        self._set_design(design, f"add source {src.name}")
        return src

    def update_source(self, name: str, **fields) -> None:
        """Change fields of a source (rect, flux, filter, free, ...); DesignError on a bad
        value, leaving the design unchanged."""
        self._set_design(
            rules.with_source_fields(self.design, name, **fields), f"edit source {name}"
        )

    def move_source(self, name: str, du: float, dv: float) -> None:
        """Shift a source by (du, dv) metres, kept inside its zone."""
        s = self.design.source(name)
        rect = rules.moved_rect(s, du, dv, self.zone_size(s.zone), self.zone_outline(s.zone))
        self._set_design(rules.with_source_fields(self.design, name, rect=rect), f"move {name}")

    def remove_source(self, name: str) -> None:
        """Delete a source and the rules that name it."""
        design = rules.without_source(self.design, name)
        if self.current_source == name:
            self.current_source = design.sources[0].name if design.sources else None
        self._set_design(design, f"remove source {name}")

    def set_current_source(self, name: str | None) -> None:
        """Which source the source panel edits and the viewport drags."""
        self.current_source = name
        self._emit_design()

    # -- rules ----------------------------------------------------------------------------------
    def set_centred(self, name: str, centred: bool) -> None:
        """Tie (or untie) a source to the centre of its zone."""
        self._set_design(
            rules.with_centred(self.design, name, centred),
            f"{'centre' if centred else 'free'} {name}",
        )

    def set_mirror(self, name: str, original: str | None, axis: str = "u") -> None:
        """Make source ``name`` the mirror image of ``original`` along a zone axis (None:
        free again)."""
        self._set_design(
            rules.with_mirror(self.design, name, original, axis),
            f"mirror {name}" if original else f"unmirror {name}",
        )

    def centred(self, name: str) -> bool:
        """Whether a centred rule ties ``name``."""
        return rules.is_centred(self.design, name)

    def mirror_of(self, name: str) -> tuple[str, str] | None:
        """(original, axis) if ``name`` mirrors another source."""
        return rules.mirror_of(self.design, name)

    def add_rule(self, rule: Rule) -> None:
        """Append a geometric rule (DesignError if it names unknown sources or clashes)."""
        self._set_design(
            replace(self.design, rules=(*self.design.rules, rule)),
            f"add rule {rules.rule_text(rule)[0]}",
        )

    def remove_rule(self, index: int) -> None:
        """Delete the rule at ``index`` of the design's rules."""
        rule = self.design.rules[index]
        kept = self.design.rules[:index] + self.design.rules[index + 1 :]
        self._set_design(
            replace(self.design, rules=kept), f"remove rule {rules.rule_text(rule)[0]}"
        )

    # -- luminaire arrays -----------------------------------------------------------------------
    def set_arrays(self, arrays, label: str = "edit luminaire arrays") -> None:
        """Replace the design's luminaire arrays (DesignError if a rule or name clashes):
        add, edit and remove are this with another tuple. Rules on arrays that are gone
        go with them."""
        arrays = tuple(arrays)
        names = {a.name for a in arrays}
        kept = tuple(
            r for r in self.design.rules if r.kind not in ARRAY_RULES or set(r.sources) <= names
        )
        self._set_design(replace(self.design, arrays=arrays, rules=kept), label)
