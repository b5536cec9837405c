"""Ray casting against the patches with embreex, and cosine-weighted ray sampling.

A ray that hits the back of a patch, or nothing, is "lost": in a closed scene
none are; in an open model they leave the room (see ``lost_fraction``).
"""

from __future__ import annotations

import numpy as np
from embreex import rtcore_scene as rtcs
from embreex.mesh_construction import TriangleMesh

from lightinv_core.scene.patches import Patches

ORIGIN_OFFSET = 1e-5
"""Ray origins are lifted off their patch by this fraction of the scene diagonal
(about 0.3 mm in a 20 m hall): far above float32 round-off, far below any gap."""

CENTER_GRID = 64.0
"""Metres; see ``RayCaster``. Local coordinates stay within 32 m plus the model's
half-size, where float32 resolves 4 µm: far below ``ORIGIN_OFFSET``."""


class RayCaster:
    """An Embree scene of the patches' triangles that reports hit patch ids.

    Thread-safe after construction: ``hit_patches`` may run from several
    threads at once (Embree releases the GIL), which is how rows are traced on
    all cores.

    Embree works in float32, which resolves 0.25 mm at 3 km and 3 cm at 500 km:
    a georeferenced model traced in absolute coordinates leaks light through its
    own corners. The caster therefore works about ``center``: the middle of the
    scene's bounding box snapped to a 64 m grid, so any placement of a model gives
    the same rays, and a model within 32 m of the origin (every built-in scene)
    traces exactly the rays it always did (cached operators and published figures
    stay valid).
    """

    def __init__(self, patches: Patches) -> None:
        self.patches = patches
        """The patches traced (their geometry: ``point_formfactors`` reads it)."""
        corners = np.concatenate(
            [patches.origin, patches.origin + patches.edge1, patches.origin + patches.edge2]
        )
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        self.center = CENTER_GRID * np.round(0.5 * (lo + hi) / CENTER_GRID)
        vertices, faces, tri_patch = patches.triangle_mesh(center=self.center)
        self._scene = rtcs.EmbreeScene()
        TriangleMesh(self._scene, vertices, faces)
        self._tri_patch = tri_patch
        self._normal = patches.normal.astype(np.float32)
        self.offset = float(ORIGIN_OFFSET * np.linalg.norm(hi - lo))
        # The BVH is built on the first query; do it now, on one thread.
        self._scene.run(np.zeros((1, 3), np.float32), np.array([[0, 0, 1]], np.float32))

    def hit_patches(self, origins: np.ndarray, directions: np.ndarray) -> np.ndarray:
        """Patch id hit by each ray, or -1 if it hits nothing or a patch's back face.

        origins : (m, 3) world coordinates, m (float64 keeps far-off models exact)
        directions : (m, 3), need not be normalised
        """
        o = np.ascontiguousarray(np.asarray(origins, dtype=np.float64) - self.center, np.float32)
        d = np.ascontiguousarray(directions, dtype=np.float32)
        tri = self._scene.run(o, d, query="INTERSECT")
        hit = np.where(tri >= 0, self._tri_patch[np.maximum(tri, 0)], -1).astype(np.int32)
        front = np.einsum("ij,ij->i", d, self._normal[np.maximum(hit, 0)]) < 0.0
        return np.where(front, hit, -1)

    def occluded(
        self, origins: np.ndarray, directions: np.ndarray, lengths: np.ndarray
    ) -> np.ndarray:
        """Whether anything (either face of any patch) lies on each segment from
        ``origins`` (world coordinates, m) along unit ``directions`` for ``lengths`` m:
        a shadow ray's answer."""
        o = np.ascontiguousarray(np.asarray(origins, dtype=np.float64) - self.center, np.float32)
        d = np.ascontiguousarray(directions, dtype=np.float32)
        t = np.ascontiguousarray(lengths, dtype=np.float32)
        return self._scene.run(o, d, dists=t, query="OCCLUDED") == 0


def stratified_unit_square(
    rng: np.random.Generator, rows: int, count: int, shuffle: bool
) -> np.ndarray:
    """(rows, count, 2) points in [0, 1)², one per stratum, optionally shuffled per row.

    A jittered k x k grid when ``count`` is a perfect square, otherwise a Latin
    hypercube; both keep the estimator unbiased and cut its variance.
    """
    k = round(np.sqrt(count))
    if k * k == count:
        i, j = np.divmod(np.arange(count), k)
        cells = np.stack([i, j], axis=-1).astype(np.float64)
        pts = (cells[None] + rng.random((rows, count, 2))) / k
    else:
        a = rng.permuted(np.tile(np.arange(count), (rows, 1)), axis=1)
        b = rng.permuted(np.tile(np.arange(count), (rows, 1)), axis=1)
        pts = (np.stack([a, b], axis=-1) + rng.random((rows, count, 2))) / count
    if not shuffle:
        return pts
    order = rng.permuted(np.tile(np.arange(count), (rows, 1)), axis=1)
    return np.take_along_axis(pts, order[..., None], axis=1)


def patch_points(
    patches: Patches, rows: np.ndarray, count: int, rng: np.random.Generator
) -> np.ndarray:
    """(len(rows), count, 3) points spread uniformly and stratified over each patch of
    ``rows`` (world coordinates, m): for sampling what arrives on a patch."""
    pos = stratified_unit_square(rng, len(rows), count, shuffle=False)
    s, t = pos[..., 0], pos[..., 1]
    tri = patches.is_triangle[rows][:, None]
    fold = tri & (s + t > 1.0)
    s = np.where(fold, 1.0 - s, s)
    t = np.where(fold, 1.0 - t, t)
    e1, e2 = patches.edge1[rows], patches.edge2[rows]
    return patches.origin[rows][:, None] + s[..., None] * e1[:, None] + t[..., None] * e2[:, None]


def sample_rays(
    patches: Patches, rows: np.ndarray, count: int, rng: np.random.Generator, offset: float
) -> tuple[np.ndarray, np.ndarray]:
    """Cosine-weighted rays leaving the front of each patch in ``rows``.

    Positions are uniform over the patch and directions cosine-weighted about
    its normal, both stratified; the direction strata are shuffled against the
    position strata (one random pairing per patch), so the fraction of
    a patch's rays that hit patch j estimates the form factor F_ij.

    Returns ``(origins, directions)``, each (len(rows) * count, 3), grouped by
    row: origins float64 world coordinates (``RayCaster.hit_patches`` takes
    them to its local frame), directions float32.
    """
    b = len(rows)
    p = patch_points(patches, rows, count, rng)
    e1, n = patches.edge1[rows], patches.normal[rows]
    p += offset * n[:, None]

    dirs = stratified_unit_square(rng, b, count, shuffle=True)
    r = np.sqrt(dirs[..., 0])
    phi = 2.0 * np.pi * dirs[..., 1]
    cz = np.sqrt(np.maximum(0.0, 1.0 - dirs[..., 0]))
    t1 = e1 / np.linalg.norm(e1, axis=1)[:, None]
    t2 = np.cross(n, t1)
    d = (
        (r * np.cos(phi))[..., None] * t1[:, None]
        + (r * np.sin(phi))[..., None] * t2[:, None]
        + cz[..., None] * n[:, None]
    )
    return p.reshape(-1, 3), d.reshape(-1, 3).astype(np.float32)
