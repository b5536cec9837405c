"""The published JSON Schema of project files (docs/project.schema.json): generated from
the field declarations, a valid draft 2020-12 schema that every shipped project meets,
checked with an independent validator (``jsonschema``) against our reader. Rerun with
LIGHTINV_WRITE_DOCS=1 to regenerate the file after a declaration changes."""

from __future__ import annotations

import copy
import json
import os
from pathlib import Path

import numpy as np
import pytest
from jsonschema import Draft202012Validator

from lightinv_core.design.model import Source
from lightinv_core.project import ProjectError, load_project, project_from_dict, project_to_dict
from lightinv_core.project.schema import SCHEMA_FILE, project_schema, project_schema_text
from lightinv_core.project.specs import SOURCE
from lightinv_core.sources.types import ZoneLuminaire, register_source_type, unregister_source_type
from tests.core.test_project import VALID, WITH_RESULTS, _with_zones

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / SCHEMA_FILE
SHIPPED = sorted(
    p
    for folder in ("resources", "tests")
    for p in (ROOT / folder).rglob("*.json")
    if '"schema": 1' in p.read_text(encoding="utf-8", errors="replace")
)


def validator() -> Draft202012Validator:
    return Draft202012Validator(json.loads(DOC.read_text(encoding="utf-8")))


def test_the_published_schema_is_what_the_declarations_generate():
    text = project_schema_text()
    if os.environ.get("LIGHTINV_WRITE_DOCS") == "1":
        DOC.write_text(text, encoding="utf-8")
        return
    assert DOC.read_text(encoding="utf-8") == text, (
        "docs/project.schema.json is out of date with the field declarations; regenerate "
        "it with LIGHTINV_WRITE_DOCS=1 .venv/bin/python -m pytest tests/core/test_project_schema.py"
    )
    Draft202012Validator.check_schema(project_schema())


def test_the_repository_ships_projects_to_check():
    assert len(SHIPPED) >= 11 and all(p.parent.name == "projects" for p in SHIPPED)


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_every_shipped_project_meets_the_schema(path):
    data = json.loads(path.read_text(encoding="utf-8"))
    errors = [f"{list(e.absolute_path)}: {e.message}" for e in validator().iter_errors(data)]
    assert not errors, errors
    load_project(path)  # and our reader takes it


@pytest.mark.parametrize("name", ["valid", "with_results", "zones"])
def test_what_we_write_meets_the_schema(name):
    data = {"valid": VALID, "with_results": WITH_RESULTS}.get(name) or _with_zones()
    written = project_to_dict(project_from_dict(copy.deepcopy(data)))
    errors = [f"{list(e.absolute_path)}: {e.message}" for e in validator().iter_errors(written)]
    assert not errors, errors


def _set(path: str, value):
    """A change to a project's data: ``value`` at the JSON path (dots and [i])."""

    def change(data: dict) -> None:
        keys = [
            int(k) if k.isdigit() else k for k in path.replace("[", ".").replace("]", "").split(".")
        ]
        node = data
        for k in keys[:-1]:
            node = node[k]
        node[keys[-1]] = value

    return change


BAD = [
    (_set("schema", 2), "unknown project schema 2"),
    (_set("sources[0].rect", "0 0 1 1"), "sources[0].rect"),
    (_set("sources[0].kind", "lamp"), "sources[0].kind"),
    (_set("sources[0].filtre", 0.5), "sources[0]"),
    (_set("sources[0].filter", 1.5), "sources[0].filter"),
    (_set("goals", []), "goals"),
    (_set("intentions[0].quantity", "candela"), "intentions[0].quantity"),
    (_set("scene.resolution", -0.5), "scene.resolution"),
    (_set("penalty_power", 3), "penalty_power"),
]


@pytest.mark.parametrize(("change", "where"), BAD, ids=[w for _, w in BAD])
def test_bad_projects_are_refused_by_the_schema_and_the_reader(change, where):
    data = copy.deepcopy(VALID)
    change(data)
    assert list(validator().iter_errors(data)), "the schema took it"
    with pytest.raises(ProjectError) as err:
        project_from_dict(data)
    assert str(err.value).startswith(where), str(err.value)


def test_a_kinds_own_field_is_refused_on_another_kind_by_both():
    data = copy.deepcopy(VALID)
    sky = next(s for s in data["sources"] if s["kind"] == "skylight")
    sky["efficacy"] = 90.0
    assert list(validator().iter_errors(data))
    with pytest.raises(ProjectError, match=r"\.efficacy: only luminaires have this"):
        project_from_dict(data)


class Panel(ZoneLuminaire):
    """A test kind: a luminaire that takes a fixed exitance only."""

    kind = "panel"
    label = "Panel"
    stem = "P"
    fields = ("exitance", "efficacy")


@pytest.fixture
def panel():
    register_source_type(Panel())
    yield
    unregister_source_type("panel")


def test_a_registered_source_kind_extends_the_reader_and_the_schema(panel):
    p = Source("P1", "z", "panel", (0, 0, 1, 1), exitance=500.0)
    assert p.kind == "panel" and SOURCE.write(p)["exitance"] == 500.0
    assert SOURCE.kinds_of(SOURCE.field("exitance")) == ("luminaire", "panel")
    with pytest.raises(ProjectError, match=r"^s\.flux: only luminaires have this"):
        SOURCE.read(
            {"name": "P", "zone": "z", "kind": "panel", "rect": [0, 0, 1, 1], "flux": 1}, "s"
        )
    schema = project_schema()["$defs"]["source"]
    assert "panel" in schema["properties"]["kind"]["enum"]
    rules = {
        r["if"]["properties"]["kind"]["const"]: r["then"]["properties"] for r in schema["allOf"]
    }
    assert set(rules["panel"]) == {"flux", "flux_range", "filter", "glazing", "control_group"}
    assert np.isclose(SOURCE.read({**SOURCE.write(p)}, "s")["exitance"], 500.0)
