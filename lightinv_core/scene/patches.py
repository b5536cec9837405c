"""Patches: the scene's surfaces meshed into small planar elements.

A patch is either a parallelogram ``origin + s*edge1 + t*edge2`` (s, t in
[0, 1]; the cells of a rectangle's grid) or a triangle
``origin + s*edge1 + t*edge2`` (s, t >= 0, s + t <= 1). The radiosity of a
patch is constant over it. Units: metres, m².
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import SceneError
from lightinv_core.scene.model import Scene, Surface

MAX_PATCHES = 2_000_000


@dataclass(frozen=True, eq=False)
class Patches:
    """The meshed scene, one row per patch.

    Attributes
    ----------
    origin, edge1, edge2 : (n, 3) float
        Patch geometry (see module docstring).
    is_triangle : (n,) bool
    area : (n,) float, m²
    centroid, normal : (n, 3) float (unit front normals)
    rho : (n,) float, diffuse reflectance
    surface_id, group_id : (n,) int32, indices into ``surface_names`` / ``group_names``
    zone_id : (n,) int32, index into ``zone_names`` or -1
    grid_ij : (n, 2) int32, cell (i along u, j along v) of a rectangle's grid, -1 for triangles
    grid_shape : dict surface name -> (nu, nv) for rectangle surfaces
    """

    origin: np.ndarray
    edge1: np.ndarray
    edge2: np.ndarray
    is_triangle: np.ndarray
    area: np.ndarray
    centroid: np.ndarray
    normal: np.ndarray
    rho: np.ndarray
    surface_id: np.ndarray
    group_id: np.ndarray
    zone_id: np.ndarray
    grid_ij: np.ndarray
    surface_names: tuple[str, ...]
    group_names: tuple[str, ...]
    zone_names: tuple[str, ...]
    grid_shape: dict

    @property
    def n(self) -> int:
        """Number of patches."""
        return len(self.area)

    def __len__(self) -> int:
        return self.n

    def group_index(self, name: str) -> np.ndarray:
        """Patch indices of group ``name`` (SceneError listing the groups if unknown)."""
        if name not in self.group_names:
            known = ", ".join(self.group_names)
            raise SceneError(f"no group {name!r} in the scene (groups: {known})")
        return np.flatnonzero(self.group_id == self.group_names.index(name))

    def zone_index(self, name: str) -> np.ndarray:
        """Patch indices of emitter zone ``name``."""
        if name not in self.zone_names:
            known = ", ".join(self.zone_names) or "none"
            raise SceneError(f"no emitter zone {name!r} in the scene (zones: {known})")
        return np.flatnonzero(self.zone_id == self.zone_names.index(name))

    def triangle_mesh(
        self, center: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Triangles covering the patches, for ray casting and display.

        ``center`` (m, world coordinates) is subtracted in float64 before the
        vertices are rounded to float32, so far-off models keep their precision.
        Returns ``(vertices (m, 3) float32, faces (t, 3) int32, tri_patch (t,) int32)``:
        a quad patch gives two triangles, a triangle patch one; vertices are not
        shared between patches.
        """
        quads = np.flatnonzero(~self.is_triangle)
        tris = np.flatnonzero(self.is_triangle)
        o, e1, e2 = self.origin, self.edge1, self.edge2
        if center is not None:
            o = o - np.asarray(center, dtype=np.float64)
        qv = np.stack(
            [
                o[quads],
                o[quads] + e1[quads],
                o[quads] + e1[quads] + e2[quads],
                o[quads] + e2[quads],
            ],
            axis=1,
        ).reshape(-1, 3)
        tv = np.stack([o[tris], o[tris] + e1[tris], o[tris] + e2[tris]], axis=1).reshape(-1, 3)
        nq = len(quads)
        base = 4 * np.arange(nq, dtype=np.int64)[:, None]
        qf = np.concatenate([base + np.array([0, 1, 2]), base + np.array([0, 2, 3])], axis=0)
        qp = np.concatenate([quads, quads])
        tf = 4 * nq + 3 * np.arange(len(tris), dtype=np.int64)[:, None] + [0, 1, 2]
        vertices = np.ascontiguousarray(np.concatenate([qv, tv]), dtype=np.float32)
        faces = np.ascontiguousarray(np.concatenate([qf, tf]), dtype=np.int32)
        tri_patch = np.concatenate([qp, tris]).astype(np.int32)
        return vertices, faces, tri_patch

    def digest(self) -> str:
        """SHA-256 of the geometry and reflectances: the key of anything derived from them."""
        h = hashlib.sha256()
        for arr in (self.origin, self.edge1, self.edge2, self.rho):
            h.update(np.ascontiguousarray(arr, dtype=np.float64).tobytes())
        h.update(self.is_triangle.tobytes())
        return h.hexdigest()


def grid_counts(length_u: float, length_v: float, resolution: float) -> tuple[int, int]:
    """Cells along u and v for a rectangle meshed at a target patch size."""
    return max(1, round(length_u / resolution)), max(1, round(length_v / resolution))


def _subdivisions(tri: np.ndarray, resolution: float) -> np.ndarray:
    """Subdivision level m (m² sub-triangles) per triangle: longest edge / resolution."""
    edges = np.stack([tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 1], tri[:, 0] - tri[:, 2]], 1)
    longest = np.linalg.norm(edges, axis=2).max(axis=1)
    return np.maximum(1, np.ceil(longest / resolution - 1e-9)).astype(np.int64)


def count_patches(scene: Scene, resolution: float | None = None) -> int:
    """Number of patches ``mesh_patches`` would make at ``resolution`` m (default the
    scene's), computed without meshing; ``math.inf`` gives the fewest possible."""
    res = scene.resolution if resolution is None else resolution
    total = 0
    for s in scene.surfaces:
        if s.rect is not None:
            nu, nv = s.grid or grid_counts(*s.rect.size, res)
            total += nu * nv
        else:
            total += int((_subdivisions(s.triangles, res) ** 2).sum())
    return total


def _span(scene: Scene) -> float:
    """Largest extent of the scene's bounding box (m)."""
    pts = [s.rect.point(a, b) for s in scene.surfaces if s.rect is not None for a, b in CORNERS]
    pts += [s.triangles.reshape(-1, 3) for s in scene.surfaces if s.triangles is not None]
    allp = np.vstack([np.atleast_2d(p) for p in pts])
    return float(np.ptp(allp, axis=0).max())


CORNERS = ((0, 0), (1, 0), (0, 1), (1, 1))


def too_many_patches(scene: Scene, count: int) -> str:
    """Why ``count`` patches is over ``MAX_PATCHES`` and what would help: a coarser
    resolution that fits, or (when each face alone is a patch too many) a simpler model."""
    head = f"resolution {scene.resolution} m would make {count:,} patches (limit {MAX_PATCHES:,})"
    fewest = count_patches(scene, math.inf)
    if fewest > MAX_PATCHES:
        advice = (
            f"the model itself has {fewest:,} faces and each is at least one patch, so no "
            "resolution can help; simplify it in the modeller (merge coplanar faces, drop "
            "furniture detail) or import one floor or room at a time"
        )
    else:
        res = scene.resolution * math.sqrt(count / MAX_PATCHES)
        for _ in range(60):
            if count_patches(scene, res) <= MAX_PATCHES:
                break
            res *= 1.1
        advice = f"use a resolution of at least {res:.3g} m"
    span = _span(scene)
    if span > BIG_SPAN:
        advice += (
            f"; the model is {span:,.0f} m across: if it was drawn in millimetres import it "
            "with scale 0.001 (--scale 0.001; centimetres 0.01)"
        )
    return f"{head}; {advice}"


BIG_SPAN = 1000.0
"""Metres; a model wider than this was probably not drawn in metres."""


def _mesh_rect(surface: Surface, resolution: float):
    r = surface.rect
    nu, nv = surface.grid or grid_counts(*r.size, resolution)
    e1, e2 = r.u / nu, r.v / nv
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    i, j = i.ravel(), j.ravel()
    origin = r.origin + i[:, None] * e1 + j[:, None] * e2
    m = len(i)
    return (
        origin,
        np.tile(e1, (m, 1)),
        np.tile(e2, (m, 1)),
        np.zeros(m, bool),
        np.stack([i, j], 1),
        (nu, nv),
    )


def _subdivide_triangle(a, b, c, m: int):
    """Regular subdivision of triangle abc into m² triangles (origin, e1, e2 each (m², 3))."""
    d1, d2 = (b - a) / m, (c - a) / m
    i, j = np.meshgrid(np.arange(m), np.arange(m), indexing="ij")
    up = (i + j) <= m - 1
    iu, ju = i[up], j[up]
    up_o = a + iu[:, None] * d1 + ju[:, None] * d2
    down = (i + j) <= m - 2
    idn, jdn = i[down], j[down]
    # The inverted triangle of a cell has corners (i+1, j), (i+1, j+1)... written
    # from (i+1, j+1) with edges -d1, -d2 so its normal matches the parent's.
    dn_o = a + (idn[:, None] + 1) * d1 + (jdn[:, None] + 1) * d2
    origin = np.concatenate([up_o, dn_o])
    e1 = np.concatenate([np.tile(d1, (len(iu), 1)), np.tile(-d1, (len(idn), 1))])
    e2 = np.concatenate([np.tile(d2, (len(iu), 1)), np.tile(-d2, (len(idn), 1))])
    return origin, e1, e2


def _mesh_triangles(surface: Surface, resolution: float):
    tri = surface.triangles
    ms = _subdivisions(tri, resolution)
    parts = [_subdivide_triangle(t[0], t[1], t[2], int(m)) for t, m in zip(tri, ms, strict=True)]
    origin = np.concatenate([p[0] for p in parts])
    e1 = np.concatenate([p[1] for p in parts])
    e2 = np.concatenate([p[2] for p in parts])
    m = len(origin)
    return origin, e1, e2, np.ones(m, bool), np.full((m, 2), -1), None


def mesh_patches(scene: Scene) -> Patches:
    """Mesh every surface of ``scene`` at ``scene.resolution`` into patches."""
    n_expected = count_patches(scene)
    if n_expected > MAX_PATCHES:
        raise SceneError(too_many_patches(scene, n_expected))
    groups = scene.groups
    zone_of_surface = {z.surface: k for k, z in enumerate(scene.zones)}
    cols: dict[str, list] = {k: [] for k in ("o", "e1", "e2", "tri", "sid", "gid", "zid", "ij")}
    grid_shape = {}
    for sid, s in enumerate(scene.surfaces):
        mesher = _mesh_rect if s.rect is not None else _mesh_triangles
        o, e1, e2, tri, ij, shape = mesher(s, scene.resolution)
        if shape is not None:
            grid_shape[s.name] = shape
        m = len(o)
        cols["o"].append(o)
        cols["e1"].append(e1)
        cols["e2"].append(e2)
        cols["tri"].append(tri)
        cols["sid"].append(np.full(m, sid))
        cols["gid"].append(np.full(m, groups.index(s.group)))
        cols["zid"].append(np.full(m, zone_of_surface.get(s.name, -1)))
        cols["ij"].append(ij)
    origin = np.concatenate(cols["o"])
    e1 = np.concatenate(cols["e1"])
    e2 = np.concatenate(cols["e2"])
    is_tri = np.concatenate(cols["tri"])
    cross = np.cross(e1, e2)
    norm = np.linalg.norm(cross, axis=1)
    area = np.where(is_tri, 0.5, 1.0) * norm
    bad = np.flatnonzero(area <= 1e-14)
    if len(bad):
        sid = int(np.concatenate(cols["sid"])[bad[0]])
        raise SceneError(
            f"surface {scene.surfaces[sid].name!r} has {len(bad)} zero-area patch(es); "
            "remove degenerate faces"
        )
    centroid = origin + np.where(is_tri, 1.0 / 3.0, 0.5)[:, None] * (e1 + e2)
    surface_id = np.concatenate(cols["sid"]).astype(np.int32)
    rho = np.array([s.reflectance for s in scene.surfaces])[surface_id]
    return Patches(
        origin=origin,
        edge1=e1,
        edge2=e2,
        is_triangle=is_tri,
        area=area,
        centroid=centroid,
        normal=cross / norm[:, None],
        rho=rho,
        surface_id=surface_id,
        group_id=np.concatenate(cols["gid"]).astype(np.int32),
        zone_id=np.concatenate(cols["zid"]).astype(np.int32),
        grid_ij=np.concatenate(cols["ij"]).astype(np.int32),
        surface_names=tuple(s.name for s in scene.surfaces),
        group_names=groups,
        zone_names=tuple(z.name for z in scene.zones),
        grid_shape=grid_shape,
    )
