"""Project files: round trips, atomic saving, and a clear ProjectError for every bad file."""

from __future__ import annotations

import copy
import dataclasses
import json
import math
import os
import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import lightinv_core.project as project_module
from lightinv_core.design.model import Design, DesignError, Goal, Source
from lightinv_core.design.solution import ParetoFront, Solution, Violation
from lightinv_core.errors import LightInvError, SceneError
from lightinv_core.project import (
    OperatorSettings,
    OptimizerSettings,
    Project,
    ProjectError,
    SceneSpec,
    load_project,
    project_from_dict,
    project_to_dict,
    save_project,
)
from lightinv_core.scene.edits import ZoneEdit

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "resources" / "models"
DOC = ROOT / "docs" / "project-file.md"

# A project using every field, written the way project_to_dict writes it.
VALID: dict = {
    "schema": 1,
    "name": "corridor study",
    "description": "Skylights and luminaires for the corridor.",
    "scene": {"builtin": "corridor", "resolution": 0.5},
    "operator": {"tol": 0.02, "rank": None, "rays": 512, "seed": 1},
    "daylight": {"exterior_lux": 12000, "transmittance": 0.5},
    "penalty_power": 4,
    "sources": [
        {
            "name": "S1",
            "zone": "S1",
            "kind": "skylight",
            "rect": [1, 0.5, 3, 1.5],
            "free": ["u0", "v0", "u1", "v1"],
        },
        {
            "name": "S2",
            "zone": "S2",
            "kind": "skylight",
            "rect": [2, 0.5, 4, 1.5],
            "free": ["u0", "v0", "filter"],
            "filter": 0.8,
        },
        {"name": "S3", "zone": "S3", "kind": "skylight", "rect": [3, 0.5, 5, 1.5]},
        {
            "name": "L1",
            "zone": "A1",
            "kind": "luminaire",
            "rect": [0, 0, 1, 0.6],
            "free": ["u0", "u1", "flux"],
            "flux": 2000,
            "flux_range": [0, 10000],
            "efficacy": 120,
        },
        {
            "name": "L2",
            "zone": "A1",
            "kind": "luminaire",
            "rect": [2, 0, 3, 0.6],
            "free": ["u0", "u1"],
            "flux": 1500,
            "control_group": "window row",
        },
        {
            "name": "P2",
            "zone": "A2",
            "kind": "luminaire",
            "rect": [0, 0, 3, 0.6],
            "exitance": 3000,
            "efficacy": 90,
        },
    ],
    "target_sources": [
        {"name": "T1", "zone": "A3", "kind": "luminaire", "rect": [0, 0, 3, 0.6], "flux": 3000}
    ],
    "arrays": [
        {
            "name": "R1",
            "zone": "A2",
            "product": "Downlight 2000 lm 20 W",
            "rect": [0, 0, 3, 0.6],
            "rows": 1,
            "columns": 3,
            "rotation": 90,
            "free": ["columns", "dimming"],
            "columns_range": [1, 6],
            "maintenance_factor": 0.8,
            "control_group": "inner",
        }
    ],
    "workplanes": [{"name": "wp", "height": 0.8, "border": 0.5, "group": "floor"}],
    "observers": [
        {"name": "desk", "position": [2.0, 1.0], "height": 1.2, "azimuth": 90.0, "group": "floor"}
    ],
    "control_groups": [
        {"name": "window row", "sensor": [0.0, 0.0, 2.0, 2.0], "min_level": 0.2},
        {"name": "inner", "workplane": "wp"},
    ],
    "calc_objects": [
        {"name": "task", "kind": "task_area", "corners": [[1, 1], [3, 1], [3, 2], [1, 2]]},
        {"name": "faces", "kind": "cylindrical", "positions": [[2.0, 2.0]], "height": 1.2},
    ],
    "rules": [
        {"kind": "area", "sources": ["S1"], "min": 1, "max": 4},
        {"kind": "aspect", "sources": ["S1", "S2"], "max": 3},
        {"kind": "mirror", "sources": ["S3", "S1"], "axis": "u"},
        {"kind": "centred", "sources": ["S2"]},
        {"kind": "spacing", "sources": ["L1", "L2"], "min": 0.5},
        {"kind": "align", "sources": ["S1", "S2", "S3"], "axis": "u"},
        {"kind": "shr", "sources": ["R1"], "max": 1.5},
        {"kind": "clearance", "sources": ["R1"], "min": 0.05},
    ],
    "intentions": [
        {
            "name": "panels",
            "group": "panels",
            "quantity": "lux",
            "min": 300,
            "average": 500,
            "uniformity": 0.6,
            "weight": 100,
        },
        {"name": "picked", "patches": [1, 2, 3], "quantity": "C", "max": 800, "weight": 10},
        {
            "name": "desks",
            "quantity": "lux",
            "average": 300,
            "uniformity": 0.4,
            "weight": 100,
            "grid": "wp",
        },
    ],
    "goals": [
        {"kind": "max_light_power", "kinds": ["skylight"]},
        {"kind": "min_electric_power"},
        {"kind": "match"},
    ],
    "optimizer": {
        "method": "multilevel",
        "seed": 3,
        "max_evals": 5000,
        "time_limit": 60,
        "target": None,
        "stall": 2000,
        "trials": 16,
        "divisors": [64, 16, 1],
        "level_max_evals": 1000,
        "level_target": 0.03,
        "runs": 4,
        "population": 24,
        "epsilons": [100, 200.5],
        "epsilon_count": 8,
    },
}

SKY = {"name": "S1", "zone": "S1", "kind": "skylight", "rect": [1, 0.5, 3, 1.5]}
SOLUTION = {
    "sources": [SKY],
    "objectives": {"max_light_power": 123.4, "min_electric_power": "inf"},
    "penalty": "inf",
    "violations": [
        {
            "name": "area S1",
            "constraint": "geometry",
            "amount": 0.5,
            "value": "nan",
            "bound": "nan",
            "units": "",
        },
        {
            "name": "panels",
            "constraint": "min",
            "amount": 0.1,
            "value": 270.0,
            "bound": 300,
            "units": "lux",
        },
    ],
    "x": [1, 0.5, 3.25, "-inf"],
    "info": {
        "seed": 3,
        "seconds": 2.0,
        "status": "max_evals",
        "epsilon": "inf",
        "trace": [1, "nan"],
    },
}
RESULTS = {
    "solutions": [SOLUTION],
    "pareto": {
        "objectives": ["min_electric_power", "max_light_power"],
        "method": "epsilon-constraint",
        "solutions": [SOLUTION],
        "candidates": [SOLUTION, {**SOLUTION, "penalty": 0.25, "violations": []}],
    },
}
WITH_RESULTS = {**VALID, "results": RESULTS}


def valid(**changes) -> dict:
    """A deep copy of VALID (with results), top-level keys replaced by ``changes``."""
    return copy.deepcopy({**WITH_RESULTS, **changes})


def strict_json(text: str):
    """Parse JSON that must not use the NaN/Infinity extensions."""

    def refuse(name):
        raise AssertionError(f"non-standard JSON constant {name}")

    return json.loads(text, parse_constant=refuse)


# -- round trips ----------------------------------------------------------------------------


def test_dict_round_trip_is_exact():
    p = project_from_dict(copy.deepcopy(WITH_RESULTS))
    d = project_to_dict(p)
    assert d == WITH_RESULTS
    assert project_to_dict(project_from_dict(d)) == d
    without = project_from_dict(copy.deepcopy(VALID))
    assert project_from_dict(project_to_dict(without)) == without  # no nan: dataclasses compare


def test_loaded_values_have_the_model_types():
    p = project_from_dict(copy.deepcopy(WITH_RESULTS))
    assert p.scene == SceneSpec(builtin="corridor", resolution=0.5)
    assert p.operator == OperatorSettings(tol=0.02, rays=512, seed=1)
    assert p.optimizer.divisors == (64, 16, 1) and p.optimizer.epsilons == (100.0, 200.5)
    assert p.optimizer.time_limit == 60.0 and isinstance(p.optimizer.time_limit, float)
    d = p.design
    assert isinstance(d, Design) and d.penalty_power == 4
    assert d.daylight.exterior_lux == 12000.0
    l1 = d.source("L1")
    assert l1.rect == (0.0, 0.0, 1.0, 0.6) and l1.flux_range == (0.0, 10000.0)
    assert l1.free == ("u0", "u1", "flux") and l1.efficacy == 120.0
    assert d.goals[0] == Goal("max_light_power", ("skylight",))
    assert d.intentions[1].patches == (1, 2, 3)
    s = p.solutions[0]
    assert s.penalty == math.inf and s.objectives["min_electric_power"] == math.inf
    assert math.isnan(s.violations[0].value) and s.violations[1].bound == 300.0
    assert s.x[3] == -math.inf
    assert s.info.epsilon == math.inf and math.isnan(s.info.extra["trace"][1])
    assert isinstance(s.info.seconds, float) and isinstance(s.info.seed, int)
    assert p.pareto.objectives == ("min_electric_power", "max_light_power")
    assert len(p.pareto.candidates) == 2 and p.pareto.candidates[1].feasible is False


def test_minimal_project_takes_the_defaults():
    p = project_from_dict(
        {
            "schema": 1,
            "name": "m",
            "scene": {"builtin": "patio"},
            "sources": [],
            "goals": [{"kind": "max_light_power"}],
        }
    )
    assert p.operator == OperatorSettings() and p.optimizer == OptimizerSettings()
    assert p.description == "" and p.solutions == () and p.pareto is None
    assert p.design.daylight.exterior_lux == 10000.0 and p.design.penalty_power == 2
    d = project_to_dict(p)
    assert "results" not in d and d["optimizer"]["divisors"] == [64, 16, 1]


def test_file_round_trip_with_inf_nan_and_a_pareto_front(tmp_path):
    sky = Source("S1", "S1", "skylight", (1, 0.5, 3, 1.5), ("u0", "u1"))
    sol = Solution(
        (sky,),
        {"max_light_power": float("inf")},
        float("inf"),
        (Violation("area S1", "geometry", 0.5, float("nan"), float("nan"), ""),),
        (1.0, float("nan")),
        {"status": "cancelled", "best": float("-inf")},
    )
    base = project_from_dict(copy.deepcopy(VALID))
    p = Project(
        base.name,
        base.scene,
        base.design,
        solutions=(sol,),
        pareto=ParetoFront(("max_light_power",), (sol,), "two-step", (sol, sol)),
    )
    path = tmp_path / "experiment3.json"
    save_project(p, path)
    text = path.read_text(encoding="utf-8")
    assert text.endswith("}\n") and '"penalty": "inf"' in text and '"value": "nan"' in text
    assert strict_json(text) == project_to_dict(p)
    q = load_project(path)
    assert q.path == path.resolve()
    assert project_to_dict(q) == project_to_dict(p)
    assert q.design == p.design and q.solutions[0].info.extra["best"] == -math.inf
    assert math.isnan(q.pareto.candidates[1].x[1])
    assert [f.name for f in tmp_path.iterdir()] == ["experiment3.json"]


def test_the_saved_file_is_pretty_and_stable(tmp_path):
    p = project_from_dict(copy.deepcopy(WITH_RESULTS))
    save_project(p, tmp_path / "a.json")
    save_project(load_project(tmp_path / "a.json"), tmp_path / "b.json")
    text = (tmp_path / "a.json").read_text(encoding="utf-8")
    assert text == (tmp_path / "b.json").read_text(encoding="utf-8")
    assert '\n  "schema": 1,\n' in text
    assert '"rect": [1, 0.5, 3, 1.5]' in text  # short lists on one line, whole numbers bare
    assert max(len(line) for line in text.splitlines()) <= 100


def test_relative_scene_paths_resolve_against_the_project_folder(tmp_path):
    data = copy.deepcopy(VALID)
    data["scene"] = {
        "obj": "meeting_room.obj",
        "resolution": 0.5,
        "materials": "meeting_room-materials.json",
        "scale": 1,
        "up": "z",
    }
    data.update(sources=[], target_sources=[], rules=[], intentions=[])
    data["goals"] = [{"kind": "max_light_power"}]
    spec = project_from_dict(copy.deepcopy(data)).scene
    assert spec.obj == "meeting_room.obj"  # no base folder: kept as written
    assert spec.load(MODELS).name == "meeting_room"

    (tmp_path / "models").mkdir()
    for name in ("meeting_room.obj", "meeting_room.mtl", "meeting_room-materials.json"):
        (tmp_path / "models" / name).write_bytes((MODELS / name).read_bytes())
    path = tmp_path / "models" / "room.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    p = load_project(path)
    assert p.scene.obj == str(tmp_path / "models" / "meeting_room.obj")
    assert p.scene.load().zones[0].name == "skylight"

    (tmp_path / "projects").mkdir()
    save_project(p, tmp_path / "projects" / "copy.json")
    saved = json.loads((tmp_path / "projects" / "copy.json").read_text(encoding="utf-8"))
    assert saved["scene"]["obj"] == "../models/meeting_room.obj"
    assert saved["scene"]["materials"] == "../models/meeting_room-materials.json"
    q = load_project(tmp_path / "projects" / "copy.json")
    assert os.path.samefile(q.scene.obj, p.scene.obj)
    assert q.scene.obj == p.scene.obj  # read back as saved from, no "projects/../"


def test_builtin_scene_spec_loads():
    scene = SceneSpec(builtin="cornell", resolution=0.5).load()
    assert scene.name == "cornell"


def test_documented_example_loads_and_is_in_canonical_form():
    text = DOC.read_text(encoding="utf-8")
    example = json.loads(re.search(r"```json\n(.*?)```", text, re.S).group(1))
    assert project_to_dict(project_from_dict(copy.deepcopy(example))) == example


# -- saving ---------------------------------------------------------------------------------


def test_save_is_atomic_when_serialisation_fails(tmp_path, monkeypatch):
    path = tmp_path / "experiment3.json"
    path.write_text("previous contents\n", encoding="utf-8")
    real = json.dumps
    calls = []

    def failing(*args, **kwargs):
        calls.append(1)
        if len(calls) > 20:  # some of the file is already written
            raise RuntimeError("disk on fire")
        return real(*args, **kwargs)

    monkeypatch.setattr(project_module.json, "dumps", failing)
    with pytest.raises(RuntimeError, match="disk on fire"):
        save_project(project_from_dict(copy.deepcopy(WITH_RESULTS)), path)
    assert path.read_text(encoding="utf-8") == "previous contents\n"
    assert [f.name for f in tmp_path.iterdir()] == ["experiment3.json"]


def test_save_refuses_a_project_it_could_not_read_back(tmp_path):
    p = project_from_dict(copy.deepcopy(WITH_RESULTS))
    bad = Solution((), {}, 0.0, info={"when": object()})
    path = tmp_path / "experiment3.json"
    message = r"^experiment3\.json: results\.solutions\[0\]\.info\.when: cannot save a value"
    with pytest.raises(ProjectError, match=message):
        save_project(Project(p.name, p.scene, p.design, solutions=(bad,)), path)
    # A goal given twice is now refused by the design model itself, before any saving.
    goals = (*p.design.goals, Goal("match"))
    with pytest.raises(DesignError, match="goal names must be unique"):
        Design(p.design.sources, goals, target_sources=p.design.target_sources)
    assert not path.exists() and list(tmp_path.iterdir()) == []


def test_settings_validate_when_built_in_code():
    with pytest.raises(ProjectError, match=r"^method: expected one of 'auto', 'vns'"):
        OptimizerSettings(method="ga")
    with pytest.raises(
        ProjectError, match=r"^rays: expected an integer from 1 to 65,536, got true"
    ):
        OperatorSettings(rays=True)
    with pytest.raises(ProjectError, match=r"^give exactly one of"):
        SceneSpec()
    assert OptimizerSettings(divisors=[4, 1]).divisors == (4, 1)
    assert issubclass(ProjectError, LightInvError)


# -- errors ---------------------------------------------------------------------------------


def _set(path: str, value):
    """A mutation of valid(): set the value at a dotted path (``a.b[2].c``)."""

    def mutate(d):
        parts = re.findall(r"[^.\[\]]+", path)
        *head, last = [int(p) if p.isdigit() else p for p in parts]
        for p in head:
            d = d[p]
        if value is DELETE:
            del d[last]
        else:
            d[last] = value

    return mutate


DELETE = object()
KNOWN_SOURCE = (
    "known: name, zone, kind, rect, free, flux, exitance, flux_range, efficacy, filter, glazing, "
    "control_group"
)

ERRORS = [
    # top level and schema
    (_set("schema", DELETE), "missing required field 'schema' (is this a LightInv project file?)"),
    (_set("schema", 2), "unknown project schema 2; this version of LightInv reads schema 1"),
    (_set("schema", "1"), "schema: expected an integer, got string '1'"),
    (_set("schema", True), "schema: expected an integer, got true"),
    (_set("name", DELETE), "missing required field 'name'"),
    (_set("scene", DELETE), "missing required field 'scene'"),
    (_set("sources", DELETE), "missing required field 'sources'"),
    (_set("goals", DELETE), "missing required field 'goals'"),
    (_set("name", 7), "name: expected a string, got number 7"),
    (_set("descripton", "x"), "unknown field 'descripton' (known: schema, name, description,"),
    # wrong types
    (_set("sources[0].rect", [1, 2, 3]), "sources[0].rect: expected 4 numbers, got 3"),
    (_set("sources[0].rect[2]", "1"), "sources[0].rect[2]: expected a number, got string '1'"),
    (_set("sources[0].rect", 4), "sources[0].rect: expected a list of 4 numbers, got number 4"),
    (_set("sources[0].free", "u0"), "sources[0].free: expected a list of variables, got string"),
    (_set("sources", {}), "sources: expected a list of sources, got an object"),
    (
        _set("daylight.exterior_lux", True),
        "daylight.exterior_lux: expected a number >= 0 and <= 1000000, got true",
    ),
    (_set("operator.rays", True), "operator.rays: expected an integer from 1 to 65,536, got true"),
    (
        _set("operator.rays", 512.0),
        "operator.rays: expected an integer from 1 to 65,536, got number 512.0",
    ),
    (
        _set("operator.rays", 10_000_000),
        "operator.rays: expected an integer from 1 to 65,536, got 10000000",
    ),
    (_set("optimizer.trials", "16"), "optimizer.trials: expected an integer >= 1, got string '16'"),
    (
        _set("optimizer.divisors[1]", False),
        "optimizer.divisors[1]: expected an integer >= 1, got false",
    ),
    (
        _set("intentions[1].patches[1]", 2.5),
        "intentions[1].patches[1]: expected an integer >= 0, got number 2.5",
    ),
    (_set("penalty_power", True), "penalty_power: expected an integer >= 2, got true"),
    (_set("scene", "corridor"), "scene: expected an object, got string 'corridor'"),
    (
        _set("results.solutions[0].penalty", "lots"),
        "results.solutions[0].penalty: expected a number, got string 'lots'",
    ),
    (
        _set("results.solutions[0].x[0]", None),
        "results.solutions[0].x[0]: expected a number, got null",
    ),
    (
        _set("results.solutions[0].info", []),
        "results.solutions[0].info: expected an object, got an empty list",
    ),
    # unknown fields
    (
        _set("sources[0].rec", [0, 0, 1, 1]),
        f"sources[0]: unknown field 'rec' ({KNOWN_SOURCE}); did you mean 'rect'?",
    ),
    (
        _set("optimizer.max_eval", 10),
        "optimizer: unknown field 'max_eval' (known: method, seed, max_evals,",
    ),
    (
        _set("operator.tolerance", 0.1),
        "operator: unknown field 'tolerance' (known: tol, rank, rays, seed)",
    ),
    (
        _set("rules[0].maximum", 4),
        "rules[0]: unknown field 'maximum' (known: kind, sources, min, max, axis)",
    ),
    (
        _set("results.solutions[0].violations[0].amout", 1),
        "results.solutions[0].violations[0]: unknown field 'amout'",
    ),
    (
        _set("results.pareto.front", []),
        "results.pareto: unknown field 'front' (known: objectives, method, solutions, candidates)",
    ),
    (
        _set("results.solutions[0].violations[0].units", DELETE),
        "results.solutions[0].violations[0]: missing required field 'units'",
    ),
    # out of range
    (_set("operator.tol", 1.5), "operator.tol: expected a number > 0 and < 1, got 1.5"),
    (_set("operator.rank", 0), "operator.rank: expected an integer >= 1, got 0"),
    (
        _set("daylight.transmittance", 1.2),
        "daylight.transmittance: expected a number >= 0 and <= 1, got 1.2",
    ),
    (
        _set("intentions[0].uniformity", 2),
        "intentions[0].uniformity: expected a number >= 0 and <= 1, got 2",
    ),
    (_set("optimizer.seed", -1), "optimizer.seed: expected an integer >= 0, got -1"),
    (_set("optimizer.time_limit", 0), "optimizer.time_limit: expected a number > 0, got 0"),
    (
        _set("optimizer.divisors", []),
        "optimizer.divisors: expected at least 1 divisors (integers >= 1), got 0",
    ),
    (_set("optimizer.epsilons[0]", -5), "optimizer.epsilons[0]: expected a number >= 0, got -5"),
    (
        _set("optimizer.max_evals", 2**60),
        "optimizer.max_evals: expected an integer >= 1 of at most 2**53",
    ),
    (_set("scene.resolution", 0.001), "scene.resolution: expected a number >= 0.005, got 0.001"),
    (
        _set("sources[3].flux", -1),
        "sources[3].flux: expected a number >= 0 and <= 10000000000, got -1",
    ),
    (
        _set("sources[3].flux", 1e400),
        "sources[3].flux: expected a finite number >= 0 and <= 10000000000, got inf",
    ),
    (
        _set("sources[3].efficacy", 0),
        "sources[3].efficacy: expected a number > 0 and <= 683, got 0",
    ),
    (_set("sources[1].filter", 1.5), "sources[1].filter: expected a number >= 0 and <= 1, got 1.5"),
    (_set("penalty_power", 3), "penalty_power: expected an even integer >= 2, got 3"),
    (_set("sources[0].rect[0]", "inf"), "sources[0].rect[0]: expected a number, got string 'inf'"),
    # choices
    (
        _set("optimizer.method", "ga"),
        "optimizer.method: expected one of 'auto', 'vns', 'multilevel', 'cmaes', 'epsilon', "
        "'two_step', 'nsga2', got "
        "string 'ga'",
    ),
    (
        _set("sources[0].kind", "lamp"),
        "sources[0].kind: expected one of 'luminaire', 'skylight', 'window', got string 'lamp'",
    ),
    (
        _set("sources[0].free[0]", "w"),
        "sources[0].free[0]: expected one of 'u0', 'v0', 'u1', 'v1', 'flux', 'filter', got "
        "string 'w'",
    ),
    (
        _set("rules[0].kind", "size"),
        "rules[0].kind: expected one of 'area', 'aspect', 'mirror', 'centred', 'spacing', "
        "'align', 'shr', 'clearance', got string 'size'",
    ),
    (
        _set("goals[0].kind", "max_light"),
        "goals[0].kind: expected one of 'min_electric_power', 'max_light_power', 'match', "
        "'min_installed_power', 'min_luminaire_count', 'min_annual_energy', 'max_sda', "
        "'min_glazing_area', got string 'max_light'",
    ),
    (
        _set("intentions[0].quantity", "cd"),
        "intentions[0].quantity: expected one of 'lux', 'C', 'df', 'da', 'udi', 'sda', "
        "'ase', 'ugr', 'en17037', 'sunlight', 'cda', 'dgp', got string 'cd'",
    ),
    (_set("rules[2].axis", "x"), "rules[2].axis: expected one of 'u', 'v', got string 'x'"),
    (_set("results.pareto.objectives[0]", "cost"), "results.pareto.objectives[0]: expected one of"),
    (
        _set("results.solutions[0].objectives.cost", 1),
        "results.solutions[0].objectives: unknown goal 'cost'",
    ),
    # the scene
    (
        _set("scene.obj", "room.obj"),
        'scene: give exactly one of "builtin" (a built-in scene name) or "obj"',
    ),
    (_set("scene.builtin", DELETE), 'scene: give exactly one of "builtin"'),
    (
        _set("scene.builtin", "coridor"),
        "scene.builtin: expected one of 'cornell', 'office', 'patio', 'corridor', 'building', "
        "'sidelit', 'toplit', 'flagship', got string 'coridor'",
    ),
    (
        _set("scene", {"obj": "room.3ds"}),
        "scene.obj: expected the path of a model file (.obj, .gltf, .glb, .ply or .ifc), "
        "got 'room.3ds'",
    ),
    (
        _set("scene.scale", 0.001),
        "scene.scale: only an OBJ scene takes this; a built-in scene has its own",
    ),
    (
        _set("scene", {"obj": "room.obj", "up": "x"}),
        "scene.up: expected one of 'z', 'y', got string 'x'",
    ),
    # the design model's own rules, and references inside the file
    (
        _set("sources[3].flux", DELETE),
        "sources[3]: source 'L1': a free flux needs a starting flux",
    ),
    (
        _set("sources[3].flux_range", [5, 5]),
        "sources[3]: source 'L1': flux range must satisfy 0 <= min < max",
    ),
    (_set("rules[0].min", 5), "rules[0]: rule 'area' on ['S1']: min 5.0 is larger than max 4.0"),
    (
        _set("rules[1].max", 0.5),
        "rules[1]: rule 'aspect' on ['S1', 'S2']: max aspect ratio must be at least 1, got 0.5",
    ),
    (_set("rules[3].sources", []), "rules[3].sources: expected at least 1 source names, got 0"),
    (
        _set("rules[4].sources", ["L1"]),
        "rules[4]: rule 'spacing' on ['L1']: needs exactly 2 sources",
    ),
    (
        _set("intentions[1].group", "desks"),
        "intentions[1]: intention 'picked': give one of a group, a list of patches, a "
        "work-plane grid or observers",
    ),
    (
        _set("intentions[0].max", 400),
        "intentions[0]: intention 'panels': average 500.0 is above max 400.0",
    ),
    (
        _set("rules[0].sources[0]", "S9"),
        "rules[0].sources[0]: no source 'S9' (sources: S1, S2, S3, L1, L2, P2)",
    ),
    (_set("rules[5].sources[2]", "S1"), "rules[5].sources[2]: 'S1' is listed twice"),
    (
        _set("rules[0].axis", "u"),
        "rules[0].axis: area rules do not take 'axis' (they take: sources, min, max)",
    ),
    (
        _set("rules[4].max", 3),
        "rules[4].max: spacing rules do not take 'max' (they take: sources, min)",
    ),
    (
        _set("rules[3]", {"kind": "mirror", "sources": ["S3", "S2"], "axis": "v"}),
        "rules[3].sources[0]: 'S3' already mirrors another source (rules[2])",
    ),
    (_set("sources[1].name", "S1"), "sources[1].name: 'S1' is already used by sources[0]"),
    (
        _set("intentions[1].name", "panels"),
        "intentions[1].name: 'panels' is already used by intentions[0]",
    ),
    (
        _set("goals[2]", {"kind": "max_light_power"}),
        "goals[2].kind: 'max_light_power' is already a goal (goals[0])",
    ),
    (_set("goals", []), "goals: expected at least 1 goals, got 0"),
    (
        _set("target_sources", []),
        "goals[2]: a match goal needs target_sources (the light to reproduce)",
    ),
    (
        _set("goals[1].kinds", ["luminaire"]),
        "goals[1].kinds: only a max_light_power goal takes source kinds",
    ),
    (
        _set("goals[0].kinds[0]", "skylights"),
        "goals[0].kinds[0]: expected one of 'luminaire', 'skylight', 'window', got string "
        "'skylights'",
    ),
    (_set("sources[0].free[1]", "u0"), "sources[0].free[1]: 'u0' is listed twice"),
    (
        _set("sources[0].efficacy", 80),
        "sources[0].efficacy: only luminaires have this (a skylight's own fields: filter, glazing)",
    ),
    (
        _set("sources[3].filter", 0.5),
        "sources[3].filter: only skylights or windows have this "
        "(a luminaire's own fields: flux, flux_range, exitance, efficacy, control_group)",
    ),
    (
        _set("sources[3].exitance", 100),
        "sources[3]: source 'L1': give its flux (lm) or its exitance (lm/m²), not both",
    ),
    (
        _set("target_sources[0].rect", [0, 0, 1]),
        "target_sources[0].rect: expected 4 numbers, got 3",
    ),
    (
        _set("results.solutions[0].sources[0].zone", ""),
        "results.solutions[0].sources[0].zone: expected a non-empty string",
    ),
]


@pytest.mark.parametrize(("mutate", "message"), ERRORS, ids=[m for _, m in ERRORS])
def test_every_bad_value_names_its_json_path(tmp_path, mutate, message):
    data = valid()
    mutate(data)
    with pytest.raises(ProjectError) as info:
        project_from_dict(copy.deepcopy(data))
    assert str(info.value).startswith(message), str(info.value)
    path = tmp_path / "experiment3.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(ProjectError) as info:
        load_project(path)
    assert str(info.value).startswith(f"experiment3.json: {message}"), str(info.value)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('{"schema": 1,\n  "name": "x",,\n}', r"invalid JSON at line 2, column 15: Expecting"),
        ("", r"invalid JSON at line 1, column 1: Expecting value"),
        ('["schema", 1]', r"expected a JSON object at the top level, got a list of 2"),
        ('{"schema": 1, "schema": 2}', r"unknown project schema 2"),
        ('{"schema": 2, "anything": "goes"}', r"unknown project schema 2; this version of"),
        ('{"schema": 1, "name": "a", "name": "b"}', r"field 'name' is given twice"),
        (
            json.dumps(valid()).replace(
                '"exterior_lux": 12000', '"exterior_lux": 1, "exterior_lux": 2'
            ),
            r"daylight: field 'exterior_lux' is given twice",
        ),
        (
            json.dumps(valid()).replace('"flux": 2000', '"flux": NaN'),
            r"sources\[3\]\.flux: expected a finite number >= 0 and <= 10000000000, got nan",
        ),
        ('{"schema": 1' + "0" * 5000 + "}", r"invalid JSON: a number has too many digits$"),
        ("[" * 100_000, r"invalid JSON: nested too deeply$"),
    ],
)
def test_bad_json_text(tmp_path, text, message):
    path = tmp_path / "experiment3.json"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ProjectError, match=r"^experiment3\.json: " + message):
        load_project(path)


def test_a_byte_order_mark_is_accepted(tmp_path):
    path = tmp_path / "bom.json"
    path.write_text("\ufeff" + json.dumps(VALID), encoding="utf-8")
    assert load_project(path).name == "corridor study"


def test_unreadable_files(tmp_path):
    with pytest.raises(ProjectError, match=r"^missing\.json: no such file \(.*missing\.json\)$"):
        load_project(tmp_path / "missing.json")
    (tmp_path / "folder.json").mkdir()
    with pytest.raises(ProjectError, match=r"^folder\.json: is a folder, not a project file"):
        load_project(tmp_path / "folder.json")
    (tmp_path / "binary.json").write_bytes(b'{"name": "\xff\xfe"}')
    with pytest.raises(ProjectError, match=r"^binary\.json: not a UTF-8 text file"):
        load_project(tmp_path / "binary.json")


def test_nothing_is_checked_against_the_scene_when_loading():
    data = valid()
    data["sources"][0]["zone"] = "no such zone"
    data["intentions"][0]["group"] = "no such group"
    data["intentions"][1]["patches"] = [10**9]
    p = project_from_dict(data)
    assert p.design.sources[0].zone == "no such zone"


# -- fuzzing --------------------------------------------------------------------------------

JSON_VALUES = st.recursive(
    st.none()
    | st.booleans()
    | st.integers()
    | st.floats()
    | st.text(max_size=6)
    | st.sampled_from(["inf", "nan", "u0", "lux", "skylight", "luminaire", "area", "S1", "x.obj"]),
    lambda inner: (
        st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=3)
    ),
    max_leaves=6,
)


def _slots(node, out):
    """Every (container, key) in a JSON tree."""
    keys = list(node) if isinstance(node, dict) else range(len(node))
    for k in keys:
        out.append((node, k))
        if isinstance(node[k], dict | list):
            _slots(node[k], out)
    return out


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_fuzz_mutated_projects_raise_only_project_error(data):
    d = valid()
    for _ in range(data.draw(st.integers(1, 3), label="mutations")):
        slots = _slots(d, [])
        node, key = data.draw(st.sampled_from(slots), label="where")
        action = data.draw(st.sampled_from(["delete", "replace", "add"]), label="action")
        if action == "delete":
            del node[key]
        elif action == "replace":
            node[key] = data.draw(JSON_VALUES, label="value")
        elif isinstance(node, dict):
            node[data.draw(st.text(max_size=8), label="new key")] = data.draw(JSON_VALUES)
        else:
            node.insert(key, data.draw(JSON_VALUES, label="new item"))
    try:
        p = project_from_dict(d)
    except ProjectError:
        return
    # Whatever loads also saves and loads back to the same data.
    out = project_to_dict(p)
    assert project_to_dict(project_from_dict(out)) == out


# -- new emitter zones drawn on the scene ---------------------------------------------------

# Corridor ceiling coordinates: u = x, v = 4 - y; S1 covers u 5..11, v 1..3.
ZONES = [
    {"name": "Z1", "kind": "luminaire", "surface": "ceiling", "rect": [0.5, 1, 2.5, 3]},
    {"name": "Z2", "kind": "skylight", "surface": "ceiling", "rect": [12, 1.5, 14, 2.5]},
]


def _with_zones(zones=ZONES) -> dict:
    data = valid()
    data["scene"] = {**data["scene"], "zones": copy.deepcopy(zones)}
    return data


def test_scene_zones_round_trip_and_load(tmp_path):
    data = _with_zones()
    p = project_from_dict(copy.deepcopy(data))
    assert p.scene.zones[0] == ZoneEdit("Z1", "luminaire", "ceiling", (0.5, 1.0, 2.5, 3.0))
    assert project_to_dict(p) == data
    assert "zones" not in project_to_dict(project_from_dict(valid()))["scene"]
    save_project(p, tmp_path / "zones.json")
    text = (tmp_path / "zones.json").read_text(encoding="utf-8")
    assert '"rect": [0.5, 1, 2.5, 3]' in text
    q = load_project(tmp_path / "zones.json")
    assert q.scene == p.scene and project_to_dict(q) == data
    scene = q.scene.load()
    assert [z.name for z in scene.zones][-2:] == ["Z1", "Z2"]
    assert scene.zone("Z2").kind == "skylight"
    assert scene.zone_rect("Z1").size == pytest.approx((2.0, 2.0))
    assert scene.area == pytest.approx(SceneSpec(builtin="corridor", resolution=0.5).load().area)


def test_scene_zones_in_code_and_corners_in_any_order():
    edit = ZoneEdit("Z1", "luminaire", "ceiling", (2.5, 3, 0.5, 1))
    spec = SceneSpec(builtin="corridor", resolution=0.5, zones=[edit])
    assert spec.zones == (ZoneEdit("Z1", "luminaire", "ceiling", (0.5, 1, 2.5, 3)),)
    assert SceneSpec(builtin="corridor", zones=[dict(ZONES[0])]).zones[0] == spec.zones[0]


def test_a_zone_that_does_not_fit_the_scene_fails_on_loading_the_scene():
    bad = [{"name": "Z1", "kind": "luminaire", "surface": "ceiling", "rect": [4, 1, 7, 2]}]
    spec = project_from_dict(_with_zones(bad)).scene  # not checked against the scene here
    with pytest.raises(SceneError, match=r"zone 'Z1' on surface 'ceiling'.*overlaps.*'S1'"):
        spec.load()


BOWTIE = [[4, 5.5], [8, 7], [8, 5.5], [4, 7]]

ZONE_ERRORS = [
    ("x", "scene.zones: expected a list of zone objects, got string 'x'"),
    ([7], "scene.zones[0]: expected an object, got number 7"),
    ([{**ZONES[0], "colour": 1}], "scene.zones[0]: unknown field 'colour' (known: name, kind,"),
    ([{**ZONES[0], "nam": 1}], "scene.zones[0]: unknown field 'nam'"),
    (
        [{"name": "Z1", "kind": "luminaire", "surface": "c"}],
        "scene.zones[0].rect: new emitter zone 'Z1' on surface 'c': give its rectangle (rect) "
        "or its outline",
    ),
    (
        [{**ZONES[0], "outline": [[4, 5.5], [8, 5.5]]}],
        "scene.zones[0].outline: expected a list of at least 3 [u, v] corners",
    ),
    (
        [{**ZONES[0], "outline": [[4, 5.5], [8, 5.5], [8]]}],
        "scene.zones[0].outline[2]: expected 2 numbers, got 1",
    ),
    (
        [{"name": "Z1", "kind": "luminaire", "surface": "ceiling", "outline": BOWTIE}],
        "scene.zones[0].outline: new emitter zone 'Z1' on surface 'ceiling': the outline "
        "crosses itself (edges 1 and 3)",
    ),
    (
        [{**ZONES[0], "outline": [[4, 5.5], [8, 5.5], [6, 7]]}],
        "scene.zones[0].outline: new emitter zone 'Z1' on surface 'ceiling': rect (0.5, 1, 2.5, "
        "3) is not the bounding rectangle of the outline, (4, 5.5, 8, 7)",
    ),
    (
        [ZONES[0], {**ZONES[1], "kind": "lamp"}],
        "scene.zones[1].kind: expected one of 'luminaire', 'skylight'",
    ),
    ([{**ZONES[0], "name": ""}], "scene.zones[0].name: expected a non-empty string"),
    ([{**ZONES[0], "surface": 3}], "scene.zones[0].surface: expected a string, got number 3"),
    ([{**ZONES[0], "rect": [1, 2, 3]}], "scene.zones[0].rect: expected 4 numbers, got 3"),
    ([{**ZONES[0], "rect": [1, 2, "3", 4]}], "scene.zones[0].rect[2]: expected a number"),
    ([{**ZONES[0], "rect": [1, 2, 1, 4]}], "scene.zones[0].rect: new emitter zone 'Z1' on"),
    ([ZONES[0], ZONES[0]], "scene.zones[1]: 'Z1' is listed twice"),
]


@pytest.mark.parametrize(("zones", "message"), ZONE_ERRORS, ids=[m for _, m in ZONE_ERRORS])
def test_bad_scene_zones_name_their_json_path(tmp_path, zones, message):
    data = _with_zones(zones)
    with pytest.raises(ProjectError) as info:
        project_from_dict(copy.deepcopy(data))
    assert str(info.value).startswith(message), str(info.value)
    path = tmp_path / "zones.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(ProjectError, match=r"^zones\.json: " + re.escape(message)):
        load_project(path)


# -- the run history (results.runs) ---------------------------------------------------------

RUN = {
    "number": 2,
    "method": "vns",
    "time": "2026-11-25T14:03:12",
    "seeds": [0, 1],
    "goals": ["min_electric_power"],
    "status": "feasible",
    "evaluations": 12000,
    "seconds": 3.5,
    "solutions": [{**SOLUTION, "penalty": 0.25, "violations": []}],
}


def _with_runs(*runs) -> dict:
    data = valid()
    data["results"]["runs"] = [copy.deepcopy(r) for r in runs]
    return data


def test_the_run_history_round_trips_and_older_files_read_without_it(tmp_path):
    front = {"pareto": copy.deepcopy(RESULTS["pareto"]), "solutions": []}
    data = _with_runs({**RUN, "number": 1, "settings": {"method": "epsilon"}, **front}, RUN)
    p = project_from_dict(copy.deepcopy(data))
    assert [r.number for r in p.runs] == [1, 2]
    first, second = p.runs
    assert first.settings.method == "epsilon" and len(first.pareto.candidates) == 2
    assert second.settings == OptimizerSettings() and second.seeds == (0, 1)
    assert second.seconds == 3.5 and second.solutions[0].penalty == 0.25
    assert second.results() == second.solutions and first.results() == first.pareto.candidates
    path = tmp_path / "history.json"
    save_project(p, path)
    again = load_project(path)
    assert project_to_dict(again) == project_to_dict(p)
    assert json.loads(path.read_text())["results"]["runs"][1]["time"] == "2026-11-25T14:03:12"
    # A file of before the history has no runs, and none are written back.
    old = project_from_dict(copy.deepcopy(WITH_RESULTS))
    assert old.runs == () and "runs" not in project_to_dict(old)["results"]
    # Runs alone are saved too (a project whose results are all in its history).
    only = dataclasses.replace(project_from_dict(copy.deepcopy(VALID)), runs=p.runs)
    assert project_to_dict(only)["results"] == {
        "solutions": [],
        "pareto": None,
        "runs": project_to_dict(p)["results"]["runs"],
    }


RUN_ERRORS = [
    ({**RUN, "number": 0}, "results.runs[0].number: expected an integer >= 1, got 0"),
    ({**RUN, "method": ""}, "results.runs[0].method: expected a non-empty string"),
    ({**RUN, "settings": {"method": "ga"}}, "results.runs[0].settings.method: expected one of"),
    ({**RUN, "seeds": [1.5]}, "results.runs[0].seeds[0]: expected an integer"),
    ({**RUN, "goals": ["cost"]}, "results.runs[0].goals[0]: expected one of"),
    ({**RUN, "seconds": -1}, "results.runs[0].seconds: expected a number >= 0, got -1"),
    ({**RUN, "best": 1}, "results.runs[0]: unknown field 'best'"),
    ({"method": "vns"}, "results.runs[0]: missing required field 'number'"),
]


@pytest.mark.parametrize(("run", "message"), RUN_ERRORS, ids=[m for _, m in RUN_ERRORS])
def test_bad_runs_name_their_json_path(run, message):
    with pytest.raises(ProjectError) as info:
        project_from_dict(_with_runs(run))
    assert str(info.value).startswith(message), str(info.value)


def test_a_run_listed_twice_is_refused():
    with pytest.raises(ProjectError, match=r"^results\.runs\[1\]\.number: run 2 is listed twice"):
        project_from_dict(_with_runs(RUN, RUN))


def test_imported_models_are_reused_until_their_files_change(tmp_path):
    """A zone drawn on an imported building re-imported the file (9 s for an IFC house):
    the imported scene is kept, and taken again only when the model, its ``.mtl``
    library or the materials file changes."""
    import os

    from lightinv_core.project.scene import model_scene

    obj = tmp_path / "room.obj"
    obj.write_text(
        "mtllib room.mtl\nv 0 0 0\nv 4 0 0\nv 4 3 0\nv 0 3 0\nusemtl floor\nf 1 2 3 4\n"
        "v 0 0 2.5\nv 0 3 2.5\nv 4 3 2.5\nv 4 0 2.5\nusemtl ceiling\nf 5 6 7 8\n"
    )
    mtl = tmp_path / "room.mtl"
    mtl.write_text("newmtl floor\nKd 0.2 0.2 0.2\nnewmtl ceiling\nKd 0.8 0.8 0.8\n")
    first = model_scene(str(obj), 0.5)
    assert model_scene(str(obj), 0.5) is first
    assert model_scene(str(obj), 1.0) is not first  # another resolution
    floor = next(s for s in first.surfaces if s.group.startswith("floor"))
    mtl.write_text("newmtl floor\nKd 0.9 0.9 0.9\nnewmtl ceiling\nKd 0.8 0.8 0.8\n")
    os.utime(mtl, ns=(1, 1))  # a different stamp even within the clock's resolution
    again = model_scene(str(obj), 0.5)
    assert again is not first
    refl = next(s for s in again.surfaces if s.group == floor.group).reflectance
    assert refl == pytest.approx(0.9, abs=0.01) and floor.reflectance == pytest.approx(0.2)
