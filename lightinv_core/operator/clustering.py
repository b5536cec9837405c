"""Spatially coherent clusters of patches for the low-rank radiosity operator.

A cluster never spans two surfaces, so its patches share a plane, a normal and
a material. Rectangle grids are cut into blocks of neighbouring cells about as
wide as they are long (in metres); triangle surfaces are split by k-means on
the patch centroids. Every patch belongs to exactly one cluster.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.cluster.vq import kmeans2

from lightinv_core.scene.patches import Patches


def _block_shape(nu: int, nv: int, su: float, sv: float, per_cluster: float) -> tuple[int, int]:
    """Cells per block (bu, bv) so a block holds about ``per_cluster`` cells and is
    roughly square in metres (cell sizes su x sv)."""
    ratio = sv / su  # a square block has bu / bv = sv / su cells
    bu = max(1, min(nu, round(math.sqrt(per_cluster * ratio))))
    bv = max(1, min(nv, round(per_cluster / bu)))
    return bu, bv


def _surfaces(patches: Patches):
    """(surface name, patch indices, grid shape or None, cell sizes) per non-empty surface."""
    order = np.argsort(patches.surface_id, kind="stable")
    bounds = np.searchsorted(patches.surface_id[order], np.arange(len(patches.surface_names) + 1))
    out = []
    for sid, name in enumerate(patches.surface_names):
        idx = order[bounds[sid] : bounds[sid + 1]]
        if len(idx) == 0:
            continue
        shape = patches.grid_shape.get(name)
        su = float(np.linalg.norm(patches.edge1[idx[0]]))
        sv = float(np.linalg.norm(patches.edge2[idx[0]]))
        out.append((idx, shape, su, sv))
    return out


def _count(surfaces, per_cluster: float) -> int:
    total = 0
    for idx, shape, su, sv in surfaces:
        if shape is not None:
            bu, bv = _block_shape(*shape, su, sv, per_cluster)
            total += -(-shape[0] // bu) * -(-shape[1] // bv)
        else:
            total += max(1, round(len(idx) / per_cluster))
    return total


def cluster_patches(patches: Patches, k_target: int, seed: int = 0) -> tuple[np.ndarray, int]:
    """Labels (n,) int32 in [0, k) and the cluster count k.

    k is the largest count not above ``k_target`` that the block sizes allow, but
    at least one cluster per surface (a cluster never spans two surfaces).
    """
    surfaces = _surfaces(patches)
    k_target = int(min(max(1, k_target), patches.n))
    # Bisection on patches per cluster: the count falls as clusters grow.
    lo, hi = 1.0, float(patches.n)
    for _ in range(40):
        mid = np.sqrt(lo * hi)
        if _count(surfaces, mid) > k_target:
            lo = mid
        else:
            hi = mid
    per_cluster = hi
    labels = np.empty(patches.n, np.int32)
    next_label = 0
    rng = np.random.default_rng(seed)
    for idx, shape, su, sv in surfaces:
        if shape is not None:
            nu, nv = shape
            bu, bv = _block_shape(nu, nv, su, sv, per_cluster)
            ij = patches.grid_ij[idx]
            local = (ij[:, 0] // bu) * -(-nv // bv) + ij[:, 1] // bv
        else:
            m = max(1, round(len(idx) / per_cluster))
            if m == 1:
                local = np.zeros(len(idx), np.int64)
            else:
                _, local = kmeans2(patches.centroid[idx], m, minit="++", seed=rng)
        # Renumber densely: empty k-means clusters take no label.
        _, dense = np.unique(local, return_inverse=True)
        labels[idx] = next_label + dense
        next_label += int(dense.max()) + 1
    return labels, next_label
