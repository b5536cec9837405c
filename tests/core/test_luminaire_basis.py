"""The precomputed responses of photometric luminaires agree with the reference solver
on the same traced form factors: per patch, per group and on the work plane."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.luminaires.analytic import batwing_linear, downlight
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.luminaire_basis import BASIS_SAMPLES, luminaire_responses
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.luminaires import PlacedLuminaire
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.scene_light import light_grid, light_scene
from lightinv_core.transport.workplane import WorkPlane, work_plane_grid

DOWN = (0.0, 0.0, -1.0)
SETTINGS = OperatorSettings(rays=512, seed=4, tol=0.01)


@pytest.fixture(scope="module")
def office():
    p = mesh_patches(builtin_scene("office", 0.5))
    op = build_operator(p, SETTINGS)
    # The operator's own form factors: same rays, same seed, same bits.
    F = form_factor_matrix(p, SETTINGS.rays, seed=SETTINGS.seed)
    caster = RayCaster(p)
    grid = work_plane_grid(p, caster, WorkPlane(0.8, 0.5))
    return p, op, F, caster, grid


def placements():
    down = downlight(2000.0, watts=20.0)
    wing = batwing_linear(4000.0, watts=32.0)
    return [
        PlacedLuminaire("D1", (2.0, 2.0, 2.95), down, DOWN, (1, 0, 0)),
        PlacedLuminaire("D2", (9.5, 6.0, 2.95), down, DOWN, (1, 0, 0)),
        PlacedLuminaire("W1", (6.0, 4.0, 2.95), wing, DOWN, (1, 0, 0)),
        PlacedLuminaire("W2", (6.0, 4.0, 2.95), wing, DOWN, (0, 1, 0)),
    ]


def test_responses_match_the_reference_solver(office):
    p, op, F, caster, grid = office
    rows = np.flatnonzero(
        np.isin(p.group_id, [p.group_names.index(g) for g in ("desks", "floor", "walls")])
    )
    lums = placements()
    got = luminaire_responses(
        p, F, op.lowrank, lums, rows, grid.points, caster=caster, rays=512, seed=7
    )
    for j, lum in enumerate(lums):
        ref = light_scene(p, F, caster, np.zeros(p.n), [lum], samples=BASIS_SAMPLES, seed=7)
        H = ref.H[rows]
        err = np.abs(got.at_rows[:, j] - H)
        assert err.max() <= 0.02 * H.max(), lum.name
        lit = 0.1 * H.max() < H
        assert np.all(err[lit] <= 0.02 * H[lit]), lum.name
        for g in ("desks", "floor", "walls"):
            sel = p.group_id[rows] == p.group_names.index(g)
            a = p.area[rows][sel]
            mean_ref = H[sel] @ a / a.sum()
            assert got.at_rows[sel, j] @ a / a.sum() == pytest.approx(mean_ref, rel=0.01)
        ref_grid = light_grid(grid, ref, caster, [lum], rays=512, seed=8)
        np.testing.assert_allclose(got.at_points[:, j], ref_grid.lux, rtol=0.02)


def test_layouts_are_weighted_sums_of_responses(office):
    p, op, F, caster, grid = office
    rows = p.group_index("desks")
    got = luminaire_responses(p, F, op.lowrank, placements(), rows, grid.points, caster=caster)
    w = np.array([[1.0, 0.5, 0.0, 0.0], [0.0, 0.0, 1.0, 1.0]])
    at_rows, at_points = got.evaluate(w)
    np.testing.assert_allclose(
        at_rows[:, 0], got.at_rows[:, 0] + 0.5 * got.at_rows[:, 1], rtol=1e-5
    )
    np.testing.assert_allclose(
        at_points[:, 1], got.at_points[:, 2] + got.at_points[:, 3], rtol=1e-5
    )
    assert at_rows.shape == (len(rows), 2) and at_points.shape == (len(grid.points), 2)
