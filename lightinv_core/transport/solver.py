"""Reference radiosity solvers for (I - R F) B = E, and the photometric read-outs.

Units: exitances E, B in lm/m²; illuminance H in lux (lm/m²); flux in lm.
These are the independent references every fast path is tested against.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from lightinv_core.errors import LightInvError
from lightinv_core.scene.patches import Patches

DENSE_LIMIT = 8000
"""Largest n solved densely (an n x n float64 matrix: 512 MB at 8,000)."""


@dataclass(frozen=True)
class Radiosity:
    """A radiosity solution.

    E, B : (n,) exitance, lm/m² (emitted, total)
    H : (n,) illuminance (incident flux density), lux
    iterations : Jacobi sweeps used (0 for the dense solve)
    """

    E: np.ndarray
    B: np.ndarray
    H: np.ndarray
    iterations: int = 0

    @property
    def C(self) -> np.ndarray:
        """Reflected exitance B - E, lm/m² (the paper's C)."""
        return self.B - self.E


def _check_E(E: np.ndarray, n: int) -> np.ndarray:
    E = np.asarray(E, dtype=float)
    if E.shape != (n,):
        raise LightInvError(f"emission vector has shape {E.shape}, expected ({n},)")
    if not np.all(np.isfinite(E)) or np.any(E < 0):
        raise LightInvError("emission must be finite and non-negative (lm/m²)")
    return E


def solve_dense(F: sp.spmatrix | np.ndarray, rho: np.ndarray, E: np.ndarray) -> Radiosity:
    """Exact solve of (I - R F) B = E by LU, for n up to ``DENSE_LIMIT``."""
    n = F.shape[0]
    if n > DENSE_LIMIT:
        raise LightInvError(
            f"dense solve limited to {DENSE_LIMIT} patches (got {n}); use solve_iterative"
        )
    E = _check_E(E, n)
    Fd = F.toarray() if sp.issparse(F) else np.asarray(F, dtype=float)
    A = np.eye(n) - rho[:, None] * Fd
    B = la.lu_solve(la.lu_factor(A), E)
    return Radiosity(E, B, Fd @ B)


def solve_iterative(
    F: sp.spmatrix, rho: np.ndarray, E: np.ndarray, tol: float = 1e-10, max_iter: int = 10_000
) -> Radiosity:
    """Jacobi iteration B <- E + R F B until the update is below ``tol`` relative.

    Converges for any n since every row of R F sums to at most max(rho) < 1;
    the error shrinks by that factor per sweep.
    """
    n = F.shape[0]
    E = _check_E(E, n)
    F = sp.csr_matrix(F)
    B = E.copy()
    scale = max(float(np.abs(E).max()), 1e-300)
    for it in range(1, max_iter + 1):
        H = F @ B
        B_new = E + rho * H
        delta = float(np.abs(B_new - B).max())
        B = B_new
        if delta <= tol * scale:
            return Radiosity(E, B, F @ B, it)
    raise LightInvError(f"Jacobi iteration did not converge in {max_iter} sweeps")


def solve(F: sp.spmatrix, rho: np.ndarray, E: np.ndarray) -> Radiosity:
    """Dense solve for small scenes, Jacobi otherwise."""
    if F.shape[0] <= 3000:
        return solve_dense(F, rho, E)
    return solve_iterative(F, rho, E)


MAX_FLUX = 1e10
"""Lumens; more than any building holds, and far from float overflow."""


def group_emission(patches: Patches, lumens: dict[str, float]) -> np.ndarray:
    """Emission vector E (lm/m²) where each named group emits its luminous flux (lm)
    spread uniformly over its area."""
    E = np.zeros(patches.n)
    for group, flux in lumens.items():
        if not (0 <= flux <= MAX_FLUX):
            raise LightInvError(
                f"flux for group {group!r} must be between 0 and {MAX_FLUX:.0e} lumens "
                f"(a stadium uses about 1e8), got {flux:g}"
            )
        idx = patches.group_index(group)
        E[idx] += flux / patches.area[idx].sum()
    return E


def energy_balance(patches: Patches, sol: Radiosity) -> dict[str, float]:
    """Flux budget (lm): emitted, absorbed by surfaces, and lost (escaping an open model).

    In a closed scene emitted = absorbed; the relative imbalance measures the
    form factors' and solver's accuracy.
    """
    emitted = float(np.dot(sol.E, patches.area))
    absorbed = float(np.dot((1.0 - patches.rho) * sol.H, patches.area))
    leaving = float(np.dot(sol.B, patches.area))
    arriving = float(np.dot(sol.H, patches.area))
    return {
        "emitted_lm": emitted,
        "absorbed_lm": absorbed,
        "lost_lm": leaving - arriving,
        "imbalance": (emitted - absorbed) / emitted if emitted > 0 else 0.0,
    }
