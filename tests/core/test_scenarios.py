"""Scenarios on intentions, daylight metrics and the annual goals in the optimiser.

References: the sorted-hours statistics against counting hour by hour (synthetic
years, one and two sky groups); the optimiser's annual goals and metric intentions
against a brute-force loop that relights the layout for every occupied hour with the
reference design-daylight model (``grid_light`` at that hour's exterior lux) and
scores it with ``climate.metrics``; night and overcast against the same fields.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.climate.metrics import daylight_metrics, dimming_energy
from lightinv_core.design.en12464 import preset_intention
from lightinv_core.design.model import (
    Daylight,
    Design,
    DesignError,
    Goal,
    Intention,
    LuminaireArray,
    Source,
    Workplane,
)
from lightinv_core.light.daylight_year import (
    DaylightYear,
    daylight_year,
    dimming_sum,
    hours_from,
    hours_within,
    reaches_share,
)
from lightinv_core.light.grids import grid_light
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.project import project_from_dict, project_to_dict
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches


def _year(exterior: np.ndarray) -> DaylightYear:
    T = exterior.shape[1]
    one = exterior.shape[0] == 1
    srt = np.sort(exterior[0]) if one else None
    prefix = np.concatenate([[0.0], np.cumsum(srt)]) if one else None
    months = (np.arange(T) % 12 + 1).astype(np.int8)
    return DaylightYear(
        "synthetic", "", None, exterior, np.ones(T, bool), exterior, months, srt, prefix
    )


@pytest.mark.parametrize("groups", [1, 2])
def test_sorted_hour_statistics_equal_counting_hour_by_hour(groups):
    rng = np.random.default_rng(3)
    E = rng.gamma(1.5, 9000.0, size=(groups, 700))
    year = _year(E)
    a = rng.uniform(0, 0.08, size=(40, 5, groups))
    a[0, 0] = 0.0  # a point no skylight reaches
    lux = np.einsum("pmg,gt->pmt", a, E)
    assert np.array_equal(hours_from(year, a, 300.0), (lux >= 300.0).sum(axis=2))
    for share in (0.0, 0.3, 0.5, 0.999, 1.0):
        want = (lux >= 300.0).sum(axis=2) >= np.ceil(share * E.shape[1])
        assert np.array_equal(reaches_share(year, a, 300.0, share), want)
    within = ((lux >= 100.0) & (lux <= 3000.0)).sum(axis=2)
    assert np.array_equal(hours_within(year, a, 100.0, 3000.0), within)
    b = a.mean(axis=0)  # (m, G): the control plane's mean
    full = rng.uniform(200, 900, size=5)
    full[1] = 450.0
    got = dimming_sum(year, b, full, 500.0, 0.15)
    day = b @ E
    want = np.clip((500.0 - day) / full[:, None], 0.15, 1.0).sum(axis=1)
    assert np.allclose(got, want, rtol=1e-12, atol=1e-9)
    # No daylight at all: one constant level all year.
    zero = dimming_sum(year, np.zeros_like(b), full, 500.0, 0.15)
    assert np.allclose(zero, np.clip(500.0 / full, 0.15, 1.0) * E.shape[1])


@pytest.fixture(scope="module")
def office():
    scene = builtin_scene("office", 0.5)
    patches = mesh_patches(scene)
    op = build_operator(patches, OperatorSettings(rays=256))
    return LightModel(scene, patches, op)


DAYLIGHT = Daylight(exterior_lux=10000.0, transmittance=0.6, occupancy=(10.0, 14.0))
SKY = Source("S", "skylight", "skylight", (1.0, 0.5, 3.0, 1.5), free=("u0", "v0", "u1", "v1"))
LUM = Source(
    "L",
    "lum_west",
    "luminaire",
    (0.5, 2.0, 1.5, 4.0),
    free=("flux",),
    flux=8000.0,
    flux_range=(0.0, 20000.0),
)


def _design(intentions=(), goals=("min_electric_power",), daylight=DAYLIGHT):
    return Design(
        sources=(SKY, LUM),
        goals=tuple(Goal(g) for g in goals),
        intentions=tuple(intentions),
        workplanes=(Workplane("wp"),),
        daylight=daylight,
    )


def _hourly_grid(light, design, x, problem):
    """Per occupied hour, the grid's daylight relit with the design-daylight model at
    that hour's exterior lux (the brute-force reference), and the electric light."""
    sources = problem.sources_at(x)
    grids = problem.grids
    sky = tuple(s for s in sources if s.kind == "skylight")
    lum = tuple(s for s in sources if s.kind == "luminaire")
    year = daylight_year(problem.sky, design.daylight)
    unit = grid_light(light, grids, sky, (), replace(design.daylight, exterior_lux=1.0))
    # Relight for every occupied hour (linear in the exterior lux, but computed anew).
    day = np.stack(
        [
            grid_light(light, grids, sky, (), replace(design.daylight, exterior_lux=float(e)))
            for e in year.exterior[0]
        ],
        axis=1,
    )
    assert np.allclose(day[:, :3], unit[:, None] * year.exterior[0, :3], rtol=1e-6)
    electric = grid_light(light, grids, lum, (), design.daylight)
    return year, day, electric


def test_annual_goals_and_metrics_match_an_hourly_loop(office):
    intentions = (
        Intention("da", grid="wp", quantity="da", average=0.95),
        Intention("udi", grid="wp", quantity="udi", min=0.99),
        Intention("sda", grid="wp", quantity="sda", average=0.97),
    )
    design = _design(intentions, goals=("min_annual_energy", "max_sda", "min_glazing_area"))
    problem = DesignProblem(design, office)
    x = problem.vars.initial()
    ev = problem.evaluate(x[None])
    year, day, electric = _hourly_grid(office, design, x, problem)
    metrics = daylight_metrics(day)
    watts = problem.light.electric_power(design.sources, *problem.vars.decode(x[None])[:2])[0]
    dim = dimming_energy(
        day.mean(axis=0), electric.mean(), 500.0, watts, 96.0, 0.1, 0.0, year.every.shape[1]
    )
    assert ev.goals["min_annual_energy"][0] == pytest.approx(dim.energy_kwh, rel=1e-5)
    assert ev.goals["max_sda"][0] == pytest.approx(metrics.sda, abs=1e-12)
    assert ev.goals["min_glazing_area"][0] == pytest.approx(2.0)
    sol = problem.solution(x)
    checks = {(v.name, v.constraint): v for v in sol.violations}
    da_mean = metrics.da.mean()
    udi = metrics.udi[:, 1] + metrics.udi[:, 2]
    # Bounds set above what the layout reaches: each is reported with the reference's value.
    for key, want in (
        (("da", "average"), da_mean),
        (("udi", "min"), udi.min()),
        (("sda", "average"), metrics.sda),
    ):
        assert checks[key].value == pytest.approx(want, abs=1e-9)

    def loosen(it):
        return replace(it, average=it.average and 0.05, min=it.min and 0.05)

    loose = replace(design, intentions=tuple(map(loosen, intentions)))
    assert DesignProblem(loose, office).solution(x).feasible
    assert 0 < metrics.sda < 1  # the case is not trivial
    assert 0 < dim.energy_kwh < dim.full_power_kwh


def test_night_and_overcast_scenarios(office):
    night = Intention("night", grid="wp", average=1e6, scenario="night")
    design_it = Intention("design", grid="wp", average=1e6)
    over = Intention("over", grid="wp", average=1e6, scenario="overcast")
    df = Intention("df", grid="wp", quantity="df", average=100.0)
    daylight = replace(DAYLIGHT, overcast_lux=8000.0)
    design = _design((night, design_it, over, df), daylight=daylight)
    problem = DesignProblem(design, office)
    x = problem.vars.initial()
    sol = problem.solution(x)
    got = {v.name: v.value for v in sol.violations}
    sources = problem.sources_at(x)
    sky = tuple(s for s in sources if s.kind == "skylight")
    lum = tuple(s for s in sources if s.kind == "luminaire")
    grids = problem.grids
    electric = grid_light(office, grids, lum, (), daylight)
    design_day = grid_light(office, grids, sky, (), daylight)
    assert got["night"] == pytest.approx(electric.mean(), rel=1e-5)
    assert got["design"] == pytest.approx((electric + design_day).mean(), rel=1e-5)
    # A horizontal roof light sees the whole overcast sky: plane lux = horizontal lux.
    assert problem.sky.overcast == pytest.approx([1.0], abs=1e-4)
    per_lux = design_day / daylight.exterior_lux
    assert got["over"] == pytest.approx((electric + 8000.0 * per_lux).mean(), rel=1e-4)
    assert got["df"] == pytest.approx(100 * per_lux.mean(), rel=1e-4)
    units = {v.name: v.units for v in sol.violations}
    assert units["df"] == "%"


def test_night_intention_ignores_daylight_in_the_search(office):
    """A design scenario is met by daylight alone at noon; at night it is not."""
    lum = replace(LUM, flux=0.0, free=())
    day_it = Intention("desks", grid="wp", average=50.0)
    night_it = replace(day_it, scenario="night")
    for it, met in ((day_it, True), (night_it, False)):
        d = Design(
            (SKY, lum),
            (Goal("min_electric_power"),),
            (),
            (it,),
            workplanes=(Workplane("wp"),),
            daylight=DAYLIGHT,
        )
        sol = DesignProblem(d, office).solution(DesignProblem(d, office).vars.initial())
        assert sol.feasible is met


def test_scenario_vocabulary_and_project_round_trip(tmp_path):
    assert preset_intention("office", "wp").scenario == "night"
    assert Intention("a", grid="wp", quantity="df", min=2.0).scenario == "overcast"
    assert (
        Intention("a", grid="wp", quantity="sda", average=0.5, scenario="night").scenario
        == "annual"
    )
    with pytest.raises(DesignError, match="annual scenario bounds a daylight metric"):
        Intention("a", grid="wp", average=500.0, scenario="annual")
    with pytest.raises(DesignError, match="scenario must be"):
        Intention("a", grid="wp", average=500.0, scenario="dusk")
    with pytest.raises(DesignError, match="measured on a work plane"):
        Design((SKY,), (Goal("min_annual_energy"),))
    with pytest.raises(DesignError, match="daylight workplane 'x'"):
        Design((SKY,), (Goal("min_glazing_area"),), daylight=Daylight(workplane="x"))
    with pytest.raises(DesignError, match="occupancy"):
        Daylight(occupancy=(18.0, 8.0))
    from lightinv_core.project.model import Project
    from lightinv_core.project.scene import SceneSpec
    from lightinv_core.project.write import project_dict

    design = _design(
        (
            Intention("sda", grid="wp", quantity="sda", average=0.5),
            preset_intention("office", "wp"),
        ),
        goals=("min_annual_energy", "min_glazing_area"),
        daylight=replace(DAYLIGHT, weather=str(tmp_path / "w.epw"), north_deg=30.0, standby_w=5.0),
    )
    project = Project("p", SceneSpec(builtin="office", resolution=0.5), design)
    data = project_dict(project, tmp_path)
    assert data["daylight"]["weather"] == "w.epw"
    assert data["intentions"][1]["scenario"] == "night"
    back = project_from_dict(data, tmp_path)
    assert back.design == design
    assert project_from_dict(project_to_dict(project)).design == design


def test_annual_goal_search_trades_glazing_for_energy(office):
    """More glazing, less energy: the annual goal rewards skylight area."""
    design = _design(goals=("min_annual_energy",))
    problem = DesignProblem(design, office)
    small = problem.vars.initial().copy()
    big = small.copy()
    big[:4] = [0.0, 0.0, 4.0, 2.0]
    ev = problem.evaluate(np.stack([small, big]))
    assert ev.goals["min_glazing_area"][1] > ev.goals["min_glazing_area"][0]
    assert ev.goals["min_annual_energy"][1] < ev.goals["min_annual_energy"][0]


def test_annual_goals_with_luminaire_arrays_judged_exactly(office):
    arr = LuminaireArray(
        "A", "lum_east", "Downlight 2000 lm 20 W", (0.5, 0.5, 1.5, 5.5), rows=3, columns=1
    )
    design = Design(
        (SKY,),
        (Goal("min_annual_energy"),),
        arrays=(arr,),
        workplanes=(Workplane("wp"),),
        intentions=(Intention("n", grid="wp", average=1.0, scenario="night"),),
        daylight=DAYLIGHT,
    )
    problem = DesignProblem(design, office)
    from lightinv_core.light.daylight import layout_daylight
    from lightinv_core.optimize.quality import front_scales
    from lightinv_core.optimize.search import random_start

    x = random_start(problem, np.random.default_rng(5))  # arrays off the lattice's nodes
    ev = problem.evaluate(x[None])
    sol = problem.solution(x)
    exact = layout_daylight(office, design, sol.sources, sol.arrays).energy().energy_kwh
    # The solution's year comes from the arrays placed exactly; the search's from the blend.
    assert sol.objectives["min_annual_energy"] == pytest.approx(exact, rel=1e-6)
    assert ev.goals["min_annual_energy"][0] == pytest.approx(exact, rel=1e-3)
    assert 0 < exact < 60 * 8760 / 1000
    # The front's energy scale counts the arrays' watts (3 x 20 W all year and more).
    climate = replace(design, goals=(Goal("min_annual_energy"), Goal("min_glazing_area")))
    assert front_scales(climate, office)[0] >= 60 * 8760 / 1000


def test_annual_goals_and_schedules_refuse_what_cannot_be_measured(office):
    no_plane = Design((SKY, LUM), (Goal("min_electric_power"),), daylight=DAYLIGHT)
    with pytest.raises(DesignError, match="measured on a work plane"):
        DesignProblem(no_plane, office, epsilon=(("min_annual_energy", 50.0),))
    with pytest.raises(DesignError, match="holds no hour"):
        Daylight(occupancy=(8.6, 9.4))
    assert Daylight(occupancy=(8.4, 8.6)).occupancy == (8.4, 8.6)


def test_layout_daylight_agrees_with_the_problem(office):
    intentions = (Intention("df", grid="wp", quantity="df", average=99.0),)
    design = _design(intentions, goals=("min_annual_energy", "max_sda"))
    problem = DesignProblem(design, office)
    x = problem.vars.initial()
    ev = problem.evaluate(x[None])
    sol = problem.solution(x)
    from lightinv_core.light.daylight import layout_daylight

    lay = layout_daylight(office, design, sol.sources, sol.arrays)
    energy = lay.energy()
    assert energy.energy_kwh == pytest.approx(ev.goals["min_annual_energy"][0], rel=1e-5)
    assert sum(energy.monthly_kwh) == pytest.approx(energy.energy_kwh, rel=1e-9)
    assert energy.leni == pytest.approx(energy.energy_kwh / 96.0, rel=1e-6)
    df = 100 * lay.points.overcast_daylight()[:, 0].mean()
    assert sol.violations[0].value == pytest.approx(df, rel=1e-5)
    sda = (lay.points.da()[:, 0] >= 0.5).mean()
    assert sda == pytest.approx(ev.goals["max_sda"][0])
    # An hour of the year: unoccupied at night (no luminaires, no sun), lit at noon.
    year = lay.patches.year()
    night = int(np.flatnonzero(~year.occupied & (year.every[0] == 0))[0])
    assert lay.level_at(night) == 0.0
    assert np.all(lay.hour_lux(night) == 0)
    noon = int(np.flatnonzero(year.occupied)[2])
    lux = lay.hour_lux(noon)
    want = (
        lay.patches.electric[:, 0] * lay.level_at(noon)
        + year.every[0, noon] * lay.patches.sky[0, :, 0]
    )
    assert np.allclose(lux, want)
    with pytest.raises(DesignError, match="outside the year"):
        lay.hour_lux(9000)


def test_layout_checks_agree_with_the_solution_in_every_scenario(office):
    from lightinv_core.light.daylight import layout_daylight

    intentions = (
        Intention("night", grid="wp", average=1e6, scenario="night"),
        Intention("over", grid="wp", uniformity=0.99, scenario="overcast"),
        Intention("desks", group="desks", average=1e6, scenario="overcast"),
        Intention("udi", grid="wp", quantity="udi", average=0.999),
    )
    design = _design(intentions)
    problem = DesignProblem(design, office)
    x = problem.vars.initial()
    sol = problem.solution(x)
    lay = layout_daylight(office, design, sol.sources, sol.arrays)
    for v in sol.violations:
        it = next(i for i in intentions if i.name == v.name)
        chk = next(c for c in lay.checks(it) if str(c.bound) == v.constraint)
        assert float(chk.value[0]) == pytest.approx(v.value, rel=1e-4)
    assert {v.name for v in sol.violations} == {i.name for i in intentions}


def test_climate_front_trades_glazing_area_for_annual_energy(office):
    from lightinv_core.optimize.mop import CLIMATE, epsilon_constraint, front_pair
    from lightinv_core.optimize.quality import front_quality, front_scales
    from lightinv_core.optimize.termination import StopRule

    sky = replace(SKY, free=("u0", "v0", "u1", "v1"))
    design = Design(
        (sky, LUM),
        (Goal("min_annual_energy"), Goal("min_glazing_area")),
        intentions=(Intention("n", group="desks", average=150.0, scenario="night"),),
        workplanes=(Workplane("wp"),),
        daylight=DAYLIGHT,
    )
    assert front_pair(design) == CLIMATE
    front = epsilon_constraint(design, office, epsilons=[1.0, 6.0], stop=StopRule(max_evals=1500))
    assert front.objectives == ("min_annual_energy", "min_glazing_area")
    pts = sorted(
        (s.objectives["min_glazing_area"], s.objectives["min_annual_energy"])
        for s in front.candidates
    )
    assert all(s.feasible for s in front.candidates)
    assert pts[0][0] <= 1.0 * (1 + 1e-3) and pts[1][0] <= 6.0 * (1 + 1e-3)
    assert pts[1][1] < pts[0][1]  # more glazing, less energy
    q = front_quality(front.solutions, front_scales(design, office))
    assert q.objectives == ("min_annual_energy", "min_glazing_area")
    assert 0 < q.hypervolume < 1
