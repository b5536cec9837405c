"""The light model against independent references: the dense radiosity solve on the same
traced form factors, energy balance, closed-form source sums, and the optimizer's own
constraint values (one set of formulas for every view)."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.design.model import Daylight, Design, Goal, Intention, Rule, Source
from lightinv_core.errors import DesignError
from lightinv_core.kinds import SourceKind, source_kind_names
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.sources.emission import electric_power, source_flux, source_stack
from lightinv_core.sources.types import SOURCE_TYPES, source_type
from lightinv_core.transport.solver import solve_dense

CORNERS = ("u0", "v0", "u1", "v1")


@pytest.fixture(scope="module")
def cornell():
    scene = builtin_scene("cornell")
    patches = mesh_patches(scene)
    # Seed 1 and 1,024 rays: the operator traces the same F as the cornell_F fixture.
    op = build_operator(patches, OperatorSettings(rays=1024, seed=1))
    return LightModel(scene, patches, op)


@pytest.fixture(scope="module")
def office():
    scene = builtin_scene("office", 0.6)
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rank=120, rays=128)))


def lamp(rect=(0.05, 0.1, 0.4, 0.45), flux=1000.0, **kw):
    return Source("L", "light", "luminaire", rect, flux=flux, **kw)


def test_field_matches_the_dense_solver_on_the_same_form_factors(cornell, cornell_F):
    field = cornell.field((lamp(),), Daylight())
    ref = solve_dense(cornell_F, cornell.patches.rho, field.emission)
    p = cornell.patches
    for g in p.group_names:
        idx = p.group_index(g)
        want = float(ref.H[idx] @ p.area[idx] / p.area[idx].sum())
        got = float(field.group_stats(g).average[0])
        assert got == pytest.approx(want, rel=0.02), g
    # Per patch, away from the emitter, within a few percent on average.
    lit = 0.05 * ref.H.max() < ref.H
    assert np.mean(np.abs(field.illuminance[lit] / ref.H[lit] - 1)) < 0.03
    np.testing.assert_allclose(field.radiosity, field.emission + p.rho * field.illuminance)
    np.testing.assert_allclose(field.luminance, field.radiosity / np.pi)


def test_energy_balance_and_source_sums(cornell):
    s = lamp(flux=1234.0)
    field = cornell.field((s,), Daylight())
    p = cornell.patches
    # What is emitted is the luminaire's flux, to float32 rounding.
    assert float(field.emission @ p.area) == pytest.approx(1234.0, rel=1e-5)
    assert field.source_flux(s) == 1234.0 and field.electric_power == pytest.approx(1234.0 / 100)
    # In a closed room every lumen emitted or reflected is absorbed somewhere:
    # sum (1 - rho) H A = emitted flux (H counts the light arriving).
    absorbed = float(((1 - p.rho) * field.illuminance) @ p.area)
    assert absorbed == pytest.approx(1234.0, rel=0.02)
    assert field.reflected_power == pytest.approx(float(field.reflected @ p.area))
    # The optimizer's O(nz) reflected power agrees with the field's.
    V = cornell.zone_emission((s,), *source_stack((s,)), Daylight())
    assert float(cornell.reflected_power(V)[0]) == pytest.approx(field.reflected_power, rel=1e-4)


def test_every_source_kind_is_registered_and_consistent(office):
    # Every kind the vocabulary names has a type, and every type's kind is a valid name
    # (the window kind included).
    assert set(SourceKind) == set(SOURCE_TYPES) <= set(source_kind_names())
    day = Daylight(exterior_lux=8000.0, transmittance=0.5)
    sky = Source("S", "skylight", "skylight", (1.0, 1.0, 3.0, 2.0), filter=0.4)
    lum = Source("L", "lum_west", "luminaire", (0.5, 1.0, 1.5, 3.0), flux=3000.0, efficacy=120)
    panel = Source("P", "lum_west", "luminaire", (0.0, 0.0, 1.0, 1.0), exitance=500.0)
    for s, flux, watts in (
        (sky, 0.4 * 0.5 * 8000 * 2.0, 0.0),
        (lum, 3000.0, 25.0),
        (panel, 500.0, 5.0),
    ):
        assert source_flux(s, day) == pytest.approx(flux)
        field = office.field((s,), day)
        p = office.patches
        assert float(field.emission @ p.area) == pytest.approx(flux, rel=1e-5), s.name
        assert field.electric_power == pytest.approx(watts)
        rect, fl, _ = source_stack((s,))
        assert electric_power((s,), rect, fl)[0] == pytest.approx(watts)
    with pytest.raises(DesignError, match="unknown source kind 'laser'"):
        source_type("laser")


def test_design_field_applies_the_tied_rules(office):
    a = Source("A", "lum_west", "luminaire", (0.2, 0.5, 1.0, 2.0), free=CORNERS, flux=2000.0)
    b = Source("B", "lum_east", "luminaire", (0.0, 0.0, 0.1, 0.1), flux=2000.0)
    d = Design((a, b), (Goal("min_electric_power"),), (Rule("mirror", ("B", "A"), axis="u"),))
    lit = office.layout(d)
    assert lit[0] == a and lit[1].rect != b.rect  # B placed as A's mirror image
    field = office.design_field(d)
    np.testing.assert_array_equal(field.illuminance, office.field(lit, d.daylight).illuminance)
    # The light of other sources under the design's rules (a pinned result's).
    other = (a, b)
    assert office.design_field(d, other).sources == lit


def test_intention_values_are_the_optimizers_constraints(office):
    it = Intention("desks", group="desks", min=300.0, max=900.0, average=400.0, uniformity=0.6)
    c = Intention("walls", group="walls", quantity="C", max=50.0)
    s = Source("L", "lum_west", "luminaire", (0.5, 1.0, 1.5, 3.0), free=CORNERS, flux=3000.0)
    d = Design((s,), (Goal("min_electric_power"),), intentions=(it, c))
    problem = DesignProblem(d, office)
    x = problem.vars.initial()
    ev = problem.evaluate(x[None])
    field = office.field(problem.sources_at(x), d.daylight)
    checks = [chk for i in (it, c) for chk in field.intention(i).checks]
    lighting = [k for k in problem.constraints if k.kind != "geometry"]
    assert [(k.name, k.bound) for k in lighting] == [(k.intention.name, k.bound) for k in checks]
    G = ev.G[0, -len(checks) :]
    np.testing.assert_allclose(G, [float(k.c[0]) - 1e-3 for k in checks], rtol=1e-4, atol=1e-9)
    # And against a direct computation from the illuminance.
    idx = office.patches.group_index("desks")
    H, a = field.illuminance[idx], office.patches.area[idx]
    res = field.intention(it)
    assert float(res.stats.min[0]) == pytest.approx(H.min())
    assert float(res.stats.average[0]) == pytest.approx(float(H @ a / a.sum()))
    assert ev.feasible[0] == all(bool(k.met[0]) for k in checks)
    # Offending patches are the ones past a bound.
    for bound, ids in field.offending_patches(it):
        if bound == "min":
            assert np.all(field.illuminance[ids] < 300.0)


def test_a_foreign_operator_or_source_is_refused(office, cornell):
    with pytest.raises(DesignError, match="another scene"):
        LightModel(office.scene, office.patches, cornell.op)
    with pytest.raises(DesignError, match="no emitter zone 'nowhere'"):
        office.field((Source("L", "nowhere", "luminaire", (0, 0, 1, 1), flux=1.0),), Daylight())
