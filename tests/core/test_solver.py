"""Reference solvers: furnace test, energy balance, dense vs iterative."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.errors import LightInvError
from lightinv_core.scene.builders import room_faces
from lightinv_core.scene.model import Scene, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.solver import (
    energy_balance,
    group_emission,
    solve_dense,
    solve_iterative,
)


@pytest.mark.parametrize("rho", [0.3, 0.5, 0.8])
def test_furnace_closed_box_uniform_emission(rho):
    faces = room_faces(0, 0, 0, 3, 2, 1.5)
    scene = Scene(
        "furnace", tuple(Surface(k, k, rho, rect=r) for k, r in faces.items()), resolution=0.25
    )
    p = mesh_patches(scene)
    F = form_factor_matrix(p, 256, seed=3)
    E = np.full(p.n, 100.0)
    sol = solve_dense(F, p.rho, E)
    np.testing.assert_allclose(sol.B, 100.0 / (1.0 - rho), rtol=0.01)
    # Illuminance from both read-outs agrees: H = F B and H = (B - E) / rho.
    np.testing.assert_allclose(sol.H, (sol.B - sol.E) / rho, rtol=1e-9)


@pytest.mark.parametrize("group", ["ceiling", "red_wall", "floor"])
def test_energy_balance_in_the_closed_cornell_box(cornell_patches, cornell_F, group):
    # The imbalance is the reciprocity noise of the emitting patches' columns, so it
    # shrinks with the emitter's area: ~0.1% for these surfaces, up to ~0.7% for the
    # nine-patch light zone at 1,024 rays (noted in docs/engine.md).
    E = group_emission(cornell_patches, {group: 1000.0})
    sol = solve_dense(cornell_F, cornell_patches.rho, E)
    bal = energy_balance(cornell_patches, sol)
    assert bal["emitted_lm"] == pytest.approx(1000.0)
    assert bal["absorbed_lm"] == pytest.approx(1000.0, rel=0.005)
    assert abs(bal["imbalance"]) < 0.005


def test_dense_and_iterative_agree_on_cornell(cornell_patches, cornell_F):
    rng = np.random.default_rng(0)
    E = np.where(rng.random(cornell_patches.n) < 0.05, rng.random(cornell_patches.n) * 500, 0.0)
    dense = solve_dense(cornell_F, cornell_patches.rho, E)
    it = solve_iterative(cornell_F, cornell_patches.rho, E, tol=1e-12)
    assert it.iterations > 5
    rel = np.linalg.norm(it.B - dense.B) / np.linalg.norm(dense.B)
    assert rel < 1e-6
    np.testing.assert_allclose(it.H, dense.H, rtol=1e-6, atol=1e-9)


def test_group_emission_spreads_flux_over_area(cornell_patches):
    E = group_emission(cornell_patches, {"light": 250.0, "floor": 40.0})
    idx = cornell_patches.group_index("light")
    assert np.dot(E[idx], cornell_patches.area[idx]) == pytest.approx(250.0)
    assert np.dot(E, cornell_patches.area) == pytest.approx(290.0)
    assert np.ptp(E[idx]) < 1e-9


def test_solver_input_errors(cornell_patches, cornell_F):
    with pytest.raises(LightInvError, match="shape"):
        solve_dense(cornell_F, cornell_patches.rho, np.zeros(3))
    with pytest.raises(LightInvError, match="non-negative"):
        solve_iterative(cornell_F, cornell_patches.rho, np.full(cornell_patches.n, -1.0))
    with pytest.raises(LightInvError, match="no group 'sky'"):
        group_emission(cornell_patches, {"sky": 10.0})
    for flux in (float("nan"), -1.0, 1e300, float("inf")):
        with pytest.raises(LightInvError, match="must be between 0 and 1e"):
            group_emission(cornell_patches, {"light": flux})
