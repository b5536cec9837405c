"""IFC import (ifcopenshell, the optional extra): a room built with ``ifcopenshell.api``
(slab, four walls, a window in an opening, a roof slab with a skylight, a ceiling
covering, a space) checked against the dimensions it was built with."""

from __future__ import annotations

import builtins
import json
import sys
from pathlib import Path

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.errors import ObjImportError
from lightinv_core.project.scene import SceneSpec
from lightinv_core.scene.importers.ifc import MISSING, ROLE_REFLECTANCE, load_ifc
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix, lost_fraction
from tests.core.ifc_rooms import ifc_model

ifcopenshell = pytest.importorskip("ifcopenshell")

# The room inside: x 0..6, y 0..4, z 0..3 m; walls, floor and roof 0.2 m thick.
L, W, H, T = 6.0, 4.0, 3.0, 0.2
WINDOW = (1.0, 2.5, 0.9, 2.1)  # south wall opening: x from, x to, z from, z to
SKY = (2.5, 3.5, 1.5, 2.5)  # roof opening: x from, x to, y from, y to
CEILING = (4.0, 6.0, 2.7, 0.02)  # covering: x from, x to, height of its underside, thickness


def ifc_room(path: Path, unit: str = "mm", extra=None, floor: bool = True) -> Path:
    """Write the test room as IFC4 with lengths in ``unit`` ("mm" or "m"); ``extra(box,
    file)`` may add elements (``box(cls, name, x, y, z, lx, ly, lz, ...)``, metres);
    ``floor=False`` leaves the floor slab out (as in models of one discipline)."""

    m = ifc_model("IFC4", metres=unit != "mm")
    api, f, storey, box = m.api, m.f, m.storey, m.box

    if floor:
        box("IfcSlab", "Floor", -T, -T, -T, L + 2 * T, W + 2 * T, T, predefined="FLOOR")
    south = box("IfcWall", "South", -T, -T, 0, L + 2 * T, T, H)
    box("IfcWall", "North", -T, W, 0, L + 2 * T, T, H)
    box("IfcWall", "West", -T, 0, 0, T, W, H)
    box("IfcWall", "East", L, 0, 0, T, W, H)
    roof = api.root.create_entity(f, ifc_class="IfcRoof", name="Roof")
    api.spatial.assign_container(f, relating_structure=storey, products=[roof])
    slab = box("IfcSlab", "Roof slab", -T, -T, H, L + 2 * T, W + 2 * T, T, "ROOF", contained=False)
    api.aggregate.assign_object(f, relating_object=roof, products=[slab])
    # A 1.5 x 1.2 m window, 50 mm thick, 0.1 m into the 0.2 m wall from outside.
    x0, x1, z0, z1 = WINDOW
    hole = box(
        "IfcOpeningElement",
        "W1 opening",
        x0,
        -T - 0.1,
        z0,
        x1 - x0,
        T + 0.2,
        z1 - z0,
        contained=False,
    )
    api.feature.add_feature(f, feature=hole, element=south)
    window = box("IfcWindow", "W1", x0, -0.1, z0, x1 - x0, 0.05, z1 - z0)
    api.feature.add_filling(f, opening=hole, element=window)
    # A 1 x 1 m skylight, 50 mm thick, 0.1 m up in the roof slab.
    x0, x1, y0, y1 = SKY
    hole = box(
        "IfcOpeningElement",
        "S1 opening",
        x0,
        y0,
        H - 0.1,
        x1 - x0,
        y1 - y0,
        T + 0.2,
        contained=False,
    )
    api.feature.add_feature(f, feature=hole, element=slab)
    sky = box("IfcWindow", "S1", x0, y0, H + 0.1, x1 - x0, y1 - y0, 0.05)
    api.feature.add_filling(f, opening=hole, element=sky)
    cx0, cx1, cz, ct = CEILING
    box("IfcCovering", "Panel", cx0, 0, cz, cx1 - cx0, W, ct, predefined="CEILING")
    space = box("IfcSpace", "Office", 0, 0, 0, L, W, H, contained=False)
    api.aggregate.assign_object(f, relating_object=storey, products=[space])
    if extra is not None:
        extra(box, f)
    f.write(str(path))
    return path


@pytest.fixture(scope="module")
def room(tmp_path_factory) -> Path:
    return ifc_room(tmp_path_factory.mktemp("ifc") / "room.ifc")


def areas(scene) -> dict[str, float]:
    out: dict[str, float] = {}
    for s in scene.surfaces:
        out[s.group] = out.get(s.group, 0.0) + s.area
    return out


def test_the_room_has_the_built_dimensions(room):
    scene = load_ifc(room, resolution=0.5)
    got = areas(scene)
    wx0, wx1, wz0, wz1 = WINDOW
    window = (wx1 - wx0) * (wz1 - wz0)
    sx0, sx1, sy0, sy1 = SKY
    sky = (sx1 - sx0) * (sy1 - sy0)
    cx0, cx1, _, ct = CEILING
    # Only what faces the room: the slab's top inside the walls, the walls' inner faces
    # less the window opening (plus the opening's reveals on the room side of the
    # window: 0.05 m deep) and less the strips the ceiling panel touches; the roof
    # slab's underside less the skylight opening (plus its reveals, 0.1 m deep); the
    # panel's underside, its top (it hangs free under the roof) and its free edge.
    reveal = 2 * ((wx1 - wx0) + (wz1 - wz0)) * 0.05
    assert got["IfcSlab:Floor"] == pytest.approx(L * W)
    assert got["IfcWall:South"] == pytest.approx(L * H - window - (cx1 - cx0) * ct + reveal)
    assert got["IfcWall:North"] == pytest.approx(L * H - (cx1 - cx0) * ct)
    assert got["IfcWall:West"] == pytest.approx(W * H)
    assert got["IfcWall:East"] == pytest.approx(W * H - W * ct)
    assert got["IfcSlab:Roof slab"] == pytest.approx(L * W - sky + 4 * 1.0 * 0.1)
    assert got["IfcWindow:W1"] == pytest.approx(window)
    assert got["IfcWindow:S1"] == pytest.approx(sky)
    assert got["IfcCovering:Panel"] == pytest.approx(2 * (cx1 - cx0) * W + W * ct)
    info = scene.info["ifc"]
    assert info["spaces"] == ["Office"]
    assert info["elements"] == 9
    assert scene.info["warnings"] == []


def test_windows_become_glazing_zones_and_the_ceiling_a_luminaire_zone(room):
    scene = load_ifc(room, resolution=0.5)
    zones = {z.name: z.kind for z in scene.zones}
    assert zones == {
        "IfcWindow:W1": "window",
        "IfcWindow:S1": "skylight",
        "IfcCovering:Panel": "luminaire",
    }
    assert scene.info["ifc"]["zones"] == {
        "IfcWindow:W1": "wall window",
        "IfcWindow:S1": "roof window",
        "IfcCovering:Panel": "ceiling",
    }
    wall = scene.zone_rect("IfcWindow:W1")
    assert sorted(wall.size) == pytest.approx([1.2, 1.5])
    assert np.allclose(wall.normal, [0, 1, 0])  # into the room, on the window's inner face
    assert wall.origin[1] == pytest.approx(-0.05)
    sky = scene.zone_rect("IfcWindow:S1")
    assert sky.size == pytest.approx((1.0, 1.0))
    assert np.allclose(sky.normal, [0, 0, -1]) and sky.origin[2] == pytest.approx(H + 0.1)
    panel = scene.zone_rect("IfcCovering:Panel")
    assert sorted(panel.size) == pytest.approx([2.0, 4.0])
    assert np.allclose(panel.normal, [0, 0, -1]) and panel.origin[2] == pytest.approx(2.7)


def test_default_reflectances_follow_the_faces_roles(room):
    scene = load_ifc(room, resolution=0.5)
    by = {}
    for s in scene.surfaces:
        by.setdefault(s.group, set()).add(s.reflectance)
    assert by["IfcSlab:Floor"] == {ROLE_REFLECTANCE["floor"]} == {0.2}
    assert by["IfcWall:West"] == {ROLE_REFLECTANCE["wall"]} == {0.5}
    # The roof slab's underside is a ceiling; its reveals are walls.
    assert by["IfcSlab:Roof slab"] == {0.7, 0.5}
    assert by["IfcWindow:S1"] == {ROLE_REFLECTANCE["glazing"]} == {0.1}
    mapped = load_ifc(
        room,
        resolution=0.5,
        materials={"groups": {"IfcWall:West": 0.8}, "materials": {"wall": 0.6}},
    )
    by = {s.group: s.reflectance for s in mapped.surfaces if "Wall" in s.group}
    assert by["IfcWall:West"] == 0.8 and by["IfcWall:North"] == 0.6


def test_the_room_is_closed_and_the_units_do_not_matter(room, tmp_path):
    scene = load_ifc(room, resolution=0.5)
    p = mesh_patches(scene)
    assert lost_fraction(form_factor_matrix(p, 256, seed=1), p) < 1e-3
    inside = np.array([3.0, 2.0, 1.5])
    faces_in = ((inside - p.centroid) * p.normal).sum(axis=1) > 0
    # Everything faces into the room but the ceiling panel's top (towards the roof) and
    # the reveals of the openings (towards the opening's middle).
    panel_top = (p.normal[:, 2] > 0.9) & (p.centroid[:, 2] > 2.71)
    reveals = (p.centroid[:, 1] < 0) | (p.centroid[:, 2] > H)
    assert np.all(faces_in | panel_top | reveals)
    metres = load_ifc(ifc_room(tmp_path / "m.ifc", unit="m"), resolution=0.5)
    assert areas(metres) == pytest.approx(areas(scene))
    assert mesh_patches(metres).n == p.n


def test_scene_spec_load_scene_and_cli_take_ifc(room, tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    spec = SceneSpec(obj=str(room), resolution=0.5)
    assert spec.up == "z"
    assert spec.load().area == pytest.approx(load_scene(str(room), 0.5).area)
    argv = ["simulate", str(room), "--resolution", "0.5", "--emit", "IfcCovering:Panel=2000"]
    assert cli.main([*argv, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["lost_fraction"] < 1e-3
    assert out["energy"]["absorbed_lm"] == pytest.approx(2000, rel=5e-3)


def test_windows_sharing_a_name_get_unique_zones_and_odd_ceilings_warn(tmp_path):
    def extra(box, f):
        # A second window called W1, standing against the north wall, and a second
        # ceiling panel.
        box("IfcWindow", "W1", 1.0, W - 0.05, 1.0, 1.0, 0.05, 1.0)
        box("IfcCovering", "Strip", 0.5, 0.5, 2.0, 0.5, 0.5, 0.02, predefined="CEILING")

    scene = load_ifc(ifc_room(tmp_path / "two.ifc", extra=extra), resolution=0.5)
    names = sorted(z.name for z in scene.zones if z.name.startswith("IfcWindow:W1"))
    assert len(names) == 2 and all(" #" in n for n in names)
    assert "IfcCovering:Strip" in {z.name for z in scene.zones}


def test_a_ceiling_that_is_not_a_rectangle_is_a_surface_with_a_warning(tmp_path):
    def extra(box, f):
        # A ceiling panel with a hole cut by an opening element.
        import ifcopenshell.api.feature

        panel = box("IfcCovering", "Holed", 0.0, 0.0, 2.5, 2.0, 2.0, 0.02, predefined="CEILING")
        hole = box("IfcOpeningElement", "hole", 0.5, 0.5, 2.4, 0.5, 0.5, 0.3, contained=False)
        ifcopenshell.api.feature.add_feature(f, feature=hole, element=panel)

    scene = load_ifc(ifc_room(tmp_path / "holed.ifc", extra=extra), resolution=0.5)
    assert "IfcCovering:Holed" not in {z.name for z in scene.zones}
    assert areas(scene)["IfcCovering:Holed"] > 3.7  # its faces stay, as plain surfaces
    (warning,) = scene.info["warnings"]
    assert "1 window(s) or ceiling(s) ('IfcCovering:Holed') have no rectangular face" in warning


def test_without_the_extra_the_error_says_what_to_install(room, monkeypatch):
    real = builtins.__import__

    def no_ifc(name, *args, **kwargs):
        if name.startswith("ifcopenshell"):
            raise ImportError(name)
        return real(name, *args, **kwargs)

    monkeypatch.delitem(sys.modules, "ifcopenshell", raising=False)
    monkeypatch.setattr(builtins, "__import__", no_ifc)
    with pytest.raises(ObjImportError) as info:
        load_ifc(room)
    assert (
        str(info.value)
        == MISSING
        == ("IFC import needs the optional extra: pip install 'lightinv[ifc]'")
    )


def test_bad_ifc_files_are_one_line_errors(tmp_path):
    (tmp_path / "junk.ifc").write_text("this is not a STEP file\n")
    with pytest.raises(ObjImportError, match=r"^junk\.ifc: cannot read it as IFC \(") as info:
        load_ifc(tmp_path / "junk.ifc")
    assert "\n" not in str(info.value)
    with pytest.raises(ObjImportError, match=r"IFC file '.*gone\.ifc' does not exist"):
        load_ifc(tmp_path / "gone.ifc")
    import ifcopenshell.api.project

    empty = ifcopenshell.api.project.create_file(version="IFC4")
    empty.write(str(tmp_path / "empty.ifc"))
    with pytest.raises(ObjImportError, match=r"^empty\.ifc: no building elements with geometry"):
        load_ifc(tmp_path / "empty.ifc")


def test_an_ifc_file_too_large_for_the_memory_is_refused_before_it_is_read(room, monkeypatch):
    """ifcopenshell holds the whole model and its geometry: a file that would need more
    than 80% of the memory available is refused up front, with what it needs."""
    import lightinv_core.scene.importers.size as size

    need = size.check_ifc_size(room, room.name)
    assert need == size.IFC_BASE_BYTES + size.IFC_BYTES_PER_FILE_BYTE * (room.stat().st_size)
    monkeypatch.setattr(size, "available_memory_bytes", lambda: int(need / 0.8) - 1)
    with pytest.raises(ObjImportError, match=r"^room\.ifc: importing .* of IFC needs about"):
        load_ifc(room)
    monkeypatch.setattr(size, "available_memory_bytes", lambda: int(need / 0.8) + 1)
    assert load_ifc(room).zones
