"""Every field of the design's JSON objects, declared once, and their readers.

Reading (``read_sources``, ``read_rules``, ...: JSON data -> design objects, with the
checks that span a list, such as unique names), the per-field error messages, writing
(``project/write.py``) and the field tables of docs/project-file.md
(``tests/core/test_fields.py`` regenerates them) all come from these specs. Checks that
tie several fields together (a luminaire's flux or exitance, min <= max) stay with the
model classes in ``design/model.py``.
"""

from __future__ import annotations

from functools import partial
from typing import Any

from lightinv_core.design.model import (
    ARRAY_RULES,
    ARRAY_VARIABLES,
    AXES,
    ROTATIONS,
    SOURCE_KINDS,
    VARIABLES,
    Daylight,
    Goal,
    Intention,
    LuminaireArray,
    Rule,
    Source,
    Workplane,
)
from lightinv_core.fields import (
    Field,
    ObjectSpec,
    _boolean,
    _choice,
    _fail,
    _integer,
    _join,
    _list,
    _number,
    _numbers,
    _string,
    _unique,
    _within,
)
from lightinv_core.goals import goal_names
from lightinv_core.kinds import MAX_LUX, GoalKind, Quantity, RuleKind, Scenario, SourceKind
from lightinv_core.quantities import quantity_names

LUMINAIRE = (str(SourceKind.LUMINAIRE),)
SKYLIGHT = (str(SourceKind.SKYLIGHT),)
_D = {f: Source.__dataclass_fields__[f].default for f in ("flux_range", "efficacy", "filter")}


def _either(values: tuple[str, ...]) -> str:
    """The allowed values as the docs show them: ``"a"`` or ``"b"``."""
    return " or ".join(f'`"{v}"`' for v in values)


MAX_FLUX = 1e10
"""Lumens: the most a luminaire or a source may emit (the photometry readers' cap)."""
MAX_EFFICACY = 683.0
"""lm/W: the luminous efficacy of radiation at 555 nm, which no light source exceeds."""
MAX_WATTS = 1e9
"""W: the largest electric power a project may name."""


def _nonneg(v: Any, p: str) -> float:
    return _number(v, p, lo=0.0)


def _flux(v: Any, p: str) -> float:
    return _number(v, p, lo=0.0, hi=MAX_FLUX)


def _lux(v: Any, p: str) -> float:
    return _number(v, p, lo=0.0, hi=MAX_LUX)


def _variables(v: Any, p: str) -> tuple[str, ...]:
    return _unique(_list(v, p, lambda x, q: _choice(x, q, VARIABLES), "variables"), p)


def _source_not_taken(kind: str, field: str) -> str:
    if kind == SourceKind.SKYLIGHT:
        return (
            "only luminaires have this; a skylight's exitance is "
            "filter x transmittance x exterior illuminance"
        )
    return "only skylights have a filter"


SOURCE = ObjectSpec(
    "source",
    (
        Field("name", _string, type="string", meaning="unique among the sources"),
        Field("zone", _string, type="string", meaning="the emitter zone it is placed in"),
        Field(
            "kind",
            lambda v, p: _choice(v, p, SOURCE_KINDS),
            type=_either(SOURCE_KINDS),
            meaning="must match the zone's kind",
        ),
        Field(
            "rect",
            lambda v, p: _numbers(v, p, 4),
            type="4 numbers",
            meaning="`[u0, v0, u1, v1]`: two diagonal corners in the zone's axes, m",
        ),
        Field(
            "free",
            _variables,
            (),
            "list of variables",
            "what the optimiser may change: `u0`, `v0`, `u1`, `v1`, `flux`, `filter`",
        ),
        Field(
            "flux",
            _flux,
            None,
            "number >= 0",
            "luminous flux, lm (exitance = flux / area); the start of a free flux",
            LUMINAIRE,
            nullable=True,
        ),
        Field(
            "exitance",
            _lux,
            None,
            "number >= 0",
            "fixed exitance, lm/m² (a luminous panel)",
            LUMINAIRE,
            nullable=True,
        ),
        Field(
            "flux_range",
            lambda v, p: _numbers(v, p, 2, lo=0.0, hi=MAX_FLUX),
            _D["flux_range"],
            "2 numbers",
            "bounds of a free flux, lm; 0 <= min < max",
            LUMINAIRE,
        ),
        Field(
            "efficacy",
            lambda v, p: _number(v, p, gt=0.0, hi=MAX_EFFICACY),
            _D["efficacy"],
            "number > 0",
            "lm/W, for the electric power",
            LUMINAIRE,
        ),
        Field(
            "filter",
            lambda v, p: _number(v, p, lo=0.0, hi=1.0),
            _D["filter"],
            "number in [0, 1]",
            "fraction of the glazed daylight let in",
            SKYLIGHT,
        ),
    ),
    kind_field="kind",
    not_taken=_source_not_taken,
)

RULE_TAKES = {
    RuleKind.AREA: ("min", "max"),
    RuleKind.ASPECT: ("max",),
    RuleKind.MIRROR: ("axis",),
    RuleKind.CENTRED: (),
    RuleKind.SPACING: ("min",),
    RuleKind.ALIGN: ("axis",),
    RuleKind.SHR: ("max",),
    RuleKind.CLEARANCE: ("min",),
}
"""Which of min, max and axis each rule kind takes."""


def _taking(key: str) -> tuple[str, ...]:
    return tuple(str(k) for k, takes in RULE_TAKES.items() if key in takes)


def _rule_not_taken(kind: str, field: str) -> str:
    also = ", ".join(("sources", *RULE_TAKES[RuleKind(kind)]))
    return f"{kind} rules do not take {field!r} (they take: {also})"


RULE = ObjectSpec(
    "rule",
    (
        Field(
            "kind",
            lambda v, p: _choice(v, p, tuple(str(k) for k in RuleKind)),
            type="rule kind",
            meaning="see the table of rule kinds",
        ),
        Field(
            "sources",
            lambda v, p: _unique(_list(v, p, _string, "source names", 1), p),
            type="list of names",
            meaning="the sources it constrains, each once (`shr`, `clearance`: luminaire arrays)",
        ),
        Field("min", _nonneg, None, "number >= 0", "lower bound", _taking("min"), nullable=True),
        Field("max", _nonneg, None, "number >= 0", "upper bound", _taking("max"), nullable=True),
        Field(
            "axis",
            lambda v, p: _choice(v, p, AXES),
            None,
            _either(AXES),
            "the zone axis",
            _taking("axis"),
            nullable=True,
        ),
    ),
    kind_field="kind",
    not_taken=_rule_not_taken,
    kinds_first=True,
)

_I = Intention.__dataclass_fields__
INTENTION = ObjectSpec(
    "intention",
    (
        Field("name", _string, type="string", meaning="unique among the intentions"),
        Field(
            "group",
            _string,
            None,
            "string",
            'a lighting group of the scene, or `"*"` (every patch); this, `patches` or `grid`',
            nullable=True,
        ),
        Field(
            "patches",
            lambda v, p: _list(v, p, lambda x, q: _integer(x, q, lo=0), "patch ids", 1),
            None,
            "list of integers >= 0",
            "patch ids (at least one); this, `group` or `grid`",
            nullable=True,
        ),
        Field(
            "grid",
            _string,
            None,
            "string",
            "a work plane's name: EN 12464-1 values over its grid points (lux only); "
            "this, `group` or `patches`",
            nullable=True,
        ),
        Field(
            "quantity",
            lambda v, p: _choice(v, p, quantity_names()),
            _I["quantity"].default,
            _either(tuple(Quantity)),
            "illuminance (lux) or reflected exitance C (lm/m²) in the scenario; or a "
            "daylight metric: daylight factor `df` (%), DA300 `da` and UDI 100-3000 `udi` "
            "(fractions of the occupied hours), `sda` (1 where DA300 >= 50%: its average "
            "is sDA300/50%)",
            always=True,
        ),
        Field(
            "scenario",
            lambda v, p: _choice(v, p, tuple(str(q) for q in Scenario)),
            _I["scenario"].default,
            _either(tuple(Scenario)),
            "the light it is judged in: `design` (luminaires + skylights at the design "
            "exterior lux), `night` (luminaires only), `overcast` (luminaires + the CIE "
            "overcast sky); `df` is always `overcast` and `da`, `udi`, `sda` `annual`",
        ),
        Field("min", _nonneg, None, "number >= 0", "lower bound on every patch", nullable=True),
        Field("max", _nonneg, None, "number >= 0", "upper bound on every patch", nullable=True),
        Field(
            "average",
            _nonneg,
            None,
            "number >= 0",
            "lower bound on the area-weighted mean",
            nullable=True,
        ),
        Field(
            "uniformity",
            lambda v, p: _number(v, p, lo=0.0, hi=1.0),
            None,
            "number in [0, 1]",
            "lower bound on U0 = min / mean",
            nullable=True,
        ),
        Field(
            "weight",
            _nonneg,
            _I["weight"].default,
            "number >= 0",
            "scales its penalty",
            always=True,
        ),
    ),
)

GOAL = ObjectSpec(
    "goal",
    (
        Field(
            "kind",
            lambda v, p: _choice(v, p, goal_names()),
            type="goal kind",
            meaning="see the table of goal kinds",
        ),
        Field(
            "kinds",
            lambda v, p: _unique(_list(v, p, lambda x, q: _choice(x, q, SOURCE_KINDS), "kinds"), p),
            (),
            "list of source kinds",
            "count the light of these kinds (all when empty)",
            (str(GoalKind.MAX_LIGHT_POWER),),
        ),
    ),
    kind_field="kind",
    not_taken=lambda kind, field: "only a max_light_power goal takes source kinds",
    default_anywhere=True,  # an empty list is the default: any goal may write it
)

_DL = Daylight.__dataclass_fields__
DAYLIGHT = ObjectSpec(
    "daylight",
    (
        Field(
            "exterior_lux",
            _lux,
            _DL["exterior_lux"].default,
            "number >= 0",
            "exterior diffuse illuminance, lux",
            always=True,
        ),
        Field(
            "transmittance",
            lambda v, p: _number(v, p, lo=0.0, hi=1.0),
            _DL["transmittance"].default,
            "number in [0, 1]",
            "fraction of it the skylight glazing lets through",
            always=True,
        ),
        Field(
            "weather",
            _string,
            _DL["weather"].default,
            "string",
            'EPW or TMY3 weather file (relative to the project), or `"builtin"`: '
            "the shipped Greensboro TMY3 (docs/daylight.md)",
        ),
        Field(
            "north_deg",
            lambda v, p: _number(v, p, lo=-360.0, hi=360.0),
            _DL["north_deg"].default,
            "number",
            "compass bearing of the scene's +y axis, degrees (0: +y is north)",
        ),
        Field(
            "occupancy",
            lambda v, p: _numbers(v, p, 2, lo=0.0, hi=24.0),
            _DL["occupancy"].default,
            "2 numbers",
            "occupied hours `[start, end)` of the day, local time",
        ),
        Field(
            "weekdays",
            _boolean,
            _DL["weekdays"].default,
            "boolean",
            "occupied Monday to Friday only",
        ),
        Field(
            "ground_reflectance",
            lambda v, p: _number(v, p, lo=0.0, hi=0.99),
            _DL["ground_reflectance"].default,
            "number in [0, 0.99]",
            "of the ground outside, for the light it reflects onto the glazing",
        ),
        Field(
            "overcast_lux",
            lambda v, p: _number(v, p, lo=0.0, hi=2e5),
            _DL["overcast_lux"].default,
            "number >= 0",
            "horizontal exterior illuminance of the design overcast sky, lux",
        ),
        Field(
            "target_lux",
            _lux,
            _DL["target_lux"].default,
            "number >= 0",
            "daylight-linked dimming keeps the work plane's mean at this, lux",
        ),
        Field(
            "min_level",
            lambda v, p: _number(v, p, lo=0.0, hi=1.0),
            _DL["min_level"].default,
            "number in [0, 1]",
            "lowest dimming level of the luminaires",
        ),
        Field(
            "standby_w",
            lambda v, p: _number(v, p, lo=0.0, hi=MAX_WATTS),
            _DL["standby_w"].default,
            "number >= 0",
            "standby power of the lighting controls, drawn all year, W",
        ),
        Field(
            "workplane",
            _string,
            None,
            "string",
            "the work plane the dimming and the annual goals read (default: the first)",
            nullable=True,
        ),
    ),
)


# -- readers: JSON data -> design objects ---------------------------------------------------


_A = LuminaireArray.__dataclass_fields__


def _array_variables(v: Any, p: str) -> tuple[str, ...]:
    return _unique(_list(v, p, lambda x, q: _choice(x, q, ARRAY_VARIABLES), "variables"), p)


def _rotation(v: Any, p: str) -> int:
    r = _integer(v, p, lo=0)
    if r not in ROTATIONS:
        _fail(p, f"expected 0 or 90 (degrees), got {r}")
    return r


def _whole_pair(v: Any, p: str) -> tuple[int, int]:
    items = _list(v, p, lambda x, q: _integer(x, q, lo=1), "whole numbers")
    if len(items) != 2:
        _fail(p, f"expected 2 whole numbers (min, max), got {len(items)}")
    return tuple(items)


ARRAY = ObjectSpec(
    "array",
    (
        Field("name", _string, type="string", meaning="unique among sources and arrays"),
        Field("zone", _string, type="string", meaning="the luminaire zone it is mounted in"),
        Field(
            "product",
            _string,
            type="string",
            meaning="a catalogue luminaire's name, or an `.ies`/`.ldt` file "
            "(relative to the project file)",
        ),
        Field(
            "rect",
            lambda v, p: _numbers(v, p, 4),
            type="4 numbers",
            meaning="`[u0, v0, u1, v1]`: the rectangle the array fills evenly, zone axes, m",
        ),
        Field(
            "rows",
            lambda v, p: _integer(v, p, lo=1),
            _A["rows"].default,
            "integer >= 1",
            "luminaires along the zone's v axis",
            always=True,
        ),
        Field(
            "columns",
            lambda v, p: _integer(v, p, lo=1),
            _A["columns"].default,
            "integer >= 1",
            "luminaires along u",
            always=True,
        ),
        Field(
            "rotation",
            _rotation,
            _A["rotation"].default,
            "`0` or `90`",
            "degrees: the product's C0 plane along u (0) or v (90)",
        ),
        Field(
            "dimming",
            lambda v, p: _number(v, p, gt=0.0, hi=1.0),
            _A["dimming"].default,
            "number in (0, 1]",
            "output (and power) of every luminaire, fraction of full",
        ),
        Field(
            "free",
            _array_variables,
            (),
            "list of variables",
            "what the optimiser may change: `u0`, `v0`, `u1`, `v1`, `rows`, `columns`, "
            "`rotation`, `dimming`",
        ),
        Field(
            "rows_range",
            _whole_pair,
            _A["rows_range"].default,
            "2 integers",
            "bounds of free rows",
        ),
        Field(
            "columns_range",
            _whole_pair,
            _A["columns_range"].default,
            "2 integers",
            "bounds of free columns",
        ),
        Field(
            "dimming_range",
            lambda v, p: _numbers(v, p, 2, lo=0.0),
            _A["dimming_range"].default,
            "2 numbers",
            "bounds of a free dimming; 0 < min <= max <= 1",
        ),
        Field(
            "maintenance_factor",
            lambda v, p: _number(v, p, gt=0.0, hi=1.0),
            _A["maintenance_factor"].default,
            "number in (0, 1]",
            "maintained / new light (EN 12464-1 Em)",
            always=True,
        ),
        Field(
            "watts",
            _nonneg,
            None,
            "number >= 0",
            "rated input power of one luminaire, W (default: the catalogue's or the file's)",
            nullable=True,
        ),
    ),
)

_W = Workplane.__dataclass_fields__
WORKPLANE = ObjectSpec(
    "workplane",
    (
        Field("name", _string, type="string", meaning="unique among the work planes"),
        Field(
            "height",
            _nonneg,
            _W["height"].default,
            "number >= 0",
            "above the floor group, m",
            always=True,
        ),
        Field(
            "border",
            _nonneg,
            _W["border"].default,
            "number >= 0",
            "left out along the floor's edges, m",
            always=True,
        ),
        Field(
            "group",
            _string,
            _W["group"].default,
            "string",
            "the floor group it lies over",
            always=True,
        ),
    ),
)


def read_arrays(v: Any, path: str) -> tuple[LuminaireArray, ...]:
    """The luminaire arrays listed at ``path``, names unique."""
    return _unique_names(_list(v, path, partial(ARRAY.build, LuminaireArray), "arrays"), path)


def read_workplanes(v: Any, path: str) -> tuple[Workplane, ...]:
    """The work planes listed at ``path``, names unique."""
    return _unique_names(_list(v, path, partial(WORKPLANE.build, Workplane), "work planes"), path)


def _unique_names(items: tuple, path: str) -> tuple:
    """``items`` (with a ``name``), failing at the second use of a name."""
    seen: dict[str, int] = {}
    for i, x in enumerate(items):
        if x.name in seen:
            where = f"{path}[{seen[x.name]}]"
            _fail(_join(_join(path, i), "name"), f"{x.name!r} is already used by {where}")
        seen[x.name] = i
    return items


def read_sources(v: Any, path: str) -> tuple[Source, ...]:
    """The sources (or target sources) listed at ``path``, names unique."""
    return _unique_names(_list(v, path, partial(SOURCE.build, Source), "sources"), path)


def _rule(v: Any, path: str, names: tuple[str, ...], arrays: tuple[str, ...] = ()) -> Rule:
    values = RULE.read(v, path)
    on_arrays = values["kind"] in ARRAY_RULES
    what, pool = ("luminaire array", arrays) if on_arrays else ("source", names)
    for i, s in enumerate(values["sources"]):
        if s not in pool:
            known = ", ".join(pool) or "none"
            _fail(_join(_join(path, "sources"), i), f"no {what} {s!r} ({what}s: {known})")
    with _within(path):
        return Rule(**values)


def read_rules(
    v: Any,
    path: str,
    sources: tuple[Source, ...] = (),
    arrays: tuple[LuminaireArray, ...] = (),
) -> tuple[Rule, ...]:
    """The rules listed at ``path``; each names some of ``sources`` (``shr`` and
    ``clearance``: of ``arrays``), and a source mirrors at most one other."""
    names = tuple(s.name for s in sources)
    array_names = tuple(a.name for a in arrays)
    rules = _list(v, path, lambda x, p: _rule(x, p, names, array_names), "rules")
    mirrored: dict[str, int] = {}
    for i, r in enumerate(rules):
        if r.kind == RuleKind.MIRROR:
            derived = r.sources[0]
            if derived in mirrored:
                _fail(
                    _join(_join(path, i), "sources[0]"),
                    f"{derived!r} already mirrors another source ({path}[{mirrored[derived]}])",
                )
            mirrored[derived] = i
    return rules


def read_intentions(v: Any, path: str) -> tuple[Intention, ...]:
    """The intentions listed at ``path``, names unique."""
    items = _list(v, path, partial(INTENTION.build, Intention), "intentions")
    return _unique_names(items, path)


def read_goals(v: Any, path: str, target_sources: tuple[Source, ...] = ()) -> tuple[Goal, ...]:
    """The goals listed at ``path``: at least one, each kind once, a match goal only with
    ``target_sources``."""
    goals = _list(v, path, partial(GOAL.build, Goal), "goals", 1)
    seen: dict[str, int] = {}
    for i, g in enumerate(goals):
        if g.kind in seen:
            _fail(
                _join(_join(path, i), "kind"),
                f"{g.kind!r} is already a goal ({path}[{seen[g.kind]}])",
            )
        seen[g.kind] = i
    for i, g in enumerate(goals):
        if g.kind == GoalKind.MATCH and not target_sources:
            _fail(_join(path, i), "a match goal needs target_sources (the light to reproduce)")
    return goals


def read_daylight(v: Any, path: str) -> Daylight:
    """The daylight object at ``path``."""
    return DAYLIGHT.build(Daylight, v, path)
