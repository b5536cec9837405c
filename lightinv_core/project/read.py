"""Reading a project: parsed JSON data -> a checked ``Project``.

``read_project`` checks the schema version first, then reads every top-level field with
its ``TOP`` spec (each nested object by its own spec), raising a ``ProjectError`` at the
JSON path of the first problem. ``object_pairs_hook`` is the ``json.loads`` hook that
lets the specs report keys given twice.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

from lightinv_core.fields import _describe, _fail
from lightinv_core.luminaires.formats import is_photometry_reference
from lightinv_core.project.model import SCHEMA, TOP, Project, project_from_values, resolve_path

# -- JSON parsing ---------------------------------------------------------------------------


class _JSONObject(dict):
    """A parsed JSON object that remembers keys given more than once."""

    duplicates: tuple[str, ...] = ()


def object_pairs_hook(pairs: list[tuple[str, Any]]) -> dict:
    """Build a JSON object, noting its repeated keys for ``_object``."""
    out = _JSONObject(pairs)
    if len(out) != len(pairs):
        seen: set[str] = set()
        out.duplicates = tuple(k for k, _ in pairs if k in seen or seen.add(k))
    return out


# -- the project ----------------------------------------------------------------------------


def read_project(data: Any, base_dir: Path | None) -> Project:
    """The project described by parsed JSON ``data``; relative scene paths are made
    absolute against ``base_dir`` when it is given."""
    if not isinstance(data, dict):
        _fail("", f"expected a JSON object at the top level, got {_describe(data)}")
    # The version comes first: a file of another version is refused before anything in
    # it is read against this version's fields.
    if "schema" not in data:
        _fail("", "missing required field 'schema' (is this a LightInv project file?)")
    schema = TOP.field("schema").check(data["schema"], "schema")
    if schema != SCHEMA:
        _fail(
            "", f"unknown project schema {schema}; this version of LightInv reads schema {SCHEMA}"
        )
    values = {**TOP.defaults(), **TOP.read(data, "")}
    scene = values["scene"]
    if base_dir is not None and scene.obj is not None:
        values["scene"] = replace(
            scene,
            obj=resolve_path(scene.obj, base_dir),
            materials=resolve_path(scene.materials, base_dir),
        )
    if base_dir is not None:
        values["arrays"] = tuple(
            replace(a, product=resolve_path(a.product, base_dir))
            if is_product_file(a.product)
            else a
            for a in values["arrays"]
        )
        dl = values["daylight"]
        if dl.weather != "builtin":
            values["daylight"] = replace(dl, weather=resolve_path(dl.weather, base_dir))
    return project_from_values(values)


def is_product_file(product: str) -> bool:
    """Whether an array's ``product`` names a photometric file (not a catalogue entry)."""
    return is_photometry_reference(product)
