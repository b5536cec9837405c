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
    zone_outlines : per zone (as ``zone_names``), its polygon outline (k, 2) in zone
        metres, or None for the whole rectangle (``EmitterZone.outline``)
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
    zone_outlines: tuple = ()

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

    def zone_outline(self, name: str) -> np.ndarray | None:
        """The polygon (k, 2) in zone metres sources in zone ``name`` must lie inside, or
        None when the whole rectangle is open to them."""
        self.zone_index(name)
        k = self.zone_names.index(name)
        return self.zone_outlines[k] if k < len(self.zone_outlines) else None

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
    _, nu, nv = _rect_grids(scene, res)
    total = int((nu * nv).sum())
    for s in scene.surfaces:
        if s.triangles is None:
            continue
        if not s.subdivide:
            total += len(s.triangles)
        else:
            total += int((_subdivisions(s.triangles, res) ** 2).sum())
    return total


def _rect_grids(scene: Scene, res: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Indices of the rectangle surfaces and their cell counts (nu, nv) at ``res``, all
    at once (``grid_counts`` per surface was most of the meshing of a big model)."""
    rows = np.array([k for k, s in enumerate(scene.surfaces) if s.rect is not None], dtype=int)
    if len(rows) == 0:
        return rows, np.zeros(0, np.int64), np.zeros(0, np.int64)
    rects = [scene.surfaces[k].rect for k in rows]
    lu = np.linalg.norm(np.array([r.u for r in rects]), axis=1)
    lv = np.linalg.norm(np.array([r.v for r in rects]), axis=1)
    with np.errstate(invalid="ignore"):
        nu = np.maximum(1, np.round(lu / res)).astype(np.int64)
        nv = np.maximum(1, np.round(lv / res)).astype(np.int64)
    for k, row in enumerate(rows):
        grid = scene.surfaces[row].grid
        if grid is not None:
            nu[k], nv[k] = grid
    return rows, nu, nv


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


def _mesh_rects(scene: Scene, res: float, slots: np.ndarray, out: dict[str, np.ndarray]) -> dict:
    """Write the grid cells of every rectangle surface into ``out`` at the surfaces'
    ``slots`` (first patch of each surface); returns {surface name: (nu, nv)}.

    Rectangles with the same grid are meshed together, each cell written where a
    surface-by-surface loop would have put it (``i`` along u slowest, then ``j``)."""
    rows, nu, nv = _rect_grids(scene, res)
    if len(rows) == 0:
        return {}
    rects = [scene.surfaces[k].rect for k in rows]
    org = np.array([r.origin for r in rects])
    U = np.array([r.u for r in rects])
    V = np.array([r.v for r in rects])
    shapes = np.column_stack([nu, nv])
    for shape in np.unique(shapes, axis=0):
        a, b = int(shape[0]), int(shape[1])
        sel = np.flatnonzero((nu == a) & (nv == b))
        e1, e2 = U[sel] / a, V[sel] / b
        i, j = np.meshgrid(np.arange(a), np.arange(b), indexing="ij")
        i, j = i.ravel(), j.ravel()
        where = (slots[rows[sel]][:, None] + np.arange(a * b)[None]).ravel()
        out["origin"][where] = (
            org[sel][:, None] + i[None, :, None] * e1[:, None] + j[None, :, None] * e2[:, None]
        ).reshape(-1, 3)
        out["e1"][where] = np.repeat(e1, a * b, axis=0)
        out["e2"][where] = np.repeat(e2, a * b, axis=0)
        out["ij"][where] = np.tile(np.column_stack([i, j]), (len(sel), 1))
    names = [scene.surfaces[k].name for k in rows]
    return dict(zip(names, zip(nu.tolist(), nv.tolist(), strict=True), strict=True))


def _subdivision_template(m: int) -> tuple[np.ndarray, np.ndarray]:
    """For m² sub-triangles of a triangle with edges d1 = (b - a)/m, d2 = (c - a)/m:
    origin coefficients (m², 2) on (d1, d2) and edge signs (m²,) (+1 up, -1 down)."""
    i, j = np.meshgrid(np.arange(m), np.arange(m), indexing="ij")
    up = (i + j) <= m - 1
    down = (i + j) <= m - 2
    # The inverted triangle of a cell has corners (i+1, j), (i+1, j+1)... written
    # from (i+1, j+1) with edges -d1, -d2 so its normal matches the parent's.
    coef = np.concatenate(
        [np.stack([i[up], j[up]], 1), np.stack([i[down] + 1, j[down] + 1], 1)]
    ).astype(float)
    sign = np.concatenate([np.ones(up.sum()), -np.ones(down.sum())])
    return coef, sign


def _mesh_triangles(surface: Surface, resolution: float):
    tri = surface.triangles
    ms = _subdivisions(tri, resolution) if surface.subdivide else np.ones(len(tri), np.int64)
    counts = ms * ms
    start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    total = int(counts.sum())
    origin, e1, e2 = np.empty((total, 3)), np.empty((total, 3)), np.empty((total, 3))
    # Triangles of one subdivision level at a time, each written to its own slots, so
    # patches keep the order of a triangle-by-triangle loop.
    for m in np.unique(ms):
        rows = np.flatnonzero(ms == m)
        coef, sign = _subdivision_template(int(m))
        a = tri[rows, 0]
        d1 = (tri[rows, 1] - a) / m
        d2 = (tri[rows, 2] - a) / m
        slots = (start[rows][:, None] + np.arange(len(sign))[None]).ravel()
        origin[slots] = (
            a[:, None] + coef[None, :, :1] * d1[:, None] + coef[None, :, 1:] * d2[:, None]
        ).reshape(-1, 3)
        e1[slots] = (sign[None, :, None] * d1[:, None]).reshape(-1, 3)
        e2[slots] = (sign[None, :, None] * d2[:, None]).reshape(-1, 3)
    return origin, e1, e2, np.ones(total, bool), np.full((total, 2), -1), None


def mesh_patches(scene: Scene) -> Patches:
    """Mesh every surface of ``scene`` at ``scene.resolution`` into patches."""
    n_expected = count_patches(scene)
    if n_expected > MAX_PATCHES:
        raise SceneError(too_many_patches(scene, n_expected))
    groups = scene.groups
    res = scene.resolution
    group_of = {g: k for k, g in enumerate(groups)}
    zone_of_surface = {z.surface: k for k, z in enumerate(scene.zones)}
    # Patches per surface, then each surface's first slot: rectangles and triangles are
    # written in place, in surface order.
    _, nu, nv = _rect_grids(scene, res)
    counts = np.zeros(len(scene.surfaces), np.int64)
    tri_parts = {}
    rect_k = 0
    for sid, s in enumerate(scene.surfaces):
        if s.rect is not None:
            counts[sid] = nu[rect_k] * nv[rect_k]
            rect_k += 1
        else:
            tri_parts[sid] = _mesh_triangles(s, res)
            counts[sid] = len(tri_parts[sid][0])
    slots = np.concatenate([[0], np.cumsum(counts)[:-1]])
    n = int(counts.sum())
    out = {
        "origin": np.empty((n, 3)),
        "e1": np.empty((n, 3)),
        "e2": np.empty((n, 3)),
        "ij": np.full((n, 2), -1, np.int64),
    }
    grid_shape = _mesh_rects(scene, res, slots, out)
    is_tri = np.zeros(n, bool)
    for sid, (o, t1, t2, *_rest) in tri_parts.items():
        part = slice(slots[sid], slots[sid] + counts[sid])
        out["origin"][part], out["e1"][part], out["e2"][part] = o, t1, t2
        is_tri[part] = True
    origin, e1, e2 = out["origin"], out["e1"], out["e2"]
    surface_id = np.repeat(np.arange(len(scene.surfaces)), counts)
    group_id = np.repeat([group_of[s.group] for s in scene.surfaces], counts)
    zone_id = np.repeat([zone_of_surface.get(s.name, -1) for s in scene.surfaces], counts)
    cross = np.cross(e1, e2)
    norm = np.linalg.norm(cross, axis=1)
    area = np.where(is_tri, 0.5, 1.0) * norm
    bad = np.flatnonzero(area <= 1e-14)
    if len(bad):
        sid = int(surface_id[bad[0]])
        raise SceneError(
            f"surface {scene.surfaces[sid].name!r} has {len(bad)} zero-area patch(es); "
            "remove degenerate faces"
        )
    centroid = origin + np.where(is_tri, 1.0 / 3.0, 0.5)[:, None] * (e1 + e2)
    surface_id = surface_id.astype(np.int32)
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
        group_id=group_id.astype(np.int32),
        zone_id=zone_id.astype(np.int32),
        grid_ij=out["ij"].astype(np.int32),
        surface_names=tuple(s.name for s in scene.surfaces),
        group_names=groups,
        zone_names=tuple(z.name for z in scene.zones),
        grid_shape=grid_shape,
        zone_outlines=tuple(z.outline for z in scene.zones),
    )
