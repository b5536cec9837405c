"""The scene a project is on, and the fields of its JSON form, declared once.

``SceneSpec`` names a built-in scene or a model file (OBJ, glTF/GLB, PLY or IFC, with its
import options) and the new emitter zones drawn on it; ``SCENE`` and ``ZONE`` declare the
fields of the ``scene`` object and of each of its ``zones``, from which the project
file's reading, messages, writing and docs tables come.
"""

from __future__ import annotations

import os
import threading
from collections import OrderedDict
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from lightinv_core.errors import SceneError
from lightinv_core.fields import (
    Boolean,
    Choice,
    Custom,
    Field,
    Nullable,
    Number,
    Numbers,
    ObjectSpec,
    String,
    _describe,
    _fail,
    _join,
    _list,
    _number,
    _numbers,
    _path_string,
    _unique,
    choice_of,
    declare,
)
from lightinv_core.kinds import source_kind_names
from lightinv_core.scene.builtin import BUILTIN_SCENES
from lightinv_core.scene.edits import ZoneEdit, apply_zone_edits
from lightinv_core.scene.importers.faces import UP_AXES
from lightinv_core.scene.importers.registry import default_up, importer_for, model_suffixes
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.model import MIN_RESOLUTION, Scene

GROUP_BY = ("node", "material")
"""What names a glTF model's lighting groups (``importers.gltf.GROUP_BY``)."""


def resolve_path(p: str | None, base_dir: Path | None) -> str | None:
    """``p`` made absolute against ``base_dir`` when it is relative (None stays None),
    without "..": a file saved as "../models/room.obj" reads back as the path it was
    saved from, not "/projects/../models/room.obj" (shown to the user as is)."""
    if p is None:
        return None
    q = Path(p).expanduser()
    if base_dir is not None and not q.is_absolute():
        q = Path(os.path.normpath(Path(base_dir) / q))
    return str(q)


def _obj_path(v: Any, path: str) -> str:
    s = _path_string(v, path)
    suffixes = model_suffixes()
    if not s.lower().endswith(suffixes):
        kinds = ", ".join(suffixes[:-1]) + " or " + suffixes[-1]
        _fail(path, f"expected the path of a model file ({kinds}), got {s!r}")
    return s


MODEL_CACHE_SIZE = 4
"""Imported model files kept (``model_scene``): a zone drawn or a reflectance changed on
an imported building re-meshes its scene, and re-importing an IFC house took 9 s."""
_models: OrderedDict[tuple, Scene] = OrderedDict()
_models_lock = threading.Lock()


def _stamp(path: str | None) -> tuple | None:
    """What tells a file's versions apart: its modification time and size."""
    if path is None:
        return None
    try:
        st = os.stat(path)
    except OSError:
        return None
    return (st.st_mtime_ns, st.st_size)


def _companions(path: str) -> tuple:
    """Stamps of the files a model may read beside it: an OBJ's ``.mtl`` libraries, a
    glTF's ``.bin`` buffers (``COMPANION_SUFFIXES``, in the model's folder)."""
    folder = Path(path).parent
    try:
        names = sorted(
            e.name
            for e in os.scandir(folder)
            if e.is_file() and Path(e.name).suffix.lower() in COMPANION_SUFFIXES
        )
    except OSError:
        return ()
    return tuple((n, _stamp(str(folder / n))) for n in names)


COMPANION_SUFFIXES = (".mtl", ".bin")


def model_scene(path: str, resolution: float | None, **options) -> Scene:
    """``load_scene`` of a model file, kept for reuse while the file, the files beside
    it that it may read (``_companions``) and its materials file are unchanged: scenes
    are immutable, so the same one serves every load."""
    materials = options.get("materials")
    stamps = (_stamp(path), _stamp(materials), _companions(path))
    key = (str(path), resolution, *sorted((k, str(v)) for k, v in options.items()), stamps)
    if stamps[0] is None or (materials is not None and stamps[1] is None):
        return load_scene(path, resolution, **options)  # its error says what is missing
    with _models_lock:
        if key in _models:
            _models.move_to_end(key)
            return _models[key]
    scene = load_scene(path, resolution, **options)
    with _models_lock:
        _models[key] = scene
        while len(_models) > MODEL_CACHE_SIZE:
            _models.popitem(last=False)
    return scene


def _outline(v: Any, path: str) -> tuple[tuple[float, float], ...]:
    """A polygon's corners: a list of [u, v] pairs (m)."""
    if not isinstance(v, list | tuple) or len(v) < 3:
        _fail(path, f"expected a list of at least 3 [u, v] corners, got {_describe(v)}")
    return tuple(tuple(_numbers(p, _join(path, i), 2)) for i, p in enumerate(v))


ZONE = ObjectSpec(
    "zone",
    (
        Field(
            "name",
            String(),
            meaning="the zone's name (sources refer to it with `zone`); also the name of its "
            "new surface",
        ),
        Field(
            "kind",
            Choice(source_kind_names),
            meaning="what may be placed in it",
        ),
        Field("surface", String(), meaning="the rectangular surface it is drawn on"),
        Field(
            "rect",
            Numbers(4),
            default=None,
            doc_default="the outline's bounds",
            meaning="(u0, v0, u1, v1) in metres along the surface's own u and v edges from its "
            "origin; two opposite corners in any order (stored smallest first); needed "
            "unless `outline` is given",
            always=True,
        ),
        Field(
            "outline",
            Custom(
                _outline,
                "list of [u, v]",
                {"type": "array", "items": Numbers(2).schema(), "minItems": 3},
            ),
            default=None,
            meaning="a zone of any shape: its polygon's corners (at least 3, in order around "
            "it, not crossing itself) in the same metres; sources must lie inside it. Its "
            "bounding rectangle becomes the zone's surface and must lie on the surface",
            optional=True,
        ),
    ),
)
"""A new emitter zone drawn on the scene (a ``ZoneEdit``)."""


def _zone_edit(v: Any, path: str) -> ZoneEdit:
    """A ``ZoneEdit`` from a JSON object (or a ``ZoneEdit`` given in code)."""
    if isinstance(v, ZoneEdit):
        return v
    values = ZONE.read(v, path)
    try:
        return ZoneEdit(**values)
    except SceneError as err:
        _fail(_join(path, "outline" if "outline" in values else "rect"), str(err))


def _zone_edits(v: Any, path: str) -> tuple[ZoneEdit, ...]:
    zones = _list(v, path, _zone_edit, "zone objects")
    _unique(tuple(z.name for z in zones), path)
    return zones


def _reflectances(v: Any, path: str) -> tuple[tuple[str, float], ...]:
    """{group: reflectance} as sorted (group, reflectance) pairs (pairs pass as they are:
    the default, and a SceneSpec made in code)."""
    if isinstance(v, tuple):
        v = dict(v) if all(isinstance(p, tuple) and len(p) == 2 for p in v) else v
    if not isinstance(v, dict):
        _fail(path, 'expected an object of reflectances by group, e.g. {"floor": 0.3}')
    return tuple((k, _number(x, _join(path, k), lo=0.0, lt=1.0)) for k, x in sorted(v.items()))


def with_reflectances(scene: Scene, reflectances) -> Scene:
    """``scene`` with the surfaces of each named group given that reflectance; a
    SceneError names a group the scene does not have."""
    wanted = dict(reflectances)
    unknown = sorted(set(wanted) - set(scene.groups))
    if unknown:
        raise SceneError(
            f"scene {scene.name!r} has no group {unknown[0]!r} to give a reflectance "
            f"(groups: {', '.join(scene.groups)})"
        )
    surfaces = tuple(
        replace(s, reflectance=wanted[s.group]) if s.group in wanted else s for s in scene.surfaces
    )
    return replace(scene, surfaces=surfaces)


def _scene_not_taken(kind: str, field: str) -> str:
    # Materials, scale and up are properties a built-in scene already has; skipping
    # degenerate faces and naming groups are import options with nothing to apply to.
    own = "" if field in ("skip_degenerate", "group_by") else "; a built-in scene has its own"
    return "only an OBJ scene takes this" + own


OBJ = ("obj",)


@dataclass(frozen=True)
class SceneSpec:
    """The scene a project is on: a built-in scene or a model file (exactly one).

    ``obj`` is the path of the model file: OBJ, glTF/GLB, PLY or IFC (the field keeps
    its first name). ``resolution`` is the target patch size in metres (None: the
    scene's default, 0.25 m for model files). ``materials`` (a reflectance JSON file),
    ``scale`` (metres per model unit), ``up`` ("z" or "y"; None on input: the format's,
    "y" for glTF) and ``skip_degenerate`` apply to model files only, ``group_by``
    ("node" or "material") to glTF files only. Relative ``obj``/``materials`` paths are
    resolved against ``base_dir`` in ``load``.
    ``reflectances`` are (group, reflectance) pairs replacing the scene's own (the
    window's materials panel). ``zones`` are new emitter zones drawn on rectangular
    surfaces of the scene (``ZoneEdit``), applied by ``load`` with ``apply_zone_edits``.
    """

    builtin: str | None = field(
        default=None,
        metadata=declare(
            Nullable(choice_of(*BUILTIN_SCENES)),
            "a built-in scene: " + ", ".join(f"`{n}`" for n in BUILTIN_SCENES),
            type="string",
        ),
    )
    obj: str | None = field(
        default=None,
        metadata=declare(
            Nullable(Custom(_obj_path, "string", {"type": "string"})),
            "path of a room model: Wavefront `.obj`, glTF `.gltf`/`.glb`, `.ply` or IFC "
            "`.ifc` (see [obj-import.md](obj-import.md); the field keeps its name for every "
            "format)",
            type="string",
        ),
    )
    resolution: float | None = field(
        default=None,
        metadata=declare(
            Nullable(Number(lo=MIN_RESOLUTION)),
            "target patch size in metres; null: the scene's default (0.25 m for model files)",
            always=True,
        ),
    )
    materials: str | None = field(
        default=None,
        metadata=declare(
            Nullable(Custom(_path_string, "string", {"type": "string"})),
            "path of the reflectance JSON file",
            type="string",
            kinds=OBJ,
        ),
    )
    scale: float = field(
        default=1.0,
        metadata=declare(
            Number(gt=0.0), "metres per model unit (0.001 for millimetres)", kinds=OBJ, always=True
        ),
    )
    up: str | None = field(
        default=None,
        metadata=declare(
            Nullable(choice_of(*UP_AXES)),
            'the model\'s up axis; none: its format\'s (`"y"` for glTF, `"z"` for OBJ, PLY '
            "and IFC), written as the axis taken",
            kinds=OBJ,
            always=True,
        ),
    )
    skip_degenerate: bool = field(
        default=False,
        metadata=declare(
            Boolean(),
            "drop degenerate faces (with a warning) instead of failing",
            type="boolean",
            kinds=OBJ,
        ),
    )
    group_by: str = field(
        default="node",
        metadata=declare(
            choice_of(*GROUP_BY),
            "glTF files: what names the lighting groups, the nodes' names or the materials'",
            kinds=OBJ,
        ),
    )
    reflectances: tuple[tuple[str, float], ...] = field(
        default=(),
        metadata=declare(
            Custom(
                _reflectances,
                schema_={"type": "object", "additionalProperties": Number(lo=0.0, lt=1.0).schema()},
            ),
            "reflectance (0 to below 1) by lighting group, replacing the scene's own "
            '(`{"floor": 0.3}`); written only when not empty',
            type="object",
            encode=dict,
        ),
    )
    zones: tuple[ZoneEdit, ...] = field(
        default=(),
        metadata=declare(
            _zone_edits,
            "[new emitter zones](#new-emitter-zones) drawn on the scene; written only when "
            "not empty",
            type="list",
            of=ZONE,
            many=True,
        ),
    )

    def __post_init__(self) -> None:
        SCENE.check_object(self)
        if (self.builtin is None) == (self.obj is None):
            _fail(
                "",
                'give exactly one of "builtin" (a built-in scene name) '
                'or "obj" (the path of a model file)',
            )
        SCENE.check_kinds(self)
        if self.obj is not None and self.up is None:
            object.__setattr__(self, "up", default_up(self.obj))
        importer = importer_for(self.obj) if self.obj is not None else None
        if self.group_by != "node" and (importer is None or "group_by" not in importer.options):
            _fail("group_by", "only a glTF scene (.gltf or .glb) takes this")

    @property
    def kind(self) -> str:
        """``"builtin"`` or ``"obj"``: the field that names the scene."""
        return "builtin" if self.builtin is not None else "obj"

    def load(self, base_dir: Path | None = None) -> Scene:
        """Build the scene (relative paths resolved against ``base_dir``) with the new
        emitter ``zones`` drawn on it."""
        if self.builtin is not None:
            scene = load_scene(self.builtin, self.resolution)
        else:
            scene = model_scene(
                resolve_path(self.obj, base_dir),
                self.resolution,
                materials=resolve_path(self.materials, base_dir),
                scale=self.scale,
                up=self.up,
                skip_degenerate=self.skip_degenerate,
                group_by=self.group_by,
            )
        if self.reflectances:
            scene = with_reflectances(scene, self.reflectances)
        return apply_zone_edits(scene, self.zones) if self.zones else scene


SCENE = ObjectSpec.of(
    SceneSpec,
    "scene",
    kind_field="kind",
    not_taken=_scene_not_taken,
    default_anywhere=True,
    kinds_doc="model files only",
)
"""The scene fields, declared in ``SceneSpec`` (exactly one of builtin and obj; the kind
of a scene is the one given)."""
