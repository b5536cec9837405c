"""The project data classes and the field names of their JSON form.

``Project`` holds everything saved in a project file: the ``SceneSpec`` it is on, the
design, the ``OperatorSettings`` and ``OptimizerSettings`` of a run, and saved results.
The settings classes check their own fields (raising ``ProjectError``). The ``*_FIELDS``
tables list the keys each JSON object may have; ``project_read`` and ``project_write``
share them.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

from lightinv_core.design.model import Design
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.errors import SceneError
from lightinv_core.fields import (
    Field,
    ObjectSpec,
    _boolean,
    _choice,
    _fail,
    _join,
    _list,
    _number,
    _numbers,
    _object,
    _optional,
    _path_string,
    _string,
    _unique,
)
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.scene.builtin import BUILTIN_SCENES
from lightinv_core.scene.edits import ZoneEdit, apply_zone_edits
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.model import MIN_RESOLUTION, ZONE_KINDS, Scene
from lightinv_core.scene.obj_parse import UP_AXES

SCHEMA = 1


def resolve_path(p: str | None, base_dir: Path | None) -> str | None:
    """``p`` made absolute against ``base_dir`` when it is relative (None stays None)."""
    if p is None:
        return None
    q = Path(p).expanduser()
    if base_dir is not None and not q.is_absolute():
        q = Path(base_dir) / q
    return str(q)


def _obj_path(v: Any, path: str) -> str:
    s = _path_string(v, path)
    if not s.lower().endswith(".obj"):
        _fail(path, f"expected the path of an .obj file, got {s!r}")
    return s


ZONE_FIELDS = ("name", "kind", "surface", "rect")


def _zone_edit(v: Any, path: str) -> ZoneEdit:
    """A ``ZoneEdit`` from a JSON object (or a ``ZoneEdit`` given in code)."""
    if isinstance(v, ZoneEdit):
        return v
    d = _object(v, path, ZONE_FIELDS, ZONE_FIELDS)
    name = _string(d["name"], _join(path, "name"))
    kind = _choice(d["kind"], _join(path, "kind"), ZONE_KINDS)
    surface = _string(d["surface"], _join(path, "surface"))
    rect = _numbers(d["rect"], _join(path, "rect"), 4)
    try:
        return ZoneEdit(name, kind, surface, rect)
    except SceneError as err:
        _fail(_join(path, "rect"), str(err))


def _zone_edits(v: Any, path: str) -> tuple[ZoneEdit, ...]:
    zones = _list(v, path, _zone_edit, "zone objects")
    _unique(tuple(z.name for z in zones), path)
    return zones


_OBJ = "OBJ only: "

SCENE = ObjectSpec(
    "scene",
    (
        Field(
            "builtin",
            _optional(lambda v, p: _choice(v, p, tuple(BUILTIN_SCENES))),
            None,
            "string",
            "a built-in scene: " + ", ".join(f"`{n}`" for n in BUILTIN_SCENES),
        ),
        Field(
            "obj",
            _optional(_obj_path),
            None,
            "string",
            "path of a Wavefront `.obj` room model (see [obj-import.md](obj-import.md))",
        ),
        Field(
            "resolution",
            _optional(lambda v, p: _number(v, p, lo=MIN_RESOLUTION)),
            None,
            f"number >= {MIN_RESOLUTION:g}",
            "target patch size in metres; null: the scene's default (0.25 m for OBJ files)",
        ),
        Field(
            "materials",
            _optional(_path_string),
            None,
            "string",
            _OBJ + "path of the reflectance JSON file",
        ),
        Field(
            "scale",
            lambda v, p: _number(v, p, gt=0.0),
            1.0,
            "number > 0",
            _OBJ + "metres per model unit (0.001 for millimetres)",
        ),
        Field(
            "up",
            lambda v, p: _choice(v, p, UP_AXES),
            "z",
            " or ".join(f'`"{a}"`' for a in UP_AXES),
            _OBJ + "the model's up axis",
        ),
        Field(
            "skip_degenerate",
            _boolean,
            False,
            "boolean",
            _OBJ + "drop degenerate faces (with a warning) instead of failing",
        ),
        Field(
            "zones",
            _zone_edits,
            (),
            "list",
            "[new emitter zones](#new-emitter-zones) drawn on the scene; written only when "
            "not empty",
        ),
    ),
)
"""The scene fields, declared once (exactly one of builtin and obj)."""


@dataclass(frozen=True)
class SceneSpec:
    """The scene a project is on: a built-in scene or an OBJ file (exactly one).

    ``resolution`` is the target patch size in metres (None: the scene's default,
    0.25 m for OBJ files). ``materials`` (a reflectance JSON file), ``scale`` (metres
    per model unit), ``up`` ("z" or "y") and ``skip_degenerate`` apply to OBJ files only.
    Relative ``obj``/``materials`` paths are resolved against ``base_dir`` in ``load``.
    ``zones`` are new emitter zones drawn on rectangular surfaces of the scene
    (``ZoneEdit``), applied by ``load`` with ``apply_zone_edits``.
    """

    builtin: str | None = SCENE.field("builtin").default
    obj: str | None = SCENE.field("obj").default
    resolution: float | None = SCENE.field("resolution").default
    materials: str | None = SCENE.field("materials").default
    scale: float = SCENE.field("scale").default
    up: str = SCENE.field("up").default
    skip_degenerate: bool = SCENE.field("skip_degenerate").default
    zones: tuple[ZoneEdit, ...] = SCENE.field("zones").default

    def __post_init__(self) -> None:
        SCENE.check_object(self)
        if (self.builtin is None) == (self.obj is None):
            _fail(
                "",
                'give exactly one of "builtin" (a built-in scene name) '
                'or "obj" (the path of an .obj file)',
            )
        if self.builtin is not None:
            for name, default in (("materials", None), ("scale", 1.0), ("up", "z")):
                if getattr(self, name) != default:
                    _fail(name, "only an OBJ scene takes this; a built-in scene has its own")
            if self.skip_degenerate:
                _fail("skip_degenerate", "only an OBJ scene takes this")

    def load(self, base_dir: Path | None = None) -> Scene:
        """Build the scene (relative paths resolved against ``base_dir``) with the new
        emitter ``zones`` drawn on it."""
        if self.builtin is not None:
            scene = load_scene(self.builtin, self.resolution)
        else:
            scene = load_scene(
                resolve_path(self.obj, base_dir),
                self.resolution,
                materials=resolve_path(self.materials, base_dir),
                scale=self.scale,
                up=self.up,
                skip_degenerate=self.skip_degenerate,
            )
        return apply_zone_edits(scene, self.zones) if self.zones else scene


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
    path: Path | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "solutions", tuple(self.solutions))


# -- JSON field tables ----------------------------------------------------------------------

TOP_FIELDS = (
    "schema",
    "name",
    "description",
    "scene",
    "operator",
    "daylight",
    "penalty_power",
    "sources",
    "target_sources",
    "rules",
    "intentions",
    "goals",
    "optimizer",
    "results",
)
SCENE_FIELDS = tuple(f.name for f in fields(SceneSpec))
OPERATOR_FIELDS = tuple(f.name for f in fields(OperatorSettings))
OPTIMIZER_FIELDS = tuple(f.name for f in fields(OptimizerSettings))
RESULTS_FIELDS = ("solutions", "pareto")
SOLUTION_FIELDS = ("sources", "objectives", "penalty", "violations", "x", "info")
VIOLATION_FIELDS = ("name", "constraint", "amount", "value", "bound", "units")
PARETO_FIELDS = ("objectives", "method", "solutions", "candidates")
