"""Illuminance at receiver points (work-plane grids): points that take light from the
patches but give none back, so they do not take part in light transport.

At a point with unit normal ``n`` the light of Lambertian surfaces of exitance B
(lm/m², emitted plus reflected) is ``sum_j B_j F_pj`` (lux), with ``F_pj`` the
point's form factor to patch j. ``receiver_factors`` computes them once per grid,
exactly (``point_formfactors``: the contour integral of each patch with its
visibility, no random rays, so a point's light does not depend on a ray count);
any radiosity solution is then a sparse product. ``traced_receiver_factors`` is the
earlier estimate, the share of cosine-weighted rays from the point that reach j's
front, kept as an independent check (tests, ``bench/point_light.py``).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from lightinv_core.errors import LightInvError
from lightinv_core.transport.formfactors import DEFAULT_RAYS, MAX_RAYS
from lightinv_core.transport.point_formfactors import point_form_factors
from lightinv_core.transport.raycast import RayCaster, stratified_unit_square


def _basis(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors completing each normal of ``n`` (m, 3) to a right-handed frame."""
    helper = np.where(np.abs(n[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]])
    t1 = np.cross(n, helper)
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    return t1, np.cross(n, t1)


def receiver_factors(
    points: np.ndarray,
    normals: np.ndarray,
    caster: RayCaster,
    n_patches: int,
    rays: int = DEFAULT_RAYS,
    seed: int = 0,
) -> sp.csr_matrix:
    """Sparse (m, n) matrix of the points' exact form factors to the patches of
    ``caster`` (``point_formfactors``): rows sum to the share of each point's view that
    is the room (1 in a closed room). ``rays`` and ``seed`` are checked and otherwise
    unused: they are the traced estimate's (``traced_receiver_factors``), which the
    callers still hand on."""
    if not 1 <= int(rays) <= MAX_RAYS:
        raise LightInvError(f"rays per point must be from 1 to {MAX_RAYS:,}, got {rays}")
    if caster.patches.n != n_patches:
        raise LightInvError(
            f"receiver factors to {n_patches:,} patches asked of a ray caster of "
            f"{caster.patches.n:,}"
        )
    return point_form_factors(points, normals, caster.patches, caster)


def traced_receiver_factors(
    points: np.ndarray,
    normals: np.ndarray,
    caster: RayCaster,
    n_patches: int,
    rays: int = DEFAULT_RAYS,
    seed: int = 0,
) -> sp.csr_matrix:
    """The points' form factors estimated by ``rays`` cosine-weighted stratified rays
    each (random stream ``seed``): the share reaching each patch's front. Unbiased, with
    a noise falling as about 1/sqrt(rays); rows sum to the share of the view that is
    the room."""
    if not 1 <= int(rays) <= MAX_RAYS:
        raise LightInvError(f"rays per point must be from 1 to {MAX_RAYS:,}, got {rays}")
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    nrm = np.asarray(normals, dtype=float).reshape(-1, 3)
    nrm = nrm / np.linalg.norm(nrm, axis=1)[:, None]
    rng = np.random.default_rng(seed)
    t1, t2 = _basis(nrm)
    rows, cols, vals = [], [], []
    block = max(1, 2**17 // rays)
    for start in range(0, len(pts), block):
        sl = slice(start, start + block)
        u = stratified_unit_square(rng, len(pts[sl]), rays, shuffle=True)
        r, phi = np.sqrt(u[..., 0]), 2 * np.pi * u[..., 1]
        cz = np.sqrt(np.maximum(0.0, 1.0 - u[..., 0]))
        d = (
            (r * np.cos(phi))[..., None] * t1[sl, None]
            + (r * np.sin(phi))[..., None] * t2[sl, None]
            + cz[..., None] * nrm[sl, None]
        )
        o = np.broadcast_to((pts[sl] + caster.offset * nrm[sl])[:, None], d.shape)
        hit = caster.hit_patches(o.reshape(-1, 3), d.reshape(-1, 3)).reshape(len(d), rays)
        local = np.repeat(np.arange(len(d)), rays)[hit.ravel() >= 0]
        keys = (start + local) * np.int64(n_patches) + hit.ravel()[hit.ravel() >= 0]
        uniq, counts = np.unique(keys, return_counts=True)
        rows.append(uniq // n_patches)
        cols.append(uniq % n_patches)
        vals.append(counts / rays)
    shape = (len(pts), n_patches)
    if not rows:
        return sp.csr_matrix(shape)
    return sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=shape
    )
