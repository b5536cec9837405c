"""Writing a project: a ``Project`` -> plain JSON data -> pretty JSON text.

``project_dict`` turns a project into plain JSON data (tuples as lists, inf/nan as
strings, whole floats as integers, defaults left out where the format allows), with
scene paths relative to the folder being written to. ``solution_to_dict`` does the same
for one solution. ``write_json`` writes such data atomically, one item per line except
for short objects and lists of scalars.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from lightinv_core.atomic import atomic_writer
from lightinv_core.design.model import Goal, Intention, Rule, Source
from lightinv_core.design.solution import Solution
from lightinv_core.fields import ProjectError, _fail, _is_int, _is_number, _join
from lightinv_core.project.model import (
    OPERATOR_FIELDS,
    OPTIMIZER_FIELDS,
    SCHEMA,
    Project,
    SceneSpec,
)
from lightinv_core.project.specs import DAYLIGHT, GOAL, INTENTION, RULE, SOURCE

INLINE_WIDTH = 88  # objects and lists of scalars up to this width are written on one line


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
    return SOURCE.write(s)


def _rule_dict(r: Rule) -> dict:
    return RULE.write(r)


def _intention_dict(it: Intention) -> dict:
    return INTENTION.write(it)


def _goal_dict(g: Goal) -> dict:
    return GOAL.write(g)


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
        "info": _Info(s.info.to_dict()),
    }


def _scene_dict(s: SceneSpec, base_dir: Path | None) -> dict:
    if s.builtin is not None:
        d: dict[str, Any] = {"builtin": s.builtin, "resolution": s.resolution}
    else:
        d = {"obj": _relative(s.obj, base_dir), "resolution": s.resolution}
        if s.materials is not None:
            d["materials"] = _relative(s.materials, base_dir)
        d.update(scale=s.scale, up=s.up)
        if s.skip_degenerate:
            d["skip_degenerate"] = True
    if s.zones:
        d["zones"] = [
            {"name": z.name, "kind": z.kind, "surface": z.surface, "rect": list(z.rect)}
            for z in s.zones
        ]
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


def project_dict(p: Project, base_dir: Path | None) -> dict:
    """``p`` as plain JSON data, scene paths relative to ``base_dir`` when it is given."""
    design = p.design
    d: dict[str, Any] = {
        "schema": SCHEMA,
        "name": p.name,
        "description": p.description,
        "scene": _scene_dict(p.scene, base_dir),
        "operator": {f: getattr(p.operator, f) for f in OPERATOR_FIELDS},
        "daylight": DAYLIGHT.write(design.daylight),
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


def solution_to_dict(solution: Solution) -> dict:
    """``solution`` as plain JSON data, as it is written in a project's results (inf/nan
    as strings, tuples as lists). Raises ``ProjectError`` if its info cannot be saved."""
    try:
        return _jsonable(_solution_dict(solution), "")
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


def write_json(data: Any, path: str | os.PathLike) -> None:
    """Write plain JSON ``data`` to ``path`` atomically as pretty JSON (UTF-8, trailing
    newline); on any failure the previous file at ``path`` is left untouched."""
    with atomic_writer(path, "w", encoding="utf-8", newline="\n") as fh:
        for piece in _iter_json(data):
            fh.write(piece)
        fh.write("\n")
