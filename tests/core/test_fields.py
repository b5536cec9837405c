"""Field specs: each field of every project-file object is declared once
(lightinv_core/fields/: Field, ObjectSpec, declare); reading, messages, writing and the field
tables of docs/project-file.md come from there. Rerun with LIGHTINV_WRITE_DOCS=1 to
regenerate the tables after a spec changes."""

from __future__ import annotations

import copy
import hashlib
import os
import re
from dataclasses import MISSING, dataclass
from pathlib import Path

import pytest

from lightinv_core.design.model import (
    Daylight,
    Goal,
    Intention,
    LuminaireArray,
    Rule,
    Source,
    Workplane,
)
from lightinv_core.design.solution import ParetoFront, Solution, Violation
from lightinv_core.fields import Field, ObjectSpec, ProjectError, _choice, _number
from lightinv_core.operator.settings import OPERATOR, OperatorSettings
from lightinv_core.optimize.settings import OPTIMIZER, OptimizerSettings
from lightinv_core.project import (
    SceneSpec,
    load_project,
    project_from_dict,
    project_to_dict,
    save_project,
)
from lightinv_core.project.model import FILE_SPECS, TOP
from lightinv_core.project.results import PARETO, RUN, SOLUTION, VIOLATION, RunRecord
from lightinv_core.project.scene import SCENE, ZONE
from lightinv_core.project.specs import ARRAY, DAYLIGHT, GOAL, INTENTION, RULE, SOURCE, WORKPLANE
from lightinv_core.scene.edits import ZoneEdit
from tests.core.test_project import VALID, WITH_RESULTS, _with_zones

DOC = Path(__file__).resolve().parents[2] / "docs" / "project-file.md"
PROJECTS = Path(__file__).resolve().parents[2] / "resources" / "projects"
BLOCK = re.compile(r"(<!-- fields:(\w+) [^>]*-->\n)(.*?)(<!-- /fields:\2 -->)", re.S)


def rendered(text: str) -> str:
    specs = {s.name: s for s in FILE_SPECS}
    return BLOCK.sub(lambda m: m[1] + specs[m[2]].markdown() + "\n" + m[4], text)


def test_docs_field_tables_come_from_the_specs():
    text = DOC.read_text(encoding="utf-8")
    assert sorted(m[2] for m in BLOCK.finditer(text)) == sorted(s.name for s in FILE_SPECS)
    new = rendered(text)
    if os.environ.get("LIGHTINV_WRITE_DOCS") == "1":
        DOC.write_text(new, encoding="utf-8")
        return
    assert new == text, (
        "docs/project-file.md is out of date with the field specs; regenerate its tables "
        "with LIGHTINV_WRITE_DOCS=1 .venv/bin/python -m pytest tests/core/test_fields.py"
    )


# -- every field declared once --------------------------------------------------------------

MODEL_CLASSES = [
    (SOURCE, Source),
    (ARRAY, LuminaireArray),
    (WORKPLANE, Workplane),
    (RULE, Rule),
    (INTENTION, Intention),
    (GOAL, Goal),
    (DAYLIGHT, Daylight),
    (OPERATOR, OperatorSettings),
    (OPTIMIZER, OptimizerSettings),
    (SCENE, SceneSpec),
    (ZONE, ZoneEdit),
    (VIOLATION, Violation),
    (SOLUTION, Solution),
    (PARETO, ParetoFront),
    (RUN, RunRecord),
]


@pytest.mark.parametrize(("spec", "cls"), MODEL_CLASSES, ids=lambda x: getattr(x, "name", ""))
def test_each_spec_names_the_fields_of_its_model_class(spec, cls):
    assert len(set(spec.names)) == len(spec.names)
    assert set(spec.names) == set(cls.__dataclass_fields__)
    for f in spec.fields:  # the docs say what each field is
        assert f.type_text and f.meaning, f.name


def test_data_class_defaults_are_the_spec_defaults():
    for spec, cls in MODEL_CLASSES:
        fields = cls.__dataclass_fields__
        for name, default in spec.defaults().items():
            if fields[name].default_factory is MISSING:
                assert fields[name].default == default, (spec.name, name)
            else:
                assert fields[name].default_factory() == default, (spec.name, name)


def test_the_top_level_names_every_section_once():
    assert TOP.names == tuple(WITH_RESULTS)
    required = {f.name for f in TOP.fields if f.required}
    assert required == {"schema", "name", "scene", "sources", "goals"}


# -- reading: messages from the specs -------------------------------------------------------

SKY = {"name": "S", "zone": "z", "kind": "skylight", "rect": [0, 0, 1, 1]}


def test_read_checks_each_field_and_the_kinds_that_take_it():
    assert SOURCE.read({**SKY, "filter": 0.5}, "s") == {
        **SKY,
        "rect": (0.0, 0.0, 1.0, 1.0),
        "filter": 0.5,
    }
    with pytest.raises(ProjectError, match=r"^s\.efficacy: only luminaires have this"):
        SOURCE.read({**SKY, "efficacy": 90}, "s")
    with pytest.raises(ProjectError, match=r"^s\.filter: expected a number >= 0 and <= 1, got 2"):
        SOURCE.read({**SKY, "filter": 2}, "s")
    with pytest.raises(ProjectError, match=r"^r\.axis: area rules do not take 'axis'"):
        RULE.read({"kind": "area", "sources": ["S"], "axis": "u"}, "r")
    # A null means "not given" only where the spec says so.
    assert "flux" not in SOURCE.read({**SKY, "flux": None}, "s")
    with pytest.raises(ProjectError, match="free"):
        SOURCE.read({**SKY, "free": None}, "s")


def test_unknown_fields_are_named_with_a_suggestion():
    with pytest.raises(ProjectError) as err:
        SOURCE.read({**SKY, "filtre": 1}, "sources[0]")
    known = ", ".join(SOURCE.names)
    assert str(err.value) == (
        f"sources[0]: unknown field 'filtre' (known: {known}); did you mean 'filter'?"
    )
    with pytest.raises(ProjectError, match=r"^results: unknown field 'solution'.*'solutions'\?$"):
        project_from_dict({**copy.deepcopy(VALID), "results": {"solution": []}})


def test_per_kind_applicability_is_data_in_the_spec():
    # The same data gives the reader's message and the writer's omission.
    assert GOAL.field("kinds").kinds == ("max_light_power",)
    with pytest.raises(ProjectError, match=r"^g\.kinds: only a max_light_power goal takes"):
        GOAL.read({"kind": "match", "kinds": ["skylight"]}, "g")
    assert GOAL.read({"kind": "match", "kinds": []}, "g") == {"kind": "match", "kinds": ()}
    # A built-in scene may state an OBJ-only field at its default, not otherwise.
    assert SceneSpec(builtin="office", scale=1.0).kind == "builtin"
    with pytest.raises(ProjectError, match=r"^scale: only an OBJ scene takes this; a built-in"):
        SceneSpec(builtin="office", scale=2.0)
    with pytest.raises(ProjectError, match=r"^skip_degenerate: only an OBJ scene takes this$"):
        SceneSpec(builtin="office", skip_degenerate=True)
    assert SCENE.write(SceneSpec(builtin="office")) == {"builtin": "office", "resolution": None}
    assert SCENE.write(SceneSpec(obj="a.obj")) == {
        "obj": "a.obj",
        "resolution": None,
        "scale": 1.0,
        "up": "z",
    }


def test_a_field_reads_the_earlier_fields_it_needs():
    data = copy.deepcopy(VALID)
    data["rules"][0]["sources"] = ["S9"]
    with pytest.raises(ProjectError, match=r"^rules\[0\]\.sources\[0\]: no source 'S9'"):
        project_from_dict(data)
    data = {**copy.deepcopy(VALID), "target_sources": []}
    with pytest.raises(ProjectError, match=r"^goals\[2\]: a match goal needs target_sources"):
        project_from_dict(data)


# -- writing ---------------------------------------------------------------------------------


def test_write_leaves_out_defaults_and_other_kinds_fields():
    lum = Source("L", "z", "luminaire", (0, 0, 1, 1), flux=100.0)
    assert SOURCE.write(lum) == {
        "name": "L",
        "zone": "z",
        "kind": "luminaire",
        "rect": [0.0, 0.0, 1.0, 1.0],
        "flux": 100.0,
    }
    sky = Source("S", "z", "skylight", (0, 0, 1, 1), filter=0.5)
    assert "efficacy" not in SOURCE.write(sky) and SOURCE.write(sky)["filter"] == 0.5
    it = Intention("desks", group="desks", average=500.0)
    assert INTENTION.write(it) == {
        "name": "desks",
        "group": "desks",
        "quantity": "lux",  # always written
        "average": 500.0,
        "weight": 100.0,
    }
    # Settings are written whole, defaults included.
    assert OPERATOR.write(OperatorSettings()) == {
        "tol": 0.01,
        "rank": None,
        "rays": 1024,
        "seed": 0,
    }


def test_a_spec_of_its_own_reads_writes_and_documents():
    @dataclass(frozen=True)
    class Thing:
        kind: str
        size: float
        tint: float = 0.5
        glow: float = 1.0

    spec = ObjectSpec(
        "thing",
        (
            Field("kind", lambda v, p: _choice(v, p, ("dull", "bright")), type="string"),
            Field("size", lambda v, p: _number(v, p, gt=0.0), type="number > 0", meaning="m"),
            Field("tint", _number, 0.5, "number", "how much", always=True),
            Field("glow", _number, 1.0, "number", "lm", ("bright",)),
        ),
        kind_field="kind",
        not_taken=lambda kind, field: f"a {kind} thing has no {field}",
    )
    assert spec.read({"kind": "dull", "size": 2}, "t") == {"kind": "dull", "size": 2.0}
    with pytest.raises(ProjectError, match=r"^t: missing required field 'size'$"):
        spec.read({"kind": "dull"}, "t")
    with pytest.raises(ProjectError, match=r"^t\.size: expected a number > 0, got 0$"):
        spec.read({"kind": "dull", "size": 0}, "t")
    with pytest.raises(ProjectError, match=r"^t\.glow: a dull thing has no glow$"):
        spec.read({"kind": "dull", "size": 1, "glow": 2}, "t")
    thing = spec.build(Thing, {"kind": "bright", "size": 1, "glow": 2}, "t")
    assert spec.write(thing) == {"kind": "bright", "size": 1.0, "tint": 0.5, "glow": 2.0}
    assert spec.write(Thing("dull", 1.0)) == {"kind": "dull", "size": 1.0, "tint": 0.5}
    table = spec.markdown()
    assert "| `tint` | no | number | `0.5` | how much |" in table
    assert "| `glow` | no | number | `1` | `bright` only: lm |" in table


# -- round trips: the saved text is the one written before the field specs ------------------

# sha256 of the text save_project wrote for each file before the writers were driven by the
# field specs (the same on this commit). If the file format changes on purpose, update them.
# (with_results and zones last changed when the test project gained an array, a work plane
# and a grid intention, then an observer, then two control groups.)
SAVED = {
    "experiment1": "374e38154fb40f071fb900cab3b58532dabc4557aebda38fb8dc938f447f0fd9",
    "experiment2": "9a6a85741c3d0325be7a86e0fb8cc1c46f4fe5d4dfc61f098ea0a886b38ead3a",
    "experiment3": "e7dddfedb0a1e281dc0dd92c96941fe20bdcef8f5ffe7f529356b3b9f1a74f99",
    "experiment3b": "f6218f028915b203b3ca6909049950291a58647fa35952a6263c5670875141eb",
    "experiment4": "e26567ac060fb531996540911e96f40bda86194ecb14c31123ad2a3ad3dcaee9",
    "experiment5-skylights": "ae8bd580aeade262144aa417d153bf6dfa55aeb59a4ceccb976af0890e5c1546",
    "experiment5-twostep": "7962957b9cd8336277433827cc5944732dfa06e067a9b3eee0c9f614db7e11f0",
    "experiment5": "52e2dde92ed16508302ee42d8709f2cbc8e446066f75bfb6b45575cb08580bee",
    "office-demo": "cbaaf5377b272f4a4fb6582e23fdb0c42bc9be5cef733652e43804c9c123af9b",
    "with_results": "a6ea34cdd46483f0433b8a1cf2e23d817f82172db1f1f77d39fb234cfc20df3d",
    "zones": "7d77bc4f65ed18ad45b34e5f5b2cc14ad99e23bd484dc6eecc4e728f40395c2c",
}


def _saved_text(project, path: Path) -> str:
    save_project(project, path)
    return path.read_text(encoding="utf-8")


def _check_round_trip(project, name: str, tmp_path: Path) -> None:
    text = _saved_text(project, tmp_path / f"{name}.json")
    again = load_project(tmp_path / f"{name}.json")
    assert project_to_dict(again) == project_to_dict(project)
    assert _saved_text(again, tmp_path / f"{name}-again.json") == text
    if name in SAVED:
        digest = hashlib.sha256(text.encode("utf-8")).hexdigest()
        assert digest == SAVED[name], f"{name}: the saved text changed"


@pytest.mark.parametrize("path", sorted(PROJECTS.glob("*.json")), ids=lambda p: p.stem)
def test_shipped_projects_round_trip_to_the_same_text(path, tmp_path):
    _check_round_trip(load_project(path), path.stem, tmp_path)


@pytest.mark.parametrize("name", ["with_results", "zones"])
def test_results_and_zones_round_trip_to_the_same_text(name, tmp_path):
    data = copy.deepcopy(WITH_RESULTS) if name == "with_results" else _with_zones()
    _check_round_trip(project_from_dict(data), name, tmp_path)
    assert project_to_dict(project_from_dict(copy.deepcopy(data))) == data
