"""The JSON Schema (draft 2020-12) of a file, derived from its ``ObjectSpec``s.

Each object becomes ``{"type": "object", "properties": ..., "required": ...,
"additionalProperties": false}`` under ``$defs`` (the top level inline), each property
from its ``Field`` (``Field.json_schema``), and a field only some kinds take becomes an
``if``/``then`` rule per kind, so an editor completes and checks a file as the reader
does. What the schema cannot say (names unique across a list, a rule naming sources that
exist, min <= max) stays with the reader and the model classes.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from lightinv_core.fields.spec import ObjectSpec, _plain

DRAFT = "https://json-schema.org/draft/2020-12/schema"


def object_schema(spec: ObjectSpec) -> dict[str, Any]:
    """The JSON Schema of one kind of object."""
    out: dict[str, Any] = {
        "type": "object",
        "properties": {f.name: f.json_schema() for f in spec.fields},
        "additionalProperties": False,
    }
    required = [f.name for f in spec.fields if f.required]
    if required:
        out["required"] = required
    rules = _kind_rules(spec)
    if rules:
        out["allOf"] = rules
    return out


def _kind_rules(spec: ObjectSpec) -> list[dict]:
    """For each kind, the fields it does not take: absent, null where a null means "not
    given", or at their default where any kind may write it."""
    if spec.kind_field not in spec.names:
        return []
    kind = spec.field(spec.kind_field)
    values = getattr(kind.check, "values", None)
    if values is None:
        return []
    rules = []
    for k in (str(v) for v in values()):
        others = {}
        for f in spec.fields:
            takers = spec.kinds_of(f)
            if not takers or k in takers:
                continue
            if spec.default_anywhere:
                others[f.name] = {"const": _plain(f.default)}
            else:
                others[f.name] = {"type": "null"} if f.nullable else False
        if others:
            rules.append(
                {
                    "if": {"properties": {spec.kind_field: {"const": k}}},
                    "then": {"properties": others},
                }
            )
    return rules


def json_schema(top: ObjectSpec, specs: Iterable[ObjectSpec], **about: str) -> dict[str, Any]:
    """The schema of a document whose top level is ``top`` and whose other objects are
    ``specs`` (``about``: ``title``, ``$id``, ``description``)."""
    out: dict[str, Any] = {"$schema": DRAFT, **about, **object_schema(top)}
    out["$defs"] = {s.name: object_schema(s) for s in specs if s is not top}
    return out
