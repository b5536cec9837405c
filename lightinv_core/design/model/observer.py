"""Observers: where a designer places an eye to rate glare (UGR, CIE 117) from."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from lightinv_core.errors import DesignError
from lightinv_core.fields import Number, Numbers, ObjectSpec, String, declare

SEATED_EYE = 1.2
"""Eye height (m) of a seated observer above the floor (CIE 117, EN 12464-1)."""
STANDING_EYE = 1.7
"""Eye height (m) of a standing observer, for reference."""


@dataclass(frozen=True)
class Observer:
    """An eye looking into the room: at ``position`` (x, y) m in scene coordinates,
    ``height`` m above the floor group ``group`` (1.2 m seated), looking along
    ``azimuth`` (degrees in the horizontal plane, counter-clockwise from the scene's +x
    axis towards +y) or along ``direction`` (a vector, x y z), one of the two.

    CIE 117's UGR rates a horizontal line of sight; a tilted ``direction`` is used as
    given, a vertical one has no line of sight and is refused.
    """

    name: str = field(metadata=declare(String(), "unique among the observers"))
    position: tuple[float, float] = field(
        metadata=declare(Numbers(2), "`[x, y]`: the eye's place in the scene's plan, m")
    )
    height: float = field(
        default=SEATED_EYE,
        metadata=declare(
            Number(lo=0.0, hi=1000.0),
            "eye above the floor group, m (1.2 seated, 1.7 standing)",
            always=True,
        ),
    )
    azimuth: float | None = field(
        default=None,
        metadata=declare(
            Number(lo=-360.0, hi=360.0),
            "horizontal view direction, degrees counter-clockwise from +x towards +y; "
            "this or `direction`",
            nullable=True,
        ),
    )
    direction: tuple[float, float, float] | None = field(
        default=None,
        metadata=declare(
            Numbers(3), "view direction `[x, y, z]`; this or `azimuth`", nullable=True
        ),
    )
    group: str = field(
        default="floor",
        metadata=declare(String(), "the floor group the eye stands over", always=True),
    )

    def __post_init__(self) -> None:
        where = f"observer {self.name!r}" if isinstance(self.name, str) else "an observer"
        OBSERVER_FIELDS.check_fields(self, where)
        if (self.azimuth is None) == (self.direction is None):
            raise DesignError(f"{where}: give its view as an azimuth or a direction (one)")
        if self.direction is not None:
            d = np.asarray(self.direction, dtype=float)
            norm = float(np.linalg.norm(d))
            if norm == 0.0:
                raise DesignError(f"{where}: the view direction [0, 0, 0] has no direction")
            if math.hypot(d[0], d[1]) < 1e-6 * norm:
                raise DesignError(
                    f"{where}: the view direction is vertical; UGR needs a line of sight "
                    "(look across the room)"
                )

    @property
    def view(self) -> np.ndarray:
        """The unit view direction (3,)."""
        if self.direction is not None:
            d = np.asarray(self.direction, dtype=float)
            return d / np.linalg.norm(d)
        a = math.radians(float(self.azimuth))
        return np.array([math.cos(a), math.sin(a), 0.0])


OBSERVER_FIELDS = ObjectSpec.of(Observer, "observer")
"""The observer's fields, in the order a project file writes them."""
