"""Scene model, patches and the built-in scenes."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.errors import SceneError
from lightinv_core.scene.builtin import BUILTIN_SCENES, builtin_scene
from lightinv_core.scene.model import EmitterZone, Rect, Scene, Surface
from lightinv_core.scene.patches import count_patches, mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix, lost_fraction

# Default patch counts the issue asks for, within 10%.
TARGETS = {
    "cornell": 1000,
    "office": 5000,
    "patio": 24000,
    "corridor": 16700,
    "building": 200_000,
    "sidelit": 2900,  # the docstrings' "~2,900" and "~4,100"
    "toplit": 4100,
    "flagship": 5800,  # scene/flagship.py: "~5,800 patches at the default 0.3 m"
}


@pytest.mark.parametrize("name", list(BUILTIN_SCENES))
def test_default_patch_counts(name):
    n = count_patches(builtin_scene(name))
    assert abs(n - TARGETS[name]) <= 0.11 * TARGETS[name], n


@pytest.mark.parametrize(
    "name,res",
    [
        ("cornell", 0.3),
        ("office", 0.6),
        ("patio", 1.0),
        ("corridor", 0.8),
        ("building", 1.0),
        ("flagship", 0.6),
    ],
)
def test_builtin_scenes_are_closed_and_consistent(name, res):
    scene = builtin_scene(name, res)
    p = mesh_patches(scene)
    assert p.n == count_patches(scene)
    assert p.area.sum() == pytest.approx(scene.area, rel=1e-9)
    np.testing.assert_allclose(np.linalg.norm(p.normal, axis=1), 1.0)
    F = form_factor_matrix(p, 64, seed=0)
    assert lost_fraction(F, p) < 1e-4  # closed: no ray leaves the building
    for z in scene.zones:
        idx = p.zone_index(z.name)
        nu, nv = p.grid_shape[z.surface]
        assert len(idx) == nu * nv
        assert p.area[idx].sum() == pytest.approx(scene.zone_rect(z.name).area)


def test_scene_groups_and_zones():
    office = builtin_scene("office")
    assert {"floor", "walls", "ceiling", "roof", "desks"} <= set(office.groups)
    assert {z.name: z.kind for z in office.zones} == {
        "skylight": "skylight",
        "lum_west": "luminaire",
        "lum_east": "luminaire",
    }
    corridor = builtin_scene("corridor")
    assert {z.name for z in corridor.zones} == {"S1", "S2", "S3", "A1", "A2", "A3"}
    assert "panels" in corridor.groups
    # S1 and S3 mirror each other about x = 18 m; S2 is centred on it.
    s1, s2, s3 = (corridor.zone_rect(k) for k in ("S1", "S2", "S3"))
    c = [r.point(0.5, 0.5) for r in (s1, s2, s3)]
    assert c[0][0] + c[2][0] == pytest.approx(36.0) and c[1][0] == pytest.approx(18.0)
    patio = builtin_scene("patio")
    assert mesh_patches(patio).grid_shape["courtyard_roof"] == (32, 32)


def test_desk_tops_face_up_at_work_height():
    p = mesh_patches(builtin_scene("office", 0.5))
    idx = p.group_index("desks")
    np.testing.assert_allclose(p.centroid[idx, 2], 0.75)
    np.testing.assert_allclose(p.normal[idx], [[0, 0, 1]] * len(idx))


def test_triangle_surfaces_are_subdivided_regularly():
    tri = np.array([[[0, 0, 0], [2, 0, 0], [0, 2, 0]]], float)
    scene = Scene("t", (Surface("t", "t", 0.5, triangles=tri),), resolution=0.5)
    p = mesh_patches(scene)
    assert p.n == 36 and p.is_triangle.all()  # longest edge 2.83 m -> 6 x 6
    np.testing.assert_allclose(p.area, 2.0 / 36)
    np.testing.assert_allclose(p.normal, [[0, 0, 1]] * 36)
    assert p.centroid[:, 0].min() > 0 and (p.centroid[:, 0] + p.centroid[:, 1]).max() < 2


def test_triangle_mesh_maps_triangles_back_to_patches(cornell_patches):
    v, f, tri_patch = cornell_patches.triangle_mesh()
    assert v.dtype == np.float32 and f.dtype == np.int32
    a = 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1)
    per_patch = np.bincount(tri_patch, weights=a, minlength=cornell_patches.n)
    np.testing.assert_allclose(per_patch, cornell_patches.area, rtol=1e-5)


def test_digest_tracks_geometry_and_materials():
    a = mesh_patches(builtin_scene("cornell", 0.4))
    b = mesh_patches(builtin_scene("cornell", 0.4))
    c = mesh_patches(builtin_scene("cornell", 0.5))
    assert a.digest() == b.digest() != c.digest()


@pytest.mark.parametrize("rho", [-0.1, 1.0, 1.5, float("nan"), "white"])
def test_bad_reflectance_is_rejected(rho):
    with pytest.raises(SceneError, match="reflectance"):
        Surface("wall", "walls", rho, rect=Rect((0, 0, 0), (1, 0, 0), (0, 1, 0)))


def test_bad_scene_input_is_rejected():
    r = Rect((0, 0, 0), (1, 0, 0), (0, 1, 0))
    with pytest.raises(SceneError, match="non-orthogonal"):
        Rect((0, 0, 0), (1, 0, 0), (1, 1, 0))
    with pytest.raises(SceneError, match="finite"):
        Rect((0, float("inf"), 0), (1, 0, 0), (0, 1, 0))
    with pytest.raises(SceneError, match="duplicate surface"):
        Scene("s", (Surface("a", "g", 0.5, rect=r), Surface("a", "g", 0.5, rect=r)))
    with pytest.raises(SceneError, match="no surface named"):
        Scene("s", (Surface("a", "g", 0.5, rect=r),), (EmitterZone("z", "skylight", "b"),))
    with pytest.raises(SceneError, match="kind"):
        EmitterZone("z", "lamp", "a")
    with pytest.raises(SceneError, match="resolution"):
        Scene("s", (Surface("a", "g", 0.5, rect=r),), resolution=0)
    with pytest.raises(SceneError, match="no built-in scene 'atrium'"):
        builtin_scene("atrium")
    with pytest.raises(SceneError, match="patches"):
        mesh_patches(builtin_scene("patio", 0.006))
