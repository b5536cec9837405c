"""The daylight of a design and its climate, and the work planes its grids lie on."""

from __future__ import annotations

from dataclasses import dataclass, field

from lightinv_core.errors import DesignError
from lightinv_core.fields import (
    Boolean,
    Choice,
    Custom,
    Number,
    Numbers,
    ObjectSpec,
    String,
    _describe,
    _fail,
    choice_of,
    declare,
)
from lightinv_core.kinds import MAX_LUX, Edition

MAX_WATTS = 1e9
"""W: the largest electric power a project may name."""

SKY_SUBDIVISIONS = (1, 2, 4)
"""Reinhart subdivisions of the sky a project's clear glazing may use (1: Tregenza's
145 patches, 2: 577, 4: 2,305), as ``lightinv-cli simulate --sky-subdivision``."""


def _sky_subdivision(v, path: str) -> int:
    if type(v) is int and v in SKY_SUBDIVISIONS:
        return v
    _fail(path, f"expected one of 1, 2, 4 (Reinhart's MF), got {_describe(v)}")


SKY_SUBDIVISION = Custom(_sky_subdivision, "`1`, `2` or `4`", {"enum": list(SKY_SUBDIVISIONS)})
"""The check of ``Daylight.sky_subdivision``."""


@dataclass(frozen=True)
class Workplane:
    """An EN 12464-1 calculation grid: a horizontal plane ``height`` m above the floor
    group ``group``, ``border`` m left out along its edges, points spaced by the
    standard's rule p = 0.2 x 5^log10(d) as its ``edition`` counts them
    (docs/photometry.md); that edition's presets and criteria apply to it. Grid points
    are receivers only: they take no part in the light transport."""

    name: str = field(metadata=declare(String(), "unique among the work planes"))
    height: float = field(
        default=0.8,
        metadata=declare(Number(lo=0.0, hi=1000.0), "above the floor group, m", always=True),
    )
    border: float = field(
        default=0.5,
        metadata=declare(
            Number(lo=0.0, hi=1000.0), "left out along the floor's edges, m", always=True
        ),
    )
    group: str = field(
        default="floor", metadata=declare(String(), "the floor group it lies over", always=True)
    )
    edition: Edition = field(
        default=Edition.EN12464_2011,
        metadata=declare(
            Choice(lambda: tuple(Edition), Edition),
            "the EN 12464-1 edition it follows: its grid rule (2011: points per side "
            "rounded up, each side on its own; 2021: the cell from the longer side, "
            "points per side rounded) and its presets; absent in files saved before "
            "editions were named, which read as 2011 (the window proposes 2021 for a "
            "new work plane)",
        ),
    )

    def __post_init__(self) -> None:
        where = f"work plane {self.name!r}" if isinstance(self.name, str) else "a work plane"
        WORKPLANE_FIELDS.check_fields(self, where)


WORKPLANE_FIELDS = ObjectSpec.of(Workplane, "workplane")
"""The work plane's fields, in the order a project file writes them."""


@dataclass(frozen=True)
class Daylight:
    """The daylight of the design and its climate (docs/daylight.md).

    ``exterior_lux`` and ``transmittance``: in the ``design`` scenario every skylight
    emits filter x transmittance x exterior_lux (the paper's model). The other fields
    serve the other scenarios and the annual goals: ``weather`` (an EPW or TMY3 path,
    or "builtin": the shipped Greensboro TMY3), ``north_deg`` (compass bearing of the
    scene's +y axis), ``occupancy`` (local hours [start, end) of the occupied day) on
    weekdays only unless ``weekdays`` is False, ``ground_reflectance``, ``overcast_lux``
    (horizontal lux of the design overcast sky), daylight-linked dimming to
    ``target_lux`` on the work plane ``workplane`` (default: the first) between
    ``min_level`` and full output, with ``standby_w`` drawn all year; fixed clear
    glazing sees the sky in Reinhart ``sky_subdivision`` patches (1: Tregenza's 145).
    """

    exterior_lux: float = field(
        default=10000.0,
        metadata=declare(
            Number(lo=0.0, hi=MAX_LUX), "exterior diffuse illuminance, lux", always=True
        ),
    )
    transmittance: float = field(
        default=0.6,
        metadata=declare(
            Number(lo=0.0, hi=1.0), "fraction of it the skylight glazing lets through", always=True
        ),
    )
    weather: str = field(
        default="builtin",
        metadata=declare(
            String(),
            'EPW or TMY3 weather file (relative to the project), or `"builtin"`: '
            "the shipped Greensboro TMY3 (docs/daylight.md)",
        ),
    )
    north_deg: float = field(
        default=0.0,
        metadata=declare(
            Number(lo=-360.0, hi=360.0),
            "compass bearing of the scene's +y axis, degrees (0: +y is north)",
        ),
    )
    occupancy: tuple[float, float] = field(
        default=(8.0, 18.0),
        metadata=declare(
            Numbers(2, Number(lo=0.0, hi=24.0)),
            "occupied hours `[start, end)` of the day, local time",
        ),
    )
    weekdays: bool = field(
        default=True, metadata=declare(Boolean(), "occupied Monday to Friday only")
    )
    ground_reflectance: float = field(
        default=0.2,
        metadata=declare(
            Number(lo=0.0, hi=0.99),
            "of the ground outside, for the light it reflects onto the glazing",
        ),
    )
    overcast_lux: float = field(
        default=10000.0,
        metadata=declare(
            Number(lo=0.0, hi=2e5),
            "horizontal exterior illuminance of the design overcast sky, lux",
        ),
    )
    target_lux: float = field(
        default=500.0,
        metadata=declare(
            Number(lo=0.0, hi=1e5),
            "daylight-linked dimming keeps the work plane's mean at this, lux",
        ),
    )
    min_level: float = field(
        default=0.1,
        metadata=declare(Number(lo=0.0, hi=1.0), "lowest dimming level of the luminaires"),
    )
    standby_w: float = field(
        default=0.0,
        metadata=declare(
            Number(lo=0.0, hi=MAX_WATTS),
            "standby power of the lighting controls, drawn all year, W",
        ),
    )
    workplane: str | None = field(
        default=None,
        metadata=declare(
            String(),
            "the work plane the dimming and the annual goals read (default: the first)",
            nullable=True,
        ),
    )
    sunlight_date: str = field(
        default="03-21",
        metadata=declare(
            String(),
            "EN 17037 sunlight exposure: the day it is counted on, `MM-DD` from 02-01 to 03-21",
        ),
    )
    sunlight_min_altitude: float | None = field(
        default=None,
        metadata=declare(
            Number(lo=-5.0, hi=89.0),
            "EN 17037 sunlight exposure: the sun counts above this altitude, degrees (the "
            "standard's value for the site; a sunlight intention needs it)",
            nullable=True,
        ),
    )
    en17037_basis: str = field(
        default="points",
        metadata=declare(
            choice_of("points", "hours"),
            "EN 17037 daylight provision: `points` (each point reaches the illuminance in "
            "half the daylight hours, over the plane fraction; Honeybee) or `hours` (each "
            "hour the plane fraction reaches it, in half the daylight hours; ClimateStudio)",
        ),
    )
    dgp_limit: float = field(
        default=0.40,
        metadata=declare(
            Number(gt=0.184, hi=1.0),
            "simplified DGP at observers (`dgp` intentions): the limit whose exceedance "
            "is counted, 0.40 (EN 17037's medium glare protection; 0.45 minimum, 0.35 high)",
        ),
    )
    sky_subdivision: int = field(
        default=1,
        metadata=declare(
            SKY_SUBDIVISION,
            "clear glazing (fixed): the sky in Reinhart MF patches, 1 (Tregenza's 145, "
            "the default), 2 (577) or 4 (2,305); the sun is traced by direction either way",
        ),
    )

    def __post_init__(self) -> None:
        DAYLIGHT_FIELDS.check_fields(self, "daylight")
        start, end = self.occupancy
        if not start < end:
            raise DesignError(f"daylight occupancy: start {start:g} h is not before end {end:g} h")
        if not any(start <= h + 0.5 < end for h in range(24)):
            raise DesignError(
                f"daylight occupancy {start:g}-{end:g} h holds no hour: an hour counts when "
                "its middle (e.g. 8:30 for 8-9) lies in [start, end)"
            )


DAYLIGHT_FIELDS = ObjectSpec.of(Daylight, "daylight")
"""The daylight's fields, in the order a project file writes them."""
