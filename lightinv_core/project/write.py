"""Writing a project: a ``Project`` -> plain JSON data -> pretty JSON text.

``project_dict`` turns a project into plain JSON data by the ``TOP`` spec and the specs
of the objects it holds (fields in their declared order, defaults left out where a spec
says so), then makes it plain (tuples as lists, inf/nan as strings, whole floats as
integers), with scene paths relative to the folder being written to.
``solution_to_dict`` does the same for one solution. ``write_json`` writes such data
atomically, one item per line except for short objects and lists of scalars.
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
from lightinv_core.design.solution import Solution
from lightinv_core.fields import ProjectError, _fail, _is_int, _is_number, _join
from lightinv_core.luminaires.formats import is_photometry_reference
from lightinv_core.project.model import TOP, Project, project_values
from lightinv_core.project.results import SOLUTION, Info

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


def _jsonable(v: Any, path: str, tidy: bool = True) -> Any:
    """Plain JSON data: tuples as lists, inf/nan as strings, numpy scalars as numbers, and
    (when ``tidy``) whole floats as integers, so that 300.0 lux is written 300."""
    if isinstance(v, Info):
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
    d = TOP.write(project_values(p))
    scene = d["scene"]
    for key in ("obj", "materials"):
        if key in scene:
            scene[key] = _relative(scene[key], base_dir)
    for a in d.get("arrays", ()):
        if is_photometry_reference(a["product"]):
            a["product"] = _relative(a["product"], base_dir)
    dl = d.get("daylight", {})
    if dl.get("weather", "builtin") != "builtin":
        dl["weather"] = _relative(dl["weather"], base_dir)
    return _jsonable(d, "")


def solution_to_dict(solution: Solution) -> dict:
    """``solution`` as plain JSON data, as it is written in a project's results (inf/nan
    as strings, tuples as lists). Raises ``ProjectError`` if its info cannot be saved."""
    try:
        return _jsonable(SOLUTION.write(solution), "")
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
