"""New emitter zones drawn on rectangular surfaces: geometry, closedness and errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lightinv_core.errors import SceneError
from lightinv_core.scene.builders import room_faces
from lightinv_core.scene.builtin import corridor, office
from lightinv_core.scene.edits import ZoneEdit, apply_zone_edits, rect_surfaces
from lightinv_core.scene.model import Scene, Surface
from lightinv_core.scene.patches import count_patches, mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix, lost_fraction

# Office ceiling coordinates: u = x, v = 8 - y. Between the skylight (v 3..5) and the
# north wall, and between the two luminaire strips (u 3..9).
Z1 = ZoneEdit("Z1", "luminaire", "ceiling", (8.0, 7.0, 4.0, 5.5))  # corners in any order
Z2 = ZoneEdit("Z2", "skylight", "ceiling", (3.5, 0.5, 8.5, 2.5))


@pytest.fixture(scope="module")
def base() -> Scene:
    return office(0.5)


def _box() -> Scene:
    """A closed 4 x 3 x 2 m room, one surface per face."""
    faces = room_faces(0, 0, 0, 4, 3, 2)
    return Scene("box", tuple(Surface(k, k, 0.5, rect=r) for k, r in faces.items()), (), 0.5)


def test_zone_edit_normalises_and_validates():
    assert Z1.rect == (4.0, 5.5, 8.0, 7.0)
    assert Z1.size == (4.0, 1.5)
    cases = [
        (("", "luminaire", "ceiling", (0, 0, 1, 1)), "name must be a non-empty string"),
        (("Z", "luminaire", " ", (0, 0, 1, 1)), "surface must be a non-empty string"),
        (("Z", "lamp", "ceiling", (0, 0, 1, 1)), "kind 'lamp' is not one of"),
        (("Z", "skylight", "ceiling", (0, 0, 1)), "rect must be 4 finite numbers"),
        (("Z", "skylight", "ceiling", (0, 0, math.nan, 1)), "rect must be 4 finite numbers"),
        (("Z", "skylight", "ceiling", (0, 0, True, 1)), "rect must be 4 finite numbers"),
        (("Z", "skylight", "ceiling", None), "give its rectangle"),
        (("Z", "skylight", "ceiling", (1, 0, 1, 2)), r"zero width or height \(0 x 2 m\)"),
    ]
    for args, message in cases:
        with pytest.raises(SceneError, match=message):
            ZoneEdit(*args)


def test_new_zone_on_the_office_ceiling(base):
    scene = apply_zone_edits(base, [Z1])
    zone = scene.zone("Z1")
    assert zone.kind == "luminaire" and zone.surface == "Z1"
    surf = scene.surface("Z1")
    assert (surf.group, surf.reflectance) == ("ceiling", base.surface("ceiling").reflectance)
    rect = scene.zone_rect("Z1")
    assert rect.size == pytest.approx((4.0, 1.5))
    # Zone (u, v) axes are the ceiling's: u = x, v = 8 - y, origin at (u0, v0).
    np.testing.assert_allclose(rect.origin, [4.0, 2.5, 3.0])
    np.testing.assert_allclose(rect.normal, [0, 0, -1])
    assert [z.name for z in scene.zones] == [z.name for z in base.zones] + ["Z1"]
    assert scene.area == pytest.approx(base.area, rel=1e-12)
    assert abs(count_patches(scene) - count_patches(base)) <= 4
    patches = mesh_patches(scene)
    assert patches.grid_shape["Z1"] == (8, 3)
    assert patches.area[patches.zone_index("Z1")].sum() == pytest.approx(6.0)
    assert len(set(s.name for s in scene.surfaces)) == len(scene.surfaces)
    assert base.surface("ceiling").name == "ceiling"  # the input scene is untouched
    F = form_factor_matrix(patches, 32)
    assert lost_fraction(F, patches) < 1e-4


def test_two_zones_on_one_surface(base):
    scene = apply_zone_edits(base, [Z1, Z2])
    assert scene.zone_rect("Z2").size == pytest.approx((5.0, 2.0))
    assert scene.zone("Z2").kind == "skylight"
    assert scene.area == pytest.approx(base.area, rel=1e-12)
    patches = mesh_patches(scene)
    assert patches.grid_shape["Z2"] == (10, 4)
    F = form_factor_matrix(patches, 32)
    assert lost_fraction(F, patches) < 1e-4


def test_a_single_surface_split_twice_keeps_its_area():
    box = _box()
    edits = [
        ZoneEdit("A", "luminaire", "ceiling", (0, 0, 1, 1)),  # in a corner
        ZoneEdit("B", "skylight", "ceiling", (2, 1, 4, 3)),  # touching two edges
        ZoneEdit("C", "luminaire", "ceiling", (1, 0, 2, 1)),  # touching A
    ]
    scene = apply_zone_edits(box, edits)
    assert [z.name for z in scene.zones] == ["A", "B", "C"]
    assert scene.area == pytest.approx(box.area, rel=1e-12)
    ceiling = [s for s in scene.surfaces if s.group == "ceiling"]
    assert sum(s.area for s in ceiling) == pytest.approx(12.0)
    assert "ceiling" not in {s.name for s in scene.surfaces}
    assert all(s.name.startswith("ceiling~") for s in ceiling if s.name not in {"A", "B", "C"})
    assert [n for n, _ in rect_surfaces(scene)].count("A") == 0
    patches = mesh_patches(scene)
    assert lost_fraction(form_factor_matrix(patches, 32), patches) < 1e-4


def test_remainder_names_never_collide():
    box = _box()
    taken = Scene(
        "box",
        (*box.surfaces, Surface("ceiling~1", "x", 0.5, rect=room_faces(0, 0, 5, 1, 1, 6)["floor"])),
    )
    scene = apply_zone_edits(taken, [ZoneEdit("A", "luminaire", "ceiling", (1, 1, 2, 2))])
    names = [s.name for s in scene.surfaces]
    assert len(set(names)) == len(names) and "ceiling~1" in names and "ceiling~2" in names


def test_rect_surfaces_lists_only_free_rectangles(base):
    names = [n for n, _ in rect_surfaces(base)]
    assert "ceiling" in names and "floor" in names
    assert not {"skylight", "lum_west", "lum_east"} & set(names)
    assert all(base.surface(n).rect is not None for n in names)
    assert apply_zone_edits(base, []) is base


def _refused(scene, edits, message):
    with pytest.raises(SceneError, match=message):
        apply_zone_edits(scene, edits)


def test_errors_name_the_zone_and_the_surface(base):
    where = r"^new emitter zone 'Z9' on surface '{}': "
    edit = ZoneEdit("Z9", "luminaire", "ceilng", (0, 0, 1, 1))
    _refused(base, [edit], where.format("ceilng") + r".*no surface.*did you mean 'ceiling'")
    edit = ZoneEdit("Z9", "luminaire", "skylight", (0, 0, 1, 1))
    _refused(base, [edit], where.format("skylight") + "the surface is already emitter zone")
    edit = ZoneEdit("Z9", "luminaire", "ceiling", (11, 1, 13, 2))
    _refused(base, [edit], where.format("ceiling") + r"the rectangle \(11, 1\)-\(13, 2\) m lies")
    edit = ZoneEdit("Z9", "luminaire", "ceiling", (1, 1, 3, 2))
    _refused(base, [edit], "the rectangle overlaps emitter zone 'lum_west'")
    edit = ZoneEdit("Z9", "luminaire", "ceiling", (5, 6, 7, 7.5))
    _refused(base, [Z1, edit], where.format("ceiling") + "the rectangle overlaps emitter zone 'Z1'")
    _refused(
        base, [ZoneEdit("lum_west", "luminaire", "ceiling", (0, 0, 1, 1))], "already has a zone"
    )
    _refused(base, [Z1, Z1], "the zone name 'Z1' is used twice")
    _refused(base, [ZoneEdit("floor", "luminaire", "ceiling", (0, 0, 1, 1))], "called 'floor'")
    # The ceiling and the floor do not continue each other.
    edit = ZoneEdit("Z9", "luminaire", "floor", (1, 1, 2, 2))
    assert apply_zone_edits(base, [edit]).zone_rect("Z9").origin[2] == 0.0
    # Triangles are refused.
    tri = Surface("tri", "t", 0.5, triangles=np.array([[[0, 0, 9], [1, 0, 9], [0, 1, 9]]]))
    odd = Scene("odd", (*base.surfaces, tri), base.zones, 0.5)
    _refused(odd, [ZoneEdit("Z9", "luminaire", "tri", (0, 0, 1, 1))], "not a planar rectangle")


def test_zones_may_not_cross_other_groups_or_fixed_grids():
    scene = corridor(0.5)
    # North wall coordinates: u = x, v = z; panel1 covers u 6.5..9.5, v 1..2.5.
    edit = ZoneEdit("W", "luminaire", "north", (6, 0.5, 7, 1.5))
    _refused(scene, [edit], "runs onto surface 'panel1' of group 'panels'")
    # Where it is, in the surface's metres, so the zone can be drawn beside it.
    _refused(scene, [edit], r"\(reflectance 0.7\) at \(6.5, 1\)-\(7, 1.5\) m on the surface")
    gridded = Surface("g", "roof", 0.5, rect=room_faces(0, 0, 0, 2, 2, 2)["floor"], grid=(2, 2))
    _refused(
        Scene("g", (gridded,)), [ZoneEdit("Z", "skylight", "g", (0, 0, 1, 1))], "fixed 2 x 2 grid"
    )
