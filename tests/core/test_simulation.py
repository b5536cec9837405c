"""``study.simulate``: the one forward-simulation path the CLI's ``simulate`` prints,
against the reference solver called directly, and its choice of method."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.errors import LightInvError
from lightinv_core.luminaires.analytic import downlight
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import SimulationSpec, simulate
from lightinv_core.study.simulation import installed_watts, luminaire_watts
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.luminaires import PlacedLuminaire
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.scene_light import light_scene
from lightinv_core.transport.solver import group_emission


@pytest.fixture(scope="module")
def cornell():
    return builtin_scene("cornell", 0.5)


def test_static_light_is_the_reference_solve(cornell):
    spec = SimulationSpec(cornell, emit={"light": 1000.0}, rays=64, seed=3)
    res = simulate(spec)
    assert res.method == "reference" and res.annual is None and res.grid is None
    p = mesh_patches(cornell)
    caster = RayCaster(p)
    F = form_factor_matrix(p, 64, seed=3, caster=caster)
    ref = light_scene(p, F, caster, group_emission(p, {"light": 1000.0}), [], seed=3)
    np.testing.assert_array_equal(res.H, ref.H)
    np.testing.assert_array_equal(res.B, ref.B)
    assert res.light.emitted_lm == pytest.approx(1000.0)
    light = next(g for g in res.groups if g["group"] == "light")
    assert light["avg_lux"] == pytest.approx(float(ref.H[p.group_index("light")].mean()))


def test_the_operator_only_for_plain_emission(cornell):
    lum = PlacedLuminaire("D", np.array([1.0, 1.0, 1.9]), downlight(1000.0, watts=12.0))
    with pytest.raises(LightInvError, match="leave out --method lrr"):
        simulate(SimulationSpec(cornell, luminaires=(lum,), method="lrr", rays=16))
    spec = SimulationSpec(cornell, emit={"light": 500.0}, method="lrr", rays=16, use_cache=False)
    res = simulate(spec)
    assert res.method == "lrr" and res.light is None and res.operator["k"] > 0
    assert res.operator["emitted_lm"] == pytest.approx(500.0)


def test_luminaire_watts_follow_the_dimming():
    full = PlacedLuminaire("a", np.array([0.0, 0.0, 2.0]), downlight(1000.0, watts=12.0))
    half = PlacedLuminaire("b", np.array([1.0, 0.0, 2.0]), full.photometry, dimming=0.5)
    unknown = PlacedLuminaire("c", np.array([2.0, 0.0, 2.0]), downlight(1000.0))
    assert luminaire_watts(half) == pytest.approx(6.0) and luminaire_watts(unknown) is None
    assert installed_watts([full, half, unknown]) == pytest.approx(18.0)
