"""The paper's five experiments (resources/projects) at small resolutions.

The full-resolution runs and their statistics are in bench/experiments.py; here
each project is loaded as shipped, coarsened (scene resolution, operator rank,
evaluation budget) and its qualitative outcome checked.
"""

from __future__ import annotations

import json
from dataclasses import replace
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.design.model import DesignError
from lightinv_core.optimize.multilevel import FULL_LEVEL_SHARE
from lightinv_core.optimize.pareto import non_dominated
from lightinv_core.project import OperatorSettings, load_project
from lightinv_core.study import prepare, solve, solve_seeds

pytestmark = pytest.mark.slow  # the paper's experiments: several optimisations each

PROJECTS = Path(__file__).resolve().parents[2] / "resources" / "projects"
FAST = OperatorSettings(rank=250, rays=256)


def coarse(name: str, resolution: float):
    project = load_project(PROJECTS / f"{name}.json")
    return replace(project, scene=replace(project.scene, resolution=resolution), operator=FAST)


@pytest.fixture(scope="module")
def patio():
    project = coarse("experiment1", 0.7)
    return prepare(project)


def test_all_example_projects_load():
    names = sorted(p.stem for p in PROJECTS.glob("*.json"))
    assert names == [
        "experiment1",
        "experiment2",
        "experiment3",
        "experiment3b",
        "experiment4",
        "experiment5",
        "experiment5-skylights",
        "experiment5-twostep",
        "office-arrays",
        "office-demo",
        "office-flagship",
        "office-integrated",
    ]
    for n in names:
        assert load_project(PROJECTS / f"{n}.json").design.goals


def test_experiment1_recovers_the_two_targets(patio):
    project = coarse("experiment1", 0.7)
    targets = project.design.target_sources
    assert all(0.02 <= t.area / 144.0 <= 0.06 for t in targets)
    for seed in (0, 1):
        r = solve(project, patio, seed=seed)
        assert r.status == "feasible" and r.best.objectives["match"] < 0.03
        found = sorted(
            tuple(np.round(np.sort(np.reshape(s.rect, (2, 2)), axis=0).ravel(), 1))
            for s in r.best.sources
        )
        want = sorted(
            tuple(np.round(np.sort(np.reshape(t.rect, (2, 2)), axis=0).ravel(), 1)) for t in targets
        )
        np.testing.assert_allclose(found, want, atol=0.8)


def test_experiment2_single_level_reaches_the_same_error(patio):
    r = solve(coarse("experiment2", 0.7), patio, seed=0)
    assert r.best.objectives["match"] < 0.03


def test_experiment3_feasible_and_cmax_over_4_infeasible(patio):
    ok = solve(coarse("experiment3", 0.7), patio, seed=0)
    assert ok.status == "feasible" and ok.best.penalty == 0.0
    assert 8.0 - 1e-9 <= ok.best.sources[0].area <= 16.0 + 1e-9
    bad = solve(coarse("experiment3b", 0.7), patio, seed=0)
    assert bad.status == "infeasible" and bad.best.penalty > 0
    assert {v.name for v in bad.best.violations} == {"every patch"}


def _verdict_on_every_patch(project, prepared, solution) -> bool:
    """An independent judge: the solution's light on every patch against the bounds of
    experiment 3's one intention (C within [min, max] to 0.1%), from the light field."""
    (it,) = project.design.intentions
    C = prepared.light.field(solution.sources, project.design.daylight).reflected
    return bool(C.min() >= it.min * (1 - 1e-3) and C.max() <= it.max * (1 + 1e-3))


@pytest.mark.parametrize(
    ("divisors", "level_evals"),
    [((64, 16, 1), 2000), ((64,), 1999), ((256, 64), 1000)],
    ids=["shipped-levels", "coarse-level-only", "coarse-levels-take-the-budget"],
)
def test_experiment3_multilevel_answer_is_judged_on_every_patch(patio, divisors, level_evals):
    """A multilevel run's answer is judged on all patches, whatever its levels: a level
    list without 1 gets a full-resolution level, and the coarse levels leave it a quarter
    of the budget. Measured before this rule: with levels (64,) and the budget spent
    there, every seed's layout broke the max bound by 76-532% on all patches. The status
    is the verdict of an independent judge (the light field on every patch)."""
    project = coarse("experiment3", 0.7)
    opt = replace(project.optimizer, divisors=divisors, level_max_evals=level_evals, stall=None)
    project = replace(project, optimizer=opt)
    for seed in (0, 1, 2):
        r = solve(project, patio, seed=seed, max_evals=2000)
        levels = r.best.info.level_evaluations
        assert len(levels) == len(divisors) + (divisors[-1] != 1)
        # A VNS batch (32 trials) may overrun a level's cap a little.
        assert sum(levels) == r.evaluations and levels[-1] >= 2000 * FULL_LEVEL_SHARE - 32
        on_all = _verdict_on_every_patch(project, patio, r.best)
        assert r.status == ("feasible" if on_all else "infeasible"), (seed, r.best.violations)
        assert r.best.feasible == on_all


def test_experiment4_area_times_filter_is_nearly_constant(patio):
    project = coarse("experiment4", 0.7)
    seen, snaps = [], []
    runs = solve_seeds(project, patio, [0, 1, 2, 3], progress=snaps.append, on_result=seen.append)
    assert runs == seen and [r.best.info.seed for r in runs] == [0, 1, 2, 3]
    assert {(s.run, s.runs) for s in snaps} == {(i, 4) for i in range(4)}
    prods = []
    for r in runs:
        assert r.status == "feasible"
        s = r.best.sources[0]
        prods.append(s.area * s.filter)
    assert np.std(prods) / np.mean(prods) < 0.1
    assert len({r.best.x for r in runs}) == 4  # four different layouts, one product
    with pytest.raises(DesignError, match="take one best layout; 'epsilon' finds a front"):
        solve_seeds(coarse("experiment5", 0.7), patio, [0, 1])


@pytest.fixture(scope="module")
def corridor():
    return prepare(coarse("experiment5", 0.6))


def test_experiment5_skylights_alone_are_infeasible(corridor):
    project = coarse("experiment5-skylights", 0.6)
    # At 0.6 m the skylights can reach ~255 lm/m² on the panels; ask a little more than
    # that, as the full-resolution project's 260 lm/m² is above their ~225 there.
    design = project.design
    it = replace(design.intentions[0], min=300.0)
    project = replace(project, design=replace(design, intentions=(it,)))
    r = solve(project, corridor, seed=0, max_evals=6000)
    assert r.status == "infeasible" and [v.name for v in r.best.violations] == ["panels"]


@pytest.mark.parametrize("name", ["experiment5", "experiment5-twostep"])
def test_experiment5_pareto_fronts(corridor, name):
    project = coarse(name, 0.6)
    opt = replace(project.optimizer, epsilon_count=5, runs=3, max_evals=8000, stall=3000)
    r = solve(replace(project, optimizer=opt), corridor, seed=0)
    front = r.pareto.solutions
    assert len(front) >= (3 if name == "experiment5" else 1)
    F = np.array(
        [[s.objectives["min_electric_power"], -s.objectives["max_light_power"]] for s in front]
    )
    assert non_dominated(F).all() and all(s.feasible for s in front)


def test_cli_solve_json_and_saved_results(tmp_path, capsys):
    src = json.loads((PROJECTS / "experiment3b.json").read_text())
    src["scene"]["resolution"] = 0.7
    src["operator"] = {"rank": 250, "rays": 256}
    path = tmp_path / "exp3b.json"
    path.write_text(json.dumps(src))
    out_path = tmp_path / "result.json"
    assert (
        cli.main(
            [
                "solve",
                str(path),
                "--max-evals",
                "3000",
                "--seed",
                "2",
                "--json",
                "-o",
                str(out_path),
            ]
        )
        == 0
    )
    out = json.loads(capsys.readouterr().out)
    for key in (
        "status",
        "objective",
        "penalty",
        "evaluations",
        "seconds",
        "precompute_seconds",
        "sources",
        "violations",
    ):
        assert key in out
    assert out["status"] == "infeasible" and out["violations"][0]["name"] == "every patch"
    src_area = out["sources"][0]["area_m2"]
    saved = load_project(out_path)
    assert saved.solutions[0].sources[0].area == pytest.approx(src_area)
    assert not saved.solutions[0].feasible
    # The same seed gives the same result, bit for bit.
    assert cli.main(["solve", str(path), "--max-evals", "3000", "--seed", "2", "--json"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["sources"] == out["sources"] and again["objective"] == out["objective"]


def test_integrated_office_demo_gives_a_front_of_glazing_against_energy():
    project = coarse("office-integrated", 0.5)
    project = replace(project, optimizer=replace(project.optimizer, epsilon_count=3))
    r = solve(project, prepare(project), seed=0)
    assert r.status == "feasible"
    pts = sorted(
        (s.objectives["min_glazing_area"], s.objectives["min_annual_energy"])
        for s in r.pareto.solutions
    )
    assert len(pts) >= 3
    # More glazing, less energy along the front; every point lights the desks at night.
    assert all(b[1] < a[1] for a, b in pairwise(pts))
    assert all(s.feasible for s in r.pareto.solutions)
