"""The operator's error estimate is a measurement, not a guess (issue #31, item 5): it
stays quiet when the operator is accurate, and when it warns, the number it gives is the
operator's real error on light it was not measured on.

The office at 0.5 m (1,424 patches, 256 rays a patch): the build stops at its second
try (k = 168, 0.3%; the first, k = 84, measured 2.9%). A design's
light (each zone lit whole) against the reference solver on the same form factors is
of the estimate's size. With the doubling stopped at the first try (memory, as on a busy
machine), the operator misses 1% and says so; its number is what fresh samples of
emission measure."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.operator import build
from lightinv_core.operator.accuracy import reference_reflected, relative_errors, sample_emissions
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches


@pytest.fixture(scope="module")
def office():
    return mesh_patches(builtin_scene("office", 0.5))


SETTINGS = OperatorSettings(rays=256)


def real_errors(op, patches, E: np.ndarray) -> np.ndarray:
    """Relative L2 error of C per column of ``E`` against the reference on the
    operator's own form factors."""
    C_ref = reference_reflected(op.F, patches.rho, E, tol=1e-7)
    return relative_errors(patches.rho[:, None] * op.illuminance(E), C_ref)


def test_an_accurate_operator_says_nothing_and_its_estimate_bounds_a_designs_error(office):
    warned: list[str] = []
    op = get_operator(office, SETTINGS, use_cache=False, warn=warned.append).operator
    assert not any("estimated error" in w for w in warned)
    est = op.info["estimated_rel_error"]
    assert op.info["tol_met"] and est < 0.01
    # A design's light: each zone emitting uniformly on its own, then all at once.
    E = np.zeros((office.n, 4))
    for q, zone in enumerate(office.zone_names):
        E[office.zone_index(zone), q] = 1000.0
    E[:, 3] = E[:, :3].sum(axis=1)
    real = real_errors(op, office, E)
    # The estimate is a mean over sampled rectangles: a design's error is of its size
    # (0.19-0.32% against 0.31% here), and within the target.
    assert np.all(real <= 1.5 * est) and np.all(real < op.info["tol"])


def test_a_missed_target_is_told_with_the_operators_real_error(office, monkeypatch):
    monkeypatch.setattr(build, "fits_in_memory", lambda *args: False)
    warned: list[str] = []
    op = get_operator(office, SETTINGS, use_cache=False, warn=warned.append).operator
    info = op.info
    assert info["memory_limited"] and not info["tol_met"] and info["k"] < 100
    assert any("estimated error" in w for w in warned)
    # Emission the build never saw (another seed): the same error, within its spread.
    fresh = real_errors(op, office, sample_emissions(office, 12, seed=99))
    assert fresh.mean() > 0.01
    assert info["estimated_rel_error"] == pytest.approx(fresh.mean(), rel=0.5)
