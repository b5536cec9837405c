"""VNS, multilevel, Pareto utilities and the multi-objective drivers."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from lightinv_core.design.model import CORNERS, Design, DesignError, Goal, Intention, Rule, Source
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.mop import epsilon_constraint, two_step
from lightinv_core.optimize.multilevel import multilevel
from lightinv_core.optimize.pareto import hypervolume_2d, non_dominated
from lightinv_core.optimize.problem import DesignProblem, representatives
from lightinv_core.optimize.search import random_start
from lightinv_core.optimize.termination import StopRule
from lightinv_core.optimize.vns import neighbourhoods, vns
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches


@pytest.fixture(scope="module")
def office():
    scene = builtin_scene("office", 0.5)
    patches = mesh_patches(scene)
    return scene, patches, build_operator(patches, OperatorSettings(rank=150, rays=256))


def match_problem(office):
    scene, patches, op = office
    target = Source("t", "lum_west", "luminaire", (0.5, 2.0, 1.5, 3.5), flux=4000.0)
    free = Source("L", "lum_west", "luminaire", (0.0, 0.0, 0.5, 0.5), free=CORNERS, flux=4000.0)
    design = Design((free,), (Goal("match"),), target_sources=(target,))
    return DesignProblem(design, LightModel(scene, patches, op))


def test_neighbourhood_grid_runs_small_to_large():
    hoods = neighbourhoods(5)
    assert hoods[:5] == [(1, 0.1), (2, 0.1), (3, 0.1), (4, 0.1), (1, 0.2)]
    assert len(hoods) == 40 and hoods[-1] == (4, 1.0)
    assert neighbourhoods(2, max_v=None)[:3] == [(1, 0.1), (2, 0.1), (1, 0.2)]


def test_vns_recovers_a_known_luminaire(office):
    p = match_problem(office)
    res = vns(p, seed=3, stop=StopRule(max_evals=6000, target=0.01))
    assert res.status == "target" and res.goal <= 0.01 and res.penalty == 0.0
    u0, v0, u1, v1 = p.sources_at(res.x)[0].rect
    assert min(u0, u1) == pytest.approx(0.5, abs=0.1) and max(v0, v1) == pytest.approx(3.5, abs=0.1)
    values = [h[1] for h in res.history]
    assert all(a > b for a, b in itertools.pairwise(values))  # strictly improving
    # Batches use a float32 Cholesky factor: e agrees with the float64 path to ~0.1%.
    assert p.solution(res.x).objectives["match"] == pytest.approx(res.goal, rel=2e-3)


def test_same_seed_same_result_other_seed_other_path(office):
    p = match_problem(office)
    stop = StopRule(max_evals=1500)
    a, b, c = (vns(p, seed=s, stop=stop) for s in (5, 5, 6))
    assert np.array_equal(a.x, b.x) and a.history == b.history
    assert not np.array_equal(a.x, c.x)


def test_stop_rules_progress_and_cancel(office):
    p = match_problem(office)
    res = vns(p, seed=0, stop=StopRule(max_evals=500), trials=16)
    assert res.status == "max_evals" and 500 <= res.evaluations < 500 + 16
    res = vns(p, seed=0, stop=StopRule(max_evals=None, stall=300))
    assert res.status == "stall"
    res = vns(p, seed=0, stop=StopRule(max_evals=None, time_limit=0.2))
    # The stop rule fires after the batch that passes 0.2 s (a few ms here): generous,
    # so a loaded machine does not fail it.
    assert res.status == "time_limit" and 0.2 <= res.seconds < 5.0
    snaps = []
    calls = iter(range(10**6))
    res = vns(
        p,
        seed=0,
        stop=StopRule(max_evals=None),
        progress=snaps.append,
        cancel=lambda: next(calls) >= 40,
    )
    assert res.status == "cancelled" and len(snaps) >= 30
    assert res.value == min(s.best_value for s in snaps)
    assert all(a.evaluations <= b.evaluations for a, b in itertools.pairwise(snaps))


def test_rules_that_cannot_be_met_are_reported_before_running(office):
    scene, patches, op = office
    s = Source("s", "skylight", "skylight", (0, 0, 1, 1), free=CORNERS)
    d = Design((s,), (Goal("max_light_power"),), (Rule("area", ("s",), min=20.0),))
    with pytest.raises(DesignError, match="geometric rules"):
        random_start(DesignProblem(d, LightModel(scene, patches, op)), np.random.default_rng(0))


def test_infeasible_intentions_are_named(office):
    scene, patches, op = office
    s = Source("s", "skylight", "skylight", (0, 0, 1, 1), free=CORNERS)
    d = Design(
        (s,),
        (Goal("max_light_power"),),
        (Rule("area", ("s",), max=2.0),),
        (Intention("desks", group="desks", min=20000.0),),
    )
    p = DesignProblem(d, LightModel(scene, patches, op))
    res = vns(p, seed=0, stop=StopRule(max_evals=1500))
    sol = p.solution(res.x)
    assert not sol.feasible and res.penalty > 0
    assert [(v.name, v.constraint) for v in sol.violations] == [("desks", "min")]


def test_feasibility_is_reached_and_kept(office):
    scene, patches, op = office
    s = Source("s", "skylight", "skylight", (0, 0, 1, 1), free=(*CORNERS, "filter"))
    d = Design(
        (s,),
        (Goal("max_light_power"),),
        (Rule("area", ("s",), max=4.0),),
        (Intention("desks", group="desks", max=400.0),),
    )
    p = DesignProblem(d, LightModel(scene, patches, op))
    res = vns(p, seed=1, stop=StopRule(max_evals=4000))
    sol = p.solution(res.x)
    assert sol.feasible and sol.penalty == 0.0
    # The upper bound is active: the optimum lights the brightest desk patch to ~400 lux.
    H = op.zone_illuminance(*_sparse(p, res.x))
    assert 380.0 < H[patches.group_index("desks")].max() <= 400.0 * 1.001


def _sparse(p, x):
    rect, flux, filt = p.vars.decode(np.asarray(x)[None])
    V = p.light.zone_emission(p.design.sources, rect, flux, filt, p.design.daylight)[:, 0]
    nz = np.flatnonzero(V)
    return p.light.op.zone_patches[nz], V[nz]


def test_representatives_cover_each_cluster_once(office):
    _scene, patches, _op = office
    p = match_problem(office)
    lv = p.level(16)
    assert abs(len(lv.rows) - patches.n // 16) <= 0.3 * patches.n / 16 + 40
    idx = patches.group_index("desks")
    labels = np.arange(patches.n) // 4
    reps, area = representatives(patches, idx, labels)
    assert len(set(labels[reps])) == len(reps) == len(set(labels[idx]))
    assert area.sum() == pytest.approx(patches.area[idx].sum())


def test_multilevel_warm_starts_and_ends_on_all_patches(office):
    p = match_problem(office)
    total, levels = multilevel(
        p,
        divisors=(16, 4, 1),
        seed=2,
        stop=StopRule(max_evals=6000, target=0.02),
        level_stop=StopRule(max_evals=2000, target=0.02),
    )
    assert [len(r.history) >= 1 for r in levels] == [True] * len(levels)
    assert total.evaluations == sum(r.evaluations for r in levels) <= 6000 + 32
    assert p.solution(total.x).objectives["match"] == pytest.approx(total.goal, rel=2e-3)


def test_non_dominated_and_hypervolume():
    F = np.array([[1, 5], [2, 3], [3, 4], [4, 1], [2, 3], [5, 5]], float)
    assert non_dominated(F).tolist() == [True, True, False, True, True, False]
    assert hypervolume_2d(F, (6, 6)) == pytest.approx(5 * 1 + 4 * 2 + 2 * 2)
    assert hypervolume_2d(np.array([[7.0, 7.0]]), (6, 6)) == 0.0


@pytest.fixture(scope="module")
def corridor():
    scene = builtin_scene("corridor", 0.6)
    patches = mesh_patches(scene)
    return scene, patches, build_operator(patches, OperatorSettings(rank=200, rays=256))


def corridor_design(with_luminaires: bool) -> Design:
    skies = (
        Source("S1", "S1", "skylight", (1, 0.5, 3, 1.5), free=CORNERS),
        Source("S2", "S2", "skylight", (2, 0.5, 4, 1.5), free=("u0", "v0")),
        Source("S3", "S3", "skylight", (3, 0.5, 5, 1.5)),
    )
    rules = [
        Rule("mirror", ("S3", "S1"), axis="u"),
        Rule("centred", ("S2",)),
        Rule("area", ("S1", "S2", "S3"), max=3.0),
        Rule("aspect", ("S1", "S2", "S3"), max=4),
    ]
    sources = skies
    if with_luminaires:
        sources += (
            Source("A1", "A1", "luminaire", (0.5, 0.1, 1.5, 0.5), free=CORNERS, exitance=6000.0),
            Source(
                "A2", "A2", "luminaire", (0.5, 0.1, 2.5, 0.5), free=("u0", "v0"), exitance=6000.0
            ),
            Source("A3", "A3", "luminaire", (0.5, 0.1, 1.5, 0.5), exitance=6000.0),
        )
        rules += [
            Rule("mirror", ("A3", "A1"), axis="u"),
            Rule("centred", ("A2",)),
            Rule("aspect", ("A1", "A2", "A3"), max=10),
        ]
    goals = (Goal("max_light_power"), Goal("min_electric_power"))
    # Skylights alone reach about C = 255 lm/m² on the panels at this resolution.
    panels = (Intention("panels", group="panels", quantity="C", min=290.0),)
    return Design(sources, goals, tuple(rules), panels)


def test_skylights_alone_cannot_light_the_panels(corridor):
    scene, patches, op = corridor
    p = DesignProblem(corridor_design(False), LightModel(scene, patches, op))
    res = vns(p, seed=0, stop=StopRule(max_evals=3000))
    sol = p.solution(res.x)
    assert not sol.feasible and [v.name for v in sol.violations] == ["panels"]


@pytest.mark.slow
@pytest.mark.parametrize("method", ["epsilon", "two_step"])
def test_multi_objective_fronts_are_non_dominated(corridor, method):
    scene, patches, op = corridor
    d = corridor_design(True)
    stop = StopRule(max_evals=8000, stall=3000)
    if method == "epsilon":
        front = epsilon_constraint(d, LightModel(scene, patches, op), count=4, stop=stop)
    else:
        front = two_step(d, LightModel(scene, patches, op), runs=5, stop=stop)
    # Two-step runs whose skylights leave the panels too dark stay infeasible, so the
    # front may be short; the epsilon sweep covers the range.
    assert len(front.solutions) >= (2 if method == "epsilon" else 1)
    assert all(s.feasible for s in front.solutions)
    F = np.array(
        [
            [s.objectives["min_electric_power"], -s.objectives["max_light_power"]]
            for s in front.solutions
        ]
    )
    assert non_dominated(F).all()
    assert np.all(np.diff(F[:, 0]) >= 0)  # sorted by electric power
    assert len(front.candidates) >= len(front.solutions)


def test_progress_carries_the_best_layout(office):
    p = match_problem(office)
    snaps = []
    res = vns(p, seed=2, stop=StopRule(max_evals=800), progress=snaps.append)
    assert snaps[-1].best_x == tuple(res.x) and (snaps[-1].run, snaps[-1].runs) == (0, 1)
    # The snapshot's x scores its best value (it is the incumbent, not the last trial).
    # (float32 batches: the same x scores the same to ~0.1%)
    assert p.evaluate(np.array(snaps[-1].best_x)[None]).value[0] == pytest.approx(
        res.value, rel=2e-3
    )


def test_offending_patches_are_the_ones_out_of_bounds(office):
    scene, patches, op = office
    s = Source("s", "skylight", "skylight", (0, 0, 1, 1), free=CORNERS)
    its = (
        Intention("desks", group="desks", min=300.0, uniformity=0.95),
        Intention("floor", group="floor", max=1e9),
    )
    design = Design((s,), (Goal("max_light_power"),), (), its)
    p = DesignProblem(design, LightModel(scene, patches, op))
    x = p.vars.initial()
    lux = op.zone_illuminance(*_sparse(p, x))
    found = {(name, bound): ids for name, bound, ids in p.offending_patches(x)}
    assert set(found) == {("desks", "min"), ("desks", "uniformity")}
    desks = patches.group_index("desks")
    np.testing.assert_array_equal(found["desks", "min"], desks[lux[desks] < 300.0])
    assert 0 < len(found["desks", "uniformity"]) < len(desks)
    # A layout that meets every bound offends nowhere.
    loose = Design((s,), (Goal("max_light_power"),), (), (Intention("d", group="desks", min=0.1),))
    assert DesignProblem(loose, LightModel(scene, patches, op)).offending_patches(x) == []


def test_sweeps_report_each_run_and_each_point(office):
    scene, patches, op = office
    sky = Source("s", "skylight", "skylight", (0, 0, 1, 1), free=CORNERS)
    lum = Source("L", "lum_west", "luminaire", (0, 0, 1, 1), free=CORNERS, flux=2000.0)
    d = Design(
        (sky, lum),
        (Goal("min_electric_power"), Goal("max_light_power")),
        (Rule("area", ("s",), max=3.0), Rule("area", ("L",), max=1.0)),
        (Intention("desks", group="desks", min=100.0),),
    )
    snaps, points = [], []
    front = epsilon_constraint(
        d,
        LightModel(scene, patches, op),
        count=3,
        stop=StopRule(max_evals=600),
        on_solution=points.append,
        progress=snaps.append,
    )
    assert points == list(front.candidates) and len(points) == 3
    assert sorted({(s.run, s.runs) for s in snaps}) == [(r, 5) for r in range(5)]
    # Cancelling during the range runs ends the sweep before any point.
    calls = iter(range(10**6))
    front = epsilon_constraint(
        d,
        LightModel(scene, patches, op),
        count=3,
        stop=StopRule(max_evals=10**6),
        cancel=lambda: next(calls) >= 20,
    )
    assert front.candidates == ()


def test_a_front_lists_a_repeated_point_once():
    from lightinv_core.design.solution import Solution
    from lightinv_core.optimize.mop import front_of

    def sol(w, lm, seed):
        objectives = {"min_electric_power": w, "max_light_power": lm}
        return Solution((), objectives, 0.0, info={"seed": seed})

    front = front_of([sol(10, 100, 0), sol(10, 100, 1), sol(20, 150, 2), sol(30, 120, 3)], "t")
    assert [s.info.seed for s in front.solutions] == [0, 2]
    assert len(front.candidates) == 4
