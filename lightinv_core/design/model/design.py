"""A complete inverse problem on one scene: the design's objects and the checks that
span them (unique names, rules naming sources that exist, intentions naming work planes
and observers that exist, goals that need a work plane or target sources)."""

from __future__ import annotations

import numbers
from dataclasses import dataclass, field

from lightinv_core.design.model.array import LuminaireArray
from lightinv_core.design.model.calc_object import CalcObject
from lightinv_core.design.model.control import DEFAULT_CONTROL_GROUP, ControlGroup
from lightinv_core.design.model.daylight import Daylight, Workplane
from lightinv_core.design.model.goal import Goal
from lightinv_core.design.model.intention import Intention
from lightinv_core.design.model.observer import Observer
from lightinv_core.design.model.rule import ARRAY_RULES, Rule
from lightinv_core.design.model.source import Source
from lightinv_core.errors import DesignError
from lightinv_core.goals import goal_spec
from lightinv_core.kinds import GoalKind


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:40] + "..."


def _items(value, where: str, what: str) -> tuple:
    """``value`` as a tuple: a list or tuple (not a string, a number or None)."""
    if isinstance(value, str | bytes) or not isinstance(value, tuple | list):
        raise DesignError(f"{where}: {what} must be a list, got {_short(value)}")
    return tuple(value)


@dataclass(frozen=True)
class Design:
    """A complete inverse problem on one scene."""

    sources: tuple[Source, ...]
    goals: tuple[Goal, ...]
    rules: tuple[Rule, ...] = ()
    intentions: tuple[Intention, ...] = ()
    target_sources: tuple[Source, ...] = ()
    daylight: Daylight = field(default_factory=Daylight)
    penalty_power: int = 2
    arrays: tuple[LuminaireArray, ...] = ()
    workplanes: tuple[Workplane, ...] = ()
    observers: tuple[Observer, ...] = ()
    control_groups: tuple[ControlGroup, ...] = ()
    calc_objects: tuple[CalcObject, ...] = ()

    def __post_init__(self) -> None:
        for name, cls in (
            ("sources", Source),
            ("goals", Goal),
            ("rules", Rule),
            ("intentions", Intention),
            ("target_sources", Source),
            ("arrays", LuminaireArray),
            ("workplanes", Workplane),
            ("observers", Observer),
            ("control_groups", ControlGroup),
            ("calc_objects", CalcObject),
        ):
            items = _items(getattr(self, name), "design", name)
            bad = [x for x in items if not isinstance(x, cls)]
            if bad:
                raise DesignError(
                    f"design: {name} must hold {cls.__name__} values, got {_short(bad[0])}"
                )
            object.__setattr__(self, name, items)
        if not isinstance(self.daylight, Daylight):
            raise DesignError(f"design: daylight must be a Daylight, got {_short(self.daylight)}")
        pp = self.penalty_power
        if not isinstance(pp, numbers.Integral) or isinstance(pp, bool):
            raise DesignError(
                f"penalty power must be an even positive integer (paper eq. 3), got {_short(pp)}"
            )
        names = [s.name for s in self.sources]
        array_names = [a.name for a in self.arrays]
        for what, items in (
            ("source", names),
            ("source or array", names + array_names),
            (
                "work plane or calculation object",
                [w.name for w in self.workplanes] + [c.name for c in self.calc_objects],
            ),
            ("observer", [o.name for o in self.observers]),
            ("target source", [s.name for s in self.target_sources]),
            ("intention", [i.name for i in self.intentions]),
            ("control group", [c.name for c in self.control_groups]),
            ("goal", [g.kind for g in self.goals]),
        ):
            if len(set(items)) != len(items):
                raise DesignError(
                    f"{what} names must be unique (repeated: "
                    f"{sorted({x for x in items if items.count(x) > 1})})"
                )
        if not self.goals:
            raise DesignError("give at least one goal")
        known, known_arrays = set(names), set(array_names)
        for r in self.rules:
            if r.kind in ARRAY_RULES:
                missing = [s for s in r.sources if s not in known_arrays]
                if missing:
                    raise DesignError(
                        f"rule {r.kind!r} names {missing}, which are not luminaire arrays"
                    )
                continue
            missing = [s for s in r.sources if s not in known]
            if missing:
                also = [s for s in missing if s in known_arrays]
                hint = f" ({also} are arrays: they take shr and clearance rules)" if also else ""
                raise DesignError(f"rule {r.kind!r} names unknown sources {missing}{hint}")
        planes = {w.name for w in self.workplanes}
        readable = planes | {c.name for c in self.calc_objects}
        for it in self.intentions:
            if it.grid is not None and it.grid not in readable:
                if not self.calc_objects:
                    raise DesignError(
                        f"intention {it.name!r}: no work plane {it.grid!r} "
                        f"(work planes: {sorted(planes) or 'none'})"
                    )
                raise DesignError(
                    f"intention {it.name!r}: no work plane or calculation object {it.grid!r} "
                    f"(they are: {sorted(readable)})"
                )
        eyes = {o.name for o in self.observers}
        for it in self.intentions:
            missing = [o for o in it.observers or () if o not in eyes]
            if missing:
                raise DesignError(
                    f"intention {it.name!r}: no observer {missing[0]!r} "
                    f"(observers: {sorted(eyes) or 'none'})"
                )
        if self.daylight.workplane is not None and self.daylight.workplane not in planes:
            raise DesignError(
                f"daylight workplane {self.daylight.workplane!r} is not a work plane "
                f"(work planes: {sorted(planes) or 'none'})"
            )
        self._check_control_groups(planes)
        annual = [str(g.kind) for g in self.goals if goal_spec(g.kind).annual]
        if annual and not self.workplanes:
            raise DesignError(
                f"goals {annual} are measured on a work plane (dimming and sDA): add one"
            )
        if any(g.kind == GoalKind.MATCH for g in self.goals) and not self.target_sources:
            raise DesignError("a match goal needs target_sources (the light to reproduce)")
        if self.penalty_power < 1 or self.penalty_power % 2:
            raise DesignError("penalty power must be an even positive integer (paper eq. 3)")

    def _check_control_groups(self, planes: set[str]) -> None:
        """Each luminaire names a declared control group (or the default one), and each
        group's sensor a work plane that exists."""
        known = {c.name for c in self.control_groups} | {DEFAULT_CONTROL_GROUP}
        for what, items in (("source", self.sources), ("array", self.arrays)):
            for x in items:
                if x.control_group not in known:
                    raise DesignError(
                        f"{what} {x.name!r}: no control group {x.control_group!r} "
                        f"(control groups: {sorted(known)})"
                    )
        for c in self.control_groups:
            if c.workplane is not None and c.workplane not in planes:
                raise DesignError(
                    f"control group {c.name!r}: no work plane {c.workplane!r} "
                    f"(work planes: {sorted(planes) or 'none'})"
                )

    @property
    def control_plane(self) -> Workplane | None:
        """The work plane the climate goals and dimming read (``daylight.workplane`` or
        the first), None without work planes."""
        name = self.daylight.workplane
        for w in self.workplanes:
            if name is None or w.name == name:
                return w
        return None

    def array(self, name: str) -> LuminaireArray:
        """The luminaire array called ``name``."""
        for a in self.arrays:
            if a.name == name:
                return a
        raise DesignError(f"no luminaire array {name!r}")

    def source(self, name: str) -> Source:
        """The source called ``name``."""
        for s in self.sources:
            if s.name == name:
                return s
        raise DesignError(f"no source {name!r}")
