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
from lightinv_core.kinds import Bound, GoalKind, Quantity, RuleKind, SourceKind, VariableName

SOURCE_KINDS = tuple(str(k) for k in SourceKind)
"""The source kinds as plain strings (the values stored in the model)."""
VARIABLES = tuple(str(v) for v in VariableName)
"""A source's variable names: the corners u0, v0, u1, v1 (m), flux (lm), filter."""
CORNERS = VARIABLES[:4]
AXES = ("u", "v")
"""A zone's two axes, as mirror and align rules name them."""
RULE_SOURCES = {RuleKind.MIRROR: 2, RuleKind.SPACING: 2}
"""Rule kinds that take an exact number of sources."""
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


@dataclass(frozen=True)
class Source:
    """A rectangular luminaire or skylight in an emitter zone.

    ``rect`` is (u0, v0, u1, v1), two diagonal corners in metres. ``free`` names
    the variables the optimizer may change (a subset of ``VARIABLES``); a
    source with no free variables is fixed. ``flux_range`` bounds a free flux.
    """

    name: str
    zone: str
    kind: str
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
        rect = _items(self.rect, where, "rect")
        if len(rect) != 4:
            raise DesignError(f"{where}: rect needs four numbers u0, v0, u1, v1 (m)")
        object.__setattr__(self, "rect", tuple(_finite(x, f"{where} rect") for x in rect))
        object.__setattr__(self, "free", _items(self.free, where, "free"))
        bad = [v for v in self.free if v not in VARIABLES]
        if bad:
            raise DesignError(f"{where}: unknown variables {bad}; choose from {VARIABLES}")
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


@dataclass(frozen=True)
class Intention:
    """A lighting intention on a patch set: a group's patches (``group="*"`` means
    every patch of the scene) or picked patch ids.

    ``quantity`` is "lux" (illuminance) or "C" (reflected exitance, lm/m²).
    ``min``/``max`` bound every patch; ``average`` is a lower bound on the
    area-weighted mean and ``uniformity`` on U0 = min / mean (EN 12464-1 style:
    desks 500 lux, U0 >= 0.6). ``weight`` scales its penalty.
    """

    name: str
    group: str | None = None
    patches: tuple[int, ...] | None = None
    quantity: str = Quantity.LUX.value
    min: float | None = None
    max: float | None = None
    average: float | None = None
    uniformity: float | None = None
    weight: float = 100.0

    def __post_init__(self) -> None:
        _name(self.name, "an intention's name")
        where = f"intention {self.name!r}"
        if (self.group is None) == (self.patches is None):
            raise DesignError(f"{where}: give either a group or a list of patches")
        if self.group is not None:
            _name(self.group, f"{where}: group")
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
        if self.quantity not in tuple(Quantity):
            raise DesignError(f"{where}: quantity must be {_either(tuple(Quantity))}")
        for key in (Bound.MIN, Bound.MAX, Bound.AVERAGE):
            v = getattr(self, key)
            if v is not None:
                object.__setattr__(self, key, _finite(v, f"{where} {key}", lo=0.0))
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


GOALS = tuple(str(g) for g in GoalKind)


@dataclass(frozen=True)
class Goal:
    """What to optimise.

    - ``min_electric_power``: sum of luminaire flux / efficacy (W);
    - ``max_light_power``: total reflected light power sum_i C_i A_i (lm), of
      the sources whose kind is in ``kinds`` (all when empty);
    - ``match``: relative distance e(E) = ||C(E) - C_obj|| / ||C_obj|| (paper
      eq. 11) to the light of the project's ``target_sources``.
    """

    kind: str
    kinds: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in GOALS:
            raise DesignError(f"goal {self.kind!r} is not one of {GOALS}")
        object.__setattr__(self, "kinds", _items(self.kinds, f"goal {self.kind!r}", "kinds"))
        bad = [k for k in self.kinds if k not in SOURCE_KINDS]
        if bad:
            raise DesignError(f"goal {self.kind!r}: kinds {bad} must be {_either(SOURCE_KINDS)}")
        if self.kinds and self.kind != GoalKind.MAX_LIGHT_POWER:
            raise DesignError(f"goal {self.kind!r}: only max_light_power counts source kinds")


@dataclass(frozen=True)
class Daylight:
    """Exterior diffuse illuminance (lux) and glazing transmittance of the skylights."""

    exterior_lux: float = 10000.0
    transmittance: float = 0.6

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "exterior_lux", _finite(self.exterior_lux, "daylight exterior_lux", lo=0.0)
        )
        object.__setattr__(
            self, "transmittance", _finite(self.transmittance, "daylight transmittance", 0.0, 1.0)
        )


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

    def __post_init__(self) -> None:
        for name, cls in (
            ("sources", Source),
            ("goals", Goal),
            ("rules", Rule),
            ("intentions", Intention),
            ("target_sources", Source),
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
        for what, items in (
            ("source", names),
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
        known = set(names)
        for r in self.rules:
            missing = [s for s in r.sources if s not in known]
            if missing:
                raise DesignError(f"rule {r.kind!r} names unknown sources {missing}")
        if any(g.kind == GoalKind.MATCH for g in self.goals) and not self.target_sources:
            raise DesignError("a match goal needs target_sources (the light to reproduce)")
        if self.penalty_power < 1 or self.penalty_power % 2:
            raise DesignError("penalty power must be an even positive integer (paper eq. 3)")

    def source(self, name: str) -> Source:
        """The source called ``name``."""
        for s in self.sources:
            if s.name == name:
                return s
        raise DesignError(f"no source {name!r}")
