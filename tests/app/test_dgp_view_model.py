"""What the DGP map at the observers and the sensor drag compute, without a window
(docs/daylight.md "DGP in the view; dragging sensors"): the editing model's
``observer_dgp`` is the core's ``light.dgp_observers.observer_dgp`` at every observer
inside the room (one outside left out and named), made once per design, refused while
the clear glazing's light is traced elsewhere; the observer maps' values, labels and
captions say the core's figures; a dragged corner or edge gives the region by hand."""

from __future__ import annotations

from dataclasses import replace

import pytest

from app.view.observer_maps import LEVEL, LEVELS, SHARE, caption, observer_colours
from app.view.sensor_drag import dragged_rect
from lightinv_core.design.model import (
    Daylight,
    Design,
    DesignError,
    Goal,
    Observer,
    Source,
    Workplane,
)
from lightinv_core.editing import DocumentModel, blank_project
from lightinv_core.light.dgp_observers import observer_dgp
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings


def _document(elsewhere: bool = False) -> DocumentModel:
    """The side-lit room (1 m patches) with its window clear and three observers: by
    the window looking at it, at the back, and one outside the room."""
    doc = DocumentModel()
    doc.set_project(blank_project("sidelit", 1.0))
    doc.clear_elsewhere = elsewhere
    size = doc.zone_size("window")
    design = Design(
        sources=(Source("W1", "window", "window", (0.0, 0.0, *size), glazing="clear"),),
        goals=(Goal("min_electric_power"),),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        daylight=Daylight(transmittance=0.7),
        observers=(
            Observer("near", (3.0, 1.5), azimuth=-90.0),
            Observer("back", (3.0, 7.0), azimuth=-90.0),
            Observer("outside", (30.0, 4.0), azimuth=0.0),
        ),
    )
    doc.project = replace(doc.project, design=design)
    doc.set_operator(build_operator(doc.patches, OperatorSettings(rank=60, rays=128, seed=0)))
    return doc


def test_the_models_dgp_is_the_cores_at_every_observer_inside():
    doc = _document()
    figures, left_out = doc.observer_dgp()
    assert left_out == ("outside",) and set(figures) == {"near", "back"}
    inside = replace(doc.design, observers=doc.design.observers[:2])
    assert figures == observer_dgp(doc.light, inside)  # the core's, figure for figure
    assert figures["near"]["exceedance"] > 0.05 >= figures["back"]["exceedance"]
    assert doc.observer_dgp()[0] is figures  # made once per design
    doc.move_observer("back", 0.0, -1.0)  # a new design: made again
    assert doc.observer_dgp()[0] is not figures

    share = observer_colours(SHARE, figures)
    assert share.values["near"] == pytest.approx(100 * figures["near"]["exceedance"])
    assert share.clim == (0.0, 10.0) and share.title.startswith("DGPs > 0.40")
    near = figures["near"]
    assert share.labels["near"] == (
        f"near: {100 * near['exceedance']:.1f}% > 0.40, {near['en17037_glare']}"
    )
    level = observer_colours(LEVEL, figures)
    assert level.values == {n: float(LEVELS.index(g["en17037_glare"])) for n, g in figures.items()}
    assert level.annotations == {0.0: "none", 1.0: "minimum", 2.0: "medium", 3.0: "high"}
    text = caption(SHARE, figures, left_out)
    assert f"{near['hours']:,} occupied hours" in text and "outside the room): outside" in text


def test_the_models_dgp_waits_for_the_clear_trace():
    doc = _document(elsewhere=True)
    assert doc.clear_pending()
    with pytest.raises(DesignError, match="being traced in the background"):
        doc.observer_dgp()


def test_a_dragged_corner_or_edge_gives_the_region():
    rect = (0.0, 0.0, 15.0, 3.0)
    assert dragged_rect(rect, 0, 3.0, 1.0) == (3.0, 1.0, 15.0, 3.0)  # the south-west corner
    assert dragged_rect(rect, 2, -1.0, 0.5) == (0.0, 0.0, 14.0, 3.5)  # the north-east one
    assert dragged_rect(rect, 1, -16.0, 0.0) == (-1.0, 0.0, 0.0, 3.0)  # past x0: reordered
    assert dragged_rect(rect, None, -1.004, 2.0) == (-1.0, 2.0, 14.0, 5.0)  # moved, to 1 cm
