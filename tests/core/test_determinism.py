"""Determinism: the same project and seed give the same result bit for bit on one
machine — whatever the number of ray-casting threads or BLAS threads (the window runs
with one BLAS thread, the command line with all), and from a fresh build or the cache."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from threadpoolctl import threadpool_limits

from lightinv_core.design.model import CORNERS, Design, Goal, Intention, Rule, Source
from lightinv_core.operator.build import build_operator
from lightinv_core.project import OperatorSettings, OptimizerSettings, Project, SceneSpec
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import prepare, solve
from lightinv_core.transport.formfactors import form_factor_matrix


@pytest.fixture(scope="module")
def office():
    return mesh_patches(builtin_scene("office", 0.6))


def test_form_factors_do_not_depend_on_the_thread_count(office):
    one = form_factor_matrix(office, 256, seed=4, workers=1)
    two = form_factor_matrix(office, 256, seed=4, workers=2)
    assert (one != two).nnz == 0


def test_operator_builds_are_identical(office):
    a = build_operator(office, OperatorSettings(rank=100, rays=256, seed=2))
    b = build_operator(office, OperatorSettings(rank=100, rays=256, seed=2))
    assert np.array_equal(a.Phi, b.Phi)


def project(method: str) -> Project:
    lum = Source("L", "lum_west", "luminaire", (0, 0, 1, 1), free=(*CORNERS, "flux"), flux=4e3)
    sky = Source("S", "skylight", "skylight", (0, 0, 1, 1), free=CORNERS)
    design = Design(
        (lum, sky),
        (Goal("min_electric_power"), Goal("max_light_power")),
        (Rule("area", ("S",), max=3.0),),
        (Intention("desks", "desks", min=150.0),),
    )
    return Project(
        "determinism",
        SceneSpec(builtin="office", resolution=0.6),
        design,
        OperatorSettings(rank=100, rays=256),
        OptimizerSettings(method=method, max_evals=1500, epsilon_count=3, divisors=(4, 1)),
    )


FRONTS = ("epsilon", "nsga2", "auto")  # auto: this design has both power goals


@pytest.mark.parametrize("method", ["vns", "multilevel", "cmaes", "epsilon", "nsga2", "auto"])
def test_same_project_and_seed_same_result(method):
    p = project(method)
    prepared = prepare(p)
    first = solve(p, prepared)
    again = solve(p, prepare(p))  # the operator now comes from the cache
    with threadpool_limits(limits=1, user_api="blas"):
        single = solve(p, prepared)
    for other in (again, single):
        if method in FRONTS:
            assert [s.x for s in other.pareto.candidates] == [s.x for s in first.pareto.candidates]
        else:
            assert other.best.x == first.best.x
            assert other.best.objectives == first.best.objectives
            assert other.history == first.history
    other_seed = solve(replace(p, optimizer=replace(p.optimizer, seed=1)), prepared)
    chosen = (lambda r: r.pareto.candidates[0].x) if method in FRONTS else (lambda r: r.best.x)
    assert chosen(other_seed) != chosen(first)
