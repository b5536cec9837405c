"""Honest budgets and counts, and multilevel levels kept with the operator.

- every registered method reports as its evaluations exactly the candidates whose light
  was computed in its search (a counting wrapper around the scoring of
  ``DesignProblem.evaluate``; judging the answers on every patch is not counted),
  and keeps within ``max_evals`` as a total (the sweeps share it out), passing it by
  at most one batch;
- a second solve on the same operator (a new light model, as the window makes for each
  run) builds no level: no clustering and no rows of Phi (counted, not timed).
"""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.design.model import CORNERS, Design, Goal, Intention, Source
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize import level_cache, registry
from lightinv_core.optimize.method import RunContext
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.optimize.termination import StopRule
from lightinv_core.project import OperatorSettings as ProjectOperator
from lightinv_core.project import Project, SceneSpec
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import Prepared, solve
from tests.core.test_optimizers import desk_design


@pytest.fixture(scope="module")
def office():
    scene = builtin_scene("office", 0.6)
    patches = mesh_patches(scene)
    op = build_operator(patches, OperatorSettings(rank=100, rays=256))
    return scene, patches, op


@pytest.fixture
def counted(monkeypatch):
    """Candidates scored (lit) by ``DesignProblem.evaluate`` during the search, batch by
    batch, counted outside the method's own bookkeeping; the judging of an answer on
    every patch (``DesignProblem.solution``, one evaluation per answer) is not a search
    step and is left out, as the results leave it out."""
    batches: list[int] = []
    judging = [0]
    score, solution = DesignProblem._score, DesignProblem.solution

    def counting(self, rect, *args, **kwargs):
        if not judging[0]:
            batches.append(rect.shape[0])
        return score(self, rect, *args, **kwargs)

    def judged(self, *args, **kwargs):
        judging[0] += 1
        try:
            return solution(self, *args, **kwargs)
        finally:
            judging[0] -= 1

    monkeypatch.setattr(DesignProblem, "_score", counting)
    monkeypatch.setattr(DesignProblem, "solution", judged)
    return batches


SETTINGS = OptimizerSettings(population=20, epsilon_count=3, runs=2, divisors=(16, 1))
BUDGET = 1500


@pytest.mark.parametrize("name", registry.method_names())
@pytest.mark.parametrize("both_goals", [False, True])
def test_every_method_reports_every_evaluation_within_its_total_budget(
    office, counted, name, both_goals
):
    scene, patches, op = office
    d = desk_design(60.0, both_goals)
    method = registry.get_method(name)
    if method.refusal(d) is not None:
        pytest.skip(f"{name} does not apply: {method.refusal(d)}")
    problem = DesignProblem(d, LightModel(scene, patches, op))
    res = method.run(problem, RunContext(SETTINGS, StopRule(max_evals=BUDGET), seed=1))
    assert counted, "nothing was evaluated"
    assert res.evaluations == sum(counted)
    # The stop rule is checked between batches: at most one batch past the total.
    assert BUDGET <= res.evaluations <= BUDGET + max(counted)


def test_the_sweeps_share_one_budget_where_they_used_one_per_run(office, counted):
    scene, patches, op = office
    problem = DesignProblem(desk_design(60.0, True), LightModel(scene, patches, op))
    eps = registry.get_method("epsilon")
    res = eps.run(problem, RunContext(SETTINGS, StopRule(max_evals=BUDGET), seed=2))
    # Five sub-runs (two range runs, three bounds) share the budget: before, each had
    # all of it (five times as many evaluations).
    assert res.evaluations == sum(counted) <= BUDGET + max(counted)
    assert len(res.front.solutions) >= 1


LUMINAIRE = Source("L", "lum_west", "luminaire", (0, 0, 1, 1), free=(*CORNERS, "flux"), flux=4e3)


def _project(method: str) -> Project:
    return Project(
        "levels",
        SceneSpec(builtin="office", resolution=0.6),
        Design(
            (LUMINAIRE,),
            (Goal("min_electric_power"),),
            intentions=(Intention("desks", "desks", min=80.0),),
        ),
        ProjectOperator(),
        OptimizerSettings(method=method, max_evals=600, divisors=(64, 16, 1)),
    )


def test_a_second_solve_on_the_same_operator_builds_no_level(office, monkeypatch):
    scene, patches, op = office
    level_cache.forget(LightModel(scene, patches, op))
    calls = {"clusters": 0, "rows": 0}
    clusters, rows = level_cache.cluster_patches, RadiosityOperator.phi_rows

    def counting_clusters(*args, **kwargs):
        calls["clusters"] += 1
        return clusters(*args, **kwargs)

    def counting_rows(self, *args, **kwargs):
        calls["rows"] += 1
        return rows(self, *args, **kwargs)

    monkeypatch.setattr(level_cache, "cluster_patches", counting_clusters)
    monkeypatch.setattr(RadiosityOperator, "phi_rows", counting_rows)
    project = _project("multilevel")
    # A new Prepared (so a new light model) per run, as the window makes.
    first = solve(project, Prepared(scene, patches, op, True, 0.0), seed=0)
    built = dict(calls)
    assert built["clusters"] == 2 and built["rows"] >= 2  # n/64 and n/16 (and all)
    second = solve(project, Prepared(scene, patches, op, True, 0.0), seed=1)
    assert calls == built
    assert first.best is not None and second.best is not None
    # The kept rows are the rows a cold build makes.
    light = LightModel(scene, patches, op)
    kept = DesignProblem(project.design, light).level(16)
    assert np.array_equal(kept.receivers.Phi_rows, op.phi_rows(kept.rows))
    with pytest.raises(ValueError):
        kept.receivers.Phi_rows[0, 0] = 1.0  # shared by every later run: read-only
