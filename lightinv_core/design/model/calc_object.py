"""Calculation objects: points and surfaces the designer places to read the light on.

Each object has a ``kind``; each kind is one ``CalcKind`` in one registry
(``register_calc_kind``): the fields it takes, what it needs beyond their own checks,
the symbol of the value it reads (E, Ev, Ez, Esc) and how it becomes receiver samples
(``readings``: a ``transport.point_sets.PointSet`` over the scene's patches). The built-in
kinds are in ``calc_kinds.py``: task areas of any polygon, rectangles on walls and
ceilings, cylindrical and semi-cylindrical illuminance points, free point sets.

Their points are receivers only, read like a work plane's grid points: the exact point
path (``transport/point_formfactors.py``: every Lambertian emitter and the reflected
light of every patch) plus each luminaire's photometry, so they serve luminaires and
daylight alike. An intention names one by its ``grid`` (as it names a work plane).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from lightinv_core.errors import DesignError
from lightinv_core.fields import Choice, ListOf, Number, Numbers, ObjectSpec, String, declare
from lightinv_core.kinds import Edition


@dataclass(frozen=True)
class CalcKind:
    """One kind of calculation object.

    ``name`` (project files), ``label`` (lists, the dialog), ``symbol`` of the value it
    reads (the report's column: "E", "Ev", "Ez", "Esc"), ``takes`` the fields beyond
    ``name`` and ``kind``, ``needs(obj)`` a message for what it lacks (None when
    complete), ``readings(obj, patches, caster)`` its receiver samples (a ``PointSet``)
    and ``describe(obj)`` a short line for the design tree.
    """

    name: str
    label: str
    symbol: str
    takes: tuple[str, ...]
    needs: Callable[[Any], str | None]
    readings: Callable[[Any, Any, Any], Any]
    describe: Callable[[Any], str] = lambda obj: ""


_KINDS: dict[str, CalcKind] = {}


def register_calc_kind(spec: CalcKind) -> CalcKind:
    """Add a kind of calculation object (ValueError when its name is taken)."""
    if spec.name in _KINDS:
        raise ValueError(f"calculation object kind {spec.name!r} is already registered")
    _KINDS[spec.name] = spec
    return spec


def unregister_calc_kind(name: str) -> None:
    """Remove a kind added by ``register_calc_kind``."""
    _KINDS.pop(name, None)


def calc_kind(name: str) -> CalcKind:
    """The spec of a kind (DesignError naming the known ones)."""
    try:
        return _KINDS[str(name)]
    except KeyError:
        raise DesignError(
            f"no calculation object kind {name!r}; kinds: {', '.join(_KINDS)}"
        ) from None


def calc_kind_names() -> tuple[str, ...]:
    """Every kind's name, in registry order."""
    return tuple(_KINDS)


def _not_taken(kind: str, name: str) -> str:
    takes = ", ".join(calc_kind(kind).takes) if kind in _KINDS else "?"
    return f"{kind} objects do not take {name!r} (they take: {takes})"


def _kind_fields(kind: str) -> tuple[str, ...]:
    return calc_kind(kind).takes if kind in _KINDS else ()


@dataclass(frozen=True)
class CalcObject:
    """A calculation object (see the module): its fields by kind are in the table of
    docs/project-file.md and its ``CalcKind``."""

    name: str = field(metadata=declare(String(), "unique among work planes and objects"))
    kind: str = field(
        metadata=declare(
            Choice(calc_kind_names),
            "`task_area` (a polygon at a height: horizontal illuminance E on an EN "
            "12464-1 grid), `surface` (a rectangle in any plane: illuminance on its "
            "front, e.g. vertical on a wall), `cylindrical` (Ez at points), "
            "`semi_cylindrical` (Esc at points, facing `facing`), `points` (free points "
            "with normals)",
            always=True,
        )
    )
    corners: tuple[tuple[float, float], ...] | None = field(
        default=None,
        metadata=declare(
            ListOf(Numbers(2), "corners", 3, name="list of [x, y]"),
            "the polygon's corners in plan, m, in order (convex or not)",
            nullable=True,
        ),
    )
    height: float = field(
        default=0.8,
        metadata=declare(
            Number(lo=0.0, hi=1000.0), "above the floor group, m (cylinders: their centre)"
        ),
    )
    border: float = field(
        default=0.0,
        metadata=declare(Number(lo=0.0, hi=1000.0), "left out along the polygon's edges, m"),
    )
    group: str = field(
        default="floor", metadata=declare(String(), "the floor group the heights are above")
    )
    edition: Edition = field(
        default=Edition.EN12464_2021,
        metadata=declare(
            Choice(lambda: tuple(Edition), Edition),
            "the EN 12464-1 edition whose grid rule lays the points",
        ),
    )
    origin: tuple[float, float, float] | None = field(
        default=None,
        metadata=declare(Numbers(3), "a corner of the rectangle, m", nullable=True),
    )
    u: tuple[float, float, float] | None = field(
        default=None,
        metadata=declare(
            Numbers(3), "its first edge from `origin`, m; the front faces u x v", nullable=True
        ),
    )
    v: tuple[float, float, float] | None = field(
        default=None,
        metadata=declare(Numbers(3), "its second edge from `origin`, m", nullable=True),
    )
    positions: tuple[tuple[float, float], ...] | None = field(
        default=None,
        metadata=declare(
            ListOf(Numbers(2), "positions", 1, name="list of [x, y]"),
            "the points in plan, m",
            nullable=True,
        ),
    )
    facing: float = field(
        default=0.0,
        metadata=declare(
            Number(lo=-360.0, hi=360.0),
            "the direction the semi-cylinders face, degrees counter-clockwise from +x",
        ),
    )
    points: tuple[tuple[float, float, float], ...] | None = field(
        default=None,
        metadata=declare(
            ListOf(Numbers(3), "points", 1, name="list of [x, y, z]"),
            "the points, m (from a CSV: `lightinv-cli simulate --points`)",
            nullable=True,
        ),
    )
    normals: tuple[tuple[float, float, float], ...] | None = field(
        default=None,
        metadata=declare(
            ListOf(Numbers(3), "normals", 1, name="list of [x, y, z]"),
            "each point's normal (default: facing up)",
            nullable=True,
        ),
    )

    def __post_init__(self) -> None:
        where = f"calculation object {self.name!r}" if isinstance(self.name, str) else "a "
        CALC_FIELDS.check_fields(self, where)
        problem = calc_kind(self.kind).needs(self)
        if problem:
            raise DesignError(f"{where}: {problem}")

    @property
    def spec(self) -> CalcKind:
        """Its kind's spec."""
        return calc_kind(self.kind)


CALC_FIELDS = ObjectSpec.of(
    CalcObject,
    "calculation_object",
    kind_field="kind",
    kind_fields=_kind_fields,
    not_taken=_not_taken,
)
"""The calculation object's fields, in the order a project file writes them."""
