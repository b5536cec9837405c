"""The inverse design problem as data: sources, geometric rules, lighting intentions,
luminaire arrays, work planes, calculation objects, observers, daylight and goals, each a
frozen dataclass that declares its project-file fields once.

Every field is declared in its class with ``fields.declare``: its typed check (which
also gives the docs' type and the JSON Schema), default, meaning with units, and how it
is written. From that one declaration come the checks run when the engine builds an
object, the project file's reading and its messages (``project/specs.py`` adds only the
checks that span a list), writing, the field tables of docs/project-file.md and
docs/project.schema.json. ``__post_init__`` keeps only the checks that tie fields
together (min <= max, flux or exitance).

Why dataclass fields with metadata, not pydantic models: the engine builds these
objects in its loops (a solution's sources, ``replace(source, rect=...)``) and frozen
dataclasses with a fast path for valid values cost no more than before; the bad-input
catalogue's messages are our own (the JSON path, what was expected, what was given,
"did you mean"), which pydantic would reword; registries extend the valid kinds at run
time (``kinds.source_kind_names()``, goals, quantities); and it needs no new runtime
dependency.

Units: source rectangles in metres in their zone's (u, v) coordinates; luminous flux in
lm, efficacy in lm/W, exitance in lm/m², illuminance in lux.
"""

from lightinv_core.design.model.array import (
    ARRAY_FIELDS,
    ARRAY_VARIABLES,
    MAX_ARRAY_SIDE,
    NEW_ARRAY_FREE,
    ROTATIONS,
    LuminaireArray,
    new_array,
)
from lightinv_core.design.model.calc_kinds import RING
from lightinv_core.design.model.calc_object import (
    CALC_FIELDS,
    CalcKind,
    CalcObject,
    calc_kind,
    calc_kind_names,
    register_calc_kind,
    unregister_calc_kind,
)
from lightinv_core.design.model.control import (
    CONTROL_GROUP_FIELDS,
    DEFAULT_CONTROL_GROUP,
    ControlGroup,
)
from lightinv_core.design.model.daylight import (
    DAYLIGHT_FIELDS,
    MAX_WATTS,
    WORKPLANE_FIELDS,
    Daylight,
    Workplane,
)
from lightinv_core.design.model.design import Design
from lightinv_core.design.model.goal import GOAL_FIELDS, GOALS, Goal
from lightinv_core.design.model.intention import INTENTION_FIELDS, MAX_PATCH_ID, Intention
from lightinv_core.design.model.observer import OBSERVER_FIELDS, SEATED_EYE, Observer
from lightinv_core.design.model.rule import (
    ARRAY_RULES,
    AXES,
    RULE_FIELDS,
    RULE_SOURCES,
    RULE_TAKES,
    Rule,
)
from lightinv_core.design.model.source import (
    CORNERS,
    MAX_EFFICACY,
    MAX_FLUX,
    SOURCE_FIELDS,
    SOURCE_KINDS,
    VARIABLES,
    Source,
    source_kind,
)
from lightinv_core.errors import DesignError

__all__ = [
    "ARRAY_FIELDS",
    "ARRAY_RULES",
    "ARRAY_VARIABLES",
    "AXES",
    "CALC_FIELDS",
    "CONTROL_GROUP_FIELDS",
    "CORNERS",
    "DAYLIGHT_FIELDS",
    "DEFAULT_CONTROL_GROUP",
    "GOALS",
    "GOAL_FIELDS",
    "INTENTION_FIELDS",
    "MAX_ARRAY_SIDE",
    "MAX_EFFICACY",
    "MAX_FLUX",
    "MAX_PATCH_ID",
    "MAX_WATTS",
    "NEW_ARRAY_FREE",
    "OBSERVER_FIELDS",
    "RING",
    "ROTATIONS",
    "RULE_FIELDS",
    "RULE_SOURCES",
    "RULE_TAKES",
    "SEATED_EYE",
    "SOURCE_FIELDS",
    "SOURCE_KINDS",
    "VARIABLES",
    "WORKPLANE_FIELDS",
    "CalcKind",
    "CalcObject",
    "ControlGroup",
    "Daylight",
    "Design",
    "DesignError",
    "Goal",
    "Intention",
    "LuminaireArray",
    "Observer",
    "Rule",
    "Source",
    "Workplane",
    "calc_kind",
    "calc_kind_names",
    "new_array",
    "register_calc_kind",
    "source_kind",
    "unregister_calc_kind",
]
