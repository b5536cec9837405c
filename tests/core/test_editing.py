"""The editing model without a display: every editing rule, the events it fires, and the
light it shows, checked against an independent ``LightModel`` of the same scene."""

from __future__ import annotations

import functools
import itertools
from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.design.model import Design, Goal, Intention, Rule, Source
from lightinv_core.design.solution import ParetoFront, Solution, SolutionInfo
from lightinv_core.editing import (
    EVENTS,
    DesignChanged,
    DocumentModel,
    Events,
    blank_project,
    result_label,
)
from lightinv_core.editing import rules as edit_rules
from lightinv_core.editing.results import ALL, run_label
from lightinv_core.errors import DesignError, LightInvError
from lightinv_core.kinds import GoalKind, RuleKind, SourceKind
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.project import ProjectError, load_project
from lightinv_core.scene.edits import ZoneEdit

RESOLUTION = 0.7  # office at 0.7 m: ~670 patches, an operator in a fraction of a second
# A free strip of the office ceiling between the skylight and the north wall (u = x,
# v = 8 - y in the ceiling's coordinates): see docs/obj-import.md and scene/edits.py.
STRIP = (4.0, 5.5, 8.0, 7.0)


@pytest.fixture(scope="module")
def office_operator():
    """The office's operator, built once for the module (the patches mesh the same way
    every time, so each test's fresh model accepts it)."""
    model = DocumentModel()
    model.set_project(blank_project("office", RESOLUTION))
    return build_operator(model.patches, OperatorSettings(rank=100, rays=128))


class Recorder:
    """Every event a model emits, in order, and the payloads they carried."""

    def __init__(self, model: DocumentModel):
        self.seen: list[str] = []
        self.payloads: list[object] = []
        for name in EVENTS:
            model.events.connect(name, functools.partial(self._record, name))

    def _record(self, name: str, payload: object) -> None:
        self.seen.append(name)
        self.payloads.append(payload)

    def take(self) -> list[str]:
        seen, self.seen, self.payloads = self.seen, [], []
        return seen

    def last(self, name: str):
        """The payload event ``name`` last carried since the last ``take``."""
        return [p for n, p in zip(self.seen, self.payloads, strict=True) if n == name][-1]


@pytest.fixture
def doc():
    """A fresh model on a blank office project, no operator yet."""
    model = DocumentModel()
    model.set_project(blank_project("office", RESOLUTION))
    return model


@pytest.fixture
def lit(doc, office_operator):
    """``doc`` with its operator: lighting available."""
    doc.set_operator(office_operator)
    return doc


def reference(model: DocumentModel) -> LightModel:
    """A light model of the same scene built apart from the editing model's."""
    return LightModel(model.scene, model.patches, model.operator)


# -- events ---------------------------------------------------------------------------------
def test_events_call_back_in_order_and_refuse_unknown_names():
    events, calls = Events(), []
    first, second = (lambda p: calls.append((1, p))), (lambda p: calls.append((2, p)))
    events.connect("design", first)
    events.connect("design", second)
    change = DesignChanged(Design((), (Goal("min_electric_power"),)), None, frozenset())
    events.emit("design", change)
    events.disconnect("design", first)
    events.emit("design", change)
    assert calls == [(1, change), (2, change), (2, change)] and events.counts["design"] == 2
    with pytest.raises(KeyError, match="unknown event 'desing'"):
        events.connect("desing", first)
    with pytest.raises(KeyError):
        events.emit("nothing", change)
    # Each event carries its own payload type: a view relies on it.
    with pytest.raises(TypeError, match="'selection' carries a SelectionChanged"):
        events.emit("selection", change)
    assert events.counts["selection"] == 0 and events.payload_type("design") is DesignChanged


def test_opening_a_project_resets_everything_and_says_so(doc):
    rec = Recorder(doc)
    doc.set_selection([5, 3, 3])
    assert list(doc.selection) == [3, 5] and rec.take() == ["selection"]
    project = replace(blank_project("cornell", 0.3), name="c")
    doc.set_project(project)
    assert rec.take() == ["scene", "design", "selection", "path", "results"]
    assert doc.project is project and doc.scene.name == "cornell" and not doc.dirty
    assert doc.operator is None and doc.light is None and len(doc.selection) == 0
    assert doc.lighting() is None and doc.field is None and doc.problem() is None
    assert doc.effective_sources() == () and doc.current_source is None
    assert doc.zone_size("light") == pytest.approx((0.5, 0.5), abs=0.05)


# -- sources and their rules ----------------------------------------------------------------
def test_new_sources_are_centred_named_and_current(lit):
    rec = Recorder(lit)
    lum = lit.add_source("lum_west")
    assert rec.take() == ["design", "lighting"] and lit.dirty
    assert lum.name == "L1" and lum.kind == SourceKind.LUMINAIRE and lum.flux == 3000.0
    w, h = lit.zone_size("lum_west")
    assert lum.rect == pytest.approx(((w - 1) / 2, (h - 1) / 2, (w + 1) / 2, (h + 1) / 2))
    assert lum.free == ("u0", "v0", "u1", "v1", "flux")  # a least-power run may dim it
    sky = lit.add_source("skylight")
    assert sky.name == "S1" and sky.kind == SourceKind.SKYLIGHT and sky.filter == 1.0
    assert sky.free == ("u0", "v0", "u1", "v1", "filter")
    assert lit.current_source == "S1"
    assert lit.add_source("lum_east").name == "L2"
    lit.set_current_source("L1")
    assert lit.current_source == "L1" and rec.take()[-1] == "design"


def test_moving_keeps_a_source_in_its_zone_and_a_bad_edit_changes_nothing(lit):
    s = lit.add_source("lum_west")
    w = lit.zone_size("lum_west")[0]
    lit.move_source(s.name, 100.0, -100.0)  # far past the zone's edges: clipped
    (u0, v0, u1, _) = lit.design.source(s.name).rect
    assert (u1, v0) == pytest.approx((w, 0.0)) and u1 - u0 == pytest.approx(1.0)
    before = lit.project
    with pytest.raises(LightInvError):
        lit.update_source(s.name, flux=-5.0)
    with pytest.raises(DesignError):
        lit.update_source("nobody", flux=10.0)
    assert lit.project is before


def test_removing_a_source_removes_the_rules_that_name_it(lit):
    a = lit.add_source("lum_west")
    b = lit.add_source("lum_east")
    c = lit.add_source("skylight")
    lit.set_mirror(b.name, a.name, "u")
    lit.set_centred(a.name, True)
    lit.set_centred(c.name, True)
    assert len(lit.design.rules) == 3
    lit.set_current_source(a.name)
    lit.remove_source(a.name)
    assert [s.name for s in lit.design.sources] == [b.name, c.name]
    assert lit.design.rules == (Rule(RuleKind.CENTRED, (c.name,)),)
    assert lit.current_source == b.name  # the removed one was current
    lit.remove_source(c.name)
    assert lit.design.rules == () and lit.current_source == b.name


def test_mirror_and_centred_rules_place_the_sources_as_lit(lit):
    a = lit.add_source("lum_west")
    b = lit.add_source("lum_east")
    lit.update_source(a.name, rect=(0.2, 1.0, 0.8, 2.0))
    lit.set_mirror(b.name, a.name)
    assert lit.mirror_of(b.name) == (a.name, "u") and lit.mirror_of(a.name) is None
    east = {s.name: s for s in lit.effective_sources()}[b.name]
    w = lit.zone_size("lum_east")[0]
    assert east.u_range == pytest.approx((w - 0.8, w - 0.2)) and east.flux == a.flux
    # Replacing the mirror keeps one rule; None frees the source again.
    lit.set_mirror(b.name, a.name, "v")
    assert lit.mirror_of(b.name) == (a.name, "v") and len(lit.design.rules) == 1
    lit.set_mirror(b.name, None)
    assert lit.mirror_of(b.name) is None and lit.design.rules == ()
    lit.set_centred(a.name, True)
    assert lit.centred(a.name) and not lit.centred(b.name)
    (u0, v0, u1, v1) = lit.effective_sources()[0].rect
    zw, zh = lit.zone_size("lum_west")
    assert (u0 + u1, v0 + v1) == pytest.approx((zw, zh))  # centred in its zone
    lit.set_centred(a.name, False)
    assert not lit.centred(a.name) and lit.design.rules == ()


def test_intentions_goals_and_run_settings(doc):
    rec = Recorder(doc)
    doc.add_intention(Intention("desks", group="desks", min=300.0))
    doc.add_intention(Intention("floor", group="floor", max=800.0))
    with pytest.raises(DesignError):
        doc.add_intention(Intention("desks", group="floor", min=1.0))  # name taken
    doc.remove_intention("desks")
    assert [i.name for i in doc.design.intentions] == ["floor"]
    assert rec.take() == ["design"] * 3  # no operator: nothing to relight
    doc.set_primary_goal(GoalKind.MAX_LIGHT_POWER)
    assert [g.kind for g in doc.design.goals] == ["max_light_power", "min_electric_power"]
    doc.set_primary_goal(GoalKind.MAX_LIGHT_POWER)  # already first: no edit
    assert rec.take() == ["design"]
    doc.dirty = False
    doc.set_optimizer(max_evals=500, seed=3)
    assert doc.project.optimizer.max_evals == 500 and doc.dirty and rec.take() == ["path"]
    doc.set_optimizer(max_evals=500)  # unchanged: not an edit
    assert rec.take() == []
    before = doc.project
    with pytest.raises(ProjectError):
        doc.set_optimizer(max_evals=-1)
    assert doc.project is before


# -- drawn zones ----------------------------------------------------------------------------
def test_drawn_zones_rebuild_the_scene_and_take_their_sources_with_them(lit):
    ceiling = next(i for i in range(lit.patches.n) if lit.drawable_surface(i))
    assert lit.drawable_surface(ceiling)[0].startswith(("floor", "ceiling"))
    zone_patch = int(np.flatnonzero(lit.patches.surface_id == 2)[0])  # lum_west
    assert lit.drawable_surface(zone_patch) is None
    assert lit.new_zone_name() == "Z1"
    a = lit.add_source("lum_west")
    rec = Recorder(lit)
    lit.add_user_zone("Z1", SourceKind.LUMINAIRE, "ceiling", STRIP)
    assert rec.take() == ["scene", "design", "selection", "path", "results", "path"]
    assert "Z1" in {z.name for z in lit.scene.zones} and lit.dirty
    assert lit.operator is None and lit.lighting() is None  # new patches: build again
    assert lit.user_zones == (ZoneEdit("Z1", "luminaire", "ceiling", STRIP),)
    assert lit.new_zone_name() == "Z2"
    z = lit.add_source("Z1")
    lit.set_mirror(z.name, a.name)
    # Renaming the drawn zone drops the sources placed in it and the rules naming them.
    lit.set_user_zones((replace(lit.user_zones[0], name="Z9"),))
    assert [s.name for s in lit.design.sources] == [a.name] and lit.design.rules == ()
    before = lit.project
    with pytest.raises(LightInvError):
        lit.add_user_zone("Z2", "luminaire", "ceiling", (3.0, 2.0, 9.0, 6.0))  # on zones
    assert lit.project is before and lit.user_zones[0].name == "Z9"
    lit.set_user_zones(())
    assert lit.project.scene.zones == () and "Z9" not in {z.name for z in lit.scene.zones}


# -- the light shown ------------------------------------------------------------------------
def test_the_light_shown_is_the_light_models_of_the_design(lit):
    rec = Recorder(lit)
    assert lit.lighting() is not None and not lit.lighting().any()  # no sources: dark
    a = lit.add_source("lum_west")
    b = lit.add_source("lum_east")
    lit.update_source(a.name, rect=(0.1, 0.5, 0.9, 2.5), flux=4000.0)
    lit.set_mirror(b.name, a.name)
    sky = lit.add_source("skylight")
    lit.update_source(sky.name, filter=0.5)
    assert rec.take().count("lighting") == 6  # every design edit relights
    ref = reference(lit).design_field(lit.design)
    np.testing.assert_array_equal(lit.lighting(), ref.illuminance)
    B = ref.emission + lit.patches.rho * ref.illuminance  # B = E + rho H
    np.testing.assert_allclose(lit.field.radiosity, B)
    assert lit.field.sources == lit.effective_sources() == ref.sources
    assert lit.design_field() is lit.field and np.isfinite(lit.last_eval_ms)
    lit.set_selection([1, 2])  # not a design edit: the light stays
    assert rec.take() == ["selection"]


def test_a_preview_lights_another_layout_without_touching_the_design(lit):
    a = lit.add_source("lum_west")
    lit.update_source(a.name, free=("u0", "v0", "u1", "v1", "flux"))
    design, dirty = lit.design, lit.dirty
    problem = lit.problem()
    assert problem is lit.problem() and problem.vars.n == 5  # kept until the design changes
    x = problem.vars.initial()
    x[-1] = 9000.0  # a brighter luminaire
    sources = problem.sources_at(x)
    rec = Recorder(lit)
    lit.set_preview(sources)
    assert rec.take() == ["lighting"] and lit.preview_sources() == sources
    assert lit.design is design and lit.dirty == dirty
    ref = reference(lit)
    np.testing.assert_allclose(
        lit.lighting(), ref.field(sources, design.daylight).illuminance, rtol=1e-12
    )
    np.testing.assert_allclose(
        lit.design_field().illuminance, ref.design_field(design).illuminance, rtol=1e-12
    )
    assert lit.lighting().max() == pytest.approx(3 * lit.design_field().illuminance.max())
    assert lit.effective_sources() == ref.layout(design)
    lit.set_preview(None)
    assert lit.preview_sources() is None
    np.testing.assert_array_equal(lit.lighting(), ref.design_field(design).illuminance)


def test_the_difference_view_lights_other_sources_under_the_design_rules(lit):
    assert DocumentModel().lighting_of(()) is None  # no operator: no light
    a = lit.add_source("lum_west")
    b = lit.add_source("lum_east")
    lit.set_mirror(b.name, a.name)
    other = (replace(a, rect=(0.0, 0.0, 1.0, 1.0)), b)
    lux = lit.lighting_of(other)
    ref = reference(lit).design_field(lit.design, other)
    np.testing.assert_array_equal(lux, ref.illuminance)
    assert ref.sources[1].u_range == pytest.approx((1.0, 2.0))  # mirrored by the rule
    assert lit.lighting_of(other) is lux  # kept while the sources and rules stay
    lit.update_source(a.name, flux=100.0)  # an edit of the loaded layout: same answer
    assert lit.lighting_of(other) is lux
    lit.set_mirror(b.name, None)  # the rules changed: lit again
    again = lit.lighting_of(other)
    assert again is not lux and not np.allclose(again, lux)


def test_offending_patches_come_from_the_light_of_the_design(lit):
    assert lit.offending_patches() == []  # no intentions
    lit.add_source("lum_west")
    lit.add_intention(Intention("blinding", group="floor", min=1e6))
    ((name, bound, ids),) = lit.offending_patches()
    floor = lit.patches.group_index("floor")
    assert (name, bound) == ("blinding", "min") and set(ids) == set(floor)


# -- results --------------------------------------------------------------------------------
def solutions_of(model: DocumentModel, infos) -> list[Solution]:
    """Solutions of the model's design at distinct layouts, one per info."""
    problem = model.problem()
    x0 = problem.vars.initial()
    return [problem.solution(x0 - 0.05 * i, info) for i, info in enumerate(infos)]


def test_applying_a_solution_loads_its_layout_and_refuses_foreign_sources(lit):
    a = lit.add_source("lum_west")
    lit.update_source(a.name, free=("u0", "v0", "u1", "v1", "flux"))
    (_, sol) = solutions_of(lit, [SolutionInfo(), SolutionInfo(seed=1)])
    sol = replace(sol, sources=(replace(sol.sources[0], flux=1234.0),))
    lit.dirty = False
    rec = Recorder(lit)
    lit.apply_solution(sol)
    assert rec.take() == ["design", "lighting", "results"]
    got = lit.design.source(a.name)
    assert got.rect == sol.sources[0].rect and got.flux == 1234.0
    assert got.free == ("u0", "v0", "u1", "v1", "flux")  # the free variables stay
    assert lit.shown is sol and lit.dirty
    before = lit.project
    foreign = replace(sol, sources=(replace(sol.sources[0], name="X"),))
    with pytest.raises(DesignError, match="other sources"):
        lit.apply_solution(foreign)
    assert lit.project is before and lit.shown is sol
    lit.update_source(a.name, flux=2000.0)
    assert lit.shown is None  # an edited design is no longer the loaded result


def test_results_are_labelled_by_what_found_them(lit):
    lit.add_source("lum_west")
    s0, eps, two, plain = solutions_of(
        lit,
        [
            SolutionInfo(seed=0),
            SolutionInfo(epsilon=1500.0),
            SolutionInfo(step1_light_power=10.0, seed=3),
            SolutionInfo(),
        ],
    )
    assert [result_label(s) for s in (s0, eps, two, plain)] == [
        "seed 0",
        "epsilon 1,500 lm",
        "two-step seed 3",
        "result",
    ]


SETTINGS = OptimizerSettings(method="vns", seed=4, max_evals=5000, time_limit=20.0)


def test_each_run_is_kept_in_the_history_with_its_settings(lit):
    """A new run used to replace every earlier result; now each run is an entry."""
    lit.add_source("lum_west")
    s0, s1, eps, two = solutions_of(
        lit,
        [
            SolutionInfo(seed=0),
            SolutionInfo(seed=1),
            SolutionInfo(epsilon=1500.0),
            SolutionInfo(step1_light_power=10.0, seed=3),
        ],
    )
    rec = Recorder(lit)
    lit.dirty = False
    first = lit.add_run(
        (s0, s1),
        None,
        settings=SETTINGS,
        seeds=(0, 1),
        status="feasible",
        evaluations=10_000,
        seconds=3.25,
        time="2026-11-25T14:03:12",
    )
    assert rec.take() == ["path", "results"] and lit.dirty
    assert (first.number, first.method, first.goals) == (1, "vns", ("min_electric_power",))
    assert lit.browsed_run == 1 and [e.label for e in lit.results()] == ["seed 0", "seed 1"]
    assert run_label(first) == "run 1: VNS, 14:03"
    assert lit.run_summary(1) == (
        "VNS, 2 seeds (0, 1), at most 5,000 evaluations, at most 20 s, goal least electric "
        "power: feasible, 10,000 evaluations in 3.2 s; ended 2026-11-25 14:03:12"
    )
    front = ParetoFront(("min_electric_power", "max_light_power"), (eps,), "epsilon", (eps, two))
    second = lit.add_run((), front, settings=replace(SETTINGS, method="epsilon"))
    # The first run's results stay; the new run's are browsed.
    assert [r.number for r in lit.runs] == [1, 2] and lit.runs[0] == first
    assert lit.browsed_run == 2 and [e.solution.x for e in lit.results()] == [eps.x, two.x]
    assert lit.front() is front
    assert lit.on_front(eps) and not lit.on_front(two) and not lit.on_front(s1)
    assert "1 on its front" in lit.run_summary(2)
    lit.browse_run(ALL)
    assert [e.label for e in lit.results()] == [
        "run 1: seed 0",
        "run 1: seed 1",
        "run 2: epsilon 1,500 lm",
        "run 2: two-step seed 3",
    ]
    assert [e.run for e in lit.results()] == [1, 1, 2, 2]
    assert lit.front() is second.pareto  # the newest run's front
    with pytest.raises(DesignError, match="no run 7"):
        lit.browse_run(7)
    assert lit.browsed_run is ALL


def test_pinned_results_outlive_their_run_and_a_deleted_run_comes_back(lit):
    lit.add_source("lum_west")
    s0, s1, eps = solutions_of(
        lit, [SolutionInfo(seed=0), SolutionInfo(seed=1), SolutionInfo(epsilon=900.0)]
    )
    front = ParetoFront(("min_electric_power", "max_light_power"), (eps,), "epsilon", (eps,))
    lit.add_run((s0, s1), None, settings=SETTINGS, status="feasible")
    lit.add_run((), front, settings=SETTINGS, status="feasible")
    edits = []
    lit.on_edit = lambda label, before, after: edits.append((label, before, after))
    lit.apply_solution(s1)
    kept = lit.pin(s1)
    assert kept.info.pinned and lit.shown is kept and lit.pinned() == [kept]
    lit.pin(eps)  # a front point is pinned where it is, in its run's front
    assert [s.x for s in lit.pinned()] == [s1.x, eps.x]
    assert lit.runs[1].pareto.solutions[0].info.pinned
    assert lit.runs[1].pareto.candidates[0].info.pinned
    lit.pin(eps, False)
    assert [s.x for s in lit.pinned()] == [s1.x]
    # Deleting run 1 keeps its pinned result among the saved results; it is an edit.
    rec = Recorder(lit)
    lit.browse_run(1)
    rec.take()
    lit.delete_run(1)
    assert rec.take() == ["path", "results"]
    assert [r.number for r in lit.runs] == [2] and lit.browsed_run is ALL
    assert [s.x for s in lit.project.solutions] == [s1.x]
    assert [e.label for e in lit.results()] == ["saved: seed 1", "run 2: epsilon 900 lm"]
    assert edits[-1][0] == "delete run 1"
    _, before, after = edits[-1]
    # A run made after the delete stays when the delete is undone (and numbers go on).
    third = lit.add_run((s0,), None, settings=SETTINGS)
    assert third.number == 3
    lit.restore(before, after)  # undo the delete
    assert [r.number for r in lit.runs] == [1, 2, 3] and lit.project.solutions == ()
    assert lit.runs[0].solutions[1].info.pinned  # the pin came back with its run
    lit.restore(after, before)  # redo
    assert [r.number for r in lit.runs] == [2, 3]
    assert [s.x for s in lit.project.solutions] == [s1.x]
    with pytest.raises(DesignError, match="no run 1"):
        lit.delete_run(1)


def test_undoing_a_design_edit_keeps_the_results(lit):
    """Undo put the whole project back, so undoing an edit made before a run dropped the
    run's results (the docs said results are not edits and stay)."""
    edits = []
    lit.on_edit = lambda label, before, after: edits.append((label, before, after))
    a = lit.add_source("lum_west")
    (s0,) = solutions_of(lit, [SolutionInfo(seed=0)])
    lit.add_run((s0,), None, settings=SETTINGS)
    label, before, after = edits[0]
    assert label == f"add source {a.name}"
    lit.restore(before, after)
    assert lit.design.sources == () and [r.number for r in lit.runs] == [1]
    lit.restore(after, before)
    assert lit.design.sources[0].name == a.name and len(lit.runs) == 1


def test_the_history_is_saved_and_reopened(lit, tmp_path):
    lit.add_source("lum_west")
    s0, s1, eps = solutions_of(
        lit, [SolutionInfo(seed=0), SolutionInfo(seed=1), SolutionInfo(epsilon=900.0)]
    )
    front = ParetoFront(("min_electric_power", "max_light_power"), (eps,), "epsilon", (eps,))
    lit.add_run((s0, s1), None, settings=SETTINGS, seeds=(0, 1), status="feasible")
    lit.add_run((), front, settings=replace(SETTINGS, method="epsilon"), status="cancelled")
    lit.pin(s1)
    path = lit.save(tmp_path / "history.json")
    again = DocumentModel()
    again.open(path)
    assert again.project == lit.project and again.runs == lit.runs
    assert [r.status for r in again.runs] == ["feasible", "cancelled"]
    assert again.runs[1].settings.method == "epsilon" and again.runs[0].seeds == (0, 1)
    assert [s.x for s in again.pinned()] == [s1.x]
    # lightinv-cli report on such a file documents the newest run's first result (its
    # results are in the history, not in the saved solutions).
    from lightinv_core.report.chosen import choose_solution

    chosen = choose_solution(again.project)
    assert chosen.solution == eps and chosen.label == "run 2, front point 1 of 1"
    # Numbers go on after the highest one saved.
    assert again.add_run((s0,), None, settings=SETTINGS).number == 3
    chosen = choose_solution(again.project)
    assert chosen.solution.x == s0.x and chosen.label == "run 3, best 1 of 1"


def test_saving_and_opening_round_trip_and_clear_the_dirty_flag(lit, tmp_path):
    lit.add_source("lum_west")
    lit.add_intention(Intention("desks", group="desks", average=300.0))
    with pytest.raises(ValueError, match="Save As"):
        lit.save()
    rec = Recorder(lit)
    path = lit.save(tmp_path / "office.json")
    assert rec.take() == ["path"] and not lit.dirty and lit.path == path
    assert load_project(path) == lit.project
    again = DocumentModel()
    again.open(path)
    assert again.project == lit.project and again.path == path and not again.dirty
    assert again.current_source == "L1"
    again.mark_dirty()
    assert again.dirty and again.events.counts["path"] == 2


def test_editing_rules_are_pure_functions_of_the_design():
    d = Design((), (Goal("min_electric_power"),))
    s = edit_rules.new_source(d, "z", "luminaire", (0.5, 2.0))
    assert s.rect == (0.0, 0.5, 0.5, 1.5) and s.name == "L1"
    d2 = edit_rules.with_source(d, s)
    assert d.sources == () and d2.sources == (s,)
    assert edit_rules.moved_rect(s, -1.0, 0.25, (0.5, 2.0)) == (0.0, 0.75, 0.5, 1.75)
    t = Source("T", "y", "luminaire", (0.0, 0.0, 0.5, 0.5), flux=10.0)
    d3 = edit_rules.with_mirror(edit_rules.with_source(d2, t), "T", "L1")
    assert edit_rules.only_in_zones(d3, {"z"}).rules == ()  # T's zone went, and its rule
    assert edit_rules.only_in_zones(d3, {"z", "y"}) == d3


def test_every_edit_is_reported_with_its_before_and_after(lit):
    """What the window's undo stack is built on (app/undo.py)."""
    edits = []
    lit.on_edit = lambda label, before, after: edits.append((label, before, after))
    start = lit.project
    src = lit.add_source("lum_west")
    lit.update_source(src.name, flux=4321.0)
    lit.add_intention(Intention("desks", "desks", average=200.0))
    lit.set_optimizer(seed=3)
    assert [e[0] for e in edits] == [
        f"add source {src.name}",
        f"edit source {src.name}",
        "add intention desks",
        "run settings",
    ]
    assert edits[0][1] is start and edits[-1][2] is lit.project
    assert all(b is a for (_, _, a), (_, b, _) in itertools.pairwise(edits))
    events = []
    lit.events.connect("design", lambda change: events.append("design"))
    lit.restore(edits[1][1])  # back to just after adding the source
    assert lit.design.source(src.name).flux != 4321.0 and not lit.design.intentions
    assert lit.project.optimizer.seed != 3 and lit.dirty and events == ["design"]
    assert len(edits) == 4  # restoring is not itself an edit
    assert lit.lighting() is not None  # relit, same scene: the operator stays


def test_an_intention_is_replaced_in_place(lit):
    lit.add_intention(Intention("a", "desks", average=300.0))
    lit.add_intention(Intention("b", "walls", min=20.0))
    lit.replace_intention("a", Intention("a2", "desks", average=500.0, uniformity=0.6))
    assert [i.name for i in lit.design.intentions] == ["a2", "b"]
    with pytest.raises(DesignError, match="already called 'b'"):
        lit.replace_intention("a2", Intention("b", "desks", average=1.0))
    with pytest.raises(DesignError, match="no lighting intention 'zz'"):
        lit.replace_intention("zz", Intention("zz", "desks", average=1.0))
    assert [i.name for i in lit.design.intentions] == ["a2", "b"]


def test_rules_and_goals_are_added_and_removed(lit):
    lit.add_source("lum_west")
    lit.add_source("lum_east")
    lit.add_rule(Rule("aspect", ("L1",), max=3.0))
    lit.add_rule(Rule("align", ("L1", "L2"), axis="v"))
    assert edit_rules.rule_text(lit.design.rules[0]) == ("aspect L1", "at most 3")
    assert edit_rules.rule_text(lit.design.rules[1]) == ("align L1, L2", "along v")
    with pytest.raises(DesignError):
        lit.add_rule(Rule("area", ("nope",), max=1.0))
    lit.remove_rule(0)
    assert [r.kind for r in lit.design.rules] == ["align"]
    lit.set_goal("max_light_power", True)
    assert [g.kind for g in lit.design.goals] == ["min_electric_power", "max_light_power"]
    lit.set_goal("min_electric_power", False)
    with pytest.raises(DesignError, match="at least one goal"):
        lit.set_goal("max_light_power", False)
    assert [g.kind for g in lit.design.goals] == ["max_light_power"]


def test_a_groups_reflectance_is_set_and_reset(doc):
    own = doc.reflectance("walls")
    doc.set_reflectance("walls", 0.33)
    assert doc.reflectance("walls") == pytest.approx(0.33) and doc.operator is None
    assert doc.patches.rho[doc.patches.group_index("walls")] == pytest.approx(0.33)
    with pytest.raises(LightInvError):
        doc.set_reflectance("walls", 1.5)
    with pytest.raises(LightInvError, match="no group 'nope'"):
        doc.set_reflectance("nope", 0.5)
    assert doc.reflectance("walls") == pytest.approx(0.33)
    doc.set_reflectance("walls", None)
    assert doc.reflectance("walls") == pytest.approx(own) and not doc.project.scene.reflectances


def nearest_patch(model: DocumentModel, group: str, point) -> int:
    """The patch of ``group`` whose centre is nearest ``point``."""
    ids = model.patches.group_index(group)
    return int(ids[np.argmin(np.linalg.norm(model.patches.centroid[ids] - point, axis=1))])


def test_a_zone_drawn_from_above_goes_on_the_ceiling_not_the_floor_seen(doc):
    """From above, the ceiling is culled: the floor is what the view shows, and a
    luminaire zone drawn in Top view went on it."""
    down = (0.0, 0.0, -1.0)
    floor = nearest_patch(doc, "floor", (5.8, 7.5, 0.0))
    for kind in ("luminaire", "skylight"):
        name, rect = doc.zone_surface(kind, (5.8, 7.5, 20.0), down, floor)
        assert doc.scene.surface(name).group == "ceiling" and rect.normal[2] == -1.0
        assert name == "ceiling.12"  # the cell over (5.8, 7.5): x 4-8, y 7-8
    # Straight through the skylight zone (not drawable) onto the floor: nowhere to go.
    floor = nearest_patch(doc, "floor", (6.0, 4.0, 0.0))
    with pytest.raises(DesignError, match="luminaire zones are drawn on ceilings and roofs"):
        doc.zone_surface("luminaire", (6.0, 4.0, 20.0), down, floor)
    # From inside, looking at the north wall: a luminaire zone may go on it, a skylight's
    # may not.
    wall = nearest_patch(doc, "walls", (6.0, 8.0, 1.5))
    name, rect = doc.zone_surface("luminaire", (6.0, 4.0, 1.5), (0.0, 1.0, 0.0), wall)
    assert doc.scene.surface(name).group == "walls" and rect.normal[1] == pytest.approx(-1.0)
    with pytest.raises(DesignError, match="skylight zones are drawn on ceilings and roofs"):
        doc.zone_surface("skylight", (6.0, 4.0, 1.5), (0.0, 1.0, 0.0), wall)
    # Up at the ceiling from inside: the ceiling, seen from below.
    up = nearest_patch(doc, "ceiling", (2.0, 7.5, 3.0))
    name, _ = doc.zone_surface("luminaire", (2.0, 7.5, 1.0), (0.0, 0.2, 1.0), up)
    assert doc.scene.surface(name).group == "ceiling"


def test_surfaces_on_a_ray_are_listed_nearest_first_either_side(doc):
    from lightinv_core.editing.zones import surfaces_on_ray

    hits = surfaces_on_ray(doc.scene, (5.8, 7.5, 20.0), (0.0, 0.0, -2.0))
    assert [doc.scene.surface(n).group for _, n in hits] == ["ceiling", "floor"]
    assert [t for t, _ in hits] == pytest.approx([8.5, 10.0])  # in units of the direction
    assert surfaces_on_ray(doc.scene, (5.8, 7.5, 20.0), (0.0, 0.0, 1.0)) == []  # behind


def test_a_run_browsed_that_goes_is_no_longer_browsed(lit):
    """Redoing a run's deletion while it is browsed must not leave the list on a run
    that is gone."""
    lit.add_source("lum_west")
    (s0,) = solutions_of(lit, [SolutionInfo(seed=0)])
    edits = []
    lit.on_edit = lambda label, before, after: edits.append((label, before, after))
    lit.add_run((s0,), None, settings=SETTINGS)
    lit.delete_run(1)
    _, before, after = edits[-1]
    lit.restore(before, after)  # undo: run 1 is back
    lit.browse_run(1)
    assert lit.browsed_run == 1 and len(lit.results()) == 1
    lit.restore(after, before)  # redo: gone again
    assert lit.browsed_run is ALL and lit.results() == [] and lit.front() is None
