"""Front methods trade the design's own goals: NSGA-II on any pair (the integrated demo's
annual energy against glazing area), refused with the reason where it cannot apply, and
every method's reported evaluations equal those that reached the light model."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from lightinv_core.design.model import CORNERS, Design, Goal, Intention, Rule, Source
from lightinv_core.errors import DesignError
from lightinv_core.optimize.fronts import OBJECTIVES, design_pair, front_pair, front_refusal
from lightinv_core.optimize.pareto import non_dominated
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.quality import front_quality, front_scales
from lightinv_core.optimize.registry import check_applies, get_method, methods
from lightinv_core.project import OperatorSettings, load_project
from lightinv_core.study import prepare, solve

PROJECTS = Path(__file__).resolve().parents[2] / "resources" / "projects"


def _design(*kinds: str, sky_free=CORNERS) -> Design:
    lum = Source("L", "lum_west", "luminaire", (0, 0, 1, 1), free=(*CORNERS, "flux"), flux=4e3)
    sky = Source("S", "skylight", "skylight", (0, 0, 1, 1), free=sky_free)
    return Design(
        (lum, sky),
        tuple(Goal(k) for k in kinds),
        (Rule("area", ("S",), max=3.0),),
        (Intention("desks", "desks", min=60.0),),
    )


def test_the_pair_is_the_designs_own():
    assert design_pair(_design("max_light_power", "min_electric_power")) == tuple(
        map(str, OBJECTIVES)
    )
    assert design_pair(_design("min_glazing_area", "min_electric_power")) == (
        "min_glazing_area",
        "min_electric_power",
    )
    one = _design("min_electric_power")
    assert design_pair(one) is None and front_pair(one) == tuple(map(str, OBJECTIVES))
    three = _design("min_electric_power", "min_glazing_area", "min_luminaire_count")
    assert design_pair(three) is None
    assert "this design has 3" in front_refusal(three, "NSGA-II")


def test_nsga2_is_refused_with_the_reason_where_it_cannot_apply():
    one = _design("min_electric_power")
    why = get_method("nsga2").refusal(one)
    assert why.startswith("NSGA-II trades two of the design's goals")
    assert "one (electric power)" in why and "Design > Goals" in why
    with pytest.raises(DesignError, match="methods for this design: auto, vns, multilevel"):
        check_applies("nsga2", one)
    # A goal that never changes: the skylight's corners are fixed.
    fixed = _design("min_electric_power", "min_glazing_area", sky_free=())
    assert "never changes" in front_refusal(fixed, "NSGA-II")
    # The luminaire count changes only with an array's rows or columns.
    assert "rows or columns" in front_refusal(_design("min_luminaire_count", "min_electric_power"))
    # The methods for one best layout apply to every design; the sweeps follow the goals.
    can = {m.name for m in methods() if m.refusal(one) is None}
    assert can == {"auto", "vns", "multilevel", "cmaes"}
    both = _design("min_electric_power", "max_light_power")
    assert all(m.refusal(both) is None for m in methods())
    glazing = _design("min_electric_power", "min_glazing_area")
    assert "two-step" in get_method("two_step").refusal(glazing)
    assert get_method("epsilon").refusal(glazing) is None


@pytest.fixture(scope="module")
def integrated():
    project = load_project(PROJECTS / "office-integrated.json")
    project = replace(
        project,
        scene=replace(project.scene, resolution=0.7),
        operator=OperatorSettings(rank=120, rays=256),
    )
    return project, prepare(project)


def test_nsga2_on_the_integrated_demo_trades_annual_energy_for_glazing_area(integrated):
    project, prepared = integrated
    assert project.design.goals == (Goal("min_annual_energy"), Goal("min_glazing_area"))
    opt = replace(project.optimizer, method="nsga2", max_evals=600, population=12)
    result = solve(replace(project, optimizer=opt), prepared)
    front = result.pareto
    assert result.status == "feasible" and front.method == "nsga2"
    assert front.objectives == ("min_annual_energy", "min_glazing_area")
    assert 2 <= len(front.solutions) <= 12
    E = np.array(
        [
            [s.objectives["min_annual_energy"], s.objectives["min_glazing_area"]]
            for s in front.solutions
        ]
    )
    assert np.isfinite(E).all() and non_dominated(E).all()
    assert all(s.feasible and "min_electric_power" not in s.objectives for s in front.solutions)
    # The glazing is the skylight's area: the front's own numbers, not another pair's.
    for s in front.solutions:
        sky = next(x for x in s.sources if x.name == "S1")
        assert s.objectives["min_glazing_area"] == pytest.approx(sky.area, rel=1e-9)
    assert np.all(np.diff(E[:, 0]) >= 0) and np.all(np.diff(E[:, 1]) <= 0)  # a trade-off
    pair = front.objectives
    q = front_quality(front.solutions, front_scales(project.design, prepared.light, pair), pair)
    assert q.objectives == pair and 0 < q.hypervolume < 1
    # auto keeps one best layout of the first goal (the user's choice in the Run panel).
    auto = solve(replace(project, optimizer=replace(opt, method="auto")), prepared)
    assert auto.pareto is None


def test_nsga2_on_another_pair(integrated):
    project, prepared = integrated
    design = replace(project.design, goals=(Goal("min_electric_power"), Goal("min_glazing_area")))
    problem = DesignProblem(design, prepared.light)
    opt = replace(project.optimizer, method="nsga2", population=10)
    res = get_method("nsga2").run(problem, _context(opt, 400))
    assert res.front.objectives == ("min_electric_power", "min_glazing_area")
    assert all(
        set(s.objectives) == {"min_electric_power", "min_glazing_area"} for s in res.front.solutions
    )


def _context(settings, max_evals):
    from lightinv_core.optimize.method import RunContext
    from lightinv_core.optimize.termination import StopRule

    return RunContext(settings, StopRule(max_evals=max_evals), seed=0)


class _Counter:
    """Counts the candidates that reach the light model during a search: every lit
    candidate of ``DesignProblem.evaluate`` outside the judging of an answer."""

    def __init__(self, monkeypatch):
        self.evaluations, self._judging = 0, 0
        evaluate, solution = DesignProblem.evaluate, DesignProblem.solution

        def counted(problem, X, level=None):
            ev = evaluate(problem, X, level)
            if not self._judging:
                self.evaluations += ev.evaluated
            return ev

        def judging(problem, x, info=None):
            self._judging += 1
            try:
                return solution(problem, x, info)
            finally:
                self._judging -= 1

        monkeypatch.setattr(DesignProblem, "evaluate", counted)
        monkeypatch.setattr(DesignProblem, "solution", judging)


@pytest.mark.parametrize("method", ["epsilon", "two_step", "nsga2", "multilevel", "auto"])
def test_the_reported_evaluations_are_those_that_reached_the_light(integrated, monkeypatch, method):
    project, prepared = integrated
    design = project.design
    if method == "two_step":
        design = replace(design, goals=(Goal("min_electric_power"), Goal("max_light_power")))
    opt = replace(
        project.optimizer,
        method=method,
        max_evals=300,
        stall=None,
        epsilon_count=3,
        runs=2,
        population=10,
        divisors=(4, 1),
    )
    counter = _Counter(monkeypatch)
    snaps = []
    result = solve(replace(project, design=design, optimizer=opt), prepared, progress=snaps.append)
    assert result.evaluations == counter.evaluations > 0
    # Sweeps: the range runs and every level count, not only the front's points.
    if method == "epsilon":
        assert result.evaluations > sum(s.info.evaluations for s in result.pareto.candidates)


def test_a_cancelled_sweep_reports_what_it_used(integrated, monkeypatch):
    project, prepared = integrated
    opt = replace(project.optimizer, max_evals=2400, stall=None, epsilon_count=4, divisors=(1,))
    counter = _Counter(monkeypatch)
    snaps = []

    def cancel() -> bool:
        return len(snaps) >= 40  # during the third sub-run (two range runs first)

    result = solve(replace(project, optimizer=opt), prepared, progress=snaps.append, cancel=cancel)
    assert result.status == "cancelled"
    assert result.evaluations == counter.evaluations > 0
