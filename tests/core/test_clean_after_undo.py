"""Undoing every edit since the file was opened or saved leaves nothing unsaved (issue
#29: the title kept "*" and quitting asked to save); a run, a pin or recovered work
that no undo step holds keeps the project unsaved."""

from __future__ import annotations

from lightinv_core.editing import DocumentModel
from lightinv_core.optimize.settings import OptimizerSettings


def model_with_history(tmp_path):
    """A saved office project and the undo steps recorded after it."""
    model = DocumentModel()
    model.new_from_scene("office", 0.5)
    model.save(tmp_path / "office.json")
    steps = []
    model.on_edit = lambda label, before, after: steps.append((before, after))
    return model, steps


def test_undoing_every_edit_since_saving_leaves_the_project_clean(tmp_path):
    model, steps = model_with_history(tmp_path)
    source = model.add_source("lum_west")
    model.update_source(source.name, flux=4321.0)
    model.set_optimizer(seed=3)
    assert model.dirty and len(steps) == 3
    for before, after in reversed(steps):  # undo all
        assert model.dirty
        model.restore(before, after)
    assert not model.dirty
    before, after = steps[0]
    model.restore(after, before)  # redo one: unsaved again
    assert model.dirty
    model.restore(before, after)
    assert not model.dirty
    # Saved in the middle of the history: clean there, unsaved on either side.
    for before, after in steps:
        model.restore(after, before)
    model.save()
    before, after = steps[-1]
    model.restore(before, after)
    assert model.dirty
    model.restore(after, before)
    assert not model.dirty


def test_a_run_since_the_edits_keeps_the_project_unsaved(tmp_path):
    model, steps = model_with_history(tmp_path)
    model.add_source("lum_west")
    model.add_run((), None, settings=OptimizerSettings())  # no undo step of its own
    (before, after), *_ = steps
    model.restore(before, after)
    assert model.design.sources == () and len(model.runs) == 1 and model.dirty


def test_recovered_work_stays_unsaved_after_undoing_its_edits(tmp_path):
    model, steps = model_with_history(tmp_path)
    model.mark_unsaved()  # as an autosave recovered is
    model.add_source("lum_west")
    (before, after), *_ = steps
    model.restore(before, after)
    assert model.dirty
