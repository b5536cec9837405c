"""The design's daylight-linked control groups as the user edits them.

``ControlEdits`` is the document's concern for control groups (a mixin over
``state.DocumentState``): add, change (a new name follows into the luminaires that name
it), remove (its luminaires go back to the default group) and the group a luminaire
source or array is dimmed with. Each edit is one undoable ``_set_design``.
"""

from __future__ import annotations

from dataclasses import replace

from lightinv_core.design.model import DEFAULT_CONTROL_GROUP, ControlGroup, Design, DesignError
from lightinv_core.editing.state import DocumentState
from lightinv_core.light.control_groups import control_plan
from lightinv_core.light.grids import design_grids


def new_group_name(design: Design, stem: str = "group") -> str:
    """A control group name ``design`` does not use yet: "group 1", "group 2", ..."""
    used = {c.name for c in design.control_groups} | {DEFAULT_CONTROL_GROUP}
    i = 1
    while f"{stem} {i}" in used:
        i += 1
    return f"{stem} {i}"


def _regrouped(design: Design, old: str, new: str, groups: tuple[ControlGroup, ...]) -> Design:
    """``design`` with control groups ``groups`` and the luminaires of group ``old`` moved
    to ``new`` (in one step: the design checks that every luminaire's group exists)."""
    sources = tuple(
        replace(s, control_group=new) if s.control_group == old else s for s in design.sources
    )
    arrays = tuple(
        replace(a, control_group=new) if a.control_group == old else a for a in design.arrays
    )
    return replace(design, sources=sources, arrays=arrays, control_groups=groups)


class ControlEdits(DocumentState):
    """Add, change and remove control groups; put luminaires in them."""

    def control_group_names(self) -> tuple[str, ...]:
        """The groups a luminaire may join: the default one, then the declared ones."""
        declared = tuple(c.name for c in self.design.control_groups)
        return declared if DEFAULT_CONTROL_GROUP in declared else (DEFAULT_CONTROL_GROUP, *declared)

    def add_control_group(self, group: ControlGroup | None = None) -> ControlGroup:
        """Add ``group`` (default: a new one named "group N" reading the control plane)."""
        group = group or ControlGroup(new_group_name(self.design))
        design = self._checked(
            replace(self.design, control_groups=(*self.design.control_groups, group))
        )
        self._set_design(design, f"add control group {group.name}")
        return group

    def update_control_group(self, name: str, /, **fields) -> None:
        """Change a declared group's fields (name, sensor, workplane, min_level); a new
        name follows into its luminaires. DesignError on a bad value or a name in use."""
        old = self._group(name)
        group = replace(old, **fields)
        if group == old:
            return
        if group.name != name and group.name in self.control_group_names():
            raise DesignError(f"control group names must be unique: {group.name!r} is used")
        groups = tuple(group if c.name == name else c for c in self.design.control_groups)
        design = self._checked(_regrouped(self.design, name, group.name, groups))
        self._set_design(design, f"edit control group {name}")

    def remove_control_group(self, name: str) -> None:
        """Delete a declared group; its luminaires go back to the default group."""
        self._group(name)
        groups = tuple(c for c in self.design.control_groups if c.name != name)
        design = _regrouped(self.design, name, DEFAULT_CONTROL_GROUP, groups)
        self._set_design(design, f"remove control group {name}")

    def set_luminaire_group(self, name: str, group: str) -> None:
        """Put the luminaire source or array ``name`` in control group ``group``."""
        d = self.design
        if any(s.name == name for s in d.sources):
            items = tuple(
                replace(s, control_group=group) if s.name == name else s for s in d.sources
            )
            design = replace(d, sources=items)
        else:
            d.array(name)  # DesignError when there is none
            items = tuple(
                replace(a, control_group=group) if a.name == name else a for a in d.arrays
            )
            design = replace(d, arrays=items)
        if design != d:
            self._set_design(self._checked(design), f"{name}: control group {group}")

    def _checked(self, design: Design) -> Design:
        """``design``, its sensors checked on the work planes' grids when the light model
        exists (DesignError: a sensor region that holds no grid point)."""
        if self.light is not None and design.workplanes:
            control_plan(design, design_grids(self.light, design.workplanes))
        return design

    def _group(self, name: str) -> ControlGroup:
        for c in self.design.control_groups:
            if c.name == name:
                return c
        raise DesignError(f"no declared control group {name!r}")
