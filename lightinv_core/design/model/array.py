"""Luminaire arrays: regular arrays of one photometric product in a luminaire zone."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from lightinv_core.design.model.control import CONTROL_GROUP_OF, DEFAULT_CONTROL_GROUP
from lightinv_core.design.model.source import free_variables
from lightinv_core.errors import DesignError
from lightinv_core.fields import (
    Custom,
    Integer,
    Number,
    Numbers,
    ObjectSpec,
    String,
    _fail,
    _integer,
    declare,
    whole_pair,
)
from lightinv_core.kinds import ArrayVariable

ARRAY_VARIABLES = tuple(str(v) for v in ArrayVariable)
"""A luminaire array's variable names."""
ROTATIONS = (0, 90)
"""An array's rotations, degrees: the product's C0 plane along the zone's u or v axis."""
MAX_ARRAY_SIDE = 100
"""Most rows (or columns) an array may have: 10,000 luminaires in one zone."""


def _rotation(v, p: str) -> int:
    if type(v) is int and v in ROTATIONS:
        return v
    r = _integer(v, p, lo=0)
    if r not in ROTATIONS:
        _fail(p, f"expected 0 or 90 (degrees), got {r}")
    return r


@dataclass(frozen=True)
class LuminaireArray:
    """A regular array of one photometric product in a luminaire zone.

    The array fills ``rect`` (u0, v0, u1, v1, m, in the zone's axes): ``columns``
    luminaires along u and ``rows`` along v at the centres of equal cells, so the
    spacing is the rectangle's side / count and the outer luminaires sit half a
    spacing in from its edges (the usual even layout). A single luminaire is an array
    of one row and one column at the rectangle's centre (the rectangle may then be a
    point). The luminaires are mounted on the zone's surface, aimed along its normal
    into the room, their C0 plane along u (``rotation`` 0) or v (90).

    ``product`` is a catalogue name (resources/luminaires/catalogue.json) or the path
    of an IES/EULUMDAT file; ``watts`` overrides the product's rated input power.
    ``dimming`` (0..1] scales every luminaire's output and power (power proportional to
    output). ``maintenance_factor`` scales the light where maintained values are asked
    (EN 12464-1 Em on work-plane grids and every patch intention). ``free`` names the
    variables the optimiser may change (``ARRAY_VARIABLES``); rows and columns stay in
    their ranges, dimming in ``dimming_range``.
    """

    name: str = field(metadata=declare(String(), "unique among sources and arrays"))
    zone: str = field(metadata=declare(String(), "the luminaire zone it is mounted in"))
    product: str = field(
        metadata=declare(
            String(),
            "a catalogue luminaire's name, or an `.ies`/`.ldt`/`.gldf` file (relative to the "
            "project file; `FILE.gldf#VARIANT` for one variant of a GLDF)",
        )
    )
    rect: tuple[float, float, float, float] = field(
        metadata=declare(
            Numbers(4), "`[u0, v0, u1, v1]`: the rectangle the array fills evenly, zone axes, m"
        )
    )
    rows: int = field(
        default=1,
        metadata=declare(Integer(lo=1), "luminaires along the zone's v axis", always=True),
    )
    columns: int = field(
        default=1, metadata=declare(Integer(lo=1), "luminaires along u", always=True)
    )
    rotation: int = field(
        default=0,
        metadata=declare(
            Custom(_rotation, "`0` or `90`", {"enum": list(ROTATIONS)}),
            "degrees: the product's C0 plane along u (0) or v (90)",
        ),
    )
    dimming: float = field(
        default=1.0,
        metadata=declare(
            Number(gt=0.0, hi=1.0, hint="to switch it off, remove the array"),
            "output (and power) of every luminaire, fraction of full",
        ),
    )
    free: tuple[str, ...] = field(
        default=(),
        metadata=declare(
            free_variables(ARRAY_VARIABLES),
            "what the optimiser may change: `u0`, `v0`, `u1`, `v1`, `rows`, `columns`, "
            "`rotation`, `dimming`",
        ),
    )
    rows_range: tuple[int, int] = field(
        default=(1, 10), metadata=declare(whole_pair(1, MAX_ARRAY_SIDE), "bounds of free rows")
    )
    columns_range: tuple[int, int] = field(
        default=(1, 10), metadata=declare(whole_pair(1, MAX_ARRAY_SIDE), "bounds of free columns")
    )
    dimming_range: tuple[float, float] = field(
        default=(0.1, 1.0),
        metadata=declare(
            Numbers(2, Number(lo=0.0, hi=1.0)), "bounds of a free dimming; 0 < min <= max <= 1"
        ),
    )
    maintenance_factor: float = field(
        default=0.8,
        metadata=declare(
            Number(gt=0.0, hi=1.0, hint="typically 0.7-0.9"),
            "maintained / new light (EN 12464-1 Em)",
            always=True,
        ),
    )
    watts: float | None = field(
        default=None,
        metadata=declare(
            Number(lo=0.0),
            "rated input power of one luminaire, W (default: the catalogue's or the file's)",
            nullable=True,
        ),
    )
    control_group: str = field(default=DEFAULT_CONTROL_GROUP, metadata=CONTROL_GROUP_OF)

    def __post_init__(self) -> None:
        where = f"array {self.name!r}" if isinstance(self.name, str) else "an array"
        ARRAY_FIELDS.check_fields(self, where)
        for key in ("rows", "columns"):
            lo, hi = getattr(self, f"{key}_range")
            if lo > hi:
                raise DesignError(f"{where}: {key}_range min {lo} is above max {hi}")
            if not lo <= getattr(self, key) <= hi:
                raise DesignError(f"{where}: {key} {getattr(self, key)} is outside [{lo}, {hi}]")
        lo, hi = self.dimming_range
        if not 0 < lo <= hi:
            raise DesignError(f"{where}: dimming range must satisfy 0 < min <= max <= 1")

    @property
    def count(self) -> int:
        """Number of luminaires."""
        return self.rows * self.columns

    @property
    def spacing(self) -> tuple[float, float]:
        """Spacing (m) between neighbouring luminaires along u and v."""
        u0, v0, u1, v1 = self.rect
        return abs(u1 - u0) / self.columns, abs(v1 - v0) / self.rows

    def positions(self) -> list[tuple[float, float]]:
        """Zone coordinates (u, v), m, of each luminaire, row by row."""
        u0, v0, u1, v1 = self.rect
        ulo, vlo = min(u0, u1), min(v0, v1)
        su, sv = self.spacing
        return [
            (ulo + (i + 0.5) * su, vlo + (j + 0.5) * sv)
            for j in range(self.rows)
            for i in range(self.columns)
        ]


ARRAY_FIELDS = ObjectSpec.of(LuminaireArray, "array")
"""The luminaire array's fields, in the order a project file writes them."""

NEW_ARRAY_FREE = ("rows", "columns")
"""What the optimiser may change in a new array: how many luminaires, each at full
output. Dimming is left out: a free dimming makes many dimmed luminaires cost the power
of a few at full output (issue #29: 80 panels at 10% in a classroom), and it needs
dimming controls; it is asked for by freeing ``dimming``."""


def new_array(name: str, zone: str, product: str, size: tuple[float, float]) -> LuminaireArray:
    """The array a new design proposes in a zone of ``size`` (w, h) m: ``product`` filling
    the whole zone evenly, 2 x 2 to start, rows and columns free (``NEW_ARRAY_FREE``), at
    full output; the spacing rule ``DEFAULT_SHR`` holds unless a rule says otherwise
    (``design/arrays.py``)."""
    w, h = size
    return LuminaireArray(
        name, zone, product, (0.0, 0.0, float(w), float(h)), rows=2, columns=2, free=NEW_ARRAY_FREE
    )


def overlapping(array: LuminaireArray, others: Iterable[LuminaireArray]) -> tuple[str, ...]:
    """Names of the arrays of ``others`` in ``array``'s zone whose rectangles overlap its
    own (sharing an edge is not overlapping; a one-luminaire array's point overlaps a
    rectangle it lies inside)."""

    def spans(a: LuminaireArray) -> tuple[tuple[float, float], tuple[float, float]]:
        u0, v0, u1, v1 = a.rect
        return (min(u0, u1), max(u0, u1)), (min(v0, v1), max(v0, v1))

    mine = spans(array)
    out = []
    for other in others:
        if other.zone != array.zone or other.name == array.name:
            continue
        theirs = spans(other)
        if all(a[0] < b[1] and b[0] < a[1] for a, b in zip(mine, theirs, strict=True)):
            out.append(other.name)
    return tuple(out)


def free_zone(zones: Iterable[str], arrays: Iterable[LuminaireArray]) -> str | None:
    """The first of ``zones`` that no array of ``arrays`` is mounted in (where a new
    array goes by default); None when every zone has one."""
    used = {a.zone for a in arrays}
    return next((z for z in zones if z not in used), None)
