"""EN 12464-1 lighting requirements for a few common activities, as grid intentions.

Values from EN 12464-1:2011, "Light and lighting - Lighting of work places - Part 1:
Indoor work places", the schedule of lighting requirements (table and reference number
given per activity): maintained illuminance Em (lux) on the task area and its
uniformity U0 = Emin / Em, and the least colour rendering index Ra (for the record: it
is a property of the product, not of the layout). The 2021 edition keeps these as its
"required" values and adds higher "modified" ones for some contexts; check the
edition and the national annex in force for a real project.
"""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.design.model import DesignError, Intention
from lightinv_core.kinds import Scenario


@dataclass(frozen=True)
class Requirement:
    """One activity's requirement: ``em`` lux, ``u0``, ``ra``, and where it comes from."""

    key: str
    activity: str
    em: float
    u0: float
    ra: int
    reference: str


REQUIREMENTS = (
    Requirement("corridor", "Circulation areas and corridors", 100.0, 0.40, 40, "5.1.1"),
    Requirement("archive", "Archives", 200.0, 0.40, 80, "5.26.7"),
    Requirement("filing", "Filing, copying, etc.", 300.0, 0.40, 80, "5.26.1"),
    Requirement("reception", "Reception desk", 300.0, 0.60, 80, "5.26.6"),
    Requirement("classroom", "Classrooms, tutorial rooms", 300.0, 0.60, 80, "5.36.2"),
    Requirement("office", "Writing, typing, reading, data processing", 500.0, 0.60, 80, "5.26.2"),
    Requirement("meeting", "Conference and meeting rooms", 500.0, 0.60, 80, "5.26.5"),
    Requirement("cad", "CAD work stations", 500.0, 0.60, 80, "5.26.4"),
    Requirement("drawing", "Technical drawing", 750.0, 0.70, 80, "5.26.3"),
)
"""The presets, by key."""


def requirement(key: str) -> Requirement:
    """The preset called ``key`` (DesignError listing the keys otherwise)."""
    for r in REQUIREMENTS:
        if r.key == key:
            return r
    keys = ", ".join(r.key for r in REQUIREMENTS)
    raise DesignError(f"no EN 12464-1 preset {key!r}; presets: {keys}")


def preset_intention(key: str, grid: str, name: str | None = None) -> Intention:
    """An intention on work plane ``grid`` asking for the preset's Em and U0 at night
    (luminaires only): the standard's values must hold without daylight."""
    r = requirement(key)
    return Intention(
        name or r.key, grid=grid, average=r.em, uniformity=r.u0, scenario=Scenario.NIGHT.value
    )
