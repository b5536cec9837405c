"""The editing model with its clear glazing's light built elsewhere (the window's worker,
docs/daylight.md "Control groups: switching, own targets, sensors drawn; the clear trace
in a worker"): until it is built the light shown leaves it out and every figure that
needs it says why; a build stopped by its progress callback leaves nothing behind; one
built on another light model of the same operator is found, and the light shown then
equals the document's own build (``clear_elsewhere`` off, as before)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.design.model import Daylight, Design, DesignError, Goal, Source, Workplane
from lightinv_core.editing import DocumentModel, blank_project
from lightinv_core.errors import CancelledError
from lightinv_core.light.clear_build import clear_light, clear_light_key, clear_light_ready
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings


def _document(elsewhere: bool, operator=None) -> DocumentModel:
    doc = DocumentModel()
    doc.set_project(blank_project("sidelit", 1.0))
    doc.clear_elsewhere = elsewhere
    size = doc.zone_size("window")
    design = Design(
        sources=(Source("W1", "window", "window", (0.0, 0.0, *size), glazing="clear"),),
        goals=(Goal("min_electric_power"),),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        daylight=Daylight(transmittance=0.7),
    )
    doc.project = replace(doc.project, design=design)
    op = operator or build_operator(doc.patches, OperatorSettings(rank=80, rays=128, seed=0))
    doc.set_operator(op)
    return doc


def test_the_clear_light_built_elsewhere_is_waited_for_then_shown():
    doc = _document(elsewhere=True)
    assert doc.clear_pending()
    dark = doc.lighting().copy()  # the light shown without the glazing: nothing lit yet
    for ask in (doc.layout_daylight, doc.problem):
        with pytest.raises(DesignError, match="being traced in the background"):
            ask()
    assert doc.offending_patches() == [] and doc.offending_points() == []

    # Stopped by its progress callback (the worker's cancel): nothing is left built.
    worker_light = LightModel(doc.scene, doc.patches, doc.operator)
    seen: list[float] = []

    def stop_halfway(f: float) -> None:
        seen.append(f)
        if f >= 0.5:
            raise CancelledError("cancelled")

    with pytest.raises(CancelledError):
        clear_light(worker_light, doc.design, stop_halfway)
    assert doc.clear_pending() and not clear_light_ready(worker_light, doc.design)
    assert seen == sorted(seen) and 0 < seen[0] < 0.5 <= seen[-1] < 1

    # Built on the worker's own light model of the same operator: the document finds it.
    fractions: list[float] = []
    clear_light(worker_light, doc.design, fractions.append)
    assert fractions == sorted(fractions) and fractions[-1] < 1 and len(fractions) >= 6
    assert not doc.clear_pending()
    events: list = []
    doc.events.connect("lighting", events.append)
    # The worker's light in every scenario, made on its own light model, is kept.
    made = layout_daylight(worker_light, doc.design)
    doc.clear_light_changed(daylight=made)
    assert len(events) == 1 and doc.layout_daylight() is made
    lit = doc.lighting()
    assert (lit - dark).max() > 50.0  # lux: the window's daylight in the design scenario
    assert doc.problem() is not None
    # Made for a design no longer shown, it is not kept.
    doc.clear_light_changed(daylight=layout_daylight(worker_light, replace(doc.design)))
    assert doc.layout_daylight() is not made

    # The same light as a document that builds it itself (the default, as before).
    own = _document(elsewhere=False, operator=doc.operator)
    assert not own.clear_pending()
    assert np.allclose(own.lighting(), lit)


def test_a_note_says_why_when_the_trace_was_given_up():
    doc = _document(elsewhere=True)
    doc.clear_light_changed("the clear glazing's trace was cancelled")
    with pytest.raises(DesignError, match="trace was cancelled"):
        doc.layout_daylight()
    # A diffusing window needs no trace: nothing is pending, no key.
    diffusing = replace(doc.design.sources[0], glazing="diffusing")
    doc.project = replace(doc.project, design=replace(doc.design, sources=(diffusing,)))
    assert not doc.clear_pending() and clear_light_key(doc.design) is None
