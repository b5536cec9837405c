"""glTF/GLB and PLY import (through trimesh): groups, transforms, up axis, reflectances,
polygons rebuilt from triangles, zones, errors; checked against the same room as OBJ."""

from __future__ import annotations

import base64
import io
import json
import struct
from pathlib import Path

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.errors import ObjImportError
from lightinv_core.project import ProjectError
from lightinv_core.project.scene import SCENE, SceneSpec
from lightinv_core.scene.facets import join_coplanar
from lightinv_core.scene.importers.gltf import load_gltf
from lightinv_core.scene.importers.meshes import srgb_to_linear
from lightinv_core.scene.importers.obj import load_obj
from lightinv_core.scene.importers.ply import load_ply
from lightinv_core.scene.importers.report import report_of
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix, lost_fraction
from tests.core.test_obj_import import BOX

# --- a small glTF writer (the tests need exact control of names, nodes and buffers) ----------


def to_y_up(p) -> np.ndarray:
    """z-up points (metres) as a glTF file holds them (y up): (x, y, z) -> (x, z, -y)."""
    p = np.asarray(p, float).reshape(-1, 3)
    return np.column_stack([p[:, 0], p[:, 2], -p[:, 1]])


def fan(polygon) -> np.ndarray:
    """Triangles (t, 3, 3) of a convex polygon, keeping its winding."""
    p = np.asarray(polygon, float)
    return np.array([[p[0], p[i], p[i + 1]] for i in range(1, len(p) - 1)])


class Gltf:
    """glTF 2.0 built in code: meshes, materials, nodes; saved as .glb or .gltf."""

    def __init__(self):
        self.doc: dict = {
            "asset": {"version": "2.0"},
            "scene": 0,
            "scenes": [{"nodes": []}],
            "nodes": [],
            "meshes": [],
            "materials": [],
            "accessors": [],
            "bufferViews": [],
        }
        self.buf = bytearray()

    def view(self, data: bytes) -> int:
        self.buf += b"\0" * (-len(self.buf) % 4)
        self.doc["bufferViews"].append(
            {"buffer": 0, "byteOffset": len(self.buf), "byteLength": len(data)}
        )
        self.buf += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, arr: np.ndarray, ctype: int, kind: str) -> int:
        acc = {"bufferView": self.view(arr.tobytes()), "componentType": ctype}
        acc.update({"count": len(arr), "type": kind})
        if kind == "VEC3":
            acc.update({"min": arr.min(axis=0).tolist(), "max": arr.max(axis=0).tolist()})
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, prims, name: str | None = None) -> int:
        """prims: (triangles (t, 3, 3) in file coordinates, material index or None)."""
        out = []
        for tris, mat in prims:
            pos = np.asarray(tris, np.float32).reshape(-1, 3)
            idx = np.arange(len(pos), dtype=np.uint32)
            prim = {"attributes": {"POSITION": self.accessor(pos, 5126, "VEC3")}}
            prim["indices"] = self.accessor(idx, 5125, "SCALAR")
            if mat is not None:
                prim["material"] = mat
            out.append(prim)
        self.doc["meshes"].append({"primitives": out, **({"name": name} if name else {})})
        return len(self.doc["meshes"]) - 1

    def material(self, name: str | None, rgba=None, png: bytes | None = None, **extra) -> int:
        pbr: dict = {}
        if rgba is not None:
            pbr["baseColorFactor"] = list(rgba)
        if png is not None:
            self.doc.setdefault("images", []).append(
                {"bufferView": self.view(png), "mimeType": "image/png"}
            )
            self.doc.setdefault("textures", []).append({"source": len(self.doc["images"]) - 1})
            pbr["baseColorTexture"] = {"index": len(self.doc["textures"]) - 1}
        mat = {"pbrMetallicRoughness": pbr, **extra}
        if name is not None:
            mat["name"] = name
        self.doc["materials"].append(mat)
        return len(self.doc["materials"]) - 1

    def node(self, name=None, mesh=None, root=True, children=(), **trs) -> int:
        node = {k: v for k, v in trs.items()}
        if name is not None:
            node["name"] = name
        if mesh is not None:
            node["mesh"] = mesh
        if children:
            node["children"] = list(children)
        self.doc["nodes"].append(node)
        k = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(k)
        return k

    def part(self, name, polygons, mat=None, **trs) -> int:
        """A node named ``name`` with one mesh of the z-up ``polygons``."""
        tris = np.concatenate([fan(to_y_up(p)) for p in polygons])
        return self.node(name, self.mesh([(tris, mat)], name + "-mesh"), **trs)

    def save(self, path: Path, external_bin: bool = False) -> Path:
        doc = dict(self.doc)
        data = bytes(self.buf) + b"\0" * (-len(self.buf) % 4)
        if path.suffix == ".glb":
            doc["buffers"] = [{"byteLength": len(data)}]
            text = json.dumps(doc).encode()
            text += b" " * (-len(text) % 4)
            body = struct.pack("<II", len(text), 0x4E4F534A) + text
            body += struct.pack("<II", len(data), 0x004E4942) + data
            path.write_bytes(b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body)
        else:
            if external_bin:
                path.with_suffix(".bin").write_bytes(data)
                uri = path.with_suffix(".bin").name
            else:
                uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
            doc["buffers"] = [{"byteLength": len(data), "uri": uri}]
            path.write_text(json.dumps(doc))
        return path


def box_polygons() -> dict[str, list[np.ndarray]]:
    """The OBJ tests' 4 x 3 x 2.5 m box, z up, faces into the room, by group."""
    lines = BOX.splitlines()
    v = np.array([[float(x) for x in ln.split()[1:]] for ln in lines if ln.startswith("v ")])
    out: dict[str, list[np.ndarray]] = {}
    group = None
    for ln in lines:
        if ln.startswith("g "):
            group = ln.split()[1]
        elif ln.startswith("f "):
            out.setdefault(group, []).append(v[[int(i) - 1 for i in ln.split()[1:]]])
    return out


GREYS = {"floor": 0.2, "ceiling": 0.8, "walls": 0.5}


def box_gltf(path: Path, **save) -> Path:
    g = Gltf()
    for name, polys in box_polygons().items():
        grey = GREYS[name]
        g.part(name, polys, g.material(name + "-paint", [grey, grey, grey, 1.0]))
    return g.save(path, **save)


def group_area(scene, group):
    return sum(s.area for s in scene.surfaces if s.group == group)


# --- the same room as OBJ and glTF ------------------------------------------------------------


@pytest.mark.parametrize("name", ["room.glb", "room.gltf"])
def test_a_gltf_room_imports_as_the_same_scene_as_its_obj(tmp_path, name):
    scene = load_gltf(box_gltf(tmp_path / name), resolution=0.5)
    (tmp_path / "room.obj").write_text(BOX)
    ref = load_obj(tmp_path / "room.obj", resolution=0.5)
    assert scene.groups == ref.groups == ("floor", "ceiling", "walls")
    for g in ref.groups:
        assert group_area(scene, g) == pytest.approx(group_area(ref, g))
    # Each quad arrives as two triangles and is joined back into a rectangle: the same
    # grid patches as the OBJ's rectangles, not subdivided triangles.
    assert all(s.rect is not None for s in scene.surfaces)
    p, q = mesh_patches(scene), mesh_patches(ref)
    assert p.n == q.n == 236
    assert np.allclose(np.sort(p.area), np.sort(q.area))
    inward = ((np.array([2.0, 1.5, 1.25]) - p.centroid) * p.normal).sum(axis=1)
    assert np.all(inward > 0)
    # Reflectances are the base colours' luminance (linear RGB, glTF's convention).
    for g, grey in GREYS.items():
        assert [s.reflectance for s in scene.surfaces if s.group == g] == pytest.approx(
            [grey] * len([s for s in scene.surfaces if s.group == g])
        )
    assert scene.info["source"] == str(tmp_path / name)
    assert scene.info["warnings"] == []
    assert report_of(scene).summary() == f"{name}: 3 items: 0 zones, 3 groups, 0 dropped"


def test_a_closed_gltf_room_keeps_its_light(tmp_path):
    p = mesh_patches(load_gltf(box_gltf(tmp_path / "room.glb"), resolution=0.5))
    assert lost_fraction(form_factor_matrix(p, 256, seed=1), p) < 1e-3


def test_gltf_with_an_external_buffer_file(tmp_path):
    scene = load_gltf(box_gltf(tmp_path / "room.gltf", external_bin=True), resolution=0.5)
    assert scene.area == pytest.approx(59.0)


def test_gltf_is_y_up_by_default_and_up_z_keeps_the_file_axes(tmp_path):
    path = box_gltf(tmp_path / "room.glb")
    lo, hi = _bounds(load_gltf(path, resolution=0.5))
    assert np.allclose(lo, 0) and np.allclose(hi, [4, 3, 2.5])
    lo, hi = _bounds(load_gltf(path, resolution=0.5, up="z"))  # read as the file says
    assert np.allclose(lo, [0, 0, -3]) and np.allclose(hi, [4, 2.5, 0])
    # PLY has no convention: z up, as OBJ.
    assert load_scene(str(path)).area == pytest.approx(59.0)


def _bounds(scene):
    """Lowest and highest corner of the scene's surfaces (m)."""
    pts = []
    for s in scene.surfaces:
        if s.rect is not None:
            r = s.rect
            pts += [r.origin, r.origin + r.u, r.origin + r.v, r.origin + r.u + r.v]
        else:
            pts += list(s.triangles.reshape(-1, 3))
    return np.min(pts, axis=0), np.max(pts, axis=0)


def test_scale_turns_model_units_into_metres(tmp_path):
    g = Gltf()
    for name, polys in box_polygons().items():
        g.part(name, [1000 * p for p in polys])
    scene = load_gltf(g.save(tmp_path / "mm.glb"), resolution=0.5, scale=0.001)
    assert scene.area == pytest.approx(59.0)


# --- nodes, transforms, names -------------------------------------------------------------


SQUARE = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)  # faces +z


def moved(dx: float) -> np.ndarray:
    """The unit square moved ``dx`` metres along x."""
    return SQUARE + np.array([dx, 0.0, 0.0])


def test_node_transforms_are_applied_down_the_tree(tmp_path):
    g = Gltf()
    mesh = g.mesh([(fan(to_y_up(SQUARE)), None)], "tile")
    # child: scaled 2x, then moved 1 m along file x; parent: turned 90 degrees about file
    # y (z up), which takes file (x, 0, z) to (z, 0, -x), then moved 10 m along file x.
    child = g.node("Tile", mesh, root=False, translation=[1, 0, 0], scale=[2, 2, 2])
    s = np.sqrt(0.5)
    g.node("Group", children=[child], translation=[10, 0, 0], rotation=[0, s, 0, s])
    scene = load_gltf(g.save(tmp_path / "t.glb"), resolution=0.5)
    assert scene.groups == ("Tile",)
    (surface,) = scene.surfaces
    assert surface.area == pytest.approx(4.0)
    # The square's z-up point (x, y, 0) is (x, 0, -y) in the file; the child makes it
    # (2x + 1, 0, -2y), the parent (10 - 2y, 0, -2x - 1), which is z-up (10 - 2y, 2x + 1, 0):
    # x from 8 to 10, y from 1 to 3.
    corners = surface.rect.origin + np.array(
        [[0, 0, 0], surface.rect.u, surface.rect.v, surface.rect.u + surface.rect.v]
    )
    expected = [(8, 1, 0), (8, 3, 0), (10, 1, 0), (10, 3, 0)]
    assert np.allclose(sorted(map(tuple, corners.round(9))), expected)
    assert np.allclose(surface.rect.normal, [0, 0, 1])


def test_a_mirroring_node_keeps_faces_facing_the_right_way(tmp_path):
    g = Gltf()
    mesh = g.mesh([(fan(to_y_up(SQUARE)), None)])
    g.node("plain", mesh)
    g.node("mirrored", mesh, scale=[-1, 1, 1])  # mirrored in x: still faces up
    scene = load_gltf(g.save(tmp_path / "m.glb"), resolution=0.5)
    for s in scene.surfaces:
        assert np.allclose(s.rect.normal, [0, 0, 1]), s.name


def test_group_names_nodes_meshes_and_materials(tmp_path):
    g = Gltf()
    paint, glass = g.material("Paint", [0.5, 0.5, 0.5, 1]), g.material(None, [0.1, 0.1, 0.1, 1])
    a = fan(to_y_up(SQUARE))
    b = fan(to_y_up(moved(2)))
    two = g.mesh([(a, paint), (b, glass)], "two-prims")
    g.node("Desk", two)  # two primitives: one group, two materials
    g.node(None, g.mesh([(fan(to_y_up(moved(4))), paint)], "Shelf"))  # unnamed
    g.node(None, g.mesh([(fan(to_y_up(moved(6))), None)]))  # nothing named
    g.node("Desk", g.mesh([(fan(to_y_up(moved(8))), paint)]))  # same name
    path = g.save(tmp_path / "names.glb")
    scene = load_gltf(path, resolution=0.5)
    assert scene.groups == ("Desk", "Shelf", "node 2")
    assert group_area(scene, "Desk") == pytest.approx(3.0)
    desk = sorted({round(s.reflectance, 9) for s in scene.surfaces if s.group == "Desk"})
    assert desk == [0.1, 0.5]
    by_mat = load_gltf(path, resolution=0.5, group_by="material")
    assert by_mat.groups == ("Paint", "material 1", "default")
    assert group_area(by_mat, "Paint") == pytest.approx(3.0)
    # The materials mapping names glTF groups and materials as for OBJ.
    mapped = load_gltf(path, resolution=0.5, materials={"materials": {"material 1": 0.3}})
    desk = sorted({round(s.reflectance, 9) for s in mapped.surfaces if s.group == "Desk"})
    assert desk == [0.3, 0.5]
    assert "no reflectance for material" not in " ".join(mapped.info["warnings"])


def test_zone_nodes_become_emitter_zones(tmp_path):
    g = Gltf()
    for name, polys in box_polygons().items():
        g.part(name, polys)
    sky = np.array([[1, 1, 2.4], [1, 2, 2.4], [3, 2, 2.4], [3, 1, 2.4]], float)  # faces down
    g.part("zone:sky:skylight", [sky])
    scene = load_gltf(g.save(tmp_path / "z.glb"), resolution=0.5)
    (zone,) = scene.zones
    assert (zone.name, zone.kind) == ("sky", "skylight")
    rect = scene.zone_rect("sky")
    assert rect.area == pytest.approx(2.0)
    assert np.allclose(rect.normal, [0, 0, -1])


# --- reflectances from colours ------------------------------------------------------------


def png(colours) -> bytes:
    from PIL import Image

    img = Image.fromarray(np.array(colours, np.uint8))
    out = io.BytesIO()
    img.save(out, format="PNG")
    return out.getvalue()


def test_base_colour_texture_and_white_cap(tmp_path):
    g = Gltf()
    # A black-and-white checker averages 0.5 in linear light (not 0.21, the sRGB mean).
    checker = png([[[0, 0, 0], [255, 255, 255]], [[255, 255, 255], [0, 0, 0]]])
    tex = g.material("Checker", [1, 1, 1, 1], png=checker)
    white = g.material("White", [1, 1, 1, 1])
    glass = g.material("Glass", [0.9, 0.9, 0.9, 0.2], alphaMode="BLEND")
    for k, mat in enumerate((tex, white, glass)):
        g.part(f"p{k}", [moved(2 * k)], mat)
    scene = load_gltf(g.save(tmp_path / "c.glb"), resolution=0.5)
    rho = {s.group: s.reflectance for s in scene.surfaces}
    assert rho["p0"] == pytest.approx(0.5, abs=1e-6)
    # Averaging the stored (sRGB) values instead would give 0.21.
    assert srgb_to_linear(np.array(0.5)) == pytest.approx(0.214, abs=1e-3)
    assert rho["p1"] == 0.95
    warnings = scene.info["warnings"]
    assert (
        "material 'White': glTF baseColor luminance 1 capped at 0.95 (exporters write "
        "glTF baseColor 1 1 1 for white, and a reflectance of 1 makes radiosity diverge); "
        "give its reflectance in the materials mapping to silence this"
    ) in warnings
    assert any("material(s) 'Glass' are transparent" in w for w in warnings)


# --- joining triangles ---------------------------------------------------------------------


def test_join_coplanar_rebuilds_polygons_and_leaves_the_rest():
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]], float)
    t = np.array([[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]])
    f = join_coplanar(v, t, np.zeros(4, int))
    (poly,) = f.polygons
    assert not len(f.left)
    assert np.allclose(f.vertices[poly], [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]])
    # Different keys (group, material) are never joined.
    f = join_coplanar(v, t, np.array([0, 0, 1, 1]))
    assert len(f.polygons) == 2
    # A triangle turned the other way stays a triangle, as does its partner.
    flipped = t.copy()
    flipped[3] = flipped[3][::-1]
    f = join_coplanar(v, flipped, np.zeros(4, int))
    assert len(f.polygons) == 1 and sorted(f.left.tolist()) == [2, 3]


def test_join_coplanar_keeps_holes_as_triangles():
    import trimesh

    ring = trimesh.creation.annulus(1, 2, 1, sections=16)
    f = join_coplanar(ring.vertices, ring.faces, np.zeros(len(ring.faces), int))
    # The 16 side quads are joined; the two faces with a hole stay triangles.
    assert sorted(len(p) for p in f.polygons) == [4] * 32
    assert len(f.left) == 64


def test_an_l_shaped_floor_of_triangles_is_one_polygon(tmp_path):
    l_shape = [[0, 0, 0], [4, 0, 0], [4, 2, 0], [2, 2, 0], [2, 4, 0], [0, 4, 0]]
    tris = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]])
    g = Gltf()
    g.node("L", g.mesh([(to_y_up(np.array(l_shape, float))[tris], None)]))
    scene = load_gltf(g.save(tmp_path / "l.glb"), resolution=0.5)
    assert scene.area == pytest.approx(12.0)
    # Cut by the grid (polygon_mesh) as an OBJ polygon is: 48 cells of 0.5 m.
    assert mesh_patches(scene).n == 48


# --- PLY --------------------------------------------------------------------------------------


def box_ply(path: Path, colours: bool, binary: bool = False) -> Path:
    import trimesh

    polys = [p for ps in box_polygons().values() for p in ps]
    v = np.concatenate(polys)
    faces = np.concatenate([np.array([[0, 1, 2], [0, 2, 3]]) + 4 * k for k in range(len(polys))])
    mesh = trimesh.Trimesh(v, faces, process=False)
    if colours:
        c = np.array([[51, 51, 51, 255]] * 2 + [[230, 230, 230, 255]] * 2 + [[128] * 3 + [255]] * 8)
        mesh.visual.face_colors = c
    path.write_bytes(mesh.export(file_type="ply", encoding="binary" if binary else "ascii"))
    return path


@pytest.mark.parametrize("binary", [False, True])
def test_ply_faces_are_grouped_by_colour(tmp_path, binary):
    scene = load_ply(box_ply(tmp_path / "room.ply", True, binary), resolution=0.5)
    assert scene.groups == ("colour #333333", "colour #808080", "colour #E6E6E6")
    assert group_area(scene, "colour #808080") == pytest.approx(35.0)
    rho = {s.group: s.reflectance for s in scene.surfaces}
    # sRGB 51 is linear 0.0331; 230 is 0.7913.
    assert rho["colour #333333"] == pytest.approx(0.033105, abs=1e-5)
    assert rho["colour #E6E6E6"] == pytest.approx(0.791298, abs=1e-5)
    assert mesh_patches(scene).n == 236


def test_a_ply_without_colours_is_one_group(tmp_path):
    scene = load_ply(box_ply(tmp_path / "room.ply", False), resolution=0.5)
    assert scene.groups == ("room",)
    assert {s.reflectance for s in scene.surfaces} == {0.5}


# --- projects and the command line ---------------------------------------------------------


def test_a_project_scene_takes_a_glb_and_its_up_axis(tmp_path):
    path = box_gltf(tmp_path / "room.glb")
    spec = SceneSpec(obj=str(path), resolution=0.5)
    assert spec.up == "y"
    assert SCENE.write(spec)["up"] == "y"
    assert spec.load().area == pytest.approx(59.0)
    assert SceneSpec(obj="room.obj").up == "z"
    by_mat = SceneSpec(obj=str(path), resolution=0.5, group_by="material")
    assert by_mat.load().groups == ("floor-paint", "ceiling-paint", "walls-paint")
    assert SCENE.write(by_mat)["group_by"] == "material"
    with pytest.raises(ProjectError, match=r"^group_by: only a glTF scene"):
        SceneSpec(obj="room.obj", group_by="material")


def test_cli_simulates_a_glb(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    path = box_gltf(tmp_path / "room.glb")
    argv = ["simulate", str(path), "--resolution", "0.5", "--emit", "ceiling=1000", "--json"]
    assert cli.main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["patches"] == 236
    assert out["lost_fraction"] < 1e-3
    assert out["energy"]["absorbed_lm"] == pytest.approx(1000, rel=5e-3)


# --- bad files ---------------------------------------------------------------------------


def test_bad_gltf_files_are_one_line_errors(tmp_path):
    cases = {
        "text.glb": (b"solid cube\n", r"text\.glb: not a binary glTF \(GLB\) file"),
        "v1.glb": (b"glTF" + struct.pack("<II", 1, 20) + b"\0" * 8, r"glTF version 1"),
        "cut.glb": (
            b"glTF" + struct.pack("<IIII", 2, 100, 500, 0x4E4F534A) + b"{}",
            r"cut\.glb: the GLB file is truncated",
        ),
        "bad.gltf": (b"{not json", r"bad\.gltf: not a glTF file \(its JSON cannot be read"),
        "noasset.gltf": (b"{}", r'noasset\.gltf: not a glTF file \(no "asset" object\)'),
        "draco.gltf": (
            json.dumps(
                {"asset": {"version": "2.0"}, "extensionsRequired": ["KHR_draco_mesh_compression"]}
            ).encode(),
            r"draco\.gltf: its meshes are compressed \(KHR_draco_mesh_compression\)",
        ),
    }
    for name, (data, pattern) in cases.items():
        (tmp_path / name).write_bytes(data)
        with pytest.raises(ObjImportError, match=pattern) as info:
            load_gltf(tmp_path / name)
        assert "\n" not in str(info.value)
    g = Gltf()
    g.doc["accessors"].append({"componentType": 5126, "count": 3, "type": "VEC3"})
    g.node("points", g.mesh([]))
    g.doc["meshes"][-1]["primitives"] = [{"attributes": {"POSITION": 0}, "mode": 0}]
    with pytest.raises(ObjImportError, match=r"p\.glb: no triangles found"):
        load_gltf(g.save(tmp_path / "p.glb"))
    with pytest.raises(ObjImportError, match=r"glTF file '.*gone\.glb' does not exist"):
        load_gltf(tmp_path / "gone.glb")
    with pytest.raises(ObjImportError, match=r"group_by='layer' is not supported"):
        load_gltf(box_gltf(tmp_path / "room.glb"), group_by="layer")


def test_degenerate_and_huge_triangles(tmp_path):
    g = Gltf()
    for name, polys in box_polygons().items():
        g.part(name, polys)
    flat = np.array([[[0, 0, 0], [1, 0, 0], [2, 0, 0]]], float)  # zero area
    g.node("Junk", g.mesh([(to_y_up(flat.reshape(-1, 3)).reshape(1, 3, 3), None)]))
    path = g.save(tmp_path / "d.glb")
    with pytest.raises(
        ObjImportError, match=r"1 degenerate face\(s\) .* at triangle 1 of node 'Junk'"
    ):
        load_gltf(path, resolution=0.5)
    scene = load_gltf(path, resolution=0.5, skip_degenerate=True)
    assert "Junk" not in scene.groups
    assert any("dropped 1 degenerate face(s)" in w for w in scene.info["warnings"])
    g = Gltf()
    g.part("Far", [SQUARE * 1e9])
    with pytest.raises(ObjImportError, match=r"node 'Far' has a coordinate that is larger"):
        load_gltf(g.save(tmp_path / "far.glb"))


def test_bad_ply_files(tmp_path):
    (tmp_path / "a.ply").write_text("solid cube\n")
    with pytest.raises(ObjImportError, match=r"a\.ply: not a PLY file"):
        load_ply(tmp_path / "a.ply")
    cloud = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    cloud += "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
    (tmp_path / "b.ply").write_text(cloud)
    with pytest.raises(ObjImportError, match=r"b\.ply: no faces found \(3 vertices\)"):
        load_ply(tmp_path / "b.ply")


PLY_HEAD = (
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face {n}\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n"
)


@pytest.mark.parametrize(
    ("faces", "where", "number"),
    [
        (["3 0 1 99999999"], "face 1", "99,999,999"),
        (["3 0 1 2", "3 2 1 -1"], "face 2", "-1"),
        (["4 0 1 2 7"], "triangle 2 (of its faces split)", "7"),
    ],
)
def test_a_ply_face_naming_a_missing_vertex_is_a_one_line_error(tmp_path, faces, where, number):
    """trimesh passes vertex numbers through unchecked: 99,999,999 of 3 was an IndexError
    traceback, and -1 silently took the last vertex."""
    path = tmp_path / "bad.ply"
    path.write_text(PLY_HEAD.format(n=len(faces)) + "\n".join(faces) + "\n")
    with pytest.raises(ObjImportError) as info:
        load_ply(path)
    assert str(info.value) == (
        f"bad.ply: {where} names vertex {number}, but the file has 3 vertices (numbered 0 "
        "to 2); the file is damaged, export it again"
    )


def test_a_gltf_primitive_of_lines_is_in_the_import_report(tmp_path):
    """Primitives of lines or points are left out (a warning said how many): the import
    report names them, beside a group per node."""
    g = Gltf()
    for name, polys in box_polygons().items():
        g.part(name, polys)
    g.doc["accessors"].append(
        {
            "componentType": 5126,
            "count": 2,
            "type": "VEC3",
            "bufferView": g.doc["accessors"][0]["bufferView"],
            "min": [0, 0, 0],
            "max": [4, 3, 0],
        }
    )
    g.node("guide lines", g.mesh([]))
    lines = len(g.doc["accessors"]) - 1
    g.doc["meshes"][-1]["primitives"] = [{"attributes": {"POSITION": lines}, "mode": 1}]
    scene = load_gltf(g.save(tmp_path / "room.glb"), up="z")
    report = report_of(scene)
    assert [(it.kind, it.name, it.outcome) for it in report.items] == [
        ("glTF node", "floor", "group"),
        ("glTF node", "ceiling", "group"),
        ("glTF node", "walls", "group"),
        ("glTF primitive", "guide lines", "dropped"),
    ]
    assert report.dropped[0].reason == "lines or points: LightInv reads triangles only"
    assert any("ignored 1 primitive(s) of lines or points" in w for w in scene.info["warnings"])
