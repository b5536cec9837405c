"""Field specs: each field of the design's JSON objects is declared once
(lightinv_core/project/specs.py); reading, messages, writing and the field tables of
docs/project-file.md come from there. Rerun with LIGHTINV_WRITE_DOCS=1 to regenerate
the tables after a spec changes."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

from lightinv_core.design.model import Intention, Rule, Source
from lightinv_core.fields import Field, ObjectSpec, ProjectError, _number
from lightinv_core.operator.settings import OPERATOR, OperatorSettings
from lightinv_core.optimize.settings import OPTIMIZER, OptimizerSettings
from lightinv_core.project import SceneSpec, load_project, project_to_dict
from lightinv_core.project.model import SCENE
from lightinv_core.project.specs import FILE_SPECS, INTENTION, RULE, SOURCE

DOC = Path(__file__).resolve().parents[2] / "docs" / "project-file.md"
PROJECTS = Path(__file__).resolve().parents[2] / "resources" / "projects"
BLOCK = re.compile(r"(<!-- fields:(\w+) [^>]*-->\n)(.*?)(<!-- /fields:\2 -->)", re.S)


def rendered(text: str) -> str:
    specs = {s.name: s for s in FILE_SPECS}
    return BLOCK.sub(lambda m: m[1] + specs[m[2]].markdown() + "\n" + m[4], text)


def test_docs_field_tables_come_from_the_specs():
    text = DOC.read_text(encoding="utf-8")
    assert {m[2] for m in BLOCK.finditer(text)} == {s.name for s in FILE_SPECS}
    new = rendered(text)
    if os.environ.get("LIGHTINV_WRITE_DOCS") == "1":
        DOC.write_text(new, encoding="utf-8")
        return
    assert new == text, "docs/project-file.md is stale: rerun with LIGHTINV_WRITE_DOCS=1"


def test_every_model_field_is_declared_once():
    pairs = ((SOURCE, Source), (RULE, Rule), (INTENTION, Intention))
    pairs += ((OPERATOR, OperatorSettings), (OPTIMIZER, OptimizerSettings), (SCENE, SceneSpec))
    for spec, cls in pairs:
        assert spec.names == tuple(f for f in cls.__dataclass_fields__ if f != "KINDS")
        assert len(set(spec.names)) == len(spec.names)


def test_read_checks_each_field_and_the_kinds_that_take_it():
    sky = {"name": "S", "zone": "z", "kind": "skylight", "rect": [0, 0, 1, 1]}
    assert SOURCE.read({**sky, "filter": 0.5}, "s") == {
        **sky,
        "rect": (0.0, 0.0, 1.0, 1.0),
        "filter": 0.5,
    }
    with pytest.raises(ProjectError, match=r"^s\.efficacy: only luminaires have this"):
        SOURCE.read({**sky, "efficacy": 90}, "s")
    with pytest.raises(ProjectError, match=r"^s\.filter: expected a number >= 0 and <= 1, got 2"):
        SOURCE.read({**sky, "filter": 2}, "s")
    with pytest.raises(ProjectError, match=r"unknown field 'filtre'.*did you mean 'filter'"):
        SOURCE.read({**sky, "filtre": 1}, "s")
    with pytest.raises(ProjectError, match=r"^r\.axis: area rules do not take 'axis'"):
        RULE.read({"kind": "area", "sources": ["S"], "axis": "u"}, "r")
    # A null means "not given" only where the spec says so.
    assert "flux" not in SOURCE.read({**sky, "flux": None}, "s")
    with pytest.raises(ProjectError, match="free"):
        SOURCE.read({**sky, "free": None}, "s")


def test_write_leaves_out_defaults_and_other_kinds_fields():
    lum = Source("L", "z", "luminaire", (0, 0, 1, 1), flux=100.0)
    assert SOURCE.write(lum) == {
        "name": "L",
        "zone": "z",
        "kind": "luminaire",
        "rect": [0.0, 0.0, 1.0, 1.0],
        "flux": 100.0,
    }
    it = Intention("desks", group="desks", average=500.0)
    assert INTENTION.write(it) == {
        "name": "desks",
        "group": "desks",
        "quantity": "lux",
        "average": 500.0,
        "weight": 100.0,
    }


def test_a_spec_of_its_own_reads_writes_and_documents():
    spec = ObjectSpec(
        "thing",
        (
            Field("size", lambda v, p: _number(v, p, gt=0.0), type="number > 0", meaning="m"),
            Field("tint", lambda v, p: _number(v, p), 0.5, "number", "how much", always=True),
        ),
    )
    assert spec.read({"size": 2}, "t") == {"size": 2.0}
    with pytest.raises(ProjectError, match="missing required field 'size'"):
        spec.read({}, "t")
    assert "| `tint` | no | number | `0.5` | how much |" in spec.markdown()


@pytest.mark.parametrize("path", sorted(PROJECTS.glob("*.json")), ids=lambda p: p.stem)
def test_shipped_projects_round_trip(path):
    project = load_project(path)
    again = project_to_dict(project)
    from lightinv_core.project import project_from_dict

    assert project_to_dict(project_from_dict(again)) == again
