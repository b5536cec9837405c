"""Sources: rectangular luminaires and skylights in an emitter zone, and their variables.

Units: rectangles in metres in their zone's (u, v) coordinates; luminous flux in lm,
efficacy in lm/W, exitance in lm/m².

A source's emission:
- luminaire: exitance = flux / area (``flux`` given, possibly a variable), or a
  fixed ``exitance`` (a luminous panel: flux = exitance * area);
- skylight: exitance = filter * transmittance * exterior diffuse illuminance.

The fields that belong to one kind only are the source type's
(``sources.types.source_type(kind).fields``, a layer above): the project reader and
``project.kinds`` refuse them on another kind; here, the checks any kind shares.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lightinv_core.design.model.control import CONTROL_GROUP_OF, DEFAULT_CONTROL_GROUP
from lightinv_core.errors import DesignError
from lightinv_core.fields import (
    Choice,
    ListOf,
    Number,
    Numbers,
    ObjectSpec,
    String,
    choice_of,
    declare,
)
from lightinv_core.kinds import MAX_LUX, GlazingKind, SourceKind, VariableName, source_kind_names

SOURCE_KINDS = tuple(str(k) for k in SourceKind)
GLAZING_KINDS = tuple(str(k) for k in GlazingKind)
"""How a daylit source's glazing passes daylight: ``diffusing`` (a glow) or ``clear``."""
"""The built-in source kinds as plain strings (``kinds.source_kind_names()`` adds the
registered ones)."""
VARIABLES = tuple(str(v) for v in VariableName)
"""A source's variable names: the corners u0, v0, u1, v1 (m), flux (lm), filter."""
CORNERS = VARIABLES[:4]
MAX_FLUX = 1e10
"""Lumens: the most a luminaire or a source may emit (the photometry readers' cap)."""
MAX_EFFICACY = 683.0
"""lm/W: the luminous efficacy of radiation at 555 nm, which no light source exceeds."""


def source_kind(name: str) -> SourceKind | str:
    """The ``SourceKind`` member of a built-in kind, the name itself for a registered one."""
    return SourceKind(name) if name in SOURCE_KINDS else str(name)


def free_variables(names: tuple[str, ...]) -> ListOf:
    """The check of a ``free`` list: each of ``names`` at most once."""
    return ListOf(choice_of(*names), "variables", unique=True, name="list of variables")


@dataclass(frozen=True)
class Source:
    """A rectangular luminaire or skylight in an emitter zone.

    ``rect`` is (u0, v0, u1, v1), two diagonal corners in metres. ``free`` names
    the variables the optimizer may change (a subset of ``VARIABLES``); a
    source with no free variables is fixed. ``flux_range`` bounds a free flux.
    """

    name: str = field(metadata=declare(String(), "unique among the sources"))
    zone: str = field(metadata=declare(String(), "the emitter zone it is placed in"))
    kind: SourceKind = field(
        metadata=declare(Choice(source_kind_names, source_kind), "must match the zone's kind")
    )
    rect: tuple[float, float, float, float] = field(
        metadata=declare(
            Numbers(4), "`[u0, v0, u1, v1]`: two diagonal corners in the zone's axes, m"
        )
    )
    free: tuple[str, ...] = field(
        default=(),
        metadata=declare(
            free_variables(VARIABLES),
            "what the optimiser may change: `u0`, `v0`, `u1`, `v1`, `flux`, `filter`",
        ),
    )
    flux: float | None = field(
        default=None,
        metadata=declare(
            Number(lo=0.0, hi=MAX_FLUX),
            "luminous flux, lm (exitance = flux / area); the start of a free flux",
            nullable=True,
        ),
    )
    exitance: float | None = field(
        default=None,
        metadata=declare(
            Number(lo=0.0, hi=MAX_LUX), "fixed exitance, lm/m² (a luminous panel)", nullable=True
        ),
    )
    flux_range: tuple[float, float] = field(
        default=(0.0, 20000.0),
        metadata=declare(
            Numbers(2, Number(lo=0.0, hi=MAX_FLUX)), "bounds of a free flux, lm; 0 <= min < max"
        ),
    )
    efficacy: float = field(
        default=100.0,
        metadata=declare(Number(gt=0.0, hi=MAX_EFFICACY), "lm/W, for the electric power"),
    )
    filter: float = field(
        default=1.0,
        metadata=declare(Number(lo=0.0, hi=1.0), "fraction of the glazed daylight let in"),
    )
    glazing: GlazingKind = field(
        default=GlazingKind.DIFFUSING,
        metadata=declare(
            Choice(lambda: GLAZING_KINDS, GlazingKind),
            '`"diffusing"` (a Lambertian glow) or `"clear"` (the sky and sun by direction: '
            "docs/daylight.md)",
        ),
    )
    control_group: str = field(default=DEFAULT_CONTROL_GROUP, metadata=CONTROL_GROUP_OF)

    def __post_init__(self) -> None:
        where = f"source {self.name!r}" if isinstance(self.name, str) else "a source"
        SOURCE_FIELDS.check_fields(self, where)
        if self.flux is not None and self.exitance is not None:
            raise DesignError(f"{where}: give its flux (lm) or its exitance (lm/m²), not both")
        if VariableName.FLUX in self.free and self.flux is None:
            raise DesignError(f"{where}: a free flux needs a starting flux")
        lo, hi = self.flux_range
        if not lo < hi:
            raise DesignError(f"{where}: flux range must satisfy 0 <= min < max")
        strength = {VariableName.FLUX, VariableName.FILTER} & set(self.free)
        if self.glazing == GlazingKind.CLEAR and strength:
            # Its light is traced per zone cell and summed by the share glazed: linear in
            # the rectangle, not in the glass's transmittance (docs/daylight.md).
            raise DesignError(
                f"{where}: clear glazing frees only its rectangle (u0, v0, u1, v1), not "
                f"its {', '.join(sorted(strength))}: make it diffusing to free that"
            )

    @property
    def u_range(self) -> tuple[float, float]:
        """(min, max) of the rectangle along u."""
        return min(self.rect[0], self.rect[2]), max(self.rect[0], self.rect[2])

    @property
    def v_range(self) -> tuple[float, float]:
        """(min, max) of the rectangle along v."""
        return min(self.rect[1], self.rect[3]), max(self.rect[1], self.rect[3])

    @property
    def size(self) -> tuple[float, float]:
        """Extent (m) along u and v."""
        (a, b), (c, d) = self.u_range, self.v_range
        return b - a, d - c

    @property
    def area(self) -> float:
        """Area, m²."""
        w, h = self.size
        return w * h


SOURCE_FIELDS = ObjectSpec.of(Source, "source")
"""The source's fields (``project.specs.SOURCE`` adds which kinds take which)."""
