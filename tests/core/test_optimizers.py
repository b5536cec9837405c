"""CMA-ES, NSGA-II, the ``auto`` portfolio and the front-quality measures."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from lightinv_core.design.geometry import rule_violations
from lightinv_core.design.model import CORNERS, Design, Goal, Intention, Rule, Source
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.cmaes import cmaes, ranking_fitness
from lightinv_core.optimize.method import RunContext
from lightinv_core.optimize.nsga2 import thin
from lightinv_core.optimize.pareto import non_dominated
from lightinv_core.optimize.portfolio import AUTO, interleaved
from lightinv_core.optimize.problem import DesignProblem, Evaluation
from lightinv_core.optimize.quality import front_quality, front_scales, hypervolume, spacing
from lightinv_core.optimize.registry import get_method
from lightinv_core.optimize.search import better, random_layouts
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.optimize.termination import StopRule
from lightinv_core.optimize.vns import vns
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches


@pytest.fixture(scope="module")
def light():
    scene = builtin_scene("office", 0.6)
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rank=100, rays=256)))


def match_problem(light) -> DesignProblem:
    target = Source("t", "lum_west", "luminaire", (0.5, 2.0, 1.5, 3.5), flux=4000.0)
    free = Source("L", "lum_west", "luminaire", (0.0, 0.0, 0.5, 0.5), free=CORNERS, flux=4000.0)
    return DesignProblem(Design((free,), (Goal("match"),), target_sources=(target,)), light)


def desk_design(lux: float = 150.0, both_goals: bool = False) -> Design:
    lum = Source("L", "lum_west", "luminaire", (0, 0, 1, 1), free=(*CORNERS, "flux"), flux=4e3)
    sky = Source("S", "skylight", "skylight", (0, 0, 1, 1), free=CORNERS)
    goals = (Goal("min_electric_power"),)
    if both_goals:
        goals += (Goal("max_light_power"),)
    return Design(
        (lum, sky),
        goals,
        (Rule("area", ("S",), max=3.0),),
        (Intention("desks", "desks", min=lux),),
    )


def test_cmaes_recovers_a_known_luminaire(light):
    p = match_problem(light)
    res = cmaes(p, seed=2, stop=StopRule(max_evals=3000, target=0.03))
    assert res.status == "target" and res.evaluations < 3000
    assert p.solution(res.x).objectives["match"] < 0.03


def test_ranking_is_feasible_first_then_penalty_then_geometry():
    def ev(value, penalty, ok, geometry):
        return Evaluation(
            np.array(value),
            np.array(penalty),
            np.array(ok),
            {},
            int(sum(ok)),
            np.array(geometry, float),
            (),
            (),
        )

    e = ev(
        [0.9, 0.1, 0.2, np.inf, np.inf],
        [0.0, 0.05, 0.0, np.inf, np.inf],
        [True, True, True, False, False],
        [[0.0], [0.0], [0.0], [0.5], [0.1]],
    )
    # Feasible by value (2, 0), then infeasible (1), then rejected by violation (4, 3).
    assert np.argsort(ranking_fitness(e)).tolist() == [2, 0, 1, 4, 3]


def test_cmaes_stays_in_bounds_keeps_feasibility_and_numpys_global_state(light):
    p = DesignProblem(desk_design(), light)
    # The legacy global state is what must stay untouched.
    np.random.seed(123)  # noqa: NPY002
    before = np.random.get_state()[1].copy()  # noqa: NPY002
    snaps = []
    res = cmaes(p, seed=0, stop=StopRule(max_evals=2500), progress=snaps.append)
    assert np.array_equal(np.random.get_state()[1], before)  # noqa: NPY002
    assert p.solution(res.x).feasible
    X = np.array([s.best_x for s in snaps])
    assert np.all(p.vars.lo <= X) and np.all(p.vars.hi >= X)
    penalties = [s.best_penalty for s in snaps]
    first = penalties.index(0.0)
    assert all(q == 0.0 for q in penalties[first:])
    values = [s.best_value for s in snaps[first:]]
    assert all(b <= a for a, b in itertools.pairwise(values))


def test_cmaes_same_seed_same_answer_other_seed_other(light):
    p = match_problem(light)
    a = cmaes(p, seed=5, stop=StopRule(max_evals=600))
    b = cmaes(p, seed=5, stop=StopRule(max_evals=600))
    c = cmaes(p, seed=6, stop=StopRule(max_evals=600))
    assert np.array_equal(a.x, b.x) and a.history == b.history
    assert not np.array_equal(a.x, c.x)


def test_nsga2_front_is_feasible_non_dominated_and_sorted(light):
    p = DesignProblem(desk_design(60.0, both_goals=True), light)
    res = get_method("nsga2").run(
        p, RunContext(OptimizerSettings(population=24), StopRule(max_evals=2400), seed=0)
    )
    sols = res.front.solutions
    assert res.status == "feasible" and 2 <= len(sols) <= 24
    assert all(s.feasible for s in sols)
    F = np.array(
        [[s.objectives["min_electric_power"], -s.objectives["max_light_power"]] for s in sols]
    )
    assert non_dominated(F).all() and np.all(np.diff(F[:, 0]) >= 0)
    assert res.evaluations >= 2400


def test_nsga2_explains_an_impossible_design(light):
    p = DesignProblem(desk_design(1e6, both_goals=True), light)
    res = get_method("nsga2").run(
        p, RunContext(OptimizerSettings(population=12), StopRule(max_evals=300), seed=0)
    )
    assert res.status == "infeasible" and res.best is None
    assert res.front.solutions == () and len(res.front.candidates) == 1
    assert [v.name for v in res.front.candidates[0].violations] == ["desks"]


def test_auto_finds_a_front_only_with_both_power_goals(light):
    auto = AUTO
    assert auto.finds_front(desk_design(both_goals=True))
    assert not auto.finds_front(desk_design())
    single = auto.run(
        DesignProblem(desk_design(), light),
        RunContext(OptimizerSettings(), StopRule(max_evals=800), seed=0),
    )
    assert single.front is None and single.best.info.method == "auto"
    front = auto.run(
        DesignProblem(desk_design(60.0, both_goals=True), light),
        RunContext(OptimizerSettings(population=12), StopRule(max_evals=600), seed=0),
    )
    assert front.front is not None and front.front.method == "nsga2"


def test_auto_interleaves_cmaes_and_vns_each_step_for_step_as_alone(light):
    p = DesignProblem(desk_design(), light)
    snaps = []
    both, used = interleaved(
        p, RunContext(seed=1, stop=StopRule(max_evals=3000), progress=snaps.append)
    )
    assert both.evaluations == used["cmaes"] + used["vns"]
    assert 3000 <= both.evaluations <= 3000 + 32 and min(used.values()) > 0
    # Each search draws from the run's seed as it would alone: until VNS restarts, its
    # path is VNS's alone (the same history over the same evaluations).
    alone = vns(p, seed=1, stop=StopRule(max_evals=used["vns"]))
    cma_alone = cmaes(p, seed=1, stop=StopRule(max_evals=used["cmaes"]))
    assert both.value <= min(alone.value, cma_alone.value) or not (
        better(alone.value, alone.penalty, both.value, both.penalty)
        or better(cma_alone.value, cma_alone.penalty, both.value, both.penalty)
    )
    evals = [s.evaluations for s in snaps]
    assert all(b >= a for a, b in itertools.pairwise(evals))  # one continuous curve
    values = [s.best_value for s in snaps]
    assert all(b <= a for a, b in itertools.pairwise(values))  # the best so far
    assert [h[1] for h in both.history] == sorted((h[1] for h in both.history), reverse=True)


def test_auto_reaches_a_deceptive_match_cmaes_alone_cannot(light):
    """Three luminaires matching three targets (bench/optimizers.py's
    ``three-luminaires``): every CMA-ES restart settles on one luminaire over two
    targets; the portfolio moves the budget to VNS and gets there."""
    targets = (
        Source("t1", "lum_west", "luminaire", (0.2, 0.5, 0.9, 2.0), flux=4000.0),
        Source("t2", "lum_west", "luminaire", (0.3, 3.0, 1.2, 4.2), flux=4000.0),
        Source("t3", "lum_east", "luminaire", (0.5, 1.0, 1.4, 3.0), flux=4000.0),
    )
    free = tuple(
        Source(f"L{i}", t.zone, "luminaire", (0, 0, 0.3, 0.3), free=CORNERS, flux=4000.0)
        for i, t in enumerate(targets)
    )
    p = DesignProblem(Design(free, (Goal("match"),), target_sources=targets), light)
    stop = StopRule(max_evals=6000, target=0.03)
    res, _ = interleaved(p, RunContext(seed=0, stop=stop))
    assert res.status == "target" and res.goal < 0.03
    stuck = cmaes(p, seed=0, stop=StopRule(max_evals=3000, target=0.03))
    assert stuck.status == "max_evals" and stuck.goal > 0.08


def test_auto_stops_at_a_target_reached_by_cmaes(light):
    p = match_problem(light)
    alone = cmaes(p, seed=2, stop=StopRule(max_evals=3000, target=0.03))
    both, used = interleaved(p, RunContext(seed=2, stop=StopRule(max_evals=3000, target=0.03)))
    assert alone.status == both.status == "target"
    # CMA-ES's steps are its steps alone: it gets there within as many of its own.
    assert used["cmaes"] <= alone.evaluations and both.goal < 0.03


def test_random_layouts_meet_the_geometric_rules(light):
    p = DesignProblem(desk_design(), light)
    X = random_layouts(p, np.random.default_rng(0), 50)
    rect, _, _ = p.vars.decode(X)
    assert X.shape == (50, p.vars.n)
    assert not np.any(rule_violations(p.design, rect, p.zone_size) > 0)


def test_two_dimensional_non_dominated_matches_the_pairwise_test():
    rng = np.random.default_rng(1)
    for _ in range(200):
        F = rng.integers(0, 6, (int(rng.integers(1, 30)), 2)).astype(float)
        pairwise = [
            not (np.all(F[i] >= F, axis=1) & np.any(F[i] > F, axis=1)).any() for i in range(len(F))
        ]
        assert non_dominated(F).tolist() == pairwise


def test_thinning_drops_the_least_contributing_point_first():
    F = np.array([[0, 1.0], [0.1, 0.5], [0.12, 0.48], [0.5, 0.2], [1.0, 0.0]])
    # Exclusive areas of the inner points: 0.01, 0.0076, 0.14 -> drop [0.12, 0.48];
    # then 0.2 and 0.15 -> drop [0.5, 0.2]. The extremes always stay.
    assert sorted(thin(F, 3).tolist()) == [0, 1, 4]
    assert sorted(thin(F, 4).tolist()) == [0, 1, 3, 4]
    assert sorted(thin(F, 9).tolist()) == [0, 1, 2, 3, 4]


def test_hypervolume_and_spacing_in_normalised_objectives():
    scales = (200.0, 1000.0)
    # One point at half power and half light dominates a quarter of the unit square.
    assert hypervolume(np.array([[100.0, 500.0]]), scales) == pytest.approx(0.25)
    two = np.array([[50.0, 250.0], [150.0, 750.0]])
    assert hypervolume(two, scales) == pytest.approx(0.75 * 0.25 + 0.25 * 0.5)
    assert spacing(np.array([[100.0, 500.0]]), scales) is None
    even = np.array([[0.0, 0.0], [20.0, 100.0], [40.0, 200.0]])
    assert spacing(even, scales) == pytest.approx(0.0)
    uneven = np.array([[0.0, 0.0], [20.0, 100.0], [100.0, 500.0]])
    d = np.array([0.2, 0.2, 0.8])  # nearest-neighbour L1 distances, normalised
    assert spacing(uneven, scales) == pytest.approx(np.sqrt(((d - d.mean()) ** 2).sum() / 2))


def test_front_quality_of_a_run(light):
    d = desk_design(60.0, both_goals=True)
    p = DesignProblem(d, light)
    res = get_method("nsga2").run(p, RunContext(OptimizerSettings(population=16), StopRule(1600)))
    q = front_quality(res.front.solutions, front_scales(d, light))
    assert 0.0 < q.hypervolume < 1.0 and q.points == len(res.front.solutions)
    assert q.to_dict()["reference"] == [1.0, 0.0]


@pytest.mark.parametrize("method", ["cmaes", "auto"])
def test_a_design_with_one_free_variable_is_searched(light, method):
    # cma refuses one dimension; the flux alone free must still be optimised. The desks'
    # least illuminance is linear in the flux: 10 lux needs 10 / (E at 1 lm).
    lum = Source("L", "lum_west", "luminaire", (0, 0, 1, 1), free=("flux",), flux=4e3)
    desks = (Intention("desks", "desks", min=10.0),)
    p = DesignProblem(Design((lum,), (Goal("min_electric_power"),), (), desks), light)
    assert p.vars.n == 1
    per_lumen = p.solution(np.array([1e3])).violations[0].value / 1e3
    res = get_method(method).run(p, RunContext(stop=StopRule(max_evals=3000), seed=1))
    assert res.status == "feasible"
    assert 0.995 <= res.best.sources[0].flux * per_lumen / 10.0 < 1.02  # within tolerance
