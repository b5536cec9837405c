"""Exact form factors from receiver points to patches: no random rays.

The form factor from a differential area at point p with unit normal n to a planar
polygon with vertices v_1..v_V is Lambert's contour integral (by Stokes' theorem;
Hottel and Sarofim, *Radiative Transfer*, 1967; Siegel and Howell's contour form):

    F = 1 / (2 pi) |sum_k gamma_k  n . (R_k x R_k+1) / |R_k x R_k+1||

with R_k = v_k - p and gamma_k the angle between R_k and R_k+1 (radians). It holds for
a polygon wholly above the point's tangent plane; a polygon straddling that plane is
first clipped to it (Sutherland-Hodgman against one plane), since only the part above
can send light to the point's front.

**Visibility.** The formula is the factor of an unobstructed polygon. Each pair of a
point and a patch it faces gets shadow rays towards fixed points of the patch (no
random numbers, so the factors depend on no ray count or seed):

- probes: a pair whose factor is at most ``NEAR_FACTOR`` (a patch seen small: the size
  rule) gets five, its corners (inset by ``INSET``) and its centroid; a larger one a
  ``PROBES`` x ``PROBES`` lattice over the patch, outline included. Only probes in
  front of the point's tangent plane vote (those behind send it no light);
- all seen keeps the whole polygon's factor, none seen gives 0;
- where they disagree (an occluder's outline crosses the patch) a patch seen large is
  cut into ``FINE`` x ``FINE`` sub-cells and the factor is the sum of each sub-cell's
  own contour-integral factor times the visibility of its centre: a fixed quadrature
  of the visibility only, the geometry staying exact. A patch seen small keeps its
  exact factor times the share of its ``FINE_SMALL`` x ``FINE_SMALL`` cells seen, each
  weighed by its centre's point factor.

The sub-cells tile the patch, so where all are seen the sum is the whole factor (the
contour integrals of adjacent cells cancel along shared edges). Neighbouring patches
share corners and edges, so each edge's term is computed once per point
(``_contours``): a point costs O(patches), like a few hundred traced rays.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np
import scipy.sparse as sp

from lightinv_core.scene.patches import Patches
from lightinv_core.transport.raycast import RayCaster

NEAR_FACTOR = 1e-4
"""Factor above which a patch gets ``PROBES`` x ``PROBES`` visibility probes instead of
five (at most 10,000 patches can exceed it from one point). On the patio's work plane
(columns and arches above it) 1e-3 left 0.33% rms against a fine trace, 1e-4 0.11%."""
PROBES = 4
FINE = 16
FINE_SMALL = 4
INSET = 0.01
"""Probes sit this share of an edge inside a patch's outline: clear of the surfaces
meeting it there, which a ray grazing the corner would hit."""
PAIRS_PER_BLOCK = 1 << 18
"""Point-edge pairs examined at once (about 100 bytes each)."""
CULL_PAIRS = 1 << 26
"""Point-patch pairs above which each block of points looks only at the surfaces it
can see (a building's grids: 2,000 points x 200,000 patches)."""
CULL_BLOCK = 64
CULL_DIRECTIONS = 4096
"""Fixed cosine-weighted directions per point (64 x 64 cell centres) that find the
surfaces it sees: a surface none of them reaches lies within 3.6 degrees of the
horizon or is a sliver of the view (with 1,024, the sidelit room's south wall pieces
below the sill were missed, 0.3% of the view; with 4,096 nothing is)."""
_TINY = 1e-300


@cache
def _cells(q: int, triangle: bool) -> tuple[np.ndarray, np.ndarray]:
    """Sub-cells of a patch in its (s, t) parameters: ``(q*q, 4, 2)`` vertices (a
    triangle's sub-triangles repeat their last vertex) and ``(q*q, 2)`` centroids.
    A rectangle (s, t in [0, 1]) is cut into q x q cells, a triangle (s + t <= 1) into
    q² similar triangles; both keep the patch's winding."""
    cells, centres = [], []
    for i in range(q):
        for j in range(q):
            if not triangle:
                c = np.array([[i, j], [i + 1, j], [i + 1, j + 1], [i, j + 1]], float) / q
                cells.append(c)
                centres.append(c.mean(axis=0))
                continue
            if i + j < q:
                c = np.array([[i, j], [i + 1, j], [i, j + 1]], float) / q
                cells.append(np.vstack([c, c[-1:]]))
                centres.append(c.mean(axis=0))
            if i + j < q - 1:
                c = np.array([[i + 1, j], [i + 1, j + 1], [i, j + 1]], float) / q
                cells.append(np.vstack([c, c[-1:]]))
                centres.append(c.mean(axis=0))
    return np.array(cells), np.array(centres)


def patch_polygons(patches: Patches, idx: np.ndarray) -> np.ndarray:
    """(len(idx), 4, 3) vertices (m) of patches ``idx`` in their winding; a triangle
    repeats its last vertex (a zero-length edge adds nothing to a contour integral)."""
    o, e1, e2 = patches.origin[idx], patches.edge1[idx], patches.edge2[idx]
    quad = np.stack([o, o + e1, o + e1 + e2, o + e2], axis=1)
    tri = patches.is_triangle[idx]
    quad[tri, 2] = o[tri] + e2[tri]
    return quad


def sub_cells(patches: Patches, idx: np.ndarray, q: int) -> tuple[np.ndarray, np.ndarray]:
    """Sub-cells of patches ``idx``: ``(len(idx), q*q, 4, 3)`` vertices and
    ``(len(idx), q*q, 3)`` centroids (m), q x q per rectangle, q² per triangle."""
    o, e1, e2 = patches.origin[idx], patches.edge1[idx], patches.edge2[idx]
    verts = np.empty((len(idx), q * q, 4, 3))
    centres = np.empty((len(idx), q * q, 3))
    for triangle in (False, True):
        sel = patches.is_triangle[idx] == triangle
        if not sel.any():
            continue
        st, mid = _cells(q, triangle)
        oo, a, b = o[sel][:, None], e1[sel][:, None], e2[sel][:, None]
        verts[sel] = (
            oo[:, :, None] + st[None, ..., :1] * a[:, :, None] + st[None, ..., 1:] * (b[:, :, None])
        )
        centres[sel] = oo + mid[None, :, :1] * a + mid[None, :, 1:] * b
    return verts, centres


def _clip(R: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Polygons ``R`` (K, V, 3), vertex heights ``h`` (K, V) above the tangent plane,
    clipped to h >= 0: (K, 2V, 3), the kept vertices first, padded by repeating the last
    (an empty polygon is all zeros)."""
    K, V = h.shape
    Rn, hn = np.roll(R, -1, axis=1), np.roll(h, -1, axis=1)
    crossing = ((h > 0) & (hn < 0)) | ((h < 0) & (hn > 0))
    t = np.where(crossing, h / np.where(crossing, h - hn, 1.0), 0.0)
    slots = np.stack([R, R + t[..., None] * (Rn - R)], axis=2).reshape(K, 2 * V, 3)
    keep = np.stack([h >= 0, crossing], axis=2).reshape(K, 2 * V)
    order = np.argsort(~keep, axis=1, kind="stable")
    slots = np.take_along_axis(slots, order[..., None], axis=1)
    count = keep.sum(axis=1)
    last = np.maximum(count - 1, 0)
    pad = np.arange(2 * V)[None] >= count[:, None]
    fill = slots[np.arange(K), last]
    slots = np.where(pad[..., None], fill[:, None], slots)
    slots[count == 0] = 0.0
    return slots


def polygon_factor(points: np.ndarray, normals: np.ndarray, verts: np.ndarray) -> np.ndarray:
    """Form factor from differential areas at ``points`` (K, 3) m with unit ``normals``
    (K, 3) to the polygons ``verts`` (K, V, 3) m (in order, either winding; repeated
    vertices allowed), each clipped to the half-space in front of its point (see the
    module): dimensionless, 0 to 1, unobstructed."""
    R = verts - points[:, None]
    h = np.einsum("kvc,kc->kv", R, normals)
    behind = (h <= 0).all(axis=1)
    straddle = (h < 0).any(axis=1) & (h > 0).any(axis=1)
    if straddle.any():
        clipped = _clip(R[straddle], h[straddle])
        R = np.concatenate([R, R[:, -1:].repeat(R.shape[1], axis=1)], axis=1)
        R[straddle] = clipped
    Rn = np.roll(R, -1, axis=1)
    c = np.cross(R, Rn)
    size = np.linalg.norm(c, axis=2)
    gamma = np.arctan2(size, np.einsum("kvc,kvc->kv", R, Rn))
    along = np.einsum("kvc,kc->kv", c, normals)
    term = np.where(size > _TINY, gamma * along / np.maximum(size, _TINY), 0.0)
    return np.where(behind, 0.0, np.abs(term.sum(axis=1)) / (2.0 * np.pi))


def _seen(caster: RayCaster, origins: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Whether each ``targets`` point (on a patch) is seen from its ``origins`` point: a
    shadow ray stopped ``2 * caster.offset`` short of the target (the patch itself)."""
    d = targets - origins
    length = np.linalg.norm(d, axis=-1)
    unit = d / np.maximum(length, _TINY)[..., None]
    short = np.maximum(length - 2.0 * caster.offset, 0.0)
    flat = caster.occluded(origins.reshape(-1, 3), unit.reshape(-1, 3), short.ravel())
    return ~flat.reshape(length.shape)


def probe_points(patches: Patches, idx: np.ndarray, q: int) -> np.ndarray:
    """(len(idx), q*q, 3) points (m) of patches ``idx`` on a q x q lattice that includes
    the corners and edges, inset by ``INSET`` of each edge (a triangle folds the
    lattice's far half onto itself): an occluder's shadow crossing a patch's outline
    covers a probe unless it is narrower than the lattice step."""
    g = INSET + (1.0 - 2.0 * INSET) * np.arange(q) / (q - 1)
    s, t = (x.ravel() for x in np.meshgrid(g, g, indexing="ij"))
    tri = patches.is_triangle[idx][:, None]
    fold = tri & (s + t > 1.0)[None]
    s, t = np.where(fold, 1.0 - s, s), np.where(fold, 1.0 - t, t)
    o, e1, e2 = patches.origin[idx], patches.edge1[idx], patches.edge2[idx]
    return o[:, None] + s[..., None] * e1[:, None] + t[..., None] * e2[:, None]


def _visible_factor(
    patches: Patches,
    caster: RayCaster,
    P: np.ndarray,
    N: np.ndarray,
    j: np.ndarray,
    F: np.ndarray,
) -> np.ndarray:
    """The unobstructed factors ``F`` of pairs (points ``P``, normals ``N``, patches
    ``j``) times their visibility, by the rule of the module."""
    out = F.copy()
    share = np.empty(len(F))
    near = F > NEAR_FACTOR
    for sel, q in ((~near, 2), (near, PROBES)):
        k = np.flatnonzero(sel)
        if not len(k):
            continue
        probes = probe_points(patches, j[k], q)
        if q == 2:  # a small patch's corners and its centroid
            probes = np.concatenate([probes, patches.centroid[j[k]][:, None]], axis=1)
        seen = _seen(caster, np.broadcast_to(P[k][:, None], probes.shape), probes)
        # Probes behind the point's tangent plane send it no light: they do not vote.
        ahead = np.einsum("kqc,kc->kq", probes - P[k][:, None], N[k]) > 0
        votes = ahead.sum(axis=1)
        share[k] = np.where(votes > 0, (seen & ahead).sum(axis=1) / np.maximum(votes, 1), 1.0)
    out[share == 0] = 0.0
    partly = (share > 0) & (share < 1)
    # A partly hidden patch seen large: its cells' own factors times their centres'
    # visibility (the quadrature of the module).
    mixed = np.flatnonzero(partly & near)
    if len(mixed):
        verts, centres = sub_cells(patches, j[mixed], FINE)
        k, c = len(mixed), FINE * FINE
        Pm = np.repeat(P[mixed], c, axis=0)
        Nm = np.repeat(N[mixed], c, axis=0)
        f = polygon_factor(Pm, Nm, verts.reshape(k * c, 4, 3)).reshape(k, c)
        vis = _seen(caster, np.broadcast_to(P[mixed][:, None], centres.shape), centres)
        out[mixed] = (f * vis).sum(axis=1)
    # One seen small (at most NEAR_FACTOR): its exact factor times the share of its
    # FINE_SMALL x FINE_SMALL cells seen, each weighed by its centre's point factor
    # cos cos / r² (equal cells; far away, so the weights' own error hardly counts).
    small = np.flatnonzero(partly & ~near)
    if len(small):
        _, centres = sub_cells(patches, j[small], FINE_SMALL)
        d = P[small][:, None] - centres
        r2 = np.maximum(np.einsum("kcx,kcx->kc", d, d), _TINY)
        w = np.maximum(-np.einsum("kcx,kx->kc", d, N[small]), 0.0) * np.maximum(
            np.einsum("kcx,kx->kc", d, patches.normal[j[small]]), 0.0
        )
        w /= r2 * r2
        vis = _seen(caster, np.broadcast_to(P[small][:, None], centres.shape), centres)
        out[small] *= (w * vis).sum(axis=1) / np.maximum(w.sum(axis=1), _TINY)
    return out


@dataclass(frozen=True)
class _Contours:
    """The patches' outlines as a mesh: distinct ``verts`` (nv, 3) m, edges ``lo`` ->
    ``hi`` (vertex ids), ``incidence`` (n, ne) +-1 (each patch's edges in its winding),
    the corner ``ids`` (n, 4) and ``polys`` (n, 4, 3)."""

    verts: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    incidence: sp.csr_matrix
    ids: np.ndarray
    polys: np.ndarray


def _contours(patches: Patches) -> _Contours:
    """The outline mesh of ``patches``: neighbours on a surface grid share corners and
    edges, so an edge's term of the contour integral is computed once per point (a
    corner not recognised as shared is merely computed twice)."""
    n = patches.n
    polys = patch_polygons(patches, np.arange(n))
    flat = polys.reshape(-1, 3)
    step = 1e-9 * max(1.0, float(np.abs(flat).max()))
    _, first, inverse = np.unique(
        np.round(flat / step).astype(np.int64), axis=0, return_index=True, return_inverse=True
    )
    ids = inverse.reshape(n, 4)
    a, b = ids, np.roll(ids, -1, axis=1)
    real = a != b
    lo, hi = np.minimum(a, b)[real], np.maximum(a, b)[real]
    edges, column = np.unique(lo.astype(np.int64) * len(first) + hi, return_inverse=True)
    sign = np.where(a < b, 1.0, -1.0)[real]
    owner = np.repeat(np.arange(n), 4).reshape(n, 4)[real]
    incidence = sp.csr_matrix((sign, (owner, column)), shape=(n, len(edges)))
    return _Contours(flat[first], edges // len(first), edges % len(first), incidence, ids, polys)


def _edge_terms(
    verts: np.ndarray, lo: np.ndarray, hi: np.ndarray, P: np.ndarray, N: np.ndarray
) -> np.ndarray:
    """(p, e) terms gamma n . (u_lo x u_hi) / |u_lo x u_hi| of the outline edges
    ``verts[lo] -> verts[hi]`` seen from points ``P`` (p, 3) with normals ``N`` (p, 3)."""
    used, back = np.unique(np.concatenate([lo, hi]), return_inverse=True)
    R = verts[used][None] - P[:, None]
    u = R / np.maximum(np.linalg.norm(R, axis=2), _TINY)[..., None]
    a, b = u[:, back[: len(lo)]], u[:, back[len(lo) :]]
    cx = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    cy = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    cz = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    size = np.sqrt(cx * cx + cy * cy + cz * cz)
    gamma = np.arctan2(size, np.einsum("pec,pec->pe", a, b))
    along = cx * N[:, :1] + cy * N[:, 1:2] + cz * N[:, 2:]
    return np.where(size > _TINY, gamma * along / np.maximum(size, _TINY), 0.0)


def _block(
    mesh: _Contours,
    patches: Patches,
    caster: RayCaster,
    P: np.ndarray,
    N: np.ndarray,
    cand: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The non-zero factors from points ``P`` (normals ``N``) to the candidate patches
    ``cand``: (point index in the block, patch, factor)."""
    inc = mesh.incidence[cand]
    edges = np.unique(inc.indices)
    inc = inc[:, edges]
    F = np.abs(inc @ _edge_terms(mesh.verts, mesh.lo[edges], mesh.hi[edges], P, N).T).T
    # The point must lie in front of the patch's plane, and some of the patch in front
    # of the point's tangent plane; a patch crossing that plane is clipped.
    normal = patches.normal[cand]
    ahead = P @ normal.T - np.einsum("jc,jc->j", patches.origin[cand], normal) > 0
    corner = (
        np.einsum("jvc,pc->pjv", mesh.polys[cand], N) - np.einsum("pc,pc->p", P, N)[:, None, None]
    )
    pi, k = np.nonzero(ahead & (corner.max(axis=2) > 0))
    j = cand[k]
    f = F[pi, k] / (2.0 * np.pi)
    cut = corner[pi, k].min(axis=1) < 0
    if cut.any():
        f[cut] = polygon_factor(P[pi[cut]], N[pi[cut]], mesh.polys[j[cut]])
    f = _visible_factor(patches, caster, P[pi], N[pi], j, f)
    ok = f > 0
    return pi[ok], j[ok], f[ok]


def _surfaces_seen(patches: Patches, caster: RayCaster, P: np.ndarray, N: np.ndarray) -> np.ndarray:
    """Patches of the surfaces that any of ``CULL_DIRECTIONS`` fixed cosine-weighted
    directions from points ``P`` (normals ``N``) reaches: the candidates of a block
    of points in a large scene (the rooms around the points, not the whole building)."""
    q = round(np.sqrt(CULL_DIRECTIONS))
    g = (np.arange(q) + 0.5) / q
    s, t = (x.ravel() for x in np.meshgrid(g, g, indexing="ij"))
    helper = np.where(np.abs(N[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]])
    t1 = np.cross(N, helper)
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    t2 = np.cross(N, t1)
    r, phi = np.sqrt(s), 2 * np.pi * t
    d = (
        (r * np.cos(phi))[None, :, None] * t1[:, None]
        + (r * np.sin(phi))[None, :, None] * t2[:, None]
        + np.sqrt(1.0 - s)[None, :, None] * N[:, None]
    )
    o = np.broadcast_to(P[:, None], d.shape)
    hit = caster.hit_patches(o.reshape(-1, 3), d.reshape(-1, 3))
    surfaces = np.unique(patches.surface_id[hit[hit >= 0]])
    return np.flatnonzero(np.isin(patches.surface_id, surfaces))


def point_form_factors(
    points: np.ndarray,
    normals: np.ndarray,
    patches: Patches,
    caster: RayCaster | None = None,
) -> sp.csr_matrix:
    """Sparse (m, n) form factors from points (m, 3) m with normals (m, 3) to the fronts
    of ``patches``, with occlusion (see the module): row sums are the share of each
    point's view that is the room (1 in a closed room). Points are lifted
    ``caster.offset`` along their normals first, as traced rays' origins are.

    Above ``CULL_PAIRS`` point-patch pairs (a whole building), each block of
    ``CULL_BLOCK`` points looks only at the surfaces that fixed directions from its
    points reach (``_surfaces_seen``), so the cost follows the rooms, not the scene."""
    caster = caster or RayCaster(patches)
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    nrm = np.asarray(normals, dtype=float).reshape(-1, 3)
    nrm = nrm / np.linalg.norm(nrm, axis=1)[:, None]
    P_all = pts + caster.offset * nrm
    n = patches.n
    mesh = _contours(patches)
    cull = len(pts) * n > CULL_PAIRS
    block = CULL_BLOCK if cull else max(1, PAIRS_PER_BLOCK // max(mesh.lo.size, 1))
    everything = np.arange(n)
    rows, cols, vals = [], [], []
    for start in range(0, len(pts), block):
        P, N = P_all[start : start + block], nrm[start : start + block]
        cand = _surfaces_seen(patches, caster, P, N) if cull else everything
        # Candidates a block at a time, so no array grows past PAIRS_PER_BLOCK edges
        # per point.
        step = max(1, PAIRS_PER_BLOCK // (4 * len(P)))
        for c0 in range(0, len(cand), step):
            pi, j, f = _block(mesh, patches, caster, P, N, cand[c0 : c0 + step])
            rows.append(start + pi)
            cols.append(j)
            vals.append(f)
    shape = (len(pts), n)
    if not rows:
        return sp.csr_matrix(shape)
    return sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=shape
    )
