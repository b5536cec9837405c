"""A second zone drawn on a surface a first zone has cut (issue #29, blocker 2): the
view shows the pieces the first zone left (``ceiling~3``), the drawn zones apply to the
scene as imported (``ceiling``), so the second zone names the surface it came from, in
that surface's metres, and lands where it was drawn."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from lightinv_core.editing import DocumentModel
from lightinv_core.editing.project_file import obj_project
from lightinv_core.scene.edits import ZoneEdit

ROOM = """\
g floor
v 0 0 0
v 10 0 0
v 10 7 0
v 0 7 0
f 1 2 3 4
g ceiling
v 0 0 3
v 0 7 3
v 10 7 3
v 10 0 3
f 5 6 7 8
g walls
f 1 5 8 2
f 4 3 7 6
f 1 4 6 5
f 2 8 7 3
"""
"""A 10 x 7 x 3 m room, faces inwards, in three groups."""


def write_room(folder: Path) -> Path:
    """The classroom OBJ in ``folder``."""
    path = folder / "classroom.obj"
    path.write_text(ROOM)
    return path


def draw(doc: DocumentModel, name: str, kind: str, x: float, y: float, half: float) -> ZoneEdit:
    """A square zone of ``kind`` drawn looking up at the ceiling at (x, y): its surface
    found along the view ray as the window finds it, its corners in that surface's
    metres around the point hit."""
    ids = doc.patches.group_index("ceiling")
    seen = int(ids[np.argmin(np.linalg.norm(doc.patches.centroid[ids] - (x, y, 3.0), axis=1))])
    surface, rect = doc.zone_surface(kind, (x, y, 1.0), (0.0, 0.0, 1.0), seen)
    eu, ev = rect.u / np.linalg.norm(rect.u), rect.v / np.linalg.norm(rect.v)
    u, v = (np.array([x, y, 3.0]) - rect.origin) @ eu, (np.array([x, y, 3.0]) - rect.origin) @ ev
    edit = ZoneEdit(name, kind, surface, (u - half, v - half, u + half, v + half))
    doc.set_user_zones((*doc.user_zones, edit))
    return edit


def test_a_second_zone_on_a_cut_ceiling_names_the_ceiling_and_lands_where_drawn(tmp_path):
    doc = DocumentModel()
    doc.set_project(obj_project(write_room(tmp_path), resolution=0.5))
    first = draw(doc, "sky", "skylight", 3.0, 3.5, 1.0)
    assert first.surface == "ceiling"
    # The ceiling is now the zone and the pieces around it: none is called "ceiling".
    assert "ceiling" not in {s.name for s in doc.scene.surfaces}
    second = draw(doc, "lum", "luminaire", 8.0, 5.0, 0.5)
    assert second.surface == "ceiling"
    assert {z.name: z.kind for z in doc.scene.zones} == {"sky": "skylight", "lum": "luminaire"}
    for zone, (x, y, half) in (("sky", (3.0, 3.5, 1.0)), ("lum", (8.0, 5.0, 0.5))):
        rect = doc.scene.surface(zone).rect
        centre = rect.origin + 0.5 * (rect.u + rect.v)
        assert centre == pytest.approx((x, y, 3.0), abs=1e-9)
        assert sorted(rect.size) == pytest.approx([2 * half, 2 * half])
    # A third, on a piece the second left: still the ceiling, in the ceiling's metres.
    third = draw(doc, "lum2", "luminaire", 8.0, 1.0, 0.5)
    assert third.surface == "ceiling" and len(doc.scene.zones) == 3
    # The pieces still tile the ceiling: its area is unchanged.
    ceiling = sum(s.area for s in doc.scene.surfaces if s.group == "ceiling")
    assert ceiling == pytest.approx(70.0)


def test_a_surface_no_drawn_zone_has_cut_keeps_its_name(tmp_path):
    doc = DocumentModel()
    doc.set_project(obj_project(write_room(tmp_path), resolution=0.5))
    draw(doc, "sky", "skylight", 3.0, 3.5, 1.0)
    ids = doc.patches.group_index("walls")
    seen = int(ids[np.argmin(np.linalg.norm(doc.patches.centroid[ids] - (5.0, 7.0, 1.5), axis=1))])
    name, rect = doc.zone_surface("luminaire", (5.0, 3.0, 1.5), (0.0, 1.0, 0.0), seen)
    assert doc.scene.surface(name).rect == rect and "~" not in name
