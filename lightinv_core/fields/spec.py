"""Field specs: each field of a JSON object declared once, and what is derived from them.

A ``Field`` holds a field's check (``fields.types``: the check, the docs' type and the
JSON Schema in one), its default, the kinds of object that take it, how it is written
and its docs. The model classes declare their fields in the dataclass itself:
``height: float = field(default=0.8, metadata=declare(Number(lo=0.0), "m"))``;
``ObjectSpec.of(cls)`` reads them back in order, and ``check_fields`` runs the same
checks when a model object is built in code. Reading a JSON object (``read``,
``build``), the messages, writing (``write``), the field tables of docs/project-file.md
(``markdown``) and the JSON Schema (``json_schema``) all come from one ``ObjectSpec``.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from lightinv_core.errors import DesignError
from lightinv_core.fields.checks import ProjectError, _fail, _fmt, _join, _object, _within

REQUIRED = object()
"""The default of a field that must be given."""


@dataclass(frozen=True)
class Field:
    """One field of a JSON object, declared once.

    ``check`` turns the JSON value at a JSON path into the model's value (a
    ``ProjectError`` on a bad one); with ``needs``, it also gets the values of those
    earlier fields of the same object as keyword arguments (a rule's source names).
    ``default`` is taken when the field is missing (``REQUIRED``: it must be given;
    ``doc_default`` shows a default that is not a plain JSON value in the docs).
    ``type`` and ``meaning`` (units included) are what the docs say of it. ``kinds``
    lists the kinds of object that take the field (empty: every kind). On writing, a
    field is left out at its default unless ``always``; ``of`` is the spec of the
    object(s) it holds, ``encode`` turns any other value into plain data. ``nullable``:
    a null means "not given". ``optional``: left out at its default even in an object
    that writes its defaults (a field later versions added, so older files stay as
    they were). ``many``: the field holds a list of ``of`` objects; ``schema`` replaces
    the JSON Schema its check says (a reader function that is not a typed check).
    """

    name: str
    check: Callable[..., Any]
    default: Any = REQUIRED
    type: str = ""
    meaning: str = ""
    kinds: tuple[str, ...] = ()
    always: bool = False
    nullable: bool = False
    needs: tuple[str, ...] = ()
    of: ObjectSpec | None = None
    encode: Callable[[Any], Any] | None = None
    doc_default: str | None = None
    optional: bool = False
    many: bool = False
    schema: dict | None = None

    @property
    def required(self) -> bool:
        """Whether the field must be given."""
        return self.default is REQUIRED

    @property
    def type_text(self) -> str:
        """What the docs' type column says: ``type``, else its check's ``text``."""
        return self.type or getattr(self.check, "text", "")

    def json_schema(self) -> dict:
        """The JSON Schema of the field's values: its ``schema``, the ``$ref`` of the
        object(s) it holds, else its check's; its meaning as the description, its
        default when it is plain JSON, and null when ``nullable``."""
        if self.schema is not None:
            out = dict(self.schema)
        elif self.of is not None:
            ref = {"$ref": f"#/$defs/{self.of.name}"}
            out = {"type": "array", "items": ref} if self.many else ref
        elif hasattr(self.check, "schema"):
            out = self.check.schema()
        else:  # a plain function: its values are described, not constrained
            out = {}
        if self.nullable and out:
            out = {"anyOf": [out, {"type": "null"}]}
        if self.meaning:
            out["description"] = self.meaning
        plain = _plain(self.default)
        if not self.required and plain is not _NOT_PLAIN and (plain is not None or self.nullable):
            out["default"] = plain
        return out


@dataclass(frozen=True)
class ObjectSpec:
    """The fields of one kind of JSON object, in the order they are written.

    ``kind_field`` names the field that says which kinds' fields apply (a source's
    ``kind``), or an attribute of the data class when the kind is implied (a scene's
    ``kind``: builtin or obj; then the class calls ``check_kinds``). ``not_taken(kind,
    field)`` words the error for a field the kind does not take; it is checked after
    the values unless ``kinds_first``, and with ``default_anywhere`` a field at its
    default passes whatever the kind (a built-in scene's ``"scale": 1``).
    ``write_defaults``: every field is written, defaults included (settings, results).
    ``kinds_doc`` words the docs' note on a field only some kinds take.
    """

    name: str
    fields: tuple[Field, ...]
    kind_field: str | None = None
    not_taken: Callable[[str, str], str] | None = None
    kinds_first: bool = False
    default_anywhere: bool = False
    write_defaults: bool = False
    kinds_doc: str = "{} only"
    kind_fields: Callable[[str], tuple[str, ...]] | None = None

    @classmethod
    def of(cls, model: type, name: str, **options: Any) -> ObjectSpec:
        """The spec of the dataclass ``model`` whose fields are ``declare``d, in their
        order (``options``: the other ``ObjectSpec`` fields)."""
        fields = tuple(
            dataclasses.replace(
                f.metadata[_KEY],
                name=f.name,
                default=REQUIRED if f.default is dataclasses.MISSING else f.default,
            )
            for f in dataclasses.fields(model)
            if _KEY in f.metadata
        )
        return cls(name, fields, **options)

    @property
    def names(self) -> tuple[str, ...]:
        """Every field name, in order."""
        return tuple(f.name for f in self.fields)

    def field(self, name: str) -> Field:
        """The field called ``name``."""
        return next(f for f in self.fields if f.name == name)

    def kinds_of(self, f: Field) -> tuple[str, ...]:
        """The kinds of object that take field ``f`` (empty: every kind): its ``kinds``,
        else those whose ``kind_fields`` name it (a source type's own fields)."""
        if f.kinds or self.kind_fields is None:
            return f.kinds
        kinds = self.field(self.kind_field).check.values()
        return tuple(str(k) for k in kinds if f.name in self.kind_fields(k))

    def defaults(self) -> dict[str, Any]:
        """The default of every field that need not be given."""
        return {f.name: f.default for f in self.fields if not f.required}

    def read(self, v: Any, path: str) -> dict[str, Any]:
        """The checked values of the object ``v`` at ``path`` (fields not given are left
        out): unknown, repeated and missing fields, each value's check in field order,
        then fields its kind does not take (a null counts as not given where the field
        is ``nullable``)."""
        required = tuple(f.name for f in self.fields if f.required)
        d = _object(v, path, self.names, required)
        kind = None
        if self.kind_field in self.names:
            kind = self.field(self.kind_field).check(d[self.kind_field], _join(path, "kind"))
        out: dict[str, Any] = {}
        for f in self.fields:
            if f.name not in d or (d[f.name] is None and f.nullable):
                continue
            if self.kinds_first:
                self._taken(kind, f, d[f.name], path)
            given = {n: out.get(n, self.field(n).default) for n in f.needs}
            out[f.name] = f.check(d[f.name], _join(path, f.name), **given)
        for f in self.fields:
            if f.name in out:
                self._taken(kind, f, out[f.name], path)
        return out

    def build(self, cls: type, v: Any, path: str) -> Any:
        """``cls(**values)`` of the object ``v`` at ``path``, an error of the model class
        (``DesignError``) reported at ``path``."""
        values = self.read(v, path)
        with _within(path):
            return cls(**values)

    def check_object(self, obj: Any) -> None:
        """Check and normalise, in place, the fields of the frozen dataclass ``obj`` (a
        settings object made in code or read from a file)."""
        for f in self.fields:
            object.__setattr__(obj, f.name, f.check(getattr(obj, f.name), f.name))

    def check_kinds(self, obj: Any, path: str = "") -> None:
        """Fail on a field of the data class ``obj`` that its kind does not take."""
        kind = getattr(obj, self.kind_field)
        for f in self.fields:
            value = getattr(obj, f.name)
            if not (f.nullable and value is None):
                self._taken(kind, f, value, path)

    @functools.cached_property
    def _checks(self) -> tuple[tuple[str, Callable[[Any, str], Any], bool], ...]:
        return tuple((f.name, f.check, f.nullable) for f in self.fields)

    def check_fields(self, obj: Any, where: str) -> None:
        """Check and normalise, in place, the fields of the frozen model dataclass ``obj``
        built in code: a bad value is a ``DesignError`` naming ``where`` and the field (a
        null passes where the field is ``nullable``)."""
        for name, check, nullable in self._checks:
            value = getattr(obj, name)
            if value is None and nullable:
                continue
            try:
                new = check(value, name)
            except ProjectError as err:
                raise DesignError(f"{where}: {_sentence(err)}") from None
            if new is not value:
                object.__setattr__(obj, name, new)
        if self.not_taken is not None and self.kind_field in self.names:
            kind = getattr(obj, self.kind_field)
            for f in self.fields:
                value = getattr(obj, f.name)
                takers = self.kinds_of(f)
                if takers and kind not in takers and value is not None and value != f.default:
                    raise DesignError(f"{where}: {self.not_taken(kind, f.name)}")

    def _taken(self, kind: str | None, f: Field, value: Any, path: str) -> None:
        if kind is None:
            return
        takers = self.kinds_of(f)
        if not takers or kind in takers:
            return
        if self.default_anywhere and value == f.default:
            return
        _fail(_join(path, f.name), self.not_taken(kind, f.name))

    def write(self, obj: Any) -> dict[str, Any]:
        """The fields of ``obj`` (a mapping, or attributes of the same names) as they are
        saved: the fields its kind takes that are required, ``always`` written or not at
        their default (all of them with ``write_defaults``), nested objects by their own
        spec, tuples as lists."""
        get = obj.__getitem__ if isinstance(obj, Mapping) else lambda n: getattr(obj, n)
        kind = get(self.kind_field) if self.kind_field else None
        out: dict[str, Any] = {}
        for f in self.fields:
            value = get(f.name)
            takers = self.kinds_of(f)
            if takers and kind not in takers:
                continue
            written = self.write_defaults and not f.optional
            if f.required or f.always or written or value != f.default:
                out[f.name] = _encode(f, value)
        return out

    def markdown(self) -> str:
        """The fields as a Markdown table: key, required, type, default, meaning (the
        kinds that take it, then what it is, with its units)."""
        rows = ["| key | required | type | default | meaning |", "|---|---|---|---|---|"]
        for f in self.fields:
            need = "yes" if f.required else "no"
            if f.doc_default is not None:
                default = f.doc_default
            elif f.required:
                default = ""
            elif f.default is None:
                default = "none"
            else:
                default = f"`{_doc_value(f.default)}`"
            takers = self.kinds_of(f)
            kinds = ", ".join(f"`{k}`" for k in takers)
            only = self.kinds_doc.format(kinds) + ": " if takers else ""
            rows.append(f"| `{f.name}` | {need} | {f.type_text} | {default} | {only}{f.meaning} |")
        return "\n".join(rows)


def _encode(f: Field, value: Any) -> Any:
    """A field's value as it is written (before ``_jsonable`` makes it plain JSON)."""
    if f.encode is not None:
        return f.encode(value)
    if f.of is not None and value is not None:
        if isinstance(value, tuple | list):
            return [f.of.write(x) for x in value]
        return f.of.write(value)
    return list(value) if isinstance(value, tuple) else value


def _doc_value(v: Any) -> str:
    """A default value as JSON text for the docs."""
    if isinstance(v, tuple):
        return "[" + ", ".join(_doc_value(x) for x in v) + "]"
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, bool):
        return "true" if v else "false"
    return _fmt(v)


def _sentence(err: ProjectError) -> str:
    """A field's error as the model words it: "rows must be an integer >= 1, got 0"
    (the file's reader says "rows: expected an integer >= 1, got 0")."""
    if err.detail.startswith("expected "):
        return f"{err.path} must be {err.detail.removeprefix('expected ')}"
    return f"{err.path}: {err.detail}"


_NOT_PLAIN = object()


def _plain(v: Any) -> Any:
    """``v`` as plain JSON data (tuples as lists), or ``_NOT_PLAIN`` (an object)."""
    if v is None or isinstance(v, bool | int | float | str):
        return str(v) if isinstance(v, str) else v
    if isinstance(v, tuple | list):
        items = [_plain(x) for x in v]
        return _NOT_PLAIN if any(x is _NOT_PLAIN for x in items) else items
    return _NOT_PLAIN


_KEY = "lightinv"


def declare(check: Callable[[Any, str], Any], meaning: str = "", **kw: Any) -> dict:
    """The metadata of a dataclass field declared for a file: ``field(default=0.8,
    metadata=declare(Number(lo=0.0), "height above the floor, m"))``. ``check`` is a
    typed check of ``fields.types``, ``meaning`` says what it is (with units), ``kw``
    any other ``Field`` option; the default is the dataclass field's own.
    ``ObjectSpec.of`` reads it back."""
    return {_KEY: Field("", check, meaning=meaning, **kw)}
