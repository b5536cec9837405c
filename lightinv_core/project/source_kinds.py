"""What each kind of source takes, asked of its source type (``sources.types``).

A source's fields that belong to one kind only are the type's ``fields`` (a luminaire's
flux and efficacy, a skylight's filter); the others every kind takes. A kind takes a
``free`` variable named after a field only if it takes that field, and of its own fields
that may be null (a luminaire's flux and exitance) it needs exactly one. The project
reader and ``Project`` ask here; no code branches on a kind.
"""

from __future__ import annotations

from lightinv_core.design.model import SOURCE_FIELDS, Design, Source
from lightinv_core.errors import DesignError
from lightinv_core.sources.types import source_type, source_types


def kind_fields(kind: str) -> tuple[str, ...]:
    """The source fields of kind ``kind`` alone (its source type's ``fields``)."""
    return tuple(source_type(kind).fields)


def _own_fields() -> set[str]:
    """The fields some kind owns: every registered type's ``fields``."""
    return {f for t in source_types() for f in t.fields}


def _takers(field: str) -> list[str]:
    return [str(t.kind) for t in source_types() if field in t.fields]


def source_not_taken(kind: str, field: str) -> str:
    """The message for a field source ``kind`` does not take."""
    takers = " or ".join(f"{k}s" for k in _takers(field))
    own = ", ".join(kind_fields(kind)) or "none"
    return f"only {takers} have this (a {kind}'s own fields: {own})"


def source_kind_problem(s: Source) -> tuple[str, str] | None:
    """What is wrong with ``s`` for its kind: (the field, or "" for the source, and the
    message), or None. Checks another kind's fields left at their defaults, the free
    variables its kind takes, and exactly one of its kind's fields that may be null."""
    own, mine = _own_fields(), set(kind_fields(s.kind))
    for f in SOURCE_FIELDS.fields:
        value = getattr(s, f.name)
        if f.name in own - mine and value is not None and value != f.default:
            return f.name, source_not_taken(s.kind, f.name)
    for v in s.free:
        if v in own - mine:
            return "free", f"a {s.kind} has no {v} variable (only {' or '.join(_takers(v))}s)"
    either = [f.name for f in SOURCE_FIELDS.fields if f.nullable and f.name in mine]
    given = [n for n in either if getattr(s, n) is not None]
    if len(either) > 1 and len(given) != 1:
        return "", f"a {s.kind} needs either {' or '.join(either)} (give one)"
    return None


def check_source_kinds(design: Design) -> None:
    """Fail (``DesignError``) on a source of ``design`` that its kind does not allow."""
    for s in design.sources + design.target_sources:
        problem = source_kind_problem(s)
        if problem is not None:
            field, detail = problem
            where = f"source {s.name!r}" + (f": {field}" if field else "")
            raise DesignError(f"{where}: {detail}")
