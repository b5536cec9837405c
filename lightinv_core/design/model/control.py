"""Daylight-linked control groups: luminaires dimmed together by one sensor region.

Every luminaire source and luminaire array belongs to one control group (its
``control_group``, ``DEFAULT_CONTROL_GROUP`` unless it names another). A group's sensor
reads the mean daylight over the grid points of a work plane (``workplane``, default the
design's control plane) inside a plan rectangle (``sensor``, world x0, y0, x1, y1 in m;
the whole plane when absent), and each occupied hour the group dims to top that mean up
to its ``target_lux`` (default ``daylight.target_lux``) with its own luminaires' light
there at full output, as its ``mode`` says (``climate.control_modes``: ``dimming``,
continuously down to ``min_level`` at most, the ballast's floor, default
``daylight.min_level``; or ``switching``, off while the daylight alone meets the
target and full output otherwise, with a ``dead_band``: off once it reaches the target
x (1 + band), back on below the target). A design
that declares no group and names none keeps the one group of all its luminaires read on
the whole control plane: its results are bit for bit those before groups existed.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lightinv_core.climate.control_modes import DIMMING, control_mode, control_mode_names
from lightinv_core.errors import DesignError
from lightinv_core.fields import Choice, Number, Numbers, ObjectSpec, String, declare

DEFAULT_CONTROL_GROUP = "all"
"""The control group of every luminaire that names none."""


@dataclass(frozen=True)
class ControlGroup:
    """A daylight-linked control group (see the module): its ``name``, the ``sensor``
    rectangle (x0, y0, x1, y1, m, plan; None: the whole work plane) on ``workplane``
    (None: the control plane), its lowest dimming level ``min_level`` (None: the
    daylight's), its control ``mode`` (a ``climate.control_modes`` name) and the
    illuminance ``target_lux`` its sensor is kept at (lux; None: the daylight's), and
    for switching its ``dead_band`` (fraction of the target)."""

    name: str = field(metadata=declare(String(), "unique among the control groups"))
    sensor: tuple[float, float, float, float] | None = field(
        default=None,
        metadata=declare(
            Numbers(4),
            "`[x0, y0, x1, y1]`: the plan rectangle of work-plane points its sensor reads, "
            "m (lower edges in, upper edges out); absent: the whole work plane",
            nullable=True,
        ),
    )
    workplane: str | None = field(
        default=None,
        metadata=declare(
            String(),
            "the work plane its sensor reads (default: the daylight's control plane)",
            nullable=True,
        ),
    )
    min_level: float | None = field(
        default=None,
        metadata=declare(
            Number(lo=0.0, hi=1.0),
            "lowest dimming level of its luminaires (the ballast's floor; default: the "
            "daylight's `min_level`)",
            nullable=True,
        ),
    )

    mode: str = field(
        default=DIMMING,
        metadata=declare(
            Choice(control_mode_names, name='`"dimming"` or `"switching"`'),
            "how its luminaires follow its sensor: `dimming` (continuously, to top the "
            "daylight up to the target, down to `min_level`) or `switching` (off while the "
            "daylight alone meets the target, else full output)",
        ),
    )
    target_lux: float | None = field(
        default=None,
        metadata=declare(
            Number(gt=0.0, hi=1e5),
            "illuminance its sensor's mean is kept at, lux (default: the daylight's `target_lux`)",
            nullable=True,
        ),
    )
    dead_band: float = field(
        default=0.0,
        metadata=declare(
            Number(lo=0.0, hi=2.0),
            "`switching` only: its photocell's dead band, a fraction of the target: off "
            "once the daylight reaches target x (1 + band), back on when it falls below "
            "the target, else as the hour before (0, the default: off at the target)",
        ),
    )

    def __post_init__(self) -> None:
        where = f"control group {self.name!r}" if isinstance(self.name, str) else "a group"
        CONTROL_GROUP_FIELDS.check_fields(self, where)
        if self.sensor is not None:
            x0, y0, x1, y1 = self.sensor
            if x0 == x1 or y0 == y1:
                raise DesignError(
                    f"{where}: its sensor rectangle {list(self.sensor)} has no area; give "
                    "two diagonal corners [x0, y0, x1, y1]"
                )
        if self.dead_band > 0 and control_mode(self.mode).banded is None:
            raise DesignError(
                f"{where}: a dead band ({self.dead_band:g}) applies to switching; mode "
                f"{self.mode!r} takes none (set dead_band to 0)"
            )


CONTROL_GROUP_FIELDS = ObjectSpec.of(ControlGroup, "control_group")
"""The control group's fields, in the order a project file writes them."""

CONTROL_GROUP_OF = declare(
    String(),
    "the daylight-linked control group it is dimmed with (a `control_groups` name; "
    f'default `"{DEFAULT_CONTROL_GROUP}"`)',
)
"""The declaration of a luminaire's ``control_group`` field (sources and arrays)."""
