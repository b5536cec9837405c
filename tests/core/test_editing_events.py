"""What the editing model's events carry: one frozen payload per event, with the new
state of what changed (the design and which of its fields, the selection, the light
shown, the file state, the results), checked against the model after each edit."""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import fields, replace

import numpy as np
import pytest

from lightinv_core.design.model import Design, Goal, Intention, Workplane
from lightinv_core.design.solution import SolutionInfo
from lightinv_core.editing import (
    EVENT_TYPES,
    DesignChanged,
    DocumentModel,
    LightingChanged,
    OperatorChanged,
    PathChanged,
    ResultsChanged,
    SceneChanged,
    SelectionChanged,
    blank_project,
)
from lightinv_core.editing.changes import CURRENT_SOURCE, design_changes
from lightinv_core.editing.results import ALL
from lightinv_core.kinds import GoalKind
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.settings import OptimizerSettings

RESOLUTION = 0.7  # the office at 0.7 m: an operator in a fraction of a second
STRIP = (4.0, 5.5, 8.0, 7.0)  # a free strip of the office ceiling (see test_editing.py)
EVERY_FIELD = frozenset(f.name for f in fields(Design)) | {CURRENT_SOURCE}


class Payloads:
    """The payloads a model's events carried, by event name, in order."""

    def __init__(self, model: DocumentModel):
        self.by_name: dict[str, list] = {name: [] for name in EVENT_TYPES}
        for name in EVENT_TYPES:
            model.events.connect(name, functools.partial(self._record, name))

    def _record(self, name: str, payload) -> None:
        self.by_name[name].append(payload)

    def one(self, name: str):
        """The only payload event ``name`` carried since the last ``clear``."""
        (payload,) = self.by_name[name]
        return payload

    def clear(self) -> None:
        for seen in self.by_name.values():
            seen.clear()


@pytest.fixture(scope="module")
def office_operator():
    model = DocumentModel()
    model.set_project(blank_project("office", RESOLUTION))
    return build_operator(model.patches, OperatorSettings(rank=100, rays=128))


@pytest.fixture
def doc():
    model = DocumentModel()
    model.set_project(blank_project("office", RESOLUTION))
    return model


@pytest.fixture
def lit(doc, office_operator):
    doc.set_operator(office_operator)
    return doc


def test_each_event_has_its_frozen_payload_type():
    assert {
        "scene": SceneChanged,
        "operator": OperatorChanged,
        "design": DesignChanged,
        "selection": SelectionChanged,
        "lighting": LightingChanged,
        "path": PathChanged,
        "results": ResultsChanged,
    } == EVENT_TYPES
    for kind in EVENT_TYPES.values():
        assert dataclasses.is_dataclass(kind) and kind.__dataclass_params__.frozen


def test_opening_a_project_announces_all_of_it():
    model, project = DocumentModel(), blank_project("cornell", 0.3)
    seen = Payloads(model)
    model.set_project(project)
    scene = seen.one("scene")
    assert scene.scene is model.scene and scene.patches is model.patches
    assert not scene.rebuilt
    design = seen.one("design")
    assert design.design is project.design and design.current_source is None
    assert design.changed == EVERY_FIELD and design.label == ""
    assert seen.one("selection").patches.shape == (0,)
    path = seen.one("path")
    assert path == PathChanged(None, False, project.name, project.optimizer)
    assert seen.one("results") == ResultsChanged((), (), None, ALL, None)
    with pytest.raises(dataclasses.FrozenInstanceError):
        design.label = "changed"


def test_a_design_edit_says_which_fields_changed_and_its_name(lit):
    seen = Payloads(lit)
    src = lit.add_source("lum_west")
    added = seen.one("design")
    assert added.design is lit.design and added.current_source == src.name == "L1"
    assert added.changed == {"sources", CURRENT_SOURCE} and added.label == "add source L1"
    seen.clear()
    lit.update_source("L1", flux=1234.0)
    assert seen.one("design").changed == {"sources"}
    seen.clear()
    lit.set_goal(GoalKind.MAX_LIGHT_POWER, True)
    assert seen.one("design").changed == {"goals"}
    seen.clear()
    lit.add_source("lum_east")
    lit.set_current_source("L1")
    chosen = seen.by_name["design"][-1]
    assert chosen.changed == {CURRENT_SOURCE} and chosen.current_source == "L1"
    assert chosen.label == ""  # choosing what to edit is not an edit


def test_removing_a_work_plane_names_every_field_it_changed(lit):
    lit.set_workplanes((Workplane("wp"),))
    lit.add_intention(Intention("desks", grid="wp", average=300.0))
    seen = Payloads(lit)
    lit.set_workplanes((), "remove work plane wp")
    design = seen.one("design")
    assert design.changed == {"workplanes", "intentions"}  # its intention goes with it
    assert design.label == "remove work plane wp" and design.design.intentions == ()


def test_undo_announces_the_fields_it_took_back(lit):
    edits = []
    lit.on_edit = lambda label, before, after: edits.append(before)
    lit.add_source("lum_west")
    lit.add_intention(Intention("desks", "desks", average=300.0))
    seen = Payloads(lit)
    lit.restore(edits[0])  # before the source was added
    design = seen.one("design")
    assert design.design is lit.design and design.label == ""
    assert design.changed == {"sources", "intentions", CURRENT_SOURCE}
    assert design.current_source is None
    # Back to the project as opened (issue #29: undoing every edit leaves it clean).
    assert seen.one("results").runs == lit.runs and not seen.one("path").dirty
    lit.restore(edits[1])  # redo the source: unsaved again
    assert lit.dirty


def test_the_selection_payload_is_a_read_only_copy(doc):
    seen = Payloads(doc)
    doc.set_selection([9, 2, 2, 5])
    picked = seen.one("selection").patches
    assert picked.tolist() == [2, 5, 9] and picked.dtype == np.int64
    assert not np.shares_memory(picked, doc.selection)
    with pytest.raises(ValueError, match="read-only"):
        picked[0] = 1


def test_the_operator_and_the_light_shown_come_with_their_events(doc, office_operator):
    seen = Payloads(doc)
    doc.set_operator(office_operator)
    op = seen.one("operator")
    assert op.operator is office_operator and op.light is doc.light
    light = seen.one("lighting")
    assert light.field is doc.field and not light.previewing
    assert light.eval_ms == doc.last_eval_ms >= 0.0
    doc.add_source("lum_west")
    seen.clear()
    best = (replace(doc.design.sources[0], flux=500.0),)
    doc.set_preview(best)
    shown = seen.one("lighting")
    assert shown.previewing and shown.field is doc.field
    assert shown.field.illuminance.sum() < doc.design_field().illuminance.sum()


def test_the_file_state_carries_path_dirty_flag_and_run_settings(lit, tmp_path):
    seen = Payloads(lit)
    lit.set_optimizer(seed=7)
    edited = seen.one("path")
    assert edited.dirty and edited.optimizer.seed == 7 and edited.path is None
    seen.clear()
    path = lit.save(tmp_path / "office.json")
    assert seen.one("path") == PathChanged(path, False, lit.project.name, lit.project.optimizer)


def test_the_results_payload_follows_runs_browsing_and_pins(lit):
    lit.add_source("lum_west")
    problem = lit.problem()
    s0 = problem.solution(problem.vars.initial(), SolutionInfo(seed=0))
    seen = Payloads(lit)
    run = lit.add_run((s0,), None, settings=OptimizerSettings(method="vns"))
    kept = seen.one("results")
    assert kept.runs == (run,) and kept.browsed_run == run.number == 1
    assert kept.saved == () and kept.saved_front is None and kept.shown is None
    seen.clear()
    lit.apply_solution(s0)
    assert seen.one("results").shown is s0
    seen.clear()
    pinned = lit.pin(s0)
    assert seen.one("results").shown is pinned and pinned.info.pinned
    seen.clear()
    lit.browse_run(ALL)
    assert seen.one("results").browsed_run is ALL


def test_a_drawn_zone_rebuilds_the_scene_and_says_so(doc):
    seen = Payloads(doc)
    doc.add_user_zone("Z1", "luminaire", "ceiling", STRIP)
    scene = seen.one("scene")
    assert scene.rebuilt and scene.scene is doc.scene
    assert "Z1" in {z.name for z in scene.scene.zones}
    assert seen.one("design").changed == set()  # no source was in a zone that went
    assert seen.by_name["path"][-1].dirty


def test_design_changes_compare_by_identity_then_value():
    a = Design((), (Goal(GoalKind.MIN_ELECTRIC_POWER),))
    b = replace(a, penalty_power=4)
    assert design_changes(None, a) == {f.name for f in fields(Design)}
    assert design_changes(a, b) == {"penalty_power"}
    assert design_changes(a, replace(a, rules=())) == set()  # equal, not the same object
