"""The next step of a design's workflow (issue #29, item 5): draw zones, add light, a work
plane, its intention, Run; and where a work-plane intention is broken (its grid points,
and the floor patches under them, which the window highlights)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.design.en12464 import preset_intention
from lightinv_core.design.model import Intention, Workplane
from lightinv_core.editing import DocumentModel, blank_project
from lightinv_core.editing.next_step import STEPS, document_next_step, next_step
from lightinv_core.editing.project_file import obj_project
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from tests.core.test_zone_on_cut_surface import draw, write_room


def key(doc: DocumentModel) -> str | None:
    step = document_next_step(doc)
    return None if step is None else step.key


def test_an_imported_room_is_led_through_the_steps_in_order(tmp_path):
    doc = DocumentModel()
    assert document_next_step(doc) is None  # nothing open: nothing to say
    doc.set_project(obj_project(write_room(tmp_path), resolution=0.5))
    step = document_next_step(doc)
    assert step.key == "zones" and step.number == 1
    assert step.hint().startswith(f"Next (step 1 of {len(STEPS)}): ")
    assert "Draw zone" in step.text
    draw(doc, "Z1", "luminaire", 5.0, 3.5, 1.0)
    assert key(doc) == "light"
    doc.add_source("Z1")
    assert key(doc) == "workplane"
    doc.set_workplanes((Workplane("desks"),))
    assert key(doc) == "intention"
    doc.add_intention(preset_intention("classroom", "desks"))
    assert key(doc) == "run"
    assert "Run" in document_next_step(doc).text
    # Results of a run: every step done, no hint.
    assert next_step(doc.scene, doc.design, has_results=True) is None
    # Undoing the work plane (its intention goes with it) asks for it again.
    doc.set_workplanes(())
    assert key(doc) == "workplane"


def test_light_placed_by_hand_or_an_intention_on_patches_skips_steps(tmp_path):
    doc = DocumentModel()
    doc.set_project(blank_project("office", 0.7))  # built-in: its zones drawn already
    assert doc.scene.zones and key(doc) == "light"
    doc.add_source("lum_west")
    bare = replace(doc.design, intentions=(), workplanes=())
    assert next_step(doc.scene, bare, False).key == "workplane"
    on_patches = replace(bare, intentions=(Intention("floor", group="floor", min=100.0),))
    assert next_step(doc.scene, on_patches, False).key == "run"  # no work plane needed
    # Arrays count as light like sources do; without either, zones ask for light.
    assert next_step(doc.scene, replace(bare, sources=()), False).key == "light"


@pytest.fixture(scope="module")
def office_operator():
    model = DocumentModel()
    model.set_project(blank_project("office", 0.7))
    return build_operator(model.patches, OperatorSettings(rank=100, rays=128))


@pytest.fixture
def lit(office_operator):
    doc = DocumentModel()
    doc.set_project(blank_project("office", 0.7))
    doc.set_operator(office_operator)
    doc.add_source("lum_west")
    doc.set_workplanes((Workplane("desks", height=0.8, border=0.5, group="floor"),))
    for it in doc.design.intentions:
        doc.remove_intention(it.name)
    return doc


def test_a_broken_work_plane_intention_marks_its_points_and_the_floor_under_them(lit):
    assert lit.offending_points() == []
    grids, lux = lit.shown_grids()
    assert grids is not None and lux.max() > 0
    lit.add_intention(Intention("even", grid="desks", uniformity=0.99))
    (name, bound, plane, points), *_ = lit.offending_points()
    assert (name, bound, plane) == ("even", "uniformity", "desks")
    # The points below U0 x Em, from the grid light the view shows (design scenario).
    span = grids.spans["desks"]
    expected = np.flatnonzero(lux[span] < 0.99 * lux[span].mean()) + span.start
    assert len(expected) and np.array_equal(points, expected)
    ((_, _, ids),) = [o for o in lit.offending_patches() if o[0] == "even"]
    floor = lit.patches.group_index("floor")
    assert len(ids) and set(ids) <= set(floor)
    # Each marked patch is the floor patch nearest (in plan) one of the points.
    centres = lit.patches.centroid[ids, :2]
    gaps = np.linalg.norm(grids.points[points, None, :2] - centres[None], axis=2).min(axis=0)
    assert gaps.max() < 0.7  # within a patch's size


def test_a_met_work_plane_intention_marks_nothing(lit):
    lit.add_intention(Intention("dim enough", grid="desks", max=1e9))
    assert lit.offending_points() == []
    assert all(name != "dim enough" for name, _, _ in lit.offending_patches())
