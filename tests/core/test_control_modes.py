"""Control groups' modes (dimming, switching) and their own targets (issue #30 items 5-6,
docs/daylight.md "Control groups: switching, own targets, sensors drawn").

References: a hand case counted on paper (five daylight levels at the sensor, twenty
hours each; four groups: dimming and switching, to the daylight's 500 lux and to their
own 300 lux, with the boundary hours exactly at the targets); the three ways a year's
levels are summed (hour by hour, the sorted year of one sky group, the sorted fixed
daylight of clear glazing) against that count; the forward study's groups; the
optimiser's goal against the layout's own year on the office; the project file.
"""

from __future__ import annotations

import copy
from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.climate.control_modes import (
    ControlModeSpec,
    control_mode,
    control_mode_names,
    register_control_mode,
    unregister_control_mode,
)
from lightinv_core.design.model import ControlGroup, Daylight, DesignError
from lightinv_core.fields import ProjectError
from lightinv_core.light.control_groups import (
    ControlPlan,
    GroupLight,
    group_energies,
    group_levels,
    level_sum,
)
from lightinv_core.light.daylight import ScenarioLight, layout_daylight
from lightinv_core.light.daylight_year import DaylightYear, SkyGroups
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.project import project_from_dict, project_to_dict
from lightinv_core.study.control_groups import group_dimming
from tests.core.test_control_groups_design import _office_design, office  # noqa: F401
from tests.core.test_project import VALID

# The sensor's daylight: 0, 200, 300, 500 and 800 lux, twenty occupied hours each.
DAY = np.repeat([0.0, 200.0, 300.0, 500.0, 800.0], 20)
T = len(DAY)
FULL = 250.0  # each group's own light on its sensor at full output, lux
WATTS = np.array([100.0, 100.0, 100.0, 100.0])
# By hand, per daylight level (0, 200, 300, 500, 800 lux), 20 hours each:
#  A dimming to 500, floor 0.1: clip((500 - D) / 250) = 1, 1, 0.8, 0.1, 0.1 -> 60 level-h
#  B switching at 500: on while D < 500 (500 exactly meets it) -> 60 h
#  C switching at its own 300: on while D < 300 (300 exactly meets it) -> 40 h
#  D dimming to its own 300, floor 0.1: 1, 0.4, 0.1, 0.1, 0.1 -> 34 level-h
LEVEL_HOURS = {"A": 60.0, "B": 60.0, "C": 40.0, "D": 34.0}


def _year(exterior: np.ndarray, sort: bool) -> DaylightYear:
    pd = pytest.importorskip("pandas")  # the climate extra's: weather times are pandas'
    times = pd.date_range("2001-01-01 01:00", periods=8760, freq="h")
    mask = np.zeros(8760, bool)
    mask[:T] = True
    months = np.repeat(np.arange(1, 11), 10).astype(np.int8)
    E = np.asarray(exterior, float)[None]
    srt = np.sort(E[0]) if sort else None
    prefix = None if srt is None else np.concatenate([[0.0], np.cumsum(srt)])
    return DaylightYear("hand", "", times, np.zeros((1, 8760)), mask, E, months, srt, prefix)


def _plan() -> ControlPlan:
    ids = np.array([0, 1])
    return ControlPlan(
        ("A", "B", "C", "D"),
        (ids, ids, ids, ids),
        (0.1, 0.1, 0.1, 0.1),
        tuple(np.array([k]) for k in range(4)),
        tuple(np.zeros(0, int) for _ in range(4)),
        tuple(control_mode(m) for m in ("dimming", "switching", "switching", "dimming")),
        (500.0, 500.0, 300.0, 300.0),
    )


def test_modes_and_targets_by_hand():
    # Two sensor points seeing 10% of the exterior: 10 x DAY outside gives DAY inside.
    year = _year(10.0 * DAY, sort=False)
    d = Daylight(target_lux=500.0, min_level=0.1)
    sky = np.array([0.1, 0.1])[None, :, None]
    groups = SkyGroups((("s",),), np.zeros((1, 3)), (np.zeros(0),), np.ones(1))
    points = ScenarioLight(d, groups, np.zeros((2, 1)), sky, [year])
    lit = GroupLight(_plan(), np.full((4, 2), FULL), np.zeros((4, 1)), WATTS, np.ones(4, int))
    levels = group_levels(points, year, lit, d.target_lux)
    assert dict(zip("ABCD", levels.sum(axis=1), strict=True)) == pytest.approx(LEVEL_HOURS)
    # Switching is all or nothing, and off exactly at its target.
    assert set(np.unique(levels[1:3])) == {0.0, 1.0}
    assert levels[1, DAY == 500.0].max() == 0.0 and levels[2, DAY == 300.0].max() == 0.0
    assert levels[1, DAY == 300.0].min() == 1.0
    got = {g.name: g for g in group_energies(levels, year, lit, floor_m2=50.0)}
    for name, h in LEVEL_HOURS.items():
        assert got[name].energy_kwh == pytest.approx(100.0 * h / 1000)  # e.g. 6 kWh for A
        assert got[name].leni == pytest.approx(100.0 * h / 1000 / 50.0)
        assert got[name].mean_level == pytest.approx(h / T)
    assert (got["C"].mode, got["C"].target_lux) == ("switching", 300.0)
    assert (got["A"].mode, got["A"].target_lux) == ("dimming", 500.0)
    assert got["C"].as_dict()["mode"] == "switching"


@pytest.mark.parametrize("way", ["hourly", "sorted", "fixed"])
def test_the_year_summed_three_ways_gives_the_hand_count(way):
    plan = _plan()
    # Hours shuffled: the sorted paths must not depend on the hours' order.
    order = np.random.default_rng(0).permutation(T)
    day = DAY[order]
    year = _year(10.0 * day, sort=way == "sorted")
    b = np.array([[0.1], [0.1]])  # two candidates, the same daylight
    fixed = None
    if way == "fixed":
        b, fixed = np.zeros((2, 0)), day
    for k, name in enumerate(plan.names):
        full = np.array([FULL, 2 * FULL])
        got = level_sum(plan.modes[k], year, b, full, plan.targets[k], 0.1, fixed)
        assert got[0] == pytest.approx(LEVEL_HOURS[name], abs=1e-9)
        # Twice the electric light: dimming goes deeper, switching does not care.
        want = LEVEL_HOURS[name] if plan.modes[k].name == "switching" else None
        if want is not None:
            assert got[1] == pytest.approx(want, abs=1e-9)
        else:
            by_hour = np.clip((plan.targets[k] - day) / (2 * FULL), 0.1, 1.0).sum()
            assert got[1] == pytest.approx(by_hour, abs=1e-9)


def test_the_study_counts_the_same():
    daylight = np.tile(DAY, (3, 1))  # three points, the same daylight
    pts = np.array([[0.5, 0.5, 0.8], [1.5, 0.5, 0.8], [2.5, 0.5, 0.8]])
    names = "ABCD"
    electric = {n: np.full(3, FULL) for n in names}
    groups, total = group_dimming(
        daylight,
        pts,
        electric,
        dict.fromkeys(names, 100.0),
        dict.fromkeys(names, 1),
        {},
        Daylight(target_lux=500.0, min_level=0.1, standby_w=0.0),
        50.0,
        8760,
        modes={"B": "switching", "C": "switching"},
        targets={"C": 300.0, "D": 300.0},
    )
    got = {g.name: g for g in groups}
    for name, h in LEVEL_HOURS.items():
        assert got[name].energy_kwh == pytest.approx(100.0 * h / 1000)
    assert total["energy_kwh"] == pytest.approx(sum(LEVEL_HOURS.values()) / 10)
    assert (got["C"].mode, got["C"].target_lux, got["A"].target_lux) == ("switching", 300, 500)
    with pytest.raises(Exception, match="names control group"):
        group_dimming(
            daylight, pts, electric, dict.fromkeys(names, 100.0), dict.fromkeys(names, 1), {},
            Daylight(), 50.0, 8760, modes={"Z": "switching"},
        )  # fmt: skip


def test_the_project_file_keeps_mode_and_target():
    data = copy.deepcopy(VALID)
    data["control_groups"][0]["mode"] = "switching"
    data["control_groups"][0]["target_lux"] = 300
    p = project_from_dict(copy.deepcopy(data))
    g = p.design.control_groups[0]
    assert (g.mode, g.target_lux) == ("switching", 300.0)
    back = project_to_dict(p)["control_groups"]
    assert back[0]["mode"] == "switching" and back[0]["target_lux"] == 300
    assert "mode" not in back[1] and "target_lux" not in back[1]  # defaults not written
    for field, value, message in (
        ("mode", "switch", "mode: expected one of 'dimming', 'switching'"),
        ("target_lux", 0, "target_lux"),
        ("target_lux", -5, "target_lux"),
    ):
        bad = copy.deepcopy(data)
        bad["control_groups"][1][field] = value
        with pytest.raises(ProjectError, match=message):
            project_from_dict(bad)
    assert control_mode_names()[:2] == ("dimming", "switching")


def test_a_registered_mode_is_offered_and_used():
    # A step controller (half output between half the target and the target), from this
    # module alone: the project file takes it and the levels follow it.
    def levels(day, full, target, min_level):
        day = np.asarray(day, float)
        return np.select([day >= target, day >= target / 2], [0.0, 0.5], 1.0) * np.ones(
            np.shape(full)
        )

    def sorted_sum(s, S, b0, full, target, min_level):
        b0 = np.asarray(b0, float)
        return np.array([levels(b * s, 1.0, target, 0).sum() for b in b0])

    register_control_mode(ControlModeSpec("step", "step (three levels)", levels, sorted_sum))
    try:
        assert ControlGroup("g", mode="step").mode == "step"
        year = _year(10.0 * DAY, sort=True)
        got = level_sum(control_mode("step"), year, np.array([[0.1]]), np.array([FULL]), 500, 0)
        assert got[0] == pytest.approx(40 + 0.5 * 20)  # 0, 200 lux on; 300 half; 500, 800 off
    finally:
        unregister_control_mode("step")
    with pytest.raises(DesignError, match="mode must be one of"):
        ControlGroup("g", mode="step")


def test_the_optimiser_scores_switching_and_own_targets(office):  # noqa: F811
    light = office
    base = _office_design()
    design = replace(
        base,
        sources=(replace(base.sources[0], control_group="west"), *base.sources[1:]),
        control_groups=(
            ControlGroup("west", sensor=(0, 0, 6, 8), mode="switching", target_lux=300.0),
            ControlGroup("all", target_lux=400.0),
        ),
    )
    ld = layout_daylight(light, design)
    e = ld.energy()
    west, rest = e.groups
    assert (west.mode, west.target_lux, rest.mode, rest.target_lux) == (
        "switching", 300.0, "dimming", 400.0,
    )  # fmt: skip
    # Switching: every occupied hour at 0 or 1; its mean level the share of hours on.
    levels = ld._levels
    assert set(np.unique(levels[0])) <= {0.0, 1.0} and 0 < west.mean_level < 1
    # The optimiser's batch sums the sorted year (one sky group); the layout counts hours.
    problem = DesignProblem(design, light)
    X = np.stack([problem.vars.initial(), problem.vars.initial() * 0.5])
    got = problem.evaluate(X).goals["min_annual_energy"]
    assert got[0] == pytest.approx(e.energy_kwh, rel=1e-6)
    half = layout_daylight(light, design, problem.sources_at(X[1])).energy().energy_kwh
    assert got[1] == pytest.approx(half, rel=1e-6)
    # A lower target saves energy for the same group and mode.
    higher = replace(design, control_groups=(design.control_groups[0], ControlGroup("all")))
    assert layout_daylight(light, higher).energy().groups[1].energy_kwh > rest.energy_kwh
    # The switching group's hours on, counted by hand from its sensor's daylight.
    plan = ld.groups.plan
    ids = plan.sensors[0]
    year = ld.patches.year()
    day = ld.points.sky[:, ids, 0].mean(axis=1) @ year.exterior
    assert west.mean_level == pytest.approx(np.mean(day < 300.0))
