"""Observers edited after they are placed (moved, changed, renamed, removed, each one
undo step) and an EN 12464-1 preset's UGR_L as a UGR limit at default observers
(``design/preset_glare.py``), without a display."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from lightinv_core.design.en12464 import EDITION_2011, EDITION_2021, preset_intention
from lightinv_core.design.model import Intention, Observer, Workplane
from lightinv_core.design.preset_glare import (
    EDGE_INSET,
    default_observers,
    floor_extent,
    preset_glare_intention,
    preset_ugr_limit,
    strictest_preset,
    unique_name,
)
from lightinv_core.editing.document import DocumentModel
from lightinv_core.errors import DesignError
from lightinv_core.light.glare import observer_eyes
from lightinv_core.project import project_from_dict

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def office_doc() -> DocumentModel:
    doc = DocumentModel()
    raw = json.loads((ROOT / "resources/projects/office-arrays.json").read_text())
    raw["scene"]["resolution"] = 1.0  # the floor's extent is all these tests need
    doc.set_project(project_from_dict(raw))
    return doc


def _fresh(doc: DocumentModel) -> DocumentModel:
    new = DocumentModel()
    new.set_project(doc.project)
    return new


def test_default_observers_follow_the_rule(office_doc):
    patches = office_doc.patches
    lo, hi = floor_extent(patches, "floor")
    assert lo.tolist() == pytest.approx([0.0, 0.0]) and hi.tolist() == pytest.approx([12.0, 8.0])
    wp = Workplane("wp", 0.8, 0.75, "floor", EDITION_2021)
    south, west = default_observers(patches, wp)
    # The middle of the plane's y- edge looking +y, of its x- edge looking +x; the
    # plane's border (0.75 m) is more than the least inset, so the eyes sit on its edge.
    assert (south.name, south.position, south.azimuth) == ("wp along y", (6.0, 0.75), 90.0)
    assert (west.name, west.position, west.azimuth) == ("wp along x", (0.75, 4.0), 0.0)
    assert south.height == west.height == 1.2 and south.group == west.group == "floor"
    # A border under the least inset: the eyes are 0.5 m from the floor's edge.
    s2, w2 = default_observers(patches, replace(wp, border=0.0), taken={"wp along y"})
    assert s2.position == (6.0, EDGE_INSET) and w2.position == (EDGE_INSET, 4.0)
    assert s2.name == "wp along y-2" and w2.name == "wp along x"
    # Both eyes stand over the room's floor, below its ceiling, looking into it.
    eyes = observer_eyes(patches, (south, west))
    assert eyes.points[:, 2] == pytest.approx([1.2, 1.2], abs=1e-6)
    assert np.allclose(eyes.views, [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]], atol=1e-12)
    with pytest.raises(DesignError, match="no group 'mezzanine'"):
        default_observers(patches, replace(wp, group="mezzanine"))


def test_the_presets_ugr_l_becomes_a_limit_at_observers():
    wp = Workplane("desk", 0.8, 0.5, "floor", EDITION_2021)
    it = preset_glare_intention("office", wp, ["a", "b"])
    assert (it.name, it.observers, it.quantity, it.max) == ("desk UGR_L", ("a", "b"), "ugr", 19)
    assert it.min is None and it.average is None and it.uniformity is None
    assert preset_glare_intention("drawing", wp, ["a"], taken={"desk UGR_L"}).name == (
        "desk UGR_L-2"
    )
    assert preset_glare_intention("corridor", replace(wp, edition=EDITION_2011), ["a"]).max == 28
    assert preset_ugr_limit("reception", EDITION_2021) == 22
    with pytest.raises(DesignError, match="needs an observer"):
        preset_glare_intention("office", wp, [])
    assert unique_name("x", {"x", "x-2"}) == "x-3"


def test_the_strictest_preset_is_offered_to_a_new_observer(office_doc):
    design = office_doc.design  # its work plane asks "filing" (2011: UGR_L 19)
    assert strictest_preset(design).ugr_l == 19
    drawing = preset_intention("drawing", "wp", "drawing", edition=EDITION_2011)
    assert strictest_preset(replace(design, intentions=(drawing,))).ugr_l == 16
    assert strictest_preset(replace(design, intentions=())) is None


def test_observers_are_moved_edited_renamed_and_removed_one_undo_step_each(office_doc):
    doc = _fresh(office_doc)
    steps = []
    doc.on_edit = lambda label, before, after: steps.append((label, before, after))
    limit = Intention("glare", observers=("desk",), quantity="ugr", max=19.0)
    doc.add_observer(Observer("desk", (6.0, 0.6), azimuth=90), limit)
    # A drag: every mouse move is an edit of the same label (the window merges them).
    for _ in range(3):
        doc.move_observer("desk", 0.5, 0.25)
    assert doc.design.observers[0].position == pytest.approx((7.5, 1.35))
    assert [s[0] for s in steps[1:]] == ["move observer desk"] * 3
    # Edited in its dialog: a new name is carried into the intention at it.
    new = Observer("seat", (5.0, 2.0), 1.7, azimuth=45, group="floor")
    doc.replace_observer("desk", new)
    assert doc.design.observers == (new,) and doc.design.intentions[-1].observers == ("seat",)
    assert steps[-1][0] == "edit observer desk"
    # Undo of the edit (the window's undo stack restores "before").
    _label, before, after = steps[-1]
    doc.restore(before, after)
    assert doc.design.observers[0].name == "desk" and doc.design.intentions[-1].observers == (
        "desk",
    )
    doc.add_observer(Observer("door", (0.6, 4.0), azimuth=0))
    with pytest.raises(DesignError, match="already called 'door'"):
        doc.replace_observer("desk", replace(new, name="door"))
    with pytest.raises(DesignError, match="no observer 'nobody'"):
        doc.move_observer("nobody", 1.0, 0.0)
    doc.remove_observer("desk")
    assert [o.name for o in doc.design.observers] == ["door"]
    assert all(i.observers is None for i in doc.design.intentions)
    # Several at once with their limit: one step.
    n = len(steps)
    wp = doc.design.workplanes[0]
    eyes = default_observers(doc.patches, wp, {o.name for o in doc.design.observers})
    it = preset_glare_intention("filing", wp, [o.name for o in eyes])
    doc.add_observers(eyes, it, "add UGR_L 19 at 2 observers")
    assert len(steps) == n + 1 and steps[-1][0] == "add UGR_L 19 at 2 observers"
    assert doc.design.intentions[-1] == it and len(doc.design.observers) == 3
