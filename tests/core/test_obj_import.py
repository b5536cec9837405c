"""OBJ import: geometry, groups, reflectances, emitter zones and every user error."""

from __future__ import annotations

import contextlib
import json
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.importers.materials import KD_CAP
from lightinv_core.scene.importers.obj import load_obj
from lightinv_core.scene.importers.report import report_of
from lightinv_core.scene.patches import count_patches, mesh_patches

BOX_VERTICES = """\
v 0 0 0
v 4 0 0
v 4 3 0
v 0 3 0
v 0 0 2.5
v 4 0 2.5
v 4 3 2.5
v 0 3 2.5
"""

# A closed 4 x 3 x 2.5 m room, every face counter-clockwise seen from inside.
BOX = (
    BOX_VERTICES
    + """\
g floor
f 1 2 3 4
g ceiling
f 5 8 7 6
g walls
f 1 5 6 2
f 2 6 7 3
f 3 7 8 4
f 4 8 5 1
"""
)

# Corners of the unit square at z = 0, counter-clockwise seen from above (+z).
SQUARE = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"


def vertices(pts):
    return "".join(f"v {float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in pts)


def write(tmp_path, text, name="room.obj"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def load(tmp_path, text, **kw):
    return load_obj(write(tmp_path, text), **kw)


def fails(tmp_path, text, pattern, **kw):
    """Import ``text`` expecting ObjImportError whose message matches regex ``pattern``."""
    with pytest.raises(ObjImportError, match=pattern) as info:
        load(tmp_path, text, **kw)
    return str(info.value)


def group_area(scene, group):
    return sum(s.area for s in scene.surfaces if s.group == group)


def tris_of(scene, group):
    return np.concatenate([s.triangles for s in scene.surfaces if s.group == group])


# --- geometry -------------------------------------------------------------------------


def test_box_room_groups_areas_and_patches(tmp_path):
    scene = load(tmp_path, BOX, resolution=0.5)
    assert scene.name == "room"
    assert scene.groups == ("floor", "ceiling", "walls")
    assert group_area(scene, "floor") == pytest.approx(12.0)
    assert group_area(scene, "ceiling") == pytest.approx(12.0)
    assert group_area(scene, "walls") == pytest.approx(2 * (4 + 3) * 2.5)
    assert [s.name for s in scene.surfaces][:2] == ["floor", "ceiling"]
    p = mesh_patches(scene)
    # 8 x 6 cells on floor and ceiling, 8 x 5 and 6 x 5 on the walls.
    assert p.n == count_patches(scene) == 2 * 48 + 2 * 40 + 2 * 30
    assert len(p.group_index("walls")) == 140
    # Every front face looks into the room.
    inward = ((np.array([2.0, 1.5, 1.25]) - p.centroid) * p.normal).sum(axis=1)
    assert np.all(inward > 0)
    assert scene.info["source"] == str(tmp_path / "room.obj")
    assert scene.info["warnings"] == []
    report = report_of(scene)
    # No MTL: every group has the default reflectance, which the report says.
    assert report.notes == (
        "no MTL Kd for group(s) 'ceiling', 'floor', 'walls' (every surface), and the "
        "materials mapping does not name them: they use the built-in default reflectance "
        "0.5; give reflectances in a materials JSON file (the import dialog's Materials "
        "JSON) or change them after import",
    )
    assert [(it.name, it.outcome, it.becomes) for it in report.items] == [
        ("floor", "group", "floor"),
        ("ceiling", "group", "ceiling"),
        ("walls", "group", "walls"),
    ]
    assert report.items[2].area_m2 == pytest.approx(2 * (4 + 3) * 2.5)
    assert report.summary() == "room.obj: 3 items: 0 zones, 3 groups, 0 dropped"
    assert report.needs_attention and report.lines()[-2] == "assumed (1):"


def test_rectangles_become_grids_other_quads_triangles(tmp_path):
    text = SQUARE + "v 3 0 0\nv 2 1 0\ng rect\nf 1 2 3 4\ng trapezoid\nf 2 5 6 3\n"
    scene = load(tmp_path, text, resolution=0.25)
    rect = scene.surface("rect")
    assert rect.rect is not None
    assert np.allclose(rect.rect.normal, [0, 0, 1])
    assert mesh_patches(scene).grid_shape["rect"] == (4, 4)
    # At 0.25 m the trapezoid's two triangles, subdivided, would make 4 times the
    # patches of a grid: it is cut into rectangles and border triangles instead.
    pieces = [s for s in scene.surfaces if s.group == "trapezoid"]
    assert sum(s.area for s in pieces) == pytest.approx(1.5)
    p = mesh_patches(scene)
    assert (p.group_id == p.group_names.index("trapezoid")).sum() <= 2 * 1.5 / 0.25**2
    # Coarse enough, it stays two triangles.
    trap = load(tmp_path, text, resolution=COARSE).surface("trapezoid")
    assert trap.triangles is not None and len(trap.triangles) == 2
    assert trap.area == pytest.approx(1.5)


def test_rotated_rectangle_becomes_a_rect(tmp_path):
    c, s = np.cos(0.3), np.sin(0.3)
    pts = [(0, 0, 0), (2 * c, 2 * s, 0), (2 * c - s, 2 * s + c, 0), (-s, c, 0)]
    text = vertices(pts) + "f 1 2 3 4\n"
    scene = load(tmp_path, text)
    assert scene.surfaces[0].rect is not None
    assert scene.surfaces[0].area == pytest.approx(2.0)


COARSE = 10.0
"""m; a resolution at which small polygons keep their ear-clip triangles (finer, the
importer cuts polygons whose triangles would be too many patches into a grid)."""


@pytest.mark.parametrize("start", range(6))
def test_l_shaped_polygon_is_ear_clipped(tmp_path, start):
    ring = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
    ring = ring[start:] + ring[:start]
    # Tilted out of every coordinate plane, to exercise the best-fit plane.
    rot = np.linalg.qr(np.array([[1.0, 0.3, 0.2], [0.1, 1.0, 0.4], [0.3, 0.2, 1.0]]))[0]
    pts = np.array([(x, y, 0.0) for x, y in ring]) @ rot.T
    text = vertices(pts) + "g L\nf 1 2 3 4 5 6\n"
    # Coarse: finer, the L is cut into a grid (tests/core/test_polygon_mesh.py).
    scene = load(tmp_path, text, resolution=COARSE)
    tri = tris_of(scene, "L")
    assert len(tri) == 4
    assert scene.area == pytest.approx(3.0)
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    assert np.allclose(normals / np.linalg.norm(normals, axis=1)[:, None], rot[:, 2])
    # Every triangle lies inside the L (not over the missing corner).
    centre = (tri.mean(axis=1) @ rot)[:, :2]
    assert not np.any((centre[:, 0] > 1) & (centre[:, 1] > 1))


def inside_polygon(pts, ring):
    """Even-odd rule: which of ``pts`` (n, 2) lie inside polygon ``ring`` (k, 2)."""
    x, y = pts[:, 0:1], pts[:, 1:2]
    a, b = ring, np.roll(ring, -1, axis=0)
    crosses = (a[:, 1] > y) != (b[:, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xs = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return ((crosses & (x < xs)).sum(axis=1) % 2) == 1


@settings(
    max_examples=100, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(shape=st.lists(st.tuples(st.floats(0.2, 1.0), st.floats(0.4, 1.0)), min_size=4, max_size=14))
def test_star_shaped_polygons_triangulate_exactly(tmp_path, shape):
    gaps = np.array([g for _, g in shape])
    angle = np.cumsum(gaps) / gaps.sum() * 2 * np.pi
    ring = np.array([r for r, _ in shape])[:, None] * np.column_stack(
        [np.cos(angle), np.sin(angle)]
    )
    area = 0.5 * np.sum(ring[:, 0] * np.roll(ring[:, 1], -1) - np.roll(ring[:, 0], -1) * ring[:, 1])
    pts = np.column_stack([ring, np.full(len(ring), 1.5)])
    face = " ".join(str(k) for k in range(1, len(ring) + 1))
    (surface,) = load(tmp_path, vertices(pts) + f"f {face}\n", resolution=COARSE).surfaces
    tri = surface.triangles
    if surface.rect is not None:  # a square: split it to check it the same way
        o, u, v = surface.rect.origin, surface.rect.u, surface.rect.v
        tri = np.array([[o, o + u, o + u + v], [o, o + u + v, o + v]])
    twice = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])[:, 2]
    assert np.all(twice > 0)
    assert 0.5 * twice.sum() == pytest.approx(area, rel=1e-9)
    assert np.all(inside_polygon(tri.mean(axis=1)[:, :2], ring))


def test_self_intersecting_polygon_is_fanned_with_a_warning(tmp_path):
    scene = load(tmp_path, "v 0 0 0\nv 3 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n")
    assert len(scene.surfaces[0].triangles) == 2
    assert (
        "1 self-intersecting polygon(s) at line 5 were split into a fan"
        in (scene.info["warnings"][0])
    )


def test_polygon_with_collinear_vertices(tmp_path):
    text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\ng strip\nf 1 2 3 4 5\n"
    tri = tris_of(load(tmp_path, text, resolution=COARSE), "strip")
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    assert np.all(normals[:, 2] > 0) and np.allclose(normals[:, :2], 0)
    assert 0.5 * normals[:, 2].sum() == pytest.approx(2.0)


def test_non_planar_polygon_is_fanned_with_a_warning(tmp_path):
    text = "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0.5 1.5 0\nv 0 1 0\nf 1 2 3 4 5\n"
    scene = load(tmp_path, text)
    assert len(scene.surfaces[0].triangles) == 3
    (warning,) = scene.info["warnings"]
    assert "1 non-planar polygon(s) at line 6 were split into a fan" in warning


def test_negative_indices(tmp_path):
    text = SQUARE + "f -4 -3 -2 -1\n" + SQUARE + "f -4 -3 -2\n"
    scene = load(tmp_path, text)
    assert scene.area == pytest.approx(1.5)


@pytest.mark.parametrize(
    "face", ["1//1 2//1 3//1 4//1", "1/1/1 2/2/1 3/3/1 4/4/1", "1/1 2/2 3/3 4/4"]
)
def test_vertex_reference_forms(tmp_path, face):
    text = SQUARE + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\ns off\n" + f"f {face}\n"
    scene = load(tmp_path, text)
    assert scene.surfaces[0].rect is not None and scene.area == pytest.approx(1.0)


def test_comments_blank_lines_continuations_and_unknown_statements(tmp_path):
    text = (
        "# a comment\n\n   \n"
        + SQUARE
        + "l 1 2\np 1\nvp 0.5\ncstype bezier\nvp 0.2\n"
        + "f 1 2 \\\n 3 4  # inline comment\n"
    )
    scene = load(tmp_path, text)
    assert scene.area == pytest.approx(1.0)
    (warning,) = scene.info["warnings"]
    assert warning == (
        "room.obj: ignored 3 unsupported statement(s) ('vp' x2, 'cstype' x1); "
        "LightInv reads only vertices and polygon faces"
    )


def test_latin1_and_bom_files_are_decoded(tmp_path):
    path = tmp_path / "room.obj"
    path.write_bytes((SQUARE + "g caf\xe9\nf 1 2 3 4\n").encode("latin-1"))
    assert load_obj(path).groups == ("caf\xe9",)
    path.write_bytes(b"\xef\xbb\xbf" + (SQUARE + "g caf\xe9\nf 1 2 3 4\n").encode("utf-8"))
    assert load_obj(path).groups == ("caf\xe9",)


def test_scale_and_up_axis(tmp_path):
    # A y-up, millimetre floor: the plane y = 0 facing +y, 2000 x 1000 mm.
    text = "v 0 0 0\nv 0 0 -1000\nv 2000 0 -1000\nv 2000 0 0\nf 1 4 3 2\n"
    scene = load(tmp_path, text, scale=0.001, up="y")
    rect = scene.surfaces[0].rect
    assert rect.area == pytest.approx(2.0)
    assert np.allclose(rect.normal, [0, 0, 1])
    assert np.allclose(rect.origin + rect.u + rect.v, [2, 1, 0])
    z_up = load(tmp_path, text, up="z").surfaces[0].rect
    assert np.allclose(z_up.normal, [0, 1, 0]) and z_up.area == pytest.approx(2e6)
    assert "was drawn in millimetres pass scale=0.001" in load(tmp_path, text).info["warnings"][0]


def test_name_and_group_fallbacks(tmp_path):
    text = SQUARE + (
        "f 1 2 3\nusemtl paint\nf 1 3 4\no Chair Seat\nf 1 2 3\ng a b\nf 1 3 4\n"
        "o Table\nf 1 2 3\ng # no name\nusemtl\nf 1 3 4\n"
    )
    scene = load(tmp_path, text, name="custom")
    assert scene.name == "custom"
    # Faces: default, paint (usemtl), Chair Seat (o), a (first g name), Table (o resets g).
    assert scene.groups == ("default", "paint", "Chair Seat", "a", "Table")
    assert len({s.name for s in scene.surfaces}) == len(scene.surfaces)


def test_one_group_with_two_materials_gets_two_surfaces(tmp_path):
    mats = {"materials": {"dark": 0.2, "light": 0.7}}
    text = SQUARE + "g desk\nusemtl dark\nf 1 2 3\nusemtl light\nf 1 3 4\nusemtl dark\nf 1 2 4\n"
    scene = load(tmp_path, text, materials=mats)
    assert [(s.name, s.reflectance, len(s.triangles)) for s in scene.surfaces] == [
        ("desk.dark", 0.2, 2),
        ("desk.light", 0.7, 1),
    ]


# --- reflectances ---------------------------------------------------------------------

MTL = "newmtl grey\nKd 0.2 0.4 0.6\nnewmtl white\nKd 1 1 1\nnewmtl single\nKd 0.3\n"
FACES_BY_MATERIAL = (
    "".join(
        f"g {g}\nusemtl {m}\nf 1 2 3\n"
        for g, m in [("floor", "grey"), ("desk", "grey"), ("wall", "white"), ("trim", "single")]
    )
    + "g other\nusemtl unknown\nf 1 2 3\ng bare\nf 1 2 3\n"
)


def rho_by_group(scene):
    return {s.group: s.reflectance for s in scene.surfaces}


def test_mtl_kd_luminance_and_cap(tmp_path):
    write(tmp_path, MTL, "room.mtl")
    scene = load(tmp_path, "mtllib room.mtl\n" + SQUARE + FACES_BY_MATERIAL)
    rho = rho_by_group(scene)
    assert rho["floor"] == rho["desk"] == pytest.approx(0.2126 * 0.2 + 0.7152 * 0.4 + 0.0722 * 0.6)
    assert rho["wall"] == KD_CAP == 0.95
    assert rho["trim"] == pytest.approx(0.3)
    assert rho["other"] == rho["bare"] == 0.5
    # The fixture draws every group on the same square: that repeat is warned about first.
    repeat, *warnings = scene.info["warnings"]
    assert "repeat a face of another group; both are kept" in repeat
    assert warnings == [
        "material 'white': MTL Kd luminance 1 capped at 0.95 (exporters write Kd 1 1 1 for "
        "white, and a reflectance of 1 makes radiosity diverge); give its reflectance in the "
        "materials mapping to silence this",
        "no reflectance for material(s) 'unknown' (not in the materials mapping or an MTL "
        "file); they use the default 0.5",
    ]


def test_materials_json_precedence(tmp_path):
    write(tmp_path, MTL, "room.mtl")
    spec = {"default": 0.4, "groups": {"floor": 0.1}, "materials": {"grey": 0.25, "white": 0.8}}
    mats = write(tmp_path, json.dumps(spec), "mats.json")
    for materials in (mats, str(mats), spec):
        scene = load(
            tmp_path, "mtllib room.mtl\n" + SQUARE + FACES_BY_MATERIAL, materials=materials
        )
        rho = rho_by_group(scene)
        # group beats material beats MTL Kd beats default
        assert rho == {
            "floor": 0.1,
            "desk": 0.25,
            "wall": 0.8,
            "trim": pytest.approx(0.3),
            "other": 0.4,
            "bare": 0.4,
        }
        assert not any("capped" in w for w in scene.info["warnings"])


def test_unused_mapping_names_are_warned(tmp_path):
    scene = load(tmp_path, SQUARE + "g floor\nf 1 2 3 4\n", materials={"groups": {"flor": 0.2}})
    assert scene.info["warnings"] == [
        "materials mapping: groups 'flor' do not occur in the OBJ file and are ignored; "
        "check the spelling"
    ]


def test_missing_mtllib_is_a_warning(tmp_path):
    scene = load(tmp_path, "mtllib gone.mtl\n" + SQUARE + "usemtl paint\nf 1 2 3 4\n")
    assert scene.surfaces[0].reflectance == 0.5
    assert scene.info["warnings"][0] == (
        f"room.obj line 1: material library '{tmp_path / 'gone.mtl'}' does not exist; check the "
        "path; its materials get the default reflectance"
    )


def test_mtllib_with_spaces_and_bad_kd(tmp_path):
    write(tmp_path, "newmtl a\nKd spectral file.rfl\nnewmtl b\nKd 0.5 0.5 0.5\n", "my lib.mtl")
    text = "mtllib my lib.mtl\n" + SQUARE + "usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\n"
    scene = load(tmp_path, text)
    assert [s.reflectance for s in scene.surfaces] == pytest.approx([0.5, 0.5])
    assert (
        "my lib.mtl line 2: cannot use Kd 'spectral file.rfl' of material 'a'"
        in (scene.info["warnings"][0])
    )


# --- emitter zones --------------------------------------------------------------------

# A 4 x 3 ceiling at z = 2.5 facing down; the zone is x in [1, 3], y in [1, 2].
CEILING = """\
v 0 0 2.5
v 4 0 2.5
v 4 3 2.5
v 0 3 2.5
v 1 1 2.5
v 3 1 2.5
v 3 2 2.5
v 1 2 2.5
g ceiling
f 1 4 3 2
"""


def test_zone_from_two_triangles(tmp_path):
    text = CEILING + "g zone:sky:skylight\nf 5 8 7\nf 5 7 6\n"
    scene = load(tmp_path, text, resolution=0.5, materials={"groups": {"sky": 0.7}})
    (zone,) = scene.zones
    assert (zone.name, zone.kind, zone.surface) == ("sky", "skylight", "sky")
    rect = scene.zone_rect("sky")
    assert scene.surface("sky").group == "sky"
    assert scene.surface("sky").reflectance == 0.7
    assert rect.area == pytest.approx(2.0)
    assert np.allclose(rect.normal, [0, 0, -1])
    # u runs along +x, so v = n x u runs along -y (as for the built-in ceilings).
    assert np.allclose(rect.u, [2, 0, 0]) and np.allclose(rect.v, [0, -1, 0])
    assert np.allclose(rect.origin, [1, 2, 2.5])
    p = mesh_patches(scene)
    assert len(p.zone_index("sky")) == 4 * 2
    assert p.grid_shape["sky"] == (4, 2)


def test_wall_zone_of_mixed_faces_and_reflectances(tmp_path):
    # A wall zone in the plane x = 0 facing +x, as a quad plus two triangles.
    text = (
        "v 0 0 0\nv 0 2 0\nv 0 2 1\nv 0 0 1\nv 0 3 0\nv 0 3 1\n"
        "g zone:panel:Luminaire\nusemtl a\nf 1 2 3 4\nusemtl b\nf 2 5 6\nf 2 6 3\n"
    )
    scene = load(tmp_path, text, materials={"materials": {"a": 0.2, "b": 0.8}})
    rect = scene.zone_rect("panel")
    assert scene.zones[0].kind == "luminaire"
    assert np.allclose(rect.normal, [1, 0, 0]) and rect.area == pytest.approx(3.0)
    assert np.allclose(rect.u, [0, 3, 0])
    assert scene.surface("panel").reflectance == pytest.approx((0.2 * 2 + 0.8 * 1) / 3)
    assert scene.info["warnings"] == [
        "room.obj: zone group 'zone:panel:Luminaire' (line 9): its faces have different "
        "reflectances; the zone uses their area-weighted mean 0.4"
    ]


def test_non_planar_zone_is_rejected(tmp_path):
    text = CEILING + "v 3 2 2.0\ng zone:sky:skylight\nf 5 8 9\nf 5 9 6\n"
    fails(
        tmp_path,
        text,
        re.escape(
            "room.obj: zone group 'zone:sky:skylight' (line 13) is not planar: its "
            "vertices are up to "
        )
        + r"0\.\d+ m from their common plane",
    )


def test_l_shaped_zone_is_rejected(tmp_path):
    text = CEILING + "v 2 1.5 2.5\nv 3 1.5 2.5\nv 2 2 2.5\ng zone:L:luminaire\nf 5 8 11 9 10 6\n"
    msg = fails(
        tmp_path,
        text,
        re.escape("room.obj: zone group 'zone:L:luminaire' (line 15) is not a rectangle"),
    )
    assert "cover 1.5 m² but their smallest enclosing rectangle (2 x 1 m) has 2 m²" in msg


def test_zone_errors(tmp_path):
    fails(
        tmp_path,
        CEILING + "g zone:sky:lamp\nf 5 8 7 6\n",
        re.escape(
            "room.obj line 12: group 'zone:sky:lamp': zone kind 'lamp' is not one of "
            "skylight, window, luminaire; name the group zone:sky:skylight, zone:sky:window "
            "or zone:sky:luminaire"
        ),
    )
    fails(
        tmp_path,
        CEILING + "g zone:sky\nf 5 8 7 6\n",
        re.escape("room.obj line 12: group 'zone:sky' is not a valid zone group"),
    )
    fails(
        tmp_path,
        CEILING + "g zone:sky:skylight\nf 5 8 7\nf 5 6 7\n",
        re.escape("zone group 'zone:sky:skylight' (line 12): its faces do not all face the same"),
    )
    fails(
        tmp_path,
        CEILING + "g zone:sky:skylight\nf 5 8 7 6\ng zone:sky:luminaire\nf 1 4 3 2\n",
        re.escape("zone 'sky' is already defined by group 'zone:sky:skylight'"),
    )


# --- errors ---------------------------------------------------------------------------


def test_file_errors(tmp_path):
    with pytest.raises(ObjImportError, match=r"OBJ file '.*gone\.obj' does not exist; check"):
        load_obj(tmp_path / "gone.obj")
    with pytest.raises(ObjImportError, match=r"is not a file \(a folder or device\)"):
        load_obj(tmp_path)
    with pytest.raises(ObjImportError, match="must be a str or PathLike, not int"):
        load_obj(3)
    fails(
        tmp_path, "# nothing\nv 0 0 0\nl 1 1\n", re.escape("room.obj: no faces found (1 vertices)")
    )
    fails(tmp_path, "", "no faces found")


def test_unreadable_file(tmp_path, monkeypatch):
    path = write(tmp_path, SQUARE + "f 1 2 3\n")

    def refuse(self):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(Path, "read_bytes", refuse)
    with pytest.raises(ObjImportError) as info:
        load_obj(path)
    assert (
        str(info.value)
        == f"cannot read OBJ file '{path}': Permission denied; check that it is readable"
    )


@pytest.mark.parametrize(
    "text, message",
    [
        ("v 0 0 0\nv 1 x 0\n", "room.obj line 2: vertex coordinate 'x' is not a number; fix"),
        ("v 0 0 0\nv 1,5 0 0\n", "vertex coordinate '1,5' is not a number (use a decimal point"),
        ("v 0 0 0\n\nv 1 nan 0\n", "room.obj line 3: vertex coordinate 'nan' is not finite"),
        ("v 0 0 -inf\n", "room.obj line 1: vertex coordinate '-inf' is not finite"),
        ("v 0 0\n", "room.obj line 1: a vertex needs 3 coordinates ('v x y z'), got 2"),
        ("v 1e9 0 0\nv 0 0 0\n", "room.obj line 1: a coordinate is larger than 1e+08 m"),
        (SQUARE + "f 1 2\n", "room.obj line 5: a face needs at least 3 vertices, got 2"),
        (SQUARE + "f 1 0 2\n", "room.obj line 5: vertex index 0 is invalid (OBJ indices start"),
        (
            SQUARE + "f 1 2 9\n",
            "room.obj line 5: the face refers to vertex 9 but the file "
            "defines only 4 vertices; the file may be truncated, re-export it",
        ),
        (
            SQUARE + "f 1 2 -5\n",
            "room.obj line 5: relative vertex index -5 points before the first vertex",
        ),
        (
            SQUARE + "f 1 2 a/1\n",
            "room.obj line 5: 'a/1' is not a vertex reference (v, v/vt, "
            "v//vn or v/vt/vn with whole numbers); fix the face",
        ),
    ],
)
def test_line_errors(tmp_path, text, message):
    fails(tmp_path, text, re.escape(message))


DEGENERATE = SQUARE + "v 2 0 0\nf 1 2 3\nf 1 2 2\nf 1 2 5\nf 1 3 4\nf 1 1 1 2\n"


def test_degenerate_faces(tmp_path):
    fails(
        tmp_path,
        DEGENERATE,
        re.escape(
            "room.obj: 3 degenerate face(s) (repeated vertices or zero area) at lines 7, "
            "8, 10; delete or fix them in the modeller, or pass skip_degenerate=True to "
            "drop them"
        ),
    )
    scene = load(tmp_path, DEGENERATE, skip_degenerate=True)
    assert scene.area == pytest.approx(1.0)
    assert scene.info["warnings"] == [
        "room.obj: dropped 3 degenerate face(s) (repeated vertices or zero area) at lines 7, 8, 10"
    ]
    many = SQUARE + "f 1 2 2\n" * 7
    msg = fails(tmp_path, many, "degenerate")
    # The import report lists the group whose faces were all dropped and what was.
    mixed = DEGENERATE.replace("f 1 2 2\n", "g sliver\nf 1 2 2\ng default\n")
    report = report_of(load(tmp_path, mixed, skip_degenerate=True))
    by = {it.name: it for it in report.items}
    assert by["sliver"].outcome == "dropped"
    assert by["sliver"].reason == "all its 1 face(s) were dropped (degenerate or repeated)"
    assert report.skipped == (
        "room.obj: dropped 3 degenerate face(s) (repeated vertices or zero area) at lines "
        "8, 10, 12",
    )
    assert report.needs_attention
    assert "at lines 5, 6, 7, 8, 9 and 2 more;" in msg
    fails(
        tmp_path,
        many,
        re.escape(
            "room.obj: all 7 faces are degenerate (repeated vertices or zero area); nothing to "
            "import, check the model and the scale"
        ),
        skip_degenerate=True,
    )


@pytest.mark.parametrize(
    "content, message",
    [
        (None, "materials file '{dir}/gone.json' does not exist; check the path"),
        (
            '{"groups":\n {"floor" 0.2}}',
            "materials file 'm.json' is not valid JSON: Expecting "
            "':' delimiter at line 2, column 11; fix the syntax",
        ),
        (
            "[0.5]",
            "materials file 'm.json': expected an object like {\"default\": 0.5, "
            '"groups": {"floor": 0.2}, "materials": {"white_paint": 0.8}}, got a list',
        ),
        (
            '{"group": {}}',
            "materials file 'm.json': unknown key 'group'; the keys are "
            '"default", "groups" and "materials"',
        ),
        (
            '{"groups": [0.2]}',
            "materials file 'm.json': \"groups\" must be an object mapping "
            'names to reflectances, e.g. {"floor": 0.2}, got a list',
        ),
        (
            '{"groups": {"floor": 1.2}}',
            'materials file \'m.json\': key "groups"."floor": reflectance 1.2 is outside [0, 1)',
        ),
        (
            '{"materials": {"paint": "light"}}',
            "materials file 'm.json': key \"materials\"."
            "\"paint\": reflectance 'light' is not a number",
        ),
        (
            '{"default": true}',
            "materials file 'm.json': key \"default\": reflectance True is not a number",
        ),
        ('{"default": -0.1}', 'key "default": reflectance -0.1 is outside [0, 1)'),
    ],
)
def test_materials_file_errors(tmp_path, content, message):
    mats = tmp_path / ("gone.json" if content is None else "m.json")
    if content is not None:
        mats.write_text(content)
    fails(
        tmp_path,
        SQUARE + "f 1 2 3\n",
        re.escape(message.replace("{dir}", str(tmp_path))),
        materials=mats,
    )


def test_option_errors(tmp_path):
    text = SQUARE + "f 1 2 3\n"
    fails(
        tmp_path,
        text,
        re.escape("materials must be a dict or the path of a JSON file, got list"),
        materials=[0.5],
    )
    fails(
        tmp_path,
        text,
        re.escape(
            "up='x' is not supported; use up='z' for a z-up model or up='y' for a y-up model"
        ),
        up="x",
    )
    fails(
        tmp_path,
        text,
        re.escape("scale 0 is not a positive number; give metres per model unit"),
        scale=0,
    )
    fails(tmp_path, text, "scale nan is not a positive number", scale=float("nan"))
    fails(tmp_path, text, "resolution 0 m is not a usable patch size", resolution=0)


# --- robustness -----------------------------------------------------------------------

# OBJ keywords, index forms, numbers (some malformed) and group names, for the fuzz tests.
WORDS = ["v", "f", "g", "o", "usemtl", "mtllib", "vt", "vn", "s", "l", "p", "#", "\\"]
WORDS += ["/", "0", "1", "2", "3", "4", "-1", "-2", "-9", "1/2", "1//3", "1/2/3", "2/", "//"]
WORDS += ["0.5", "-0.5", "2.5", "1e308", "1e-300", "nan", "inf", "1,5", "x", "é", "off"]
WORDS += ["box.mtl", "room.obj", "zone:a:skylight", "zone:b:luminaire", "zone:c:bad", "zone::x"]
TOKENS = (
    st.sampled_from(WORDS)
    | st.integers(-10, 12).map(str)
    | st.floats(-10, 10, allow_nan=False).map(repr)
)
LINES = st.lists(st.lists(TOKENS, max_size=7).map(" ".join), max_size=25).map("\n".join)
FUZZ = settings(
    max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)


def check_only_obj_import_errors(path):
    try:
        scene = load_obj(path, resolution=0.5)
    except ObjImportError as exc:
        assert str(exc)
        return
    assert scene.surfaces and isinstance(scene.info["warnings"], list)


@FUZZ
@given(header=st.sampled_from(["", BOX_VERTICES, CEILING]), body=LINES)
def test_fuzz_text_raises_only_obj_import_error(tmp_path, header, body):
    write(tmp_path, "newmtl x\nKd 1 2\nnewmtl y\nKd 0.5\n", "box.mtl")
    check_only_obj_import_errors(write(tmp_path, header + body))


@FUZZ
@given(data=st.binary(max_size=400))
def test_fuzz_bytes_raise_only_obj_import_error(tmp_path, data):
    path = tmp_path / "bytes.obj"
    path.write_bytes(data)
    check_only_obj_import_errors(path)


JSON = st.recursive(
    st.none() | st.booleans() | st.floats() | st.integers() | st.text(max_size=5),
    lambda inner: (
        st.lists(inner, max_size=3)
        | st.dictionaries(st.sampled_from(["default", "groups", "materials", "floor", "x"]), inner)
    ),
    max_leaves=8,
)


@FUZZ
@given(materials=JSON)
def test_fuzz_materials_raise_only_obj_import_error(tmp_path, materials):
    path = write(tmp_path, SQUARE + "g floor\nusemtl x\nf 1 2 3\n")
    with contextlib.suppress(ObjImportError):
        load_obj(path, materials=materials if isinstance(materials, dict) else [materials])


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-le", "utf-16-be", "utf-8-sig"])
def test_utf16_files_from_windows_tools_are_read(tmp_path, encoding):
    """A UTF-16 OBJ used to be reported as "no faces found"."""
    (tmp_path / "room.obj").write_bytes(("# made on Windows\n" + BOX).encode(encoding))
    scene = load_obj(tmp_path / "room.obj", resolution=0.5)
    assert scene.groups == ("floor", "ceiling", "walls")
    assert scene.area == pytest.approx(2 * (12 + 10 + 7.5))


def test_a_repeated_face_is_dropped_but_the_two_sides_of_a_thin_wall_are_kept(tmp_path):
    # The floor again, from another corner (same turning order), then a thin partition
    # across the room drawn as two faces back to back.
    extra = (
        "g floor\nf 3 4 1 2\n"
        "v 0 1.5 0\nv 4 1.5 0\nv 4 1.5 2.5\nv 0 1.5 2.5\n"
        "g partition\nf 9 10 11 12\nf 12 11 10 9\n"
    )
    scene = load(tmp_path, BOX + extra)
    (warning,) = scene.info["warnings"]
    assert "dropped 1 duplicated face(s) at line 19" in warning
    areas = {g: 0.0 for g in scene.groups}
    for s in scene.surfaces:
        areas[s.group] += s.area
    assert areas["floor"] == pytest.approx(12.0) and areas["partition"] == pytest.approx(20.0)
