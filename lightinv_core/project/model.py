"""The project data class and the fields of a project file's top level, declared once.

``Project`` holds everything saved in a project file: the ``SceneSpec`` it is on, the
design, the ``OperatorSettings`` and ``OptimizerSettings`` of a run, and saved results.
``TOP`` declares the fields of the file's top level; ``FILE_SPECS`` lists every object's
spec (the scene's are in ``scene.py``, the design's in its classes in ``design/model/``,
taken in ``specs.py``, the results' in ``results.py``, the settings' beside their
classes). A ``Project`` checks each source against its kind (``source_kinds``).
``read`` and ``write`` are driven by them.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

from lightinv_core.design.model import Daylight, Design
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.fields import (
    Custom,
    Field,
    Integer,
    ObjectSpec,
    String,
    _fail,
    _integer,
    _within,
)
from lightinv_core.operator.settings import OPERATOR, OperatorSettings
from lightinv_core.optimize.settings import OPTIMIZER, OptimizerSettings
from lightinv_core.project.results import (
    PARETO,
    RESULTS,
    RUN,
    SOLUTION,
    VIOLATION,
    RunRecord,
    read_results,
)
from lightinv_core.project.scene import SCENE, ZONE, SceneSpec, resolve_path
from lightinv_core.project.source_kinds import check_source_kinds
from lightinv_core.project.specs import (
    ARRAY,
    CALC,
    CONTROL_GROUP,
    DAYLIGHT,
    GOAL,
    INTENTION,
    OBSERVER,
    RULE,
    SOURCE,
    WORKPLANE,
    read_arrays,
    read_calc_objects,
    read_control_groups,
    read_daylight,
    read_goals,
    read_intentions,
    read_observers,
    read_rules,
    read_sources,
    read_workplanes,
)

__all__ = ["FILE_SPECS", "SCHEMA", "TOP", "Project", "SceneSpec", "resolve_path"]

SCHEMA = 1


# -- the project ----------------------------------------------------------------------------


@dataclass(frozen=True)
class Project:
    """Everything saved in a project file. ``path`` is where it was loaded from (not
    saved, not compared)."""

    name: str
    scene: SceneSpec
    design: Design
    operator: OperatorSettings = field(default_factory=OperatorSettings)
    optimizer: OptimizerSettings = field(default_factory=OptimizerSettings)
    description: str = ""
    solutions: tuple[Solution, ...] = ()
    pareto: ParetoFront | None = None
    runs: tuple[RunRecord, ...] = ()  # the optimisation runs made in the window
    path: Path | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "solutions", tuple(self.solutions))
        object.__setattr__(self, "runs", tuple(self.runs))
        check_source_kinds(self.design)


# -- the top level of the file --------------------------------------------------------------


def _penalty_power(v: Any, path: str) -> int:
    power = _integer(v, path, lo=2)
    if power % 2:
        _fail(path, f"expected an even integer >= 2, got {power}")
    return power


PENALTY_POWER = Custom(
    _penalty_power, "integer", {"type": "integer", "minimum": 2, "multipleOf": 2}
)


def _see(anchor: str, text: str) -> str:
    return f"[{text}](#{anchor})"


TOP = ObjectSpec(
    "top",
    (
        Field(
            "schema",
            Integer(),
            type="integer",
            meaning=f"format version; this LightInv reads `{SCHEMA}`",
        ),
        Field("name", String(), meaning="project name"),
        Field(
            "description",
            String(empty=True),
            "",
            "string",
            "free text",
            always=True,
        ),
        Field(
            "scene",
            partial(SCENE.build, SceneSpec),
            type="object",
            meaning=_see("scene", "the scene"),
            of=SCENE,
        ),
        Field(
            "operator",
            partial(OPERATOR.build, OperatorSettings),
            OperatorSettings(),
            "object",
            _see("operator", "operator settings"),
            always=True,
            of=OPERATOR,
            doc_default="see below",
        ),
        Field(
            "daylight",
            read_daylight,
            Daylight(),
            "object",
            _see("daylight-and-penalty_power", "exterior daylight"),
            always=True,
            of=DAYLIGHT,
            doc_default="see below",
        ),
        Field(
            "penalty_power",
            PENALTY_POWER,
            2,
            "integer",
            "exponent of the penalty, even, >= 2",
            always=True,
        ),
        Field(
            "sources",
            read_sources,
            type="list",
            meaning=_see("sources-and-target_sources", "sources") + " to place (may be empty)",
            of=SOURCE,
            many=True,
        ),
        Field(
            "target_sources",
            read_sources,
            (),
            "list",
            "the light a `match` goal reproduces",
            always=True,
            of=SOURCE,
            many=True,
        ),
        Field(
            "arrays",
            read_arrays,
            (),
            "list",
            _see("arrays", "luminaire arrays") + " of photometric products",
            of=ARRAY,
            many=True,
        ),
        Field(
            "workplanes",
            read_workplanes,
            (),
            "list",
            _see("workplanes", "work planes") + " with EN 12464-1 calculation grids",
            of=WORKPLANE,
            many=True,
        ),
        Field(
            "observers",
            read_observers,
            (),
            "list",
            _see("observers", "observers") + ": eyes the glare rating (UGR) is judged from",
            of=OBSERVER,
            many=True,
        ),
        Field(
            "control_groups",
            read_control_groups,
            (),
            "list",
            _see("control_groups", "daylight-linked control groups")
            + ": luminaires dimmed together by one sensor region",
            of=CONTROL_GROUP,
            many=True,
        ),
        Field(
            "calc_objects",
            read_calc_objects,
            (),
            "list",
            _see("calc_objects", "calculation objects")
            + ": task areas, wall and ceiling surfaces, cylindrical and free points",
            of=CALC,
            many=True,
        ),
        Field(
            "rules",
            read_rules,
            (),
            "list",
            _see("rules", "geometric rules"),
            always=True,
            needs=("sources", "arrays"),
            of=RULE,
            many=True,
        ),
        Field(
            "intentions",
            read_intentions,
            (),
            "list",
            _see("intentions", "lighting intentions"),
            always=True,
            of=INTENTION,
            many=True,
        ),
        Field(
            "goals",
            read_goals,
            type="list",
            meaning=_see("goals", "goals") + ", at least one",
            needs=("target_sources",),
            of=GOAL,
            many=True,
            schema={"type": "array", "items": {"$ref": "#/$defs/goal"}, "minItems": 1},
        ),
        Field(
            "optimizer",
            partial(OPTIMIZER.build, OptimizerSettings),
            OptimizerSettings(),
            "object",
            _see("optimizer", "optimiser settings"),
            always=True,
            of=OPTIMIZER,
            doc_default="see below",
        ),
        Field(
            "results",
            read_results,
            None,
            "object",
            _see("results", "saved results"),
            of=RESULTS,
        ),
    ),
)
"""The fields of a project file's top level, in the order they are written."""

FILE_SPECS = (
    TOP,
    SCENE,
    ZONE,
    OPERATOR,
    DAYLIGHT,
    SOURCE,
    ARRAY,
    WORKPLANE,
    OBSERVER,
    CONTROL_GROUP,
    CALC,
    RULE,
    INTENTION,
    GOAL,
    OPTIMIZER,
    RESULTS,
    RUN,
    SOLUTION,
    VIOLATION,
    PARETO,
)
"""Every object of a project file; docs/project-file.md tabulates each from its spec."""


def project_from_values(values: Mapping[str, Any]) -> Project:
    """The project made of the checked top-level ``values`` (every ``TOP`` field)."""
    with _within(""):
        design = Design(
            values["sources"],
            values["goals"],
            values["rules"],
            values["intentions"],
            values["target_sources"],
            values["daylight"],
            values["penalty_power"],
            values["arrays"],
            values["workplanes"],
            values["observers"],
            values["control_groups"],
            values["calc_objects"],
        )
    results = values["results"] or {}
    return Project(
        values["name"],
        values["scene"],
        design,
        values["operator"],
        values["optimizer"],
        values["description"],
        results.get("solutions", ()),
        results.get("pareto"),
        results.get("runs", ()),
    )


def project_values(p: Project) -> dict[str, Any]:
    """The top-level values of ``p``, by ``TOP`` field (results None when there are none)."""
    d = p.design
    results = None
    if p.solutions or p.pareto is not None or p.runs:
        results = {"solutions": p.solutions, "pareto": p.pareto, "runs": p.runs}
    return {
        "schema": SCHEMA,
        "name": p.name,
        "description": p.description,
        "scene": p.scene,
        "operator": p.operator,
        "daylight": d.daylight,
        "penalty_power": d.penalty_power,
        "sources": d.sources,
        "target_sources": d.target_sources,
        "arrays": d.arrays,
        "workplanes": d.workplanes,
        "observers": d.observers,
        "control_groups": d.control_groups,
        "calc_objects": d.calc_objects,
        "rules": d.rules,
        "intentions": d.intentions,
        "goals": d.goals,
        "optimizer": p.optimizer,
        "results": results,
    }
