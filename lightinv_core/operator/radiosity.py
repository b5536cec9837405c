"""``RadiosityOperator``: build once per geometry, then evaluate lighting in microseconds.

Emission is given sparsely as (patch indices, exitances in lm/m²). Emission on
emitter-zone patches (where every source lives) goes through the zone response
basis Phi (three exact bounces + low-rank remainder); emission anywhere else
falls back to the plain low-rank operator (paper eq. 8), which blurs the
direct light over a cluster and is several times less accurate (see
docs/operator.md).

Phi (n x nz) is never stored: the operator keeps its factors, the sparse form
factors F, the low-rank Y (n x k) and G = V^T R D3 (k x nz), so its memory grows
as O(nnz(F) + n k + k nz). Phi's rows are made on demand for the patches an
evaluation reads (``phi_rows``), and the light of one layout on every patch from
sparse products (``zone_field``).

Read-outs: illuminance H (lux), reflected exitance C = rho * H (lm/m², the
paper's C), total reflected light power sum_i C_i A_i (lm), and the match
error ||C(E) - C_obj||_2 (paper eq. 11).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
from scipy.linalg.blas import strmm

from lightinv_core.errors import LightInvError
from lightinv_core.memory import format_bytes
from lightinv_core.operator.lowrank import LowRank
from lightinv_core.operator.zone_basis import (
    EXACT_BOUNCES,
    LEFT_BLOCK,
    block_rows,
    left_bounces,
    more_bounces,
    sparse_dense_product,
)

BASIS_BYTES = 2 << 30
"""Largest part of the zone basis made at once (2 GiB): the receiver rows of an
optimisation level, or the whole basis for the Gram matrix of a match goal. Beyond
it receivers are evaluated from the factors per batch, and a match goal is refused."""


def zone_part(F: sp.csr_matrix, zone_patches: np.ndarray) -> sp.csr_matrix:
    """F[:, zone_patches] as CSR (n, nz), the first bounce of the zone basis."""
    return F[:, zone_patches].tocsr()


@dataclass(eq=False)
class RadiosityOperator:
    """The precomputed radiosity operator of one scene geometry.

    Phi = S + Y G: S = D1 + D2 + D3, the exact bounces of the zone patches' light on the
    traced form factors (D1 = F[:, zone], D(b+1) = F R D(b)), made from ``F`` when read;
    the low-rank remainder Y G.

    Attributes
    ----------
    lowrank : LowRank, the rank-k cluster factorisation (any emission)
    zone_patches : (nz,) int64, the emitter-zone patches, in Phi's column order
    F : (n, n) CSR float32, the traced form factors
    G : (k, nz) float32, V^T R D3: the cluster averages of the last exact bounce
    power : (nz,) float64, (A rho)^T Phi: reflected light power (lm) per lm/m² of each
        zone patch
    digest : str, ``Patches.digest()`` of the geometry it was built for
    info : dict, settings and measurements of the build (JSON-serialisable)
    """

    lowrank: LowRank
    zone_patches: np.ndarray
    F: sp.csr_matrix
    G: np.ndarray
    power: np.ndarray
    digest: str
    info: dict = field(default_factory=dict)
    Fz: sp.csr_matrix | None = None

    def __post_init__(self) -> None:
        self._col = np.full(self.n, -1, np.int64)
        self._col[self.zone_patches] = np.arange(len(self.zone_patches))
        if self.Fz is None:
            self.Fz = zone_part(self.F, self.zone_patches)
        self._rho32 = self.rho.astype(np.float32)
        self._gram: np.ndarray | None = None
        self._gram_factor: np.ndarray | None = None

    @property
    def n(self) -> int:
        """Number of patches."""
        return self.lowrank.n

    @property
    def k(self) -> int:
        """Rank of the low-rank part."""
        return self.lowrank.k

    @property
    def nz(self) -> int:
        """Number of emitter-zone patches (Phi's columns)."""
        return len(self.zone_patches)

    @property
    def rho(self) -> np.ndarray:
        """Patch reflectances (n,)."""
        return self.lowrank.rho

    @property
    def area(self) -> np.ndarray:
        """Patch areas (n,), m²."""
        return self.lowrank.area

    def zone_columns(self, idx: np.ndarray) -> np.ndarray:
        """Phi's columns of the zone patches ``idx`` (LightInvError if one is not in a zone)."""
        cols = self._col[np.asarray(idx, dtype=np.int64)]
        if np.any(cols < 0):
            raise LightInvError("emission outside the emitter zones: use illuminance()")
        return cols

    # -- the zone basis, by rows or by emission ------------------------------------------
    def phi_rows(self, rows: np.ndarray | None = None) -> np.ndarray:
        """Phi[rows] (p, nz) float32 in Fortran order (a candidate's columns contiguous):
        lux at patches ``rows`` (default: all) per lm/m² of each zone patch.

        Costs O(nnz(F)) per row read from the left, or per zone patch read from the
        right; the smaller side is used. Memory O(p nz + n * block)."""
        rows = np.arange(self.n) if rows is None else np.asarray(rows, dtype=np.int64)
        p, nz = len(rows), self.nz
        out = np.empty((p, nz), np.float32, order="F")
        if p == 0 or nz == 0:
            return out
        if p < nz:
            step = min(LEFT_BLOCK, block_rows(self.n))
            for a in range(0, p, step):
                r = rows[a : a + step]
                XF = self.F[r].toarray()
                exact = left_bounces(XF, self.F, self.Fz, self.zone_patches, self._rho32)[0]
                out[a : a + step] = exact + self.lowrank.Y[r] @ self.G
        else:
            step = block_rows(self.n, arrays=4)
            Yr = self.lowrank.Y[rows]
            for a in range(0, nz, step):
                first = self.Fz[:, a : a + step].toarray()
                exact = more_bounces(self.F, self.rho, first, EXACT_BOUNCES)[0]
                out[:, a : a + step] = exact[rows] + Yr @ self.G[:, a : a + step]
        return out

    def zone_field(self, V: np.ndarray, rows: np.ndarray | None = None) -> np.ndarray:
        """H (lux) for zone emission V (nz,) or (nz, m) in lm/m² (Phi's column order), at
        ``rows`` (default every patch): three sparse products over F and the low-rank
        part, O(nnz(F) + n k) per emission; no row of Phi is formed."""
        V = np.asarray(V, dtype=np.float32)
        one = V.ndim == 1
        V2 = V[:, None] if one else V
        first = sparse_dense_product(self.Fz, np.ascontiguousarray(V2))
        exact = more_bounces(self.F, self.rho, first, EXACT_BOUNCES)[0]
        z = self.G @ V2
        if rows is None:
            H = exact + self.lowrank.Y @ z
        else:
            rows = np.asarray(rows, dtype=np.int64)
            H = exact[rows] + self.lowrank.Y[rows] @ z
        return H[:, 0] if one else H

    @property
    def Phi(self) -> np.ndarray:
        """The whole zone basis (n, nz) float32, made on each call (O(n nz) time and
        memory; for tests and small scenes: evaluations read ``phi_rows``). LightInvError
        when it would exceed ``BASIS_BYTES``."""
        self._check_whole_basis("the whole zone basis")
        return self.phi_rows()

    def _check_whole_basis(self, what: str) -> None:
        need = 4 * self.n * self.nz
        if need > BASIS_BYTES:
            raise LightInvError(
                f"{what} of {self.n:,} patches x {self.nz:,} zone patches would take "
                f"{format_bytes(need)} (limit {format_bytes(BASIS_BYTES)}); use fewer or "
                "smaller emitter zones or a coarser resolution"
            )

    # -- full and partial fields ------------------------------------------------------
    def illuminance(self, E: np.ndarray) -> np.ndarray:
        """H (lux) for a dense emission (n,) or a stack (n, m), any patches emitting."""
        E = np.asarray(E, dtype=np.float64)
        if E.shape[0] != self.n:
            raise LightInvError(f"emission has {E.shape[0]} rows, the operator {self.n} patches")
        H = self.zone_field(E[self.zone_patches])
        rest = E.copy()
        rest[self.zone_patches] = 0.0
        idx = np.flatnonzero(rest if rest.ndim == 1 else np.any(rest != 0, axis=1))
        if len(idx):
            H = H + self.lowrank.illuminance(self.lowrank.project_sparse(idx, rest[idx]))
        return H

    def zone_illuminance(
        self,
        idx: np.ndarray,
        values: np.ndarray,
        rows: np.ndarray | None = None,
        columns: bool = False,
    ) -> np.ndarray:
        """H (lux) from sparse zone emission: patches ``idx`` with exitances ``values``.

        ``values`` is (p,) for one candidate or (p, m) for a batch of m candidates
        sharing the index set. ``rows`` restricts the result to those patches.
        ``columns=True`` means ``idx`` are already Phi column numbers. Made from the
        factors (``zone_field``); for many batches at the same rows use ``restrict``.
        """
        cols = np.asarray(idx, dtype=np.int64) if columns else self.zone_columns(idx)
        values = np.asarray(values, dtype=np.float32)
        V = np.zeros((self.nz, *values.shape[1:]), np.float32)
        np.add.at(V, cols, values)
        return self.zone_field(V, rows)

    def reflected(
        self, idx: np.ndarray, values: np.ndarray, rows: np.ndarray | None = None
    ) -> np.ndarray:
        """C = B - E = rho * H (lm/m²) from sparse zone emission (see ``zone_illuminance``)."""
        H = self.zone_illuminance(idx, values, rows)
        r = self.rho if rows is None else self.rho[rows]
        return (r[:, None] if H.ndim == 2 else r) * H

    def restrict(self, rows: np.ndarray) -> PartialOperator:
        """An evaluator of H at the patches ``rows`` only: O(p) per emitting patch."""
        rows = np.asarray(rows, dtype=np.int64)
        return PartialOperator(
            rows, np.ascontiguousarray(self.phi_rows(rows).T), self.rho[rows], self._col
        )

    # -- scalar goals without the field ----------------------------------------------------
    def total_power(self, idx: np.ndarray, values: np.ndarray) -> np.ndarray | float:
        """Total reflected light power sum_i C_i A_i (lm), O(p) for p emitting patches."""
        return self.power[self.zone_columns(idx)] @ np.asarray(values, dtype=np.float64)

    @property
    def gram(self) -> np.ndarray:
        """Gamma = Phi^T R² Phi (nz x nz, float64): ||C||² = e^T Gamma e for zone emission e.

        Made once from the whole basis (O(nnz(F) nz) time); LightInvError when that basis
        exceeds ``BASIS_BYTES`` (a match goal over very large zones)."""
        if self._gram is None:
            self._check_whole_basis("the match goal's Gram matrix needs the zone basis")
            Phi = self.phi_rows()
            # Row blocks keep the float64 scratch small (not a float64 copy of Phi).
            G = np.zeros((self.nz, self.nz))
            for a, b in _row_blocks(self.n):
                P = Phi[a:b].astype(np.float64)
                G += P.T @ (self.rho[a:b, None] ** 2 * P)
            self._gram = G
        return self._gram

    @property
    def gram_factor32(self) -> np.ndarray:
        """Lower Cholesky factor L of the Gram matrix (float32, Fortran order), G = L L^T."""
        if self._gram_factor is None:
            G = self.gram
            jitter = 1e-12 * np.trace(G) / max(1, len(G))
            L = la.cholesky(G + jitter * np.eye(len(G)), lower=True)
            self._gram_factor = np.asfortranarray(L, dtype=np.float32)
        return self._gram_factor

    def match_target(self, obj_idx: np.ndarray, obj_values: np.ndarray) -> MatchTarget:
        """A fast evaluator of ||C(E) - C(E_obj)||_2 (paper eq. 11) for one objective."""
        return MatchTarget(self, obj_idx, obj_values)

    def match_error(
        self, idx: np.ndarray, values: np.ndarray, obj_idx: np.ndarray, obj_values: np.ndarray
    ) -> np.ndarray | float:
        """||C(E) - C(E_obj)||_2 over ALL patches; for many evaluations against the same
        objective use ``match_target`` (it precomputes the objective's terms once)."""
        return self.match_target(obj_idx, obj_values).error(idx, values)

    def nbytes(self) -> int:
        """Memory held by the operator's arrays, bytes (the Gram matrix once made)."""
        sparse = sum(m.data.nbytes + m.indices.nbytes + m.indptr.nbytes for m in (self.F, self.Fz))
        gram = 0 if self._gram is None else self._gram.nbytes
        return int(sparse + self.lowrank.Y.nbytes + self.G.nbytes + self.power.nbytes + gram)


def _row_blocks(n: int, size: int = 4096):
    """(start, stop) pairs covering range(n) in blocks of ``size`` rows."""
    return [(a, min(n, a + size)) for a in range(0, n, size)]


@dataclass(eq=False)
class PartialOperator:
    """H at p chosen patches (``rows``): ``PhiT`` (nz, p) so a candidate's rows are contiguous."""

    rows: np.ndarray
    PhiT: np.ndarray
    rho: np.ndarray
    _col: np.ndarray

    def zone_illuminance(self, idx: np.ndarray, values: np.ndarray) -> np.ndarray:
        """H (lux) at ``rows`` for sparse zone emission; values (q,) or (q, m) -> (p,) or (p, m)."""
        cols = self._col[np.asarray(idx, dtype=np.int64)]
        if np.any(cols < 0):
            raise LightInvError("emission outside the emitter zones")
        return self.PhiT[cols].T @ np.asarray(values, dtype=np.float32)


class MatchTarget:
    """||C(E) - C_obj||² = e^T G e - 2 e^T G e_obj + e_obj^T G e_obj over all patches.

    G e_obj and e_obj^T G e_obj are computed once, so an evaluation costs O(s²) for
    a candidate covering s zone patches (the quadratic term, from the Gram matrix),
    independent of n; a batch costs one (u x u) @ (u x m) float32 GEMM over the u
    zone patches the batch touches.
    """

    def __init__(self, op: RadiosityOperator, obj_idx: np.ndarray, obj_values: np.ndarray):
        self.op = op
        cols = op.zone_columns(obj_idx)
        e = np.zeros(len(op.zone_patches))
        np.add.at(e, cols, np.asarray(obj_values, dtype=np.float64))
        self.g_obj = op.gram @ e
        self.c_obj = float(e @ self.g_obj)
        self._gram32: np.ndarray | None = None

    @property
    def norm(self) -> float:
        """||C_obj||_2, lm/m²."""
        return float(np.sqrt(max(self.c_obj, 0.0)))

    def error(self, idx: np.ndarray, values: np.ndarray) -> np.ndarray | float:
        """||C(E) - C_obj||_2 (lm/m²) for one candidate (values (s,)) or a batch (s, m)."""
        cols = self.op.zone_columns(idx)
        v = np.asarray(values, dtype=np.float64)
        lin = self.g_obj[cols] @ v
        if v.ndim == 1:
            quad = v @ self.op.gram[np.ix_(cols, cols)] @ v
        else:
            if self._gram32 is None:
                self._gram32 = self.op.gram.astype(np.float32)
            v32 = v.astype(np.float32)
            if 2 * len(cols) > len(self.g_obj):
                # Most of the zones are touched: e^T G e = ||L^T e||² with the Cholesky
                # factor G = L L^T, a triangular product at half the GEMM's flops.
                full = np.zeros((len(self.g_obj), v.shape[1]), np.float32, order="F")
                np.add.at(full, cols, v32)
                LtE = strmm(1.0, self.op.gram_factor32, full, side=0, lower=1, trans_a=1)
                quad = np.einsum("im,im->m", LtE, LtE)
            else:
                quad = np.einsum("im,im->m", v32, self._gram32[np.ix_(cols, cols)] @ v32)
        return np.sqrt(np.maximum(quad - 2.0 * lin + self.c_obj, 0.0))

    def relative_error(self, idx: np.ndarray, values: np.ndarray) -> np.ndarray | float:
        """e(E) = ||C(E) - C_obj|| / ||C_obj|| (paper eq. 11)."""
        return self.error(idx, values) / self.norm
