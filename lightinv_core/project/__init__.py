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

This module is the public API. Each field of every JSON object is declared once
(``lightinv_core.fields``): the design's objects in their dataclasses in
``design/model/`` and the scene in ``SceneSpec`` (field metadata, read back by
``ObjectSpec.of``; ``specs`` adds which source kinds take which fields, from the source
types), the top level in ``model``, saved results in ``results``, the run settings beside
their classes (``operator/settings.py``, ``optimize/settings.py``). ``read`` (JSON data
-> ``Project``) and ``write`` (``Project`` -> JSON data -> file) are driven by those
specs, and so are the field tables of docs/project-file.md and its JSON Schema
(``schema``: docs/project.schema.json).
"""

from __future__ import annotations

import json
import os
from dataclasses import replace
from pathlib import Path

from lightinv_core.fields import ProjectError
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.project.model import SCHEMA, Project
from lightinv_core.project.read import object_pairs_hook, read_project
from lightinv_core.project.scene import SceneSpec
from lightinv_core.project.write import project_dict, solution_to_dict, write_json

__all__ = [
    "SCHEMA",
    "OperatorSettings",
    "OptimizerSettings",
    "Project",
    "ProjectError",
    "SceneSpec",
    "load_project",
    "project_from_dict",
    "project_to_dict",
    "save_project",
    "solution_to_dict",
]


def project_from_dict(data: dict, base_dir: Path | None = None) -> Project:
    """The project described by parsed JSON ``data``; raises ``ProjectError`` on any problem.

    With ``base_dir``, relative scene paths are made absolute against it.
    """
    try:
        return read_project(data, base_dir)
    except RecursionError:
        raise ProjectError("the document is nested too deeply") from None


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
        data = json.loads(text, object_pairs_hook=object_pairs_hook)
    except json.JSONDecodeError as e:
        detail = f"invalid JSON at line {e.lineno}, column {e.colno}: {e.msg}"
        raise ProjectError(detail, file=label) from None
    except RecursionError:
        raise ProjectError("invalid JSON: nested too deeply", file=label) from None
    except ValueError as e:  # an integer of thousands of digits
        detail = "a number has too many digits" if "digits" in str(e) else str(e)
        raise ProjectError(f"invalid JSON: {detail}", file=label) from None
    absolute = Path(os.path.abspath(path))
    try:
        project = project_from_dict(data, absolute.parent)
    except ProjectError as e:
        raise ProjectError(e.detail, e.path, label) from None
    return replace(project, path=absolute)


def project_to_dict(project: Project) -> dict:
    """The project as plain JSON data (scene paths as stored in ``project.scene``)."""
    try:
        return project_dict(project, None)
    except RecursionError:
        raise ProjectError("a solution's info is nested too deeply") from None


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
        data = project_dict(project, base)
        project_from_dict(data, base)
    except ProjectError as e:
        raise ProjectError(f"{e.detail} (the project was not saved)", e.path, label) from None
    except RecursionError:
        detail = "a value is nested too deeply (the project was not saved)"
        raise ProjectError(detail, file=label) from None
    write_json(data, path)
