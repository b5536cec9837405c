"""Project files: a design, the scene it is on, run settings and saved results, as JSON.

The format is versioned (``"schema": 1``) and described in docs/project-file.md. Loading
is all or nothing: any problem raises a ``ProjectError`` whose message starts with the
file name and names the JSON path of the offending value, e.g.
``experiment3.json: sources[0].rect: expected 4 numbers, got 3``. Nothing is half-loaded.

What is checked here: the JSON itself, types, unknown or missing fields, value ranges,
the design model's own rules, and references inside the file (rule sources, goals).
Group and zone names are checked against the scene only when the problem is built
(loading a project loads no scene).

Relative scene paths (``obj``, ``materials``) are resolved against the project file's
folder on loading, and written relative to the new file's folder on saving.
"""

from __future__ import annotations

import difflib
import json
import math
import numbers
import os
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, fields, replace
from functools import partial
from pathlib import Path
from typing import Any, NoReturn

import numpy as np

from lightinv_core.design.model import (
    GOALS,
    VARIABLES,
    Daylight,
    Design,
    DesignError,
    Goal,
    Intention,
    Rule,
    Source,
)
from lightinv_core.design.solution import ParetoFront, Solution, Violation
from lightinv_core.errors import LightInvError
from lightinv_core.io.atomic import atomic_writer
from lightinv_core.scene.builtin import BUILTIN_SCENES
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.model import MIN_RESOLUTION, Scene
from lightinv_core.scene.obj_parse import UP_AXES

SCHEMA = 1
METHODS = ("vns", "multilevel", "epsilon", "two_step")
SOURCE_KINDS = ("luminaire", "skylight")
MAX_INT = 2**53  # integers beyond this are not exact in every JSON reader
NONFINITE = {"inf": math.inf, "-inf": -math.inf, "nan": math.nan}
INLINE_WIDTH = 88  # objects and lists of scalars up to this width are written on one line


class ProjectError(LightInvError):
    """A project file or project value is invalid.

    ``detail`` says what is wrong, ``path`` is the JSON path of the value ("" for the
    whole document) and ``file`` the file name when loading or saving a file; the message
    is ``"file: path: detail"`` without the empty parts.
    """

    def __init__(self, detail: str, path: str = "", file: str | None = None):
        self.detail, self.path, self.file = detail, path, file
        super().__init__(": ".join(p for p in (file, path, detail) if p))

    def within(self, prefix: str) -> ProjectError:
        """The same error with ``prefix`` put before its path."""
        return ProjectError(self.detail, _join(prefix, self.path), self.file)


# -- low-level checks ---------------------------------------------------------------------


def _join(prefix: str, sub: str | int) -> str:
    if isinstance(sub, int):
        return f"{prefix}[{sub}]"
    if not prefix:
        return sub
    if not sub:
        return prefix
    return prefix + sub if sub.startswith("[") else f"{prefix}.{sub}"


def _fail(path: str, detail: str) -> NoReturn:
    raise ProjectError(detail, path)


class _within:
    """Context manager: prefix the path of a ProjectError; wrap a DesignError at ``path``."""

    def __init__(self, path: str):
        self.path = path

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind, err, tb) -> bool:
        if isinstance(err, ProjectError):
            raise err.within(self.path) from None
        if isinstance(err, DesignError):
            raise ProjectError(str(err), self.path) from None
        return False


def _fmt(x: float) -> str:
    """A number as the user would write it (2 not 2.0)."""
    if isinstance(x, float) and x.is_integer() and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


def _describe(v: Any) -> str:
    """A JSON value for an error message: its type, and the value when it is short."""
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return f"number {int(v)}" if abs(v) < 10**15 else "a very large number"
    if isinstance(v, numbers.Real):
        return f"number {float(v)!r}"
    if isinstance(v, str):
        return f"string {(v if len(v) <= 40 else v[:37] + '...')!r}"
    if isinstance(v, list | tuple):
        return "an empty list" if not v else f"a list of {len(v)}"
    if isinstance(v, dict):
        return "an object"
    return f"a {type(v).__name__}"


def _is_int(v: Any) -> bool:
    return isinstance(v, numbers.Integral) and not isinstance(v, bool | np.bool_)


def _is_number(v: Any) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, bool | np.bool_)


def _number(
    v: Any,
    path: str,
    lo: float | None = None,
    hi: float | None = None,
    gt: float | None = None,
    lt: float | None = None,
    finite: bool = True,
) -> float:
    """A JSON number as a float. ``finite=False`` also takes inf/nan and their strings."""
    if not finite and isinstance(v, str) and v in NONFINITE:
        return NONFINITE[v]
    cond = " and ".join(
        f"{op} {_fmt(b)}"
        for op, b in ((">=", lo), (">", gt), ("<=", hi), ("<", lt))
        if b is not None
    )
    what = f"a number {cond}" if cond else "a number"
    if not _is_number(v):
        _fail(path, f"expected {what}, got {_describe(v)}")
    try:
        x = float(v)
    except OverflowError:
        _fail(path, f"expected {what}, got a number too large to use")
    if not finite and not math.isfinite(x):
        return x
    if not math.isfinite(x):
        _fail(path, f"expected {'a finite number ' + cond if cond else 'a finite number'}, got {x}")
    if (
        (lo is not None and x < lo)
        or (gt is not None and x <= gt)
        or (hi is not None and x > hi)
        or (lt is not None and x >= lt)
    ):
        _fail(path, f"expected {what}, got {_fmt(x)}")
    return x


def _integer(v: Any, path: str, lo: int | None = None) -> int:
    what = f"an integer >= {lo}" if lo is not None else "an integer"
    if not _is_int(v):
        _fail(path, f"expected {what}, got {_describe(v)}")
    if abs(v) > MAX_INT:
        _fail(path, f"expected {what} of at most 2**53, got a larger one")
    if lo is not None and v < lo:
        _fail(path, f"expected {what}, got {int(v)}")
    return int(v)


def _string(v: Any, path: str, empty: bool = False) -> str:
    if not isinstance(v, str):
        _fail(path, f"expected a string, got {_describe(v)}")
    if not empty and not v.strip():
        _fail(path, "expected a non-empty string")
    return v


def _choice(v: Any, path: str, choices: tuple[str, ...]) -> str:
    listed = ", ".join(repr(c) for c in choices)
    if not isinstance(v, str) or v not in choices:
        _fail(path, f"expected one of {listed}, got {_describe(v)}")
    return v


def _optional(check: Callable[[Any, str], Any]) -> Callable[[Any, str], Any]:
    """``check`` that also takes null (None)."""
    return lambda v, path: None if v is None else check(v, path)


def _list(v: Any, path: str, item: Callable[[Any, str], Any], what: str, min_len: int = 0) -> tuple:
    if not isinstance(v, list | tuple):
        _fail(path, f"expected a list of {what}, got {_describe(v)}")
    if len(v) < min_len:
        _fail(path, f"expected at least {min_len} {what}, got {len(v)}")
    return tuple(item(x, _join(path, i)) for i, x in enumerate(v))


def _numbers(v: Any, path: str, count: int, **limits) -> tuple[float, ...]:
    """Exactly ``count`` numbers."""
    if not isinstance(v, list | tuple):
        _fail(path, f"expected a list of {count} numbers, got {_describe(v)}")
    if len(v) != count:
        _fail(path, f"expected {count} numbers, got {len(v)}")
    return tuple(_number(x, _join(path, i), **limits) for i, x in enumerate(v))


def _unique(items: tuple[str, ...], path: str) -> tuple[str, ...]:
    seen: dict[str, int] = {}
    for i, s in enumerate(items):
        if s in seen:
            _fail(_join(path, i), f"{s!r} is listed twice")
        seen[s] = i
    return items


def _object(v: Any, path: str, known: tuple[str, ...], required: tuple[str, ...] = ()) -> dict:
    """A JSON object with only ``known`` keys and every ``required`` key."""
    if not isinstance(v, dict):
        _fail(path, f"expected an object, got {_describe(v)}")
    for key in getattr(v, "duplicates", ()):
        _fail(path, f"field {key!r} is given twice")
    for key in v:
        if not isinstance(key, str) or key not in known:
            detail = f"unknown field {key!r} (known: {', '.join(known)})"
            close = difflib.get_close_matches(str(key), known, n=1)
            _fail(path, detail + (f"; did you mean {close[0]!r}?" if close else ""))
    for key in required:
        if key not in v:
            _fail(path, f"missing required field {key!r}")
    return v


def _check_fields(obj: Any, checks: dict[str, Callable[[Any, str], Any]]) -> None:
    """Validate and normalise the fields of a frozen dataclass in place."""
    for name, check in checks.items():
        object.__setattr__(obj, name, check(getattr(obj, name), name))


class _JSONObject(dict):
    """A parsed JSON object that remembers keys given more than once."""

    duplicates: tuple[str, ...] = ()


def _pairs_hook(pairs: list[tuple[str, Any]]) -> dict:
    out = _JSONObject(pairs)
    if len(out) != len(pairs):
        seen: set[str] = set()
        out.duplicates = tuple(k for k, _ in pairs if k in seen or seen.add(k))
    return out


# -- settings -------------------------------------------------------------------------------


def _resolve(p: str | None, base_dir: Path | None) -> str | None:
    if p is None:
        return None
    q = Path(p).expanduser()
    if base_dir is not None and not q.is_absolute():
        q = Path(base_dir) / q
    return str(q)


def _obj_path(v: Any, path: str) -> str:
    s = _string(v, path)
    if not s.lower().endswith(".obj"):
        _fail(path, f"expected the path of an .obj file, got {s!r}")
    return s


@dataclass(frozen=True)
class SceneSpec:
    """The scene a project is on: a built-in scene or an OBJ file (exactly one).

    ``resolution`` is the target patch size in metres (None: the scene's default,
    0.25 m for OBJ files). ``materials`` (a reflectance JSON file), ``scale`` (metres
    per model unit), ``up`` ("z" or "y") and ``skip_degenerate`` apply to OBJ files only.
    Relative ``obj``/``materials`` paths are resolved against ``base_dir`` in ``load``.
    """

    builtin: str | None = None
    obj: str | None = None
    resolution: float | None = None
    materials: str | None = None
    scale: float = 1.0
    up: str = "z"
    skip_degenerate: bool = False

    def __post_init__(self) -> None:
        _check_fields(
            self,
            {
                "builtin": _optional(lambda v, p: _choice(v, p, tuple(BUILTIN_SCENES))),
                "obj": _optional(_obj_path),
                "resolution": _optional(lambda v, p: _number(v, p, lo=MIN_RESOLUTION)),
                "materials": _optional(_string),
                "scale": lambda v, p: _number(v, p, gt=0.0),
                "up": lambda v, p: _choice(v, p, UP_AXES),
                "skip_degenerate": _boolean,
            },
        )
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
        """Build the scene (relative paths resolved against ``base_dir``)."""
        if self.builtin is not None:
            return load_scene(self.builtin, self.resolution)
        return load_scene(
            _resolve(self.obj, base_dir),
            self.resolution,
            materials=_resolve(self.materials, base_dir),
            scale=self.scale,
            up=self.up,
            skip_degenerate=self.skip_degenerate,
        )


def _count(v: Any, path: str) -> int:
    return _integer(v, path, lo=1)


def _boolean(v: Any, path: str) -> bool:
    if not isinstance(v, bool | np.bool_):
        _fail(path, f"expected true or false, got {_describe(v)}")
    return bool(v)


@dataclass(frozen=True)
class OperatorSettings:
    """How the radiosity operator is built: relative accuracy ``tol`` (used when ``rank``
    is None), or a fixed ``rank`` (clusters); ``rays`` per patch for the form factors and
    the ray ``seed``."""

    tol: float = 0.01
    rank: int | None = None
    rays: int = 1024
    seed: int = 0

    def __post_init__(self) -> None:
        _check_fields(
            self,
            {
                "tol": lambda v, p: _number(v, p, gt=0.0, lt=1.0),
                "rank": _optional(lambda v, p: _integer(v, p, lo=1)),
                "rays": lambda v, p: _integer(v, p, lo=1),
                "seed": lambda v, p: _integer(v, p, lo=0),
            },
        )


@dataclass(frozen=True)
class OptimizerSettings:
    """How the optimiser runs (see docs/project-file.md for every field).

    ``method``: "vns" (one VNS on all patches), "multilevel" (VNS on ``divisors``
    levels), "epsilon" (epsilon-constraint sweep) or "two_step" (paper 5.5). Stopping:
    ``max_evals``, ``time_limit`` (s), ``target`` (primary goal's units, counts only
    when feasible), ``stall`` (evaluations without improvement); None disables each.
    """

    method: str = "vns"
    seed: int = 0
    max_evals: int | None = 20000
    time_limit: float | None = None
    target: float | None = None
    stall: int | None = None
    trials: int = 32
    divisors: tuple[int, ...] = (64, 16, 1)
    level_max_evals: int | None = None
    level_target: float | None = None
    runs: int = 10
    epsilons: tuple[float, ...] | None = None
    epsilon_count: int = 12

    def __post_init__(self) -> None:
        count, value = _count, _number
        _check_fields(
            self,
            {
                "method": lambda v, p: _choice(v, p, METHODS),
                "seed": lambda v, p: _integer(v, p, lo=0),
                "max_evals": _optional(count),
                "time_limit": _optional(lambda v, p: _number(v, p, gt=0.0)),
                "target": _optional(value),
                "stall": _optional(count),
                "trials": count,
                "divisors": lambda v, p: _list(v, p, count, "divisors (integers >= 1)", 1),
                "level_max_evals": _optional(count),
                "level_target": _optional(value),
                "runs": count,
                "epsilons": _optional(
                    lambda v, p: _list(v, p, lambda x, q: _number(x, q, lo=0.0), "lm values", 1)
                ),
                "epsilon_count": count,
            },
        )


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
DAYLIGHT_FIELDS = ("exterior_lux", "transmittance")
SOURCE_FIELDS = (
    "name",
    "zone",
    "kind",
    "rect",
    "free",
    "flux",
    "exitance",
    "flux_range",
    "efficacy",
    "filter",
)
SOURCE_DEFAULTS = {f.name: f.default for f in fields(Source)}
LUMINAIRE_ONLY = ("flux", "exitance", "flux_range", "efficacy")
RULE_FIELDS = ("kind", "sources", "min", "max", "axis")
RULE_TAKES = {
    "area": ("min", "max"),
    "aspect": ("max",),
    "mirror": ("axis",),
    "centred": (),
    "spacing": ("min",),
    "align": ("axis",),
}
INTENTION_FIELDS = (
    "name",
    "group",
    "patches",
    "quantity",
    "min",
    "max",
    "average",
    "uniformity",
    "weight",
)
GOAL_FIELDS = ("kind", "kinds")
RESULTS_FIELDS = ("solutions", "pareto")
SOLUTION_FIELDS = ("sources", "objectives", "penalty", "violations", "x", "info")
VIOLATION_FIELDS = ("name", "constraint", "amount", "value", "bound", "units")
PARETO_FIELDS = ("objectives", "method", "solutions", "candidates")


def _source(v: Any, path: str) -> Source:
    d = _object(v, path, SOURCE_FIELDS, ("name", "zone", "kind", "rect"))
    at = partial(_join, path)
    kind = _choice(d["kind"], at("kind"), SOURCE_KINDS)
    kw: dict[str, Any] = {
        "name": _string(d["name"], at("name")),
        "zone": _string(d["zone"], at("zone")),
        "kind": kind,
        "rect": _numbers(d["rect"], at("rect"), 4),
    }
    if "free" in d:
        names = _list(d["free"], at("free"), lambda x, p: _choice(x, p, VARIABLES), "variables")
        kw["free"] = _unique(names, at("free"))
    for key in ("flux", "exitance"):
        if d.get(key) is not None:
            kw[key] = _number(d[key], at(key), lo=0.0)
    if "flux_range" in d:
        kw["flux_range"] = _numbers(d["flux_range"], at("flux_range"), 2, lo=0.0)
    if "efficacy" in d:
        kw["efficacy"] = _number(d["efficacy"], at("efficacy"), gt=0.0)
    if "filter" in d:
        kw["filter"] = _number(d["filter"], at("filter"), lo=0.0, hi=1.0)
    if kind == "skylight":
        for key in LUMINAIRE_ONLY:
            if key in kw:
                _fail(
                    at(key),
                    "only luminaires have this; a skylight's exitance is "
                    "filter x transmittance x exterior illuminance",
                )
    elif "filter" in kw:
        _fail(at("filter"), "only skylights have a filter")
    with _within(path):
        return Source(**kw)


def _sources(v: Any, path: str) -> tuple[Source, ...]:
    out = _list(v, path, _source, "sources")
    seen: dict[str, int] = {}
    for i, s in enumerate(out):
        if s.name in seen:
            _fail(
                _join(_join(path, i), "name"),
                f"{s.name!r} is already used by {path}[{seen[s.name]}]",
            )
        seen[s.name] = i
    return out


def _rule(v: Any, path: str, names: tuple[str, ...]) -> Rule:
    d = _object(v, path, RULE_FIELDS, ("kind", "sources"))
    at = partial(_join, path)
    kind = _choice(d["kind"], at("kind"), Rule.KINDS)
    sources = _unique(_list(d["sources"], at("sources"), _string, "source names", 1), at("sources"))
    for i, s in enumerate(sources):
        if s not in names:
            known = ", ".join(names) or "none"
            _fail(_join(at("sources"), i), f"no source {s!r} (sources: {known})")
    takes = RULE_TAKES[kind]
    kw: dict[str, Any] = {}
    for key in ("min", "max", "axis"):
        if d.get(key) is None:
            continue
        if key not in takes:
            also = ", ".join(("sources", *takes))
            _fail(at(key), f"a {kind!r} rule does not take {key!r} (it takes: {also})")
        kw[key] = (
            _choice(d[key], at(key), ("u", "v")) if key == "axis" else _number(d[key], at(key), 0.0)
        )
    with _within(path):
        return Rule(kind, sources, **kw)


def _rules(v: Any, path: str, names: tuple[str, ...]) -> tuple[Rule, ...]:
    rules = _list(v, path, lambda x, p: _rule(x, p, names), "rules")
    mirrored: dict[str, int] = {}
    for i, r in enumerate(rules):
        if r.kind == "mirror":
            derived = r.sources[0]
            if derived in mirrored:
                _fail(
                    _join(_join(path, i), "sources[0]"),
                    f"{derived!r} already mirrors another source ({path}[{mirrored[derived]}])",
                )
            mirrored[derived] = i
    return rules


def _patch_id(v: Any, path: str) -> int:
    return _integer(v, path, lo=0)


def _intention(v: Any, path: str) -> Intention:
    d = _object(v, path, INTENTION_FIELDS, ("name",))
    at = partial(_join, path)
    kw: dict[str, Any] = {"name": _string(d["name"], at("name"))}
    if d.get("group") is not None:
        kw["group"] = _string(d["group"], at("group"))
    if d.get("patches") is not None:
        kw["patches"] = _list(d["patches"], at("patches"), _patch_id, "patch ids", 1)
    if "quantity" in d:
        kw["quantity"] = _choice(d["quantity"], at("quantity"), ("lux", "C"))
    for key in ("min", "max", "average"):
        if d.get(key) is not None:
            kw[key] = _number(d[key], at(key), lo=0.0)
    if d.get("uniformity") is not None:
        kw["uniformity"] = _number(d["uniformity"], at("uniformity"), lo=0.0, hi=1.0)
    if "weight" in d:
        kw["weight"] = _number(d["weight"], at("weight"), lo=0.0)
    with _within(path):
        return Intention(**kw)


def _intentions(v: Any, path: str) -> tuple[Intention, ...]:
    out = _list(v, path, _intention, "intentions")
    seen: dict[str, int] = {}
    for i, it in enumerate(out):
        if it.name in seen:
            where = f"{path}[{seen[it.name]}]"
            _fail(_join(_join(path, i), "name"), f"{it.name!r} is already used by {where}")
        seen[it.name] = i
    return out


def _goal(v: Any, path: str) -> Goal:
    d = _object(v, path, GOAL_FIELDS, ("kind",))
    kind = _choice(d["kind"], _join(path, "kind"), GOALS)
    kinds: tuple[str, ...] = ()
    if "kinds" in d:
        at = _join(path, "kinds")
        kinds = _unique(
            _list(d["kinds"], at, lambda x, p: _choice(x, p, SOURCE_KINDS), "kinds"), at
        )
        if kinds and kind != "max_light_power":
            _fail(at, "only a max_light_power goal takes source kinds")
    with _within(path):
        return Goal(kind, kinds)


def _goals(v: Any, path: str) -> tuple[Goal, ...]:
    goals = _list(v, path, _goal, "goals", 1)
    seen: dict[str, int] = {}
    for i, g in enumerate(goals):
        if g.kind in seen:
            _fail(
                _join(_join(path, i), "kind"),
                f"{g.kind!r} is already a goal ({path}[{seen[g.kind]}])",
            )
        seen[g.kind] = i
    return goals


def _daylight(v: Any, path: str) -> Daylight:
    d = _object(v, path, DAYLIGHT_FIELDS)
    kw = {}
    if "exterior_lux" in d:
        kw["exterior_lux"] = _number(d["exterior_lux"], _join(path, "exterior_lux"), lo=0.0)
    if "transmittance" in d:
        at = _join(path, "transmittance")
        kw["transmittance"] = _number(d["transmittance"], at, lo=0.0, hi=1.0)
    return Daylight(**kw)


def _design(d: dict) -> Design:
    sources = _sources(d["sources"], "sources")
    targets = _sources(d.get("target_sources", []), "target_sources")
    names = tuple(s.name for s in sources)
    rules = _rules(d.get("rules", []), "rules", names)
    intentions = _intentions(d.get("intentions", []), "intentions")
    goals = _goals(d["goals"], "goals")
    for i, g in enumerate(goals):
        if g.kind == "match" and not targets:
            _fail(f"goals[{i}]", "a match goal needs target_sources (the light to reproduce)")
    daylight = _daylight(d["daylight"], "daylight") if "daylight" in d else Daylight()
    power = 2
    if "penalty_power" in d:
        power = _integer(d["penalty_power"], "penalty_power", lo=2)
        if power % 2:
            _fail("penalty_power", f"expected an even integer >= 2, got {power}")
    with _within(""):
        return Design(sources, goals, rules, intentions, targets, daylight, power)


def _settings(cls: type, v: Any, path: str, known: tuple[str, ...]):
    d = _object(v, path, known)
    with _within(path):
        return cls(**d)


# -- results --------------------------------------------------------------------------------


def _result_number(v: Any, path: str) -> float:
    return _number(v, path, finite=False)


def _info_value(v: Any, path: str) -> Any:
    if isinstance(v, str):
        return NONFINITE.get(v, v)
    if v is None or isinstance(v, bool):
        return v
    if _is_int(v):
        return int(v)
    if _is_number(v):
        return float(v)
    if isinstance(v, list | tuple):
        return [_info_value(x, _join(path, i)) for i, x in enumerate(v)]
    if isinstance(v, dict):
        for k in v:
            if not isinstance(k, str):
                _fail(path, f"expected string keys, got {_describe(k)}")
        return {k: _info_value(x, _join(path, k)) for k, x in v.items()}
    _fail(path, f"expected a JSON value, got {_describe(v)}")


def _violation(v: Any, path: str) -> Violation:
    d = _object(v, path, VIOLATION_FIELDS, VIOLATION_FIELDS)
    at = partial(_join, path)
    return Violation(
        _string(d["name"], at("name"), empty=True),
        _string(d["constraint"], at("constraint"), empty=True),
        _result_number(d["amount"], at("amount")),
        _result_number(d["value"], at("value")),
        _result_number(d["bound"], at("bound")),
        _string(d["units"], at("units"), empty=True),
    )


def _solution(v: Any, path: str) -> Solution:
    d = _object(v, path, SOLUTION_FIELDS, ("sources", "objectives", "penalty"))
    at = partial(_join, path)
    sources = _sources(d["sources"], at("sources"))
    obj = d["objectives"]
    if not isinstance(obj, dict):
        _fail(at("objectives"), f"expected an object, got {_describe(obj)}")
    objectives = {}
    for key, value in obj.items():
        if key not in GOALS:
            _fail(at("objectives"), f"unknown goal {key!r} (goals: {', '.join(GOALS)})")
        objectives[key] = _result_number(value, _join(at("objectives"), key))
    info = _info_value(d.get("info", {}), at("info"))
    if not isinstance(info, dict):
        _fail(at("info"), f"expected an object, got {_describe(d['info'])}")
    return Solution(
        sources,
        objectives,
        _result_number(d["penalty"], at("penalty")),
        _list(d.get("violations", []), at("violations"), _violation, "violations"),
        _list(d.get("x", []), at("x"), _result_number, "numbers"),
        info,
    )


def _pareto(v: Any, path: str) -> ParetoFront:
    d = _object(v, path, PARETO_FIELDS, ("objectives", "solutions"))
    at = partial(_join, path)
    objectives = _list(
        d["objectives"], at("objectives"), lambda x, p: _choice(x, p, GOALS), "goal kinds"
    )
    return ParetoFront(
        _unique(objectives, at("objectives")),
        _list(d["solutions"], at("solutions"), _solution, "solutions"),
        _string(d.get("method", ""), at("method"), empty=True),
        _list(d.get("candidates", []), at("candidates"), _solution, "solutions"),
    )


# -- reading --------------------------------------------------------------------------------


def project_from_dict(data: dict, base_dir: Path | None = None) -> Project:
    """The project described by parsed JSON ``data``; raises ``ProjectError`` on any problem.

    With ``base_dir``, relative scene paths are made absolute against it.
    """
    try:
        return _project(data, base_dir)
    except RecursionError:
        raise ProjectError("the document is nested too deeply") from None


def _project(data: Any, base_dir: Path | None) -> Project:
    if not isinstance(data, dict):
        _fail("", f"expected a JSON object at the top level, got {_describe(data)}")
    if "schema" not in data:
        _fail("", "missing required field 'schema' (is this a LightInv project file?)")
    schema = _integer(data["schema"], "schema")
    if schema != SCHEMA:
        _fail(
            "", f"unknown project schema {schema}; this version of LightInv reads schema {SCHEMA}"
        )
    d = _object(data, "", TOP_FIELDS, ("name", "scene", "sources", "goals"))
    name = _string(d["name"], "name")
    description = _string(d.get("description", ""), "description", empty=True)
    scene = _settings(SceneSpec, d["scene"], "scene", SCENE_FIELDS)
    if base_dir is not None and scene.obj is not None:
        scene = replace(
            scene, obj=_resolve(scene.obj, base_dir), materials=_resolve(scene.materials, base_dir)
        )
    operator = _settings(OperatorSettings, d.get("operator", {}), "operator", OPERATOR_FIELDS)
    design = _design(d)
    optimizer = _settings(OptimizerSettings, d.get("optimizer", {}), "optimizer", OPTIMIZER_FIELDS)
    solutions: tuple[Solution, ...] = ()
    pareto = None
    if "results" in d:
        r = _object(d["results"], "results", RESULTS_FIELDS)
        solutions = _list(r.get("solutions", []), "results.solutions", _solution, "solutions")
        if r.get("pareto") is not None:
            pareto = _pareto(r["pareto"], "results.pareto")
    return Project(name, scene, design, operator, optimizer, description, solutions, pareto)


def load_project(path: str | os.PathLike) -> Project:
    """Read the project file at ``path``; raises ``ProjectError`` naming the file and the
    JSON path of any problem. The project's ``path`` is the file's absolute path."""
    path = Path(path)
    label = path.name or str(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise ProjectError(f"no such file ({path})", file=label) from None
    except IsADirectoryError:
        raise ProjectError(f"is a folder, not a project file ({path})", file=label) from None
    except UnicodeDecodeError as e:
        detail = f"not a UTF-8 text file (undecodable byte at offset {e.start})"
        raise ProjectError(detail, file=label) from None
    except OSError as e:
        raise ProjectError(f"cannot read the file: {e.strerror or e}", file=label) from None
    try:
        data = json.loads(text, object_pairs_hook=_pairs_hook)
    except json.JSONDecodeError as e:
        detail = f"invalid JSON at line {e.lineno}, column {e.colno}: {e.msg}"
        raise ProjectError(detail, file=label) from None
    except (ValueError, RecursionError) as e:  # e.g. an integer of thousands of digits
        raise ProjectError(f"invalid JSON: {e}", file=label) from None
    absolute = Path(os.path.abspath(path))
    try:
        project = project_from_dict(data, absolute.parent)
    except ProjectError as e:
        raise ProjectError(e.detail, e.path, label) from None
    return replace(project, path=absolute)


# -- writing --------------------------------------------------------------------------------


def _relative(p: str | None, base_dir: Path | None) -> str | None:
    """``p`` relative to ``base_dir`` (POSIX separators) when both are known and on the
    same drive; otherwise as given."""
    if p is None or base_dir is None or not Path(p).is_absolute():
        return p
    try:
        return Path(os.path.relpath(p, base_dir)).as_posix()
    except ValueError:  # another drive (Windows)
        return p


def _source_dict(s: Source) -> dict:
    d: dict[str, Any] = {"name": s.name, "zone": s.zone, "kind": s.kind, "rect": list(s.rect)}
    if s.free:
        d["free"] = list(s.free)
    luminaire = s.kind == "luminaire"
    used = LUMINAIRE_ONLY if luminaire else ("filter",)  # the other kind's are ignored
    for key in used:
        value = getattr(s, key)
        if value != SOURCE_DEFAULTS[key]:
            d[key] = list(value) if isinstance(value, tuple) else value
    return d


def _rule_dict(r: Rule) -> dict:
    d: dict[str, Any] = {"kind": r.kind, "sources": list(r.sources)}
    for key in RULE_TAKES.get(r.kind, ()):
        if getattr(r, key) is not None:
            d[key] = getattr(r, key)
    return d


def _intention_dict(it: Intention) -> dict:
    d: dict[str, Any] = {"name": it.name}
    if it.group is not None:
        d["group"] = it.group
    if it.patches is not None:
        d["patches"] = list(it.patches)
    d["quantity"] = it.quantity
    for key in ("min", "max", "average", "uniformity"):
        if getattr(it, key) is not None:
            d[key] = getattr(it, key)
    d["weight"] = it.weight
    return d


def _goal_dict(g: Goal) -> dict:
    return {"kind": g.kind, "kinds": list(g.kinds)} if g.kinds else {"kind": g.kind}


def _solution_dict(s: Solution) -> dict:
    return {
        "sources": [_source_dict(x) for x in s.sources],
        "objectives": dict(s.objectives),
        "penalty": s.penalty,
        "violations": [
            {
                "name": v.name,
                "constraint": v.constraint,
                "amount": v.amount,
                "value": v.value,
                "bound": v.bound,
                "units": v.units,
            }
            for v in s.violations
        ],
        "x": list(s.x),
        "info": _Info(s.info),
    }


def _scene_dict(s: SceneSpec, base_dir: Path | None) -> dict:
    if s.builtin is not None:
        return {"builtin": s.builtin, "resolution": s.resolution}
    d: dict[str, Any] = {"obj": _relative(s.obj, base_dir), "resolution": s.resolution}
    if s.materials is not None:
        d["materials"] = _relative(s.materials, base_dir)
    d.update(scale=s.scale, up=s.up)
    if s.skip_degenerate:
        d["skip_degenerate"] = True
    return d


class _Info(dict):
    """A solution's free-form info: its numbers are written exactly as they are."""


def _jsonable(v: Any, path: str, tidy: bool = True) -> Any:
    """Plain JSON data: tuples as lists, inf/nan as strings, numpy scalars as numbers, and
    (when ``tidy``) whole floats as integers, so that 300.0 lux is written 300."""
    if isinstance(v, _Info):
        tidy = False
    if isinstance(v, np.generic | np.ndarray):
        v = v.tolist()
    if v is None or isinstance(v, bool | str):
        return v
    if _is_int(v):
        return int(v)
    if _is_number(v):
        x = float(v)
        if not math.isfinite(x):
            return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")
        return int(x) if tidy and x.is_integer() and abs(x) < 1e15 else x
    if isinstance(v, list | tuple):
        return [_jsonable(x, _join(path, i), tidy) for i, x in enumerate(v)]
    if isinstance(v, dict):
        out = {}
        for k, x in v.items():
            if not isinstance(k, str):
                _fail(path, f"cannot save the non-string key {k!r}")
            out[k] = _jsonable(x, _join(path, k), tidy)
        return out
    _fail(path, f"cannot save a value of type {type(v).__name__}")


def _to_dict(p: Project, base_dir: Path | None) -> dict:
    design = p.design
    d: dict[str, Any] = {
        "schema": SCHEMA,
        "name": p.name,
        "description": p.description,
        "scene": _scene_dict(p.scene, base_dir),
        "operator": {f: getattr(p.operator, f) for f in OPERATOR_FIELDS},
        "daylight": {
            "exterior_lux": design.daylight.exterior_lux,
            "transmittance": design.daylight.transmittance,
        },
        "penalty_power": design.penalty_power,
        "sources": [_source_dict(s) for s in design.sources],
        "target_sources": [_source_dict(s) for s in design.target_sources],
        "rules": [_rule_dict(r) for r in design.rules],
        "intentions": [_intention_dict(i) for i in design.intentions],
        "goals": [_goal_dict(g) for g in design.goals],
        "optimizer": {f: getattr(p.optimizer, f) for f in OPTIMIZER_FIELDS},
    }
    if p.solutions or p.pareto is not None:
        front = p.pareto
        d["results"] = {
            "solutions": [_solution_dict(s) for s in p.solutions],
            "pareto": None
            if front is None
            else {
                "objectives": list(front.objectives),
                "method": front.method,
                "solutions": [_solution_dict(s) for s in front.solutions],
                "candidates": [_solution_dict(s) for s in front.candidates],
            },
        }
    return _jsonable(d, "")


def project_to_dict(project: Project) -> dict:
    """The project as plain JSON data (scene paths as stored in ``project.scene``)."""
    try:
        return _to_dict(project, None)
    except RecursionError:
        raise ProjectError("a solution's info is nested too deeply") from None


def _iter_json(v: Any, indent: int = 0) -> Iterator[str]:
    """Pretty JSON text in pieces: objects and lists that hold only scalars (or short lists
    of scalars) go on one line when it fits, everything else one item per line."""
    if not isinstance(v, dict | list) or not v:
        yield json.dumps(v, ensure_ascii=False, allow_nan=False)
        return
    flat = all(
        not isinstance(x, dict | list)
        or (isinstance(x, list) and not any(isinstance(y, dict | list) for y in x))
        for x in (v.values() if isinstance(v, dict) else v)
    )
    if flat:
        line = json.dumps(v, ensure_ascii=False, allow_nan=False)
        if indent + len(line) <= INLINE_WIDTH:
            yield line
            return
    pad, inner = " " * indent, " " * (indent + 2)
    items = v.items() if isinstance(v, dict) else ((None, x) for x in v)
    yield "{\n" if isinstance(v, dict) else "[\n"
    for i, (key, x) in enumerate(items):
        yield ",\n" if i else ""
        yield inner if key is None else f"{inner}{json.dumps(key, ensure_ascii=False)}: "
        yield from _iter_json(x, indent + 2)
    yield f"\n{pad}" + ("}" if isinstance(v, dict) else "]")


def save_project(project: Project, path: str | os.PathLike) -> None:
    """Write ``project`` to ``path`` atomically as pretty JSON (UTF-8, trailing newline).

    Scene paths are written relative to the file's folder. The data is checked by reading
    it back first: a project that would not load is not saved (``ProjectError``), and on
    any failure the previous file at ``path`` is left untouched.
    """
    path = Path(path)
    label = path.name or str(path)
    base = Path(os.path.abspath(path)).parent
    try:
        data = _to_dict(project, base)
        project_from_dict(data, base)
    except ProjectError as e:
        raise ProjectError(f"cannot save: {e.detail}", e.path, label) from None
    except RecursionError:
        raise ProjectError("cannot save: a value is nested too deeply", file=label) from None
    with atomic_writer(path, "w", encoding="utf-8", newline="\n") as fh:
        for piece in _iter_json(data):
            fh.write(piece)
        fh.write("\n")
