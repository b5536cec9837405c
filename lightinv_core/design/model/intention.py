"""Lighting intentions: bounds on a quantity over a patch set or a work plane's grid."""

from __future__ import annotations

from dataclasses import dataclass, field

from lightinv_core.errors import DesignError
from lightinv_core.fields import Choice, Integer, ListOf, Number, ObjectSpec, String, declare
from lightinv_core.kinds import Bound, Quantity, Scenario
from lightinv_core.quantities import quantity_kind, quantity_names, quantity_spec
from lightinv_core.scenarios import scenario_kind, scenario_names, scenario_spec

MAX_PATCH_ID = 2**53  # project files limit integers to 2^53 too


def _either(names) -> str:
    """``'a' or 'b'`` (the allowed values, for a message)."""
    return " or ".join(repr(str(n)) for n in names)


@dataclass(frozen=True)
class Intention:
    """A lighting intention on a patch set: a group's patches (``group="*"`` means
    every patch of the scene) or picked patch ids.

    ``quantity`` is "lux" (illuminance) or "C" (reflected exitance, lm/m²), or a
    daylight metric (``quantities.py``). ``min``/``max`` bound every patch; ``average``
    is a lower bound on the area-weighted mean and ``uniformity`` on U0 = min / mean
    (EN 12464-1 style: desks 500 lux, U0 >= 0.6). ``weight`` scales its penalty. On a
    work plane's ``grid`` (its name) the statistics are EN 12464-1's: the plain mean of
    the grid points (Em), their min (Emin), U0 = Emin / Em, max; luminaire arrays' light
    there is maintained (their maintenance factor applied).
    """

    name: str = field(metadata=declare(String(), "unique among the intentions"))
    group: str | None = field(
        default=None,
        metadata=declare(
            String(),
            'a lighting group of the scene, or `"*"` (every patch); this, `patches` or `grid`',
            nullable=True,
        ),
    )
    patches: tuple[int, ...] | None = field(
        default=None,
        metadata=declare(
            ListOf(Integer(lo=0), "patch ids", 1, name="list of integers >= 0"),
            "patch ids (at least one); this, `group` or `grid`",
            nullable=True,
        ),
    )
    grid: str | None = field(
        default=None,
        metadata=declare(
            String(),
            "a work plane's or calculation object's name: EN 12464-1 values over its "
            "grid points (lux only); this, `group` or `patches`",
            nullable=True,
        ),
    )
    observers: tuple[str, ...] | None = field(
        default=None,
        metadata=declare(
            ListOf(String(), "observer names", 1, unique=True, name="list of observer names"),
            "the design's observers (at least one): UGR (`quantity` `ugr`), sunlight "
            "exposure or simplified DGP at each eye; "
            "this, `group`, `patches` or `grid`",
            nullable=True,
        ),
    )
    quantity: Quantity = field(
        default=Quantity.LUX,
        metadata=declare(
            Choice(quantity_names, quantity_kind),
            "illuminance (lux) or reflected exitance C (lm/m²) in the scenario; or a "
            "daylight metric: daylight factor `df` (%), DA300 `da` and UDI 100-3000 `udi` "
            "(fractions of the occupied hours), `sda` (1 where DA300 >= 50%: its average "
            "is sDA300/50%), `ase` (1 where clear glazing's direct sun exceeds 1000 lux "
            "in more than 250 occupied hours: its average is ASE1000,250), `cda` (cDA300, the "
            "mean of min(E / 300 lux, 1) over the occupied hours), `en17037` (a "
            "work plane's EN 17037 daylight provision as a level score: `min` 1, 2 or 3 "
            "asks at least the minimum, medium or high level); or the glare "
            "rating `ugr` (CIE 117), the EN 17037 sunlight exposure `sunlight` (hours of "
            "sun on `daylight.sunlight_date` through clear glazing; `min` 1.5, 3 or 4 h) "
            "or the simplified DGP `dgp` (the share of the occupied hours whose DGPs "
            "exceeds `daylight.dgp_limit`; `max` 0.05 as EN 17037's glare protection) "
            "at `observers`",
            always=True,
        ),
    )
    scenario: Scenario = field(
        default=Scenario.DESIGN,
        metadata=declare(
            Choice(scenario_names, scenario_kind),
            "the light it is judged in: `design` (luminaires + skylights at the design "
            "exterior lux), `night` (luminaires only), `overcast` (luminaires + the CIE "
            "overcast sky); `df` is always `overcast` and `da`, `udi`, `sda` `annual`",
        ),
    )
    min: float | None = field(
        default=None, metadata=declare(Number(lo=0.0), "lower bound on every patch", nullable=True)
    )
    max: float | None = field(
        default=None, metadata=declare(Number(lo=0.0), "upper bound on every patch", nullable=True)
    )
    average: float | None = field(
        default=None,
        metadata=declare(Number(lo=0.0), "lower bound on the area-weighted mean", nullable=True),
    )
    uniformity: float | None = field(
        default=None,
        metadata=declare(Number(lo=0.0, hi=1.0), "lower bound on U0 = min / mean", nullable=True),
    )
    max_average: float | None = field(
        default=None,
        metadata=declare(
            Number(lo=0.0),
            "upper bound on the area-weighted mean (e.g. ASE1000,250 at most 0.10, LEED v4)",
            nullable=True,
        ),
    )
    weight: float = field(
        default=100.0, metadata=declare(Number(lo=0.0), "scales its penalty", always=True)
    )

    def __post_init__(self) -> None:
        where = f"intention {self.name!r}" if isinstance(self.name, str) else "an intention"
        INTENTION_FIELDS.check_fields(self, where)
        where = f"intention {self.name!r}"
        spec = quantity_spec(self.quantity)
        if spec.scenario is not None:
            # A daylight metric is measured in its own scenario, whatever was written.
            object.__setattr__(self, "scenario", spec.scenario)
        elif scenario_spec(self.scenario).lux is None:
            # A scenario without an illuminance (the weather year) measures metrics only.
            its = tuple(q for q in quantity_names() if quantity_spec(q).scenario == self.scenario)
            raise DesignError(
                f"{where}: the {self.scenario} scenario bounds a daylight metric: quantity "
                f"{_either(its)}"
            )
        targets = (self.group, self.patches, self.grid, self.observers)
        if sum(x is not None for x in targets) != 1:
            raise DesignError(
                f"{where}: give one of a group, a list of patches, a work-plane grid or observers"
            )
        if spec.at_observers and self.observers is None:
            raise DesignError(
                f"{where}: {spec.noun} is measured at observers: give `observers` (names "
                "of the design's observers), not a group, patches or a grid"
            )
        if self.observers is not None and not spec.at_observers:
            its = [q for q in quantity_names() if quantity_spec(q).at_observers]
            raise DesignError(
                f"{where}: observers take quantity {_either(its)}, not {self.quantity!r}"
            )
        if (
            spec.at_observers
            and not spec.levels
            and any(
                getattr(self, k) is not None
                for k in (Bound.MIN, Bound.AVERAGE, Bound.UNIFORMITY, Bound.MAX_AVERAGE)
            )
        ):
            raise DesignError(f"{where}: {spec.noun} is bounded from above: give max only")
        if spec.levels and not spec.plane and _bounds_but(self, Bound.MIN):
            raise DesignError(f"{where}: {spec.noun} is bounded by a level: give `min` only")
        if spec.plane and (self.grid is None or _bounds_but(self, Bound.MIN)):
            raise DesignError(
                f"{where}: {spec.noun} is one figure of a work plane: give `grid` and "
                "`min` only (the level it must reach)"
            )
        if self.grid is not None and spec.needs_reflectance:
            raise DesignError(
                f"{where}: a work-plane grid takes illuminance (lux) or a daylight metric, "
                f"not {spec.noun}"
            )
        self._check_bounds(where, spec)

    def _check_bounds(self, where: str, spec) -> None:
        lo, hi, unit = spec.low, spec.high, spec.range_text
        for key in (Bound.MIN, Bound.MAX, Bound.AVERAGE, Bound.MAX_AVERAGE):
            v = getattr(self, key)
            # A maximum above the range always holds (a "no limit" of 1e9 is fine), up to a
            # sane number; a minimum or an average outside it can never be met.
            upper = key in (Bound.MAX, Bound.MAX_AVERAGE)
            if v is not None and (v < lo or (v > hi and not upper) or v > 1e12):
                raise DesignError(
                    f"{where}: {key} {v:g} is outside the range of {self.quantity} "
                    f"({unit}), {lo:g} to {hi:g}; it could never be met"
                )
        if all(getattr(self, k) is None for k in Bound):
            raise DesignError(f"{where}: give at least one of {', '.join(Bound)}")
        if self.min is not None and self.max is not None and self.min > self.max:
            raise DesignError(f"{where}: min {self.min} is above max {self.max}")
        if self.average is not None and self.max is not None and self.average > self.max:
            raise DesignError(f"{where}: average {self.average} is above max {self.max}")
        if (
            self.average is not None
            and self.max_average is not None
            and self.average > self.max_average
        ):
            raise DesignError(
                f"{where}: average at least {self.average} is above max_average "
                f"{self.max_average}: no mean can meet both"
            )


def _bounds_but(it: Intention, keep: Bound) -> bool:
    """Whether the intention sets a bound other than ``keep``."""
    return any(getattr(it, str(b)) is not None for b in Bound if b != keep)


INTENTION_FIELDS = ObjectSpec.of(Intention, "intention")
"""The intention's fields, in the order a project file writes them."""
