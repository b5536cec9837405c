"""The low-rank radiosity operator (paper eq. 5-8) and its fast evaluations.

Construction (the original LRR): cluster the patches into k coherent clusters;
W[i, c] = F(i -> cluster c) is the fraction of patch i's rays landing in c, and
V is the area-weighted cluster average, V[j, c] = A_j / A_c for j in c. Then
F ~ W V^T and, with R = diag(rho),

    H = F B ~ W h,   h = V^T B = (I_k - V^T R W)^-1 V^T E,

so the illuminance is ``H = Y z`` with ``Y = W (I_k - V^T R W)^-1`` (n x k) and
``z = V^T E`` (k). The paper's Y_k is ``-R Y``: its reflected radiosity
``C = B - E = -Y_k z = rho * H``. Keeping Y for H (not C) gives illuminance on
black (rho = 0) patches too.

Units: E, B, C in lm/m² (exitance), H in lux, powers in lm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from lightinv_core.errors import LightInvError


@dataclass(eq=False)
class LowRank:
    """The cluster low-rank factorisation: ``H ~ Y @ (V^T E)`` for any emission E.

    Attributes
    ----------
    Y : (n, k) float32, lux per unit of cluster-average exitance
    labels : (n,) int32, cluster of each patch
    area, rho : (n,) float64, patch areas (m²) and reflectances
    cluster_area : (k,) float64, m²
    """

    Y: np.ndarray
    labels: np.ndarray
    area: np.ndarray
    rho: np.ndarray
    cluster_area: np.ndarray

    @property
    def n(self) -> int:
        """Number of patches."""
        return self.Y.shape[0]

    @property
    def k(self) -> int:
        """Rank (number of clusters)."""
        return self.Y.shape[1]

    def project_sparse(self, idx: np.ndarray, values: np.ndarray) -> np.ndarray:
        """z = V^T E touching only the emitting patches ``idx`` with exitances ``values``
        ((p,) or (p, m)); cost O(p), not O(n)."""
        idx = np.asarray(idx, dtype=np.int64)
        values = np.asarray(values, dtype=np.float64)
        lab = self.labels[idx]
        w = self.area[idx] / self.cluster_area[lab]
        if values.ndim == 1:
            return np.bincount(lab, weights=w * values, minlength=self.k)
        z = np.zeros((self.k, values.shape[1]))
        np.add.at(z, lab, w[:, None] * values)
        return z

    def illuminance(self, z: np.ndarray) -> np.ndarray:
        """H = Y z, lux: (n,) for z (k,), (n, m) for a batch z (k, m) in one GEMM."""
        return self.Y @ np.asarray(z, dtype=np.float32)


def cluster_form_factors(
    F: sp.csr_matrix, labels: np.ndarray, k: int, block: int = 4096
) -> np.ndarray:
    """W[i, c] = sum_{j in c} F_ij as a dense (n, k) float32 array, built in row blocks
    so the float64 scratch stays at ``block * k`` values."""
    n = F.shape[0]
    W = np.empty((n, k), np.float32)
    for start in range(0, n, block):
        part = F[start : start + block]
        rows = np.repeat(np.arange(part.shape[0]), np.diff(part.indptr))
        flat = rows * k + labels[part.indices]
        W[start : start + part.shape[0]] = np.bincount(
            flat, weights=part.data, minlength=part.shape[0] * k
        ).reshape(-1, k)
    return W


def assemble(
    W: np.ndarray,
    labels: np.ndarray,
    area: np.ndarray,
    rho: np.ndarray,
) -> LowRank:
    """Y = W (I_k - V^T R W)^-1 from the cluster form factors W (n, k)."""
    n, k = W.shape
    cluster_area = np.bincount(labels, weights=area, minlength=k)
    if np.any(cluster_area <= 0):
        raise LightInvError("every cluster needs at least one patch")
    VT = sp.csr_matrix((area / cluster_area[labels], (labels, np.arange(n))), shape=(k, n))
    M = np.eye(k) - VT @ (rho[:, None] * W.astype(np.float64))
    Minv = la.inv(M)
    Y = W @ Minv.astype(np.float32)
    return LowRank(
        Y=Y,
        labels=labels.astype(np.int32),
        area=area.astype(np.float64),
        rho=rho.astype(np.float64),
        cluster_area=cluster_area,
    )
