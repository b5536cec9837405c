"""Project-file fields declared once: the checks, the ``ProjectError`` they raise, field
specs and what is derived from them (reading, writing, docs tables, JSON Schema).

- ``checks``: ``ProjectError`` and the low-level checks that word every message;
- ``types``: typed checks (``Number``, ``Integer``, ``Choice``, ...), each with the docs'
  type text and its JSON Schema;
- ``spec``: ``Field``, ``ObjectSpec`` and ``declare`` (a dataclass field's declaration);
- ``schema``: the JSON Schema of a file from its specs.

The model classes declare their fields where they are defined (``design/model/``,
``project/scene.py``, ...); docs/project-file.md says why dataclass fields with metadata
rather than pydantic models.
"""

from lightinv_core.fields.checks import (
    MAX_INT,
    NONFINITE,
    ProjectError,
    _boolean,
    _choice,
    _count,
    _describe,
    _fail,
    _fmt,
    _integer,
    _is_int,
    _is_number,
    _join,
    _list,
    _number,
    _numbers,
    _object,
    _optional,
    _path_string,
    _string,
    _unique,
    _within,
)
from lightinv_core.fields.schema import json_schema, object_schema
from lightinv_core.fields.spec import REQUIRED, Field, ObjectSpec, declare
from lightinv_core.fields.types import (
    Boolean,
    Check,
    Choice,
    Custom,
    Integer,
    ListOf,
    Nullable,
    Number,
    Numbers,
    String,
    choice_of,
    whole_pair,
)

__all__ = [
    "MAX_INT",
    "NONFINITE",
    "REQUIRED",
    "Boolean",
    "Check",
    "Choice",
    "Custom",
    "Field",
    "Integer",
    "ListOf",
    "Nullable",
    "Number",
    "Numbers",
    "ObjectSpec",
    "ProjectError",
    "String",
    "_boolean",
    "_choice",
    "_count",
    "_describe",
    "_fail",
    "_fmt",
    "_integer",
    "_is_int",
    "_is_number",
    "_join",
    "_list",
    "_number",
    "_numbers",
    "_object",
    "_optional",
    "_path_string",
    "_string",
    "_unique",
    "_within",
    "choice_of",
    "declare",
    "json_schema",
    "object_schema",
    "whole_pair",
]
