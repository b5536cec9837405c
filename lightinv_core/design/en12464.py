"""EN 12464-1 lighting requirements for a few common activities, as grid intentions.

Values from EN 12464-1:2011 (``EDITION``), "Light and lighting - Lighting of work places
- Part 1: Indoor work places", clause 5, the schedule of lighting requirements; each
preset gives its table row's reference number (5.26.2: table 5.26 "Offices", row 2):
maintained illuminance Em (lux) on the task area, its uniformity U0 = Emin / Em, and
the least colour rendering index Ra (for the record: a property of the product, not of
the layout). Every list and report names the edition with the row (``Requirement.label``).
The 2021 edition (EN 12464-1:2021) renumbers the schedule, gives "required" and
"modified" Em and changes some rows' values; it is not transcribed here (no copy of its
tables was at hand to check them): for a project under the 2021 edition or a national
annex, enter its values as an intention on the work plane.
"""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.design.model import DesignError, Intention
from lightinv_core.kinds import Scenario

EDITION = "EN 12464-1:2011"
"""The edition the presets' values and reference numbers come from."""


@dataclass(frozen=True)
class Requirement:
    """One activity's requirement: ``em`` lux, ``u0``, ``ra``, and where it comes from."""

    key: str
    activity: str
    em: float
    u0: float
    ra: int
    reference: str

    @property
    def label(self) -> str:
        """The activity, its edition and table row, and its values, for lists."""
        return (
            f"{self.activity} ({EDITION} ref. {self.reference}): {self.em:g} lux, U0 {self.u0:.2f}"
        )


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
