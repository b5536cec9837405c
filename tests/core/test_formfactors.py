"""Form factors against closed forms, closure, reciprocity and determinism."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.scene.model import Rect, Scene, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import (
    form_factor_matrix,
    lost_fraction,
    reciprocal_column,
    trace_rows,
)
from tests.core.closed_forms import parallel_rectangles, perpendicular_rectangles

RAYS = 16384
SEEDS = 64


def _pair_scene(second: Rect, first: Rect | None = None) -> Scene:
    first = first or Rect((0, 0, 0), (1, 0, 0), (0, 1, 0))
    return Scene(
        "pair",
        (
            Surface("a", "a", 0.5, rect=first, grid=(1, 1)),
            Surface("b", "b", 0.5, rect=second, grid=(1, 1)),
        ),
        resolution=10.0,
    )


def _mc_estimate(scene: Scene, rows=(0,), target=1) -> tuple[float, float]:
    """Mean and standard error over independent seeds of the area-weighted F(rows -> target)."""
    p = mesh_patches(scene)
    rows = np.asarray(rows)
    w = p.area[rows] / p.area[rows].sum()
    est = []
    for seed in range(SEEDS):
        F = form_factor_matrix(p, RAYS, seed=seed)
        est.append(float(w @ F[rows, target].toarray().ravel()))
    est = np.array(est)
    return est.mean(), est.std(ddof=1) / np.sqrt(len(est))


def _check(mean: float, se: float, exact: float) -> None:
    assert abs(mean - exact) <= 3 * se + 1e-12, (mean, se, exact)
    assert abs(mean - exact) / exact < 0.01


def test_closed_forms_reproduce_howell_values():
    assert parallel_rectangles(1, 1, 1) == pytest.approx(0.199825, abs=2e-6)
    assert perpendicular_rectangles(1, 1, 1) == pytest.approx(0.200044, abs=2e-6)


@pytest.mark.slow
@pytest.mark.parametrize("a,b,c", [(1, 1, 1), (2, 0.5, 1), (1, 3, 2)])
def test_parallel_opposed_rectangles(a, b, c):
    bottom = Rect((0, 0, 0), (a, 0, 0), (0, b, 0))
    top = Rect((0, b, c), (a, 0, 0), (0, -b, 0))  # facing down
    mean, se = _mc_estimate(_pair_scene(top, bottom))
    _check(mean, se, parallel_rectangles(a, b, c))


@pytest.mark.slow
@pytest.mark.parametrize("l,w,h", [(1, 1, 1), (2, 1, 0.5), (1, 0.5, 2)])
def test_perpendicular_rectangles_sharing_an_edge(l, w, h):  # noqa: E741
    # Emitter: w (along y) x l (along x) on the floor; receiver: h high x l wall at y = 0.
    floor = Rect((0, 0, 0), (l, 0, 0), (0, w, 0))
    wall = Rect((0, 0, 0), (0, 0, h), (l, 0, 0))  # normal +y, into the floor's space
    mean, se = _mc_estimate(_pair_scene(wall, floor))
    _check(mean, se, perpendicular_rectangles(l, w, h))


def test_triangle_patches_sample_like_the_square_they_tile():
    tris = np.array([[[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 0, 0], [1, 1, 0], [0, 1, 0]]], float)
    top = Rect((0, 1, 1), (1, 0, 0), (0, -1, 0))
    scene = Scene(
        "tri",
        (Surface("a", "a", 0.5, triangles=tris), Surface("b", "b", 0.5, rect=top, grid=(1, 1))),
        resolution=10.0,
    )
    mean, se = _mc_estimate(scene, rows=(0, 1), target=2)
    _check(mean, se, parallel_rectangles(1, 1, 1))


def test_rows_sum_to_one_in_a_closed_scene(cornell_patches, cornell_F):
    sums = np.asarray(cornell_F.sum(axis=1)).ravel()
    assert np.all(np.abs(sums - 1.0) <= 1e-3)
    assert lost_fraction(cornell_F, cornell_patches) < 1e-4


def test_reciprocity_holds_statistically(cornell_patches, cornell_F):
    p, F = cornell_patches, cornell_F
    A = p.area
    # Group to group: A_G F(G->H) = A_H F(H->G) with hundreds of thousands of rays each way.
    g = p.group_id
    ng = len(p.group_names)
    M = np.zeros((ng, ng))
    coo = F.tocoo()
    np.add.at(M, (g[coo.row], g[coo.col]), A[coo.row] * coo.data)
    big = 0.02 * M.max() < M
    rel = np.abs(M - M.T)[big] / M[big]
    assert rel.max() < 0.02, rel.max()
    # Patch pairs with many hits: the difference is within 4 sigma of the counting noise.
    rays = 1024
    counts = F.multiply(rays).tocsr()
    i, j = counts.nonzero()
    nij = np.asarray(counts[i, j]).ravel()
    nji = np.asarray(counts[j, i]).ravel()
    sel = (nij >= 50) & (nji >= 50)
    assert sel.sum() > 100
    a, b = A[i[sel]] * nij[sel], A[j[sel]] * nji[sel]
    sigma = np.sqrt(A[i[sel]] ** 2 * nij[sel] + A[j[sel]] ** 2 * nji[sel])
    z = (a - b) / sigma
    assert np.mean(np.abs(z) < 4) > 0.995
    # Column k from row k by reciprocity: A_j F_jk = A_k F_kj exactly.
    k = int(np.argmax(A))
    col = reciprocal_column(F, p, k)
    np.testing.assert_allclose(col * A, A[k] * F[k].toarray().ravel())


def test_same_seed_same_bits_whatever_the_thread_count(cornell_patches):
    F1 = form_factor_matrix(cornell_patches, 64, seed=7, workers=1)
    F2 = form_factor_matrix(cornell_patches, 64, seed=7, workers=2)
    F3 = form_factor_matrix(cornell_patches, 64, seed=8, workers=2)
    assert (F1 != F2).nnz == 0
    assert (F1 != F3).nnz > 0


def test_progress_reaches_one_and_cancel_stops(cornell_patches):
    seen = []
    for _ in trace_rows(cornell_patches, 256, progress=seen.append):
        pass
    assert seen[-1] == pytest.approx(1.0)
    assert all(a <= b for a, b in itertools.pairwise(seen))
    calls = []

    def cancel() -> bool:
        calls.append(1)
        return len(calls) > 1

    with pytest.raises(CancelledError):
        form_factor_matrix(cornell_patches, 256, cancel=cancel)


def test_bad_ray_count_is_a_clear_error(cornell_patches):
    with pytest.raises(LightInvError, match="rays per patch"):
        form_factor_matrix(cornell_patches, 0)
