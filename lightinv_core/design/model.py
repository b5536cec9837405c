"""The inverse design problem as data: sources, geometric rules, lighting intentions, goals.

Units: source rectangles in metres in their zone's (u, v) coordinates; luminous
flux in lm, efficacy in lm/W, exitance in lm/m², illuminance in lux.

A source's emission:
- luminaire: exitance = flux / area (``flux`` given, possibly a variable), or a
  fixed ``exitance`` (a luminous panel: flux = exitance * area);
- skylight: exitance = filter * transmittance * exterior diffuse illuminance.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field

from lightinv_core.errors import DesignError
from lightinv_core.goals import goal_kind, goal_names, goal_spec, is_goal
from lightinv_core.kinds import (
    ArrayVariable,
    Bound,
    GoalKind,
    Quantity,
    RuleKind,
    Scenario,
    SourceKind,
    VariableName,
)
from lightinv_core.quantities import is_quantity, quantity_kind, quantity_names, quantity_spec

SOURCE_KINDS = tuple(str(k) for k in SourceKind)
"""The source kinds as plain strings (the values stored in the model)."""
VARIABLES = tuple(str(v) for v in VariableName)
"""A source's variable names: the corners u0, v0, u1, v1 (m), flux (lm), filter."""
CORNERS = VARIABLES[:4]
AXES = ("u", "v")
"""A zone's two axes, as mirror and align rules name them."""
RULE_SOURCES = {RuleKind.MIRROR: 2, RuleKind.SPACING: 2}
"""Rule kinds that take an exact number of sources."""
ARRAY_RULES = (str(RuleKind.SHR), str(RuleKind.CLEARANCE))
"""Rule kinds that name luminaire arrays (the others name sources)."""
ARRAY_VARIABLES = tuple(str(v) for v in ArrayVariable)
"""A luminaire array's variable names."""
ROTATIONS = (0, 90)
"""An array's rotations, degrees: the product's C0 plane along the zone's u or v axis."""
MAX_ARRAY_SIDE = 100
"""Most rows (or columns) an array may have: 10,000 luminaires in one zone."""
MAX_PATCH_ID = 2**53  # project files limit integers to 2^53 too


def _finite(value, where: str, lo: float | None = None, hi: float | None = None) -> float:
    if isinstance(value, bool | str):
        raise DesignError(f"{where}: {_short(value)} is not a number")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise DesignError(f"{where}: {_short(value)} is not a number") from None
    except OverflowError:
        raise DesignError(f"{where}: {_short(value)} is not a finite number") from None
    if not math.isfinite(v):
        raise DesignError(f"{where}: {value!r} is not a finite number")
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        rng = f"[{lo if lo is not None else '-inf'}, {hi if hi is not None else 'inf'}]"
        raise DesignError(f"{where}: {v} is outside {rng}")
    return v


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:40] + "..."


def _items(value, where: str, what: str) -> tuple:
    """``value`` as a tuple: a list or tuple (not a string, a number or None)."""
    if isinstance(value, str | bytes) or not isinstance(value, tuple | list):
        raise DesignError(f"{where}: {what} must be a list, got {_short(value)}")
    return tuple(value)


def _either(names: tuple[str, ...]) -> str:
    """``'a' or 'b'`` (the allowed values, for a message)."""
    return " or ".join(repr(str(n)) for n in names)


def _name(value, where: str) -> str:
    if not isinstance(value, str) or not value:
        raise DesignError(f"{where} must be a non-empty string, got {_short(value)}")
    return value


def _rect_and_free(obj, where: str, allowed: tuple[str, ...]) -> None:
    """Check and store ``obj``'s ``rect`` (four finite numbers, m) and ``free`` (names
    from ``allowed``)."""
    rect = _items(obj.rect, where, "rect")
    if len(rect) != 4:
        raise DesignError(f"{where}: rect needs four numbers u0, v0, u1, v1 (m)")
    object.__setattr__(obj, "rect", tuple(_finite(x, f"{where} rect") for x in rect))
    object.__setattr__(obj, "free", _items(obj.free, where, "free"))
    bad = [v for v in obj.free if v not in allowed]
    if bad:
        raise DesignError(f"{where}: unknown variables {bad}; choose from {allowed}")


@dataclass(frozen=True)
class Source:
    """A rectangular luminaire or skylight in an emitter zone.

    ``rect`` is (u0, v0, u1, v1), two diagonal corners in metres. ``free`` names
    the variables the optimizer may change (a subset of ``VARIABLES``); a
    source with no free variables is fixed. ``flux_range`` bounds a free flux.
    """

    name: str
    zone: str
    kind: SourceKind
    rect: tuple[float, float, float, float]
    free: tuple[str, ...] = ()
    flux: float | None = None
    exitance: float | None = None
    flux_range: tuple[float, float] = (0.0, 20000.0)
    efficacy: float = 100.0
    filter: float = 1.0

    def __post_init__(self) -> None:
        _name(self.name, "a source's name")
        where = f"source {self.name!r}"
        _name(self.zone, f"{where}: zone")
        if self.kind not in SOURCE_KINDS:
            raise DesignError(f"{where}: kind must be {_either(SOURCE_KINDS)}")
        object.__setattr__(self, "kind", SourceKind(self.kind))
        _rect_and_free(self, where, VARIABLES)
        if len(_items(self.flux_range, where, "flux_range")) != 2:
            raise DesignError(f"{where}: flux_range needs two numbers (min, max) in lm")
        object.__setattr__(
            self,
            "flux_range",
            tuple(_finite(x, f"{where} flux_range", lo=0.0) for x in self.flux_range),
        )
        for key in ("flux", "exitance"):
            if getattr(self, key) is not None:
                object.__setattr__(self, key, _finite(getattr(self, key), f"{where} {key}", lo=0.0))
        if self.kind == SourceKind.LUMINAIRE:
            if self.flux is not None and self.exitance is not None:
                raise DesignError(
                    f"{where}: give a luminaire's flux (lm) or its exitance (lm/m²), not both"
                )
            if self.flux is None and self.exitance is None:
                raise DesignError(f"{where}: a luminaire needs either flux (lm) or exitance")
            if VariableName.FILTER in self.free:
                raise DesignError(f"{where}: only skylights have a filter variable")
            if VariableName.FLUX in self.free and self.flux is None:
                raise DesignError(f"{where}: a free flux needs a starting flux")
            lo, hi = self.flux_range
            if not 0 <= lo < hi:
                raise DesignError(f"{where}: flux range must satisfy 0 <= min < max")
            _finite(self.efficacy, f"{where} efficacy (lm/W)", lo=1e-6)
        else:
            if VariableName.FLUX in self.free or self.flux is not None or self.exitance is not None:
                raise DesignError(
                    f"{where}: skylights have a filter, not a flux or exitance "
                    "(their exitance is filter x transmittance x exterior lux)"
                )
            _finite(self.filter, f"{where} filter", 0.0, 1.0)

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


@dataclass(frozen=True)
class Rule:
    """A geometric rule (no radiosity needed; paper eq. 4).

    kinds and their fields:
    - ``area``: ``sources``, ``min`` and/or ``max`` (m²) for each source;
    - ``aspect``: ``sources``, ``max`` (long side / short side);
    - ``mirror``: ``sources`` = (derived, original), ``axis`` "u" or "v": the
      derived source is the original's rectangle flipped along that axis (in
      the same or another zone; coordinates scale with the zones' sizes along
      the axis when they differ) and copies its flux or filter — it has no
      variables;
    - ``centred``: ``sources``: each rectangle is centred in its zone (the
      second corner is the first mirrored through the zone centre);
    - ``spacing``: ``sources`` (two, same zone), ``min`` (m) gap between them;
    - ``align``: ``sources`` (two or more), ``axis`` "u" or "v": they lie on one
      line parallel to that axis (their centres share the other coordinate,
      within 1 cm).
    """

    kind: str
    sources: tuple[str, ...]
    min: float | None = None
    max: float | None = None
    axis: str | None = None

    KINDS = tuple(str(k) for k in RuleKind)

    def __post_init__(self) -> None:
        if isinstance(self.sources, str):
            raise DesignError(
                f"rule {self.kind!r}: sources must be a list of names, "
                f"not the string {self.sources!r}"
            )
        names = _items(self.sources, f"rule {self.kind!r}", "sources")
        for name in names:
            _name(name, f"rule {self.kind!r}: a source name")
        where = f"rule {self.kind!r} on {list(self.sources)}"
        if len(set(self.sources)) != len(tuple(self.sources)):
            raise DesignError(f"{where}: a source is named twice")
        if self.kind not in self.KINDS:
            raise DesignError(f"rule kind {self.kind!r} is not one of {self.KINDS}")
        object.__setattr__(self, "sources", tuple(self.sources))
        if not self.sources:
            raise DesignError(f"{where}: name at least one source")
        need = RULE_SOURCES.get(self.kind)
        if need and len(self.sources) != need:
            raise DesignError(f"{where}: needs exactly {need} sources")
        if self.kind == RuleKind.ALIGN and len(self.sources) < 2:
            raise DesignError(f"{where}: needs at least two sources")
        if self.kind in (RuleKind.MIRROR, RuleKind.ALIGN) and self.axis not in AXES:
            raise DesignError(f"{where}: axis must be {_either(AXES)}")
        for key in ("min", "max"):
            v = getattr(self, key)
            if v is not None:
                object.__setattr__(self, key, _finite(v, f"{where} {key}", lo=0.0))
        if self.kind == RuleKind.AREA and self.min is None and self.max is None:
            raise DesignError(f"{where}: give min and/or max area (m²)")
        if self.min is not None and self.max is not None and self.min > self.max:
            raise DesignError(f"{where}: min {self.min} is larger than max {self.max}")
        if self.kind == RuleKind.ASPECT and (self.max is None or self.max < 1):
            got = "none" if self.max is None else f"{self.max:g}"
            raise DesignError(f"{where}: max aspect ratio must be at least 1, got {got}")
        if self.kind == RuleKind.SPACING and self.min is None:
            raise DesignError(f"{where}: give the min gap (m)")
        if self.kind == RuleKind.SHR and not (self.max is not None and self.max > 0):
            raise DesignError(
                f"{where}: give the largest spacing-to-height ratio as max (e.g. 1.5)"
            )
        if self.kind == RuleKind.CLEARANCE and self.min is None:
            raise DesignError(f"{where}: give the least clearance to the zone's edges (m) as min")


@dataclass(frozen=True)
class Intention:
    """A lighting intention on a patch set: a group's patches (``group="*"`` means
    every patch of the scene) or picked patch ids.

    ``quantity`` is "lux" (illuminance) or "C" (reflected exitance, lm/m²).
    ``min``/``max`` bound every patch; ``average`` is a lower bound on the
    area-weighted mean and ``uniformity`` on U0 = min / mean (EN 12464-1 style:
    desks 500 lux, U0 >= 0.6). ``weight`` scales its penalty. On a work plane's
    ``grid`` (its name) the statistics are EN 12464-1's: the plain mean of the grid
    points (Em), their min (Emin), U0 = Emin / Em, max; luminaire arrays' light there is
    maintained (their maintenance factor applied).
    """

    name: str
    group: str | None = None
    patches: tuple[int, ...] | None = None
    quantity: Quantity = Quantity.LUX
    min: float | None = None
    max: float | None = None
    average: float | None = None
    uniformity: float | None = None
    weight: float = 100.0
    grid: str | None = None
    scenario: Scenario = Scenario.DESIGN

    def __post_init__(self) -> None:
        _name(self.name, "an intention's name")
        where = f"intention {self.name!r}"
        if self.scenario not in tuple(Scenario):
            raise DesignError(f"{where}: scenario must be {_either(tuple(Scenario))}")
        object.__setattr__(self, "scenario", Scenario(self.scenario))
        spec = quantity_spec(self.quantity) if is_quantity(self.quantity) else None
        if spec is not None and spec.scenario is not None:
            # A daylight metric is measured in its own scenario, whatever was written.
            object.__setattr__(self, "scenario", spec.scenario)
        elif self.scenario == Scenario.ANNUAL:
            annual = tuple(q for q in quantity_names() if quantity_spec(q).scenario == "annual")
            raise DesignError(
                f"{where}: the annual scenario bounds a daylight metric: quantity {_either(annual)}"
            )
        targets = sum(x is not None for x in (self.group, self.patches, self.grid))
        if targets != 1:
            raise DesignError(
                f"{where}: give one of a group, a list of patches or a work-plane grid"
            )
        if self.group is not None:
            _name(self.group, f"{where}: group")
        if self.grid is not None:
            _name(self.grid, f"{where}: grid")
            if spec is not None and spec.needs_reflectance:
                raise DesignError(
                    f"{where}: a work-plane grid takes illuminance (lux) or a daylight metric, "
                    f"not {spec.noun}"
                )
        if self.patches is not None:
            if not isinstance(self.patches, tuple | list | range) or len(self.patches) == 0:
                raise DesignError(f"{where}: patches must be a non-empty list of patch ids")
            ids = []
            for i in self.patches:
                whole = isinstance(i, numbers.Real) and not isinstance(i, bool)
                if not whole or not math.isfinite(i) or not float(i).is_integer():
                    raise DesignError(f"{where}: patch id {i!r} is not a whole number")
                if not 0 <= i <= MAX_PATCH_ID:
                    raise DesignError(f"{where}: patch id {i!r} is negative or too large")
                ids.append(int(i))
            object.__setattr__(self, "patches", tuple(ids))
        if spec is None:
            raise DesignError(f"{where}: quantity must be {_either(quantity_names())}")
        object.__setattr__(self, "quantity", quantity_kind(self.quantity))
        lo, hi, unit = spec.low, spec.high, spec.range_text
        for key in (Bound.MIN, Bound.MAX, Bound.AVERAGE):
            v = getattr(self, key)
            if v is not None:
                v = _finite(v, f"{where} {key}")
                # A maximum above the range always holds (a "no limit" of 1e9 is fine), up to
                # a sane number; a minimum or an average outside it can never be met.
                if v < lo or (v > hi and key != Bound.MAX) or v > 1e12:
                    raise DesignError(
                        f"{where}: {key} {v:g} is outside the range of {self.quantity} "
                        f"({unit}), {lo:g} to {hi:g}; it could never be met"
                    )
                object.__setattr__(self, key, v)
        if self.uniformity is not None:
            object.__setattr__(
                self, "uniformity", _finite(self.uniformity, f"{where} uniformity", 0.0, 1.0)
            )
        if all(getattr(self, k) is None for k in Bound):
            raise DesignError(f"{where}: give at least one of {', '.join(Bound)}")
        if self.min is not None and self.max is not None and self.min > self.max:
            raise DesignError(f"{where}: min {self.min} is above max {self.max}")
        if self.average is not None and self.max is not None and self.average > self.max:
            raise DesignError(f"{where}: average {self.average} is above max {self.max}")
        _finite(self.weight, f"{where} weight", lo=0.0)


def _whole(value, where: str, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise DesignError(f"{where}: {_short(value)} is not a whole number")
    if not math.isfinite(value) or not float(value).is_integer():
        raise DesignError(f"{where}: {_short(value)} is not a whole number")
    if not lo <= value <= hi:
        raise DesignError(f"{where}: {int(value)} is outside [{lo}, {hi}]")
    return int(value)


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

    name: str
    zone: str
    product: str
    rect: tuple[float, float, float, float]
    rows: int = 1
    columns: int = 1
    rotation: int = 0
    dimming: float = 1.0
    free: tuple[str, ...] = ()
    rows_range: tuple[int, int] = (1, 10)
    columns_range: tuple[int, int] = (1, 10)
    dimming_range: tuple[float, float] = (0.1, 1.0)
    maintenance_factor: float = 0.8
    watts: float | None = None

    def __post_init__(self) -> None:
        _name(self.name, "an array's name")
        where = f"array {self.name!r}"
        _name(self.zone, f"{where}: zone")
        _name(self.product, f"{where}: product")
        _rect_and_free(self, where, ARRAY_VARIABLES)
        for key in ("rows_range", "columns_range"):
            pair = _items(getattr(self, key), where, key)
            if len(pair) != 2:
                raise DesignError(f"{where}: {key} needs two whole numbers (min, max)")
            lo, hi = (_whole(x, f"{where} {key}", 1, MAX_ARRAY_SIDE) for x in pair)
            if lo > hi:
                raise DesignError(f"{where}: {key} min {lo} is above max {hi}")
            object.__setattr__(self, key, (lo, hi))
        for key in ("rows", "columns"):
            lo, hi = getattr(self, f"{key}_range")
            object.__setattr__(self, key, _whole(getattr(self, key), f"{where} {key}", lo, hi))
        if self.rotation not in ROTATIONS or isinstance(self.rotation, bool):
            raise DesignError(f"{where}: rotation must be 0 or 90 (degrees), got {self.rotation!r}")
        object.__setattr__(self, "rotation", int(self.rotation))
        pair = _items(self.dimming_range, where, "dimming_range")
        if len(pair) != 2:
            raise DesignError(f"{where}: dimming_range needs two numbers (min, max)")
        lo, hi = (_finite(x, f"{where} dimming_range", 0.0, 1.0) for x in pair)
        if not 0 < lo <= hi:
            raise DesignError(f"{where}: dimming range must satisfy 0 < min <= max <= 1")
        object.__setattr__(self, "dimming_range", (lo, hi))
        object.__setattr__(self, "dimming", _finite(self.dimming, f"{where} dimming", 0.0, 1.0))
        if self.dimming == 0:
            raise DesignError(f"{where}: dimming must be above 0 (remove the array instead)")
        object.__setattr__(
            self,
            "maintenance_factor",
            _finite(self.maintenance_factor, f"{where} maintenance_factor", 0.0, 1.0),
        )
        if self.maintenance_factor == 0:
            raise DesignError(f"{where}: maintenance factor must be above 0 (typically 0.7-0.9)")
        if self.watts is not None:
            object.__setattr__(self, "watts", _finite(self.watts, f"{where} watts", lo=0.0))

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


@dataclass(frozen=True)
class Workplane:
    """An EN 12464-1 calculation grid: a horizontal plane ``height`` m above the floor
    group ``group``, ``border`` m left out along its edges, points spaced by the
    standard's rule p = 0.2 x 5^log10(d) (docs/photometry.md). Grid points are
    receivers only: they take no part in the light transport."""

    name: str
    height: float = 0.8
    border: float = 0.5
    group: str = "floor"

    def __post_init__(self) -> None:
        _name(self.name, "a work plane's name")
        where = f"work plane {self.name!r}"
        _name(self.group, f"{where}: group")
        object.__setattr__(self, "height", _finite(self.height, f"{where} height", 0.0, 1000.0))
        object.__setattr__(self, "border", _finite(self.border, f"{where} border", 0.0, 1000.0))


GOALS = tuple(str(g) for g in GoalKind)
"""The built-in goal kinds (``goals.goal_names()`` adds the registered ones)."""


@dataclass(frozen=True)
class Goal:
    """What to optimise.

    - ``min_electric_power``: sum of luminaire flux / efficacy (W);
    - ``max_light_power``: total reflected light power sum_i C_i A_i (lm), of
      the sources whose kind is in ``kinds`` (all when empty);
    - ``match``: relative distance e(E) = ||C(E) - C_obj|| / ||C_obj|| (paper
      eq. 11) to the light of the project's ``target_sources``;
    - ``min_installed_power``: rated power (W) of every luminaire at full output: the
      arrays' count x product watts plus the luminaire sources' flux / efficacy;
    - ``min_luminaire_count``: luminaires in the arrays plus luminaire sources.
    """

    kind: GoalKind
    kinds: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not is_goal(self.kind):
            raise DesignError(f"goal {self.kind!r} is not one of {goal_names()}")
        object.__setattr__(self, "kind", goal_kind(self.kind))
        object.__setattr__(self, "kinds", _items(self.kinds, f"goal {self.kind!r}", "kinds"))
        bad = [k for k in self.kinds if k not in SOURCE_KINDS]
        if bad:
            raise DesignError(f"goal {self.kind!r}: kinds {bad} must be {_either(SOURCE_KINDS)}")
        if self.kinds and self.kind != GoalKind.MAX_LIGHT_POWER:
            raise DesignError(f"goal {self.kind!r}: only max_light_power counts source kinds")


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
    ``min_level`` and full output, with ``standby_w`` drawn all year.
    """

    exterior_lux: float = 10000.0
    transmittance: float = 0.6
    weather: str = "builtin"
    north_deg: float = 0.0
    occupancy: tuple[float, float] = (8.0, 18.0)
    weekdays: bool = True
    ground_reflectance: float = 0.2
    overcast_lux: float = 10000.0
    target_lux: float = 500.0
    min_level: float = 0.1
    standby_w: float = 0.0
    workplane: str | None = None

    def __post_init__(self) -> None:
        def put(key, lo=None, hi=None):
            object.__setattr__(self, key, _finite(getattr(self, key), f"daylight {key}", lo, hi))

        put("exterior_lux", 0.0)
        put("transmittance", 0.0, 1.0)
        put("north_deg", -360.0, 360.0)
        put("ground_reflectance", 0.0, 0.99)
        put("overcast_lux", 0.0, 2e5)
        put("target_lux", 0.0, 1e5)
        put("min_level", 0.0, 1.0)
        put("standby_w", 0.0)
        _name(self.weather, "daylight weather")
        hours = _items(self.occupancy, "daylight", "occupancy")
        if len(hours) != 2:
            raise DesignError("daylight occupancy: give two hours, start and end (0-24)")
        start, end = (_finite(h, "daylight occupancy", 0.0, 24.0) for h in hours)
        if not start < end:
            raise DesignError(f"daylight occupancy: start {start:g} h is not before end {end:g} h")
        if not any(start <= h + 0.5 < end for h in range(24)):
            raise DesignError(
                f"daylight occupancy {start:g}-{end:g} h holds no hour: an hour counts when "
                "its middle (e.g. 8:30 for 8-9) lies in [start, end)"
            )
        object.__setattr__(self, "occupancy", (start, end))
        if not isinstance(self.weekdays, bool):
            raise DesignError(
                f"daylight weekdays must be true or false, got {_short(self.weekdays)}"
            )
        if self.workplane is not None:
            _name(self.workplane, "daylight workplane")


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

    def __post_init__(self) -> None:
        for name, cls in (
            ("sources", Source),
            ("goals", Goal),
            ("rules", Rule),
            ("intentions", Intention),
            ("target_sources", Source),
            ("arrays", LuminaireArray),
            ("workplanes", Workplane),
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
            ("work plane", [w.name for w in self.workplanes]),
            ("target source", [s.name for s in self.target_sources]),
            ("intention", [i.name for i in self.intentions]),
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
        for it in self.intentions:
            if it.grid is not None and it.grid not in planes:
                raise DesignError(
                    f"intention {it.name!r}: no work plane {it.grid!r} "
                    f"(work planes: {sorted(planes) or 'none'})"
                )
        if self.daylight.workplane is not None and self.daylight.workplane not in planes:
            raise DesignError(
                f"daylight workplane {self.daylight.workplane!r} is not a work plane "
                f"(work planes: {sorted(planes) or 'none'})"
            )
        annual = [str(g.kind) for g in self.goals if goal_spec(g.kind).annual]
        if annual and not self.workplanes:
            raise DesignError(
                f"goals {annual} are measured on a work plane (dimming and sDA): add one"
            )
        if any(g.kind == GoalKind.MATCH for g in self.goals) and not self.target_sources:
            raise DesignError("a match goal needs target_sources (the light to reproduce)")
        if self.penalty_power < 1 or self.penalty_power % 2:
            raise DesignError("penalty power must be an even positive integer (paper eq. 3)")

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
