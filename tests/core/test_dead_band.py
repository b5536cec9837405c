"""Switching with a dead band (issue #30, docs/daylight.md "Finer skies in projects;
switching with a dead band").

References: a hand case scanned on paper hour by hour over two days (off from target x
(1 + band), on again below the target, the state held in between, each day starting
on); a plain state machine written here, one hour at a time, on random years; the
plain switching rule (band 0); the order of the hours (a dead band only ever keeps the
luminaires on longer than plain switching); the optimiser's sum against the layout's
own year on the office; the project file, the CLI and their refusals.
"""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.cli.solve import daylight_summary
from lightinv_core.cli.solve_text import solve_text
from lightinv_core.climate.control_modes import (
    control_mode,
    control_text,
    day_starts,
    mode_levels,
    switching_banded,
    switching_level,
)
from lightinv_core.design.model import ControlGroup, DesignError
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.daylight_year import level_sum
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.report.daylight import control_groups_table, daylight_section
from lightinv_core.study.control_groups import group_dimming
from tests.core.test_control_groups import _schedule
from tests.core.test_control_groups_design import _office_design, office  # noqa: F401

SWITCHING = control_mode("switching")

# Two days at the sensor, target 500 lux, band 0.2: off from 600 lux, on below 500.
DAY1 = [400, 550, 620, 580, 520, 480, 590, 650]
DAY2 = [560, 610, 505]
# By hand, hour by hour:
#  day 1: 400 on (below 500); 550 in the band: stays on; 620 off (>= 600); 580, 520 in
#         the band: stay off; 480 on; 590 in the band: stays on; 650 off.
#  day 2: starts on; 560 in the band: on; 610 off; 505 in the band: stays off.
BANDED = [1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 0]
#  plain switching (band 0): off wherever the daylight >= 500.
PLAIN = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0]


def _state_machine(day: np.ndarray, target: float, band: float, starts: np.ndarray):
    """The reference: one hour at a time, as a photocell's relay does."""
    out = np.empty(len(day))
    on = True
    for t, d in enumerate(day):
        if starts[t]:
            on = True  # the luminaires come on with the occupancy
        if d >= target * (1 + band):
            on = False
        elif d < target:
            on = True
        out[t] = 1.0 if on else 0.0
    return out


def test_hysteresis_by_hand():
    day = np.array(DAY1 + DAY2, float)
    starts = np.zeros(len(day), bool)
    starts[[0, len(DAY1)]] = True
    got = mode_levels(SWITCHING, day, 300.0, 500.0, 0.1, 0.2, starts)
    assert got.tolist() == BANDED
    assert mode_levels(SWITCHING, day, 300.0, 500.0, 0.1, 0.0, starts).tolist() == PLAIN
    # Without day starts the second day carries the first's state (off after 650).
    one_day = switching_banded(day, 300.0, 500.0, 0.1, 0.2)
    assert one_day.tolist() == [*BANDED[:8], 0, 0, 0]
    # Dimming takes no band.
    with pytest.raises(Exception, match="takes no dead band"):
        mode_levels(control_mode("dimming"), day, 300.0, 500.0, 0.1, 0.2, starts)
    assert control_text("switching", 500.0, 0.2) == "switching to 500 lux, off from 600 lux"
    assert control_text("switching", 300.0) == "switching to 300 lux"


def test_vectorised_scan_against_the_state_machine():
    rng = np.random.default_rng(7)
    T = 600
    starts = np.zeros(T, bool)
    starts[np.arange(0, T, 10)] = True  # ten occupied hours a day
    starts[rng.choice(T, 20)] = True
    day = rng.uniform(0, 1200, (5, T))
    day[:, rng.choice(T, 50)] = 500.0  # exactly at the target: on only below it
    day[:, rng.choice(T, 50)] = 650.0  # exactly at the upper edge: off
    for band in (0.0, 0.1, 0.3, 1.0):
        got = switching_banded(day, np.full((5, 1), 250.0), 500.0, 0.0, band, starts)
        want = np.stack([_state_machine(r, 500.0, band, starts) for r in day])
        assert np.array_equal(got, want), band
        # Its off hours are among plain switching's: a band keeps the luminaires on longer.
        plain = switching_level(day, 250.0, 500.0)
        assert np.all(got >= plain)
        if band == 0:
            assert np.array_equal(got, plain)
        # And it switches less often.
        assert np.abs(np.diff(got, axis=1)).sum() <= np.abs(np.diff(plain, axis=1)).sum()


def test_day_starts_from_hour_midpoints():
    pd = pytest.importorskip("pandas")
    t = pd.DatetimeIndex(["2001-01-01 08:30", "2001-01-01 09:30", "2001-01-02 08:30"])
    assert day_starts(t).tolist() == [True, False, True]


def test_the_study_groups_take_a_band():
    # group_dimming (the CLI's simulate) with the hand case's hours as the sensor's mean.
    from lightinv_core.design.model import Daylight

    day = np.array(DAY1 + DAY2, float)
    starts = np.zeros(len(day), bool)
    starts[[0, len(DAY1)]] = True
    pts = np.array([[1.0, 1.0, 0.8], [2.0, 1.0, 0.8]])
    args = (np.tile(day, (2, 1)), pts, {"g": np.array([300.0, 300.0])}, {"g": 100.0})
    groups, _ = group_dimming(
        *args, {"g": 1}, {}, Daylight(), 10.0, 8760, modes={"g": "switching"},
        bands={"g": 0.2}, starts=starts,
    )  # fmt: skip
    (g,) = groups
    assert g.dead_band == 0.2 and g.mean_level == pytest.approx(np.mean(BANDED))
    with pytest.raises(Exception, match="takes no dead band"):
        group_dimming(*args, {"g": 1}, {}, Daylight(), 10.0, 8760, bands={"g": 0.2})


def test_the_project_field():
    assert ControlGroup("g").dead_band == 0.0
    g = ControlGroup("g", mode="switching", dead_band=0.15)
    assert g.dead_band == 0.15
    with pytest.raises(DesignError, match="applies to switching"):
        ControlGroup("g", mode="dimming", dead_band=0.15)
    with pytest.raises(DesignError, match="dead_band"):
        ControlGroup("g", mode="switching", dead_band=-0.1)


def test_the_optimiser_and_the_layout_agree_with_a_band(office):  # noqa: F811
    light = office
    base = _office_design()
    group = ControlGroup("west", sensor=(0, 0, 6, 8), mode="switching", target_lux=300.0)
    designs = [
        replace(
            base,
            sources=(replace(base.sources[0], control_group="west"), *base.sources[1:]),
            control_groups=(replace(group, dead_band=band), ControlGroup("all")),
        )
        for band in (0.0, 0.5)
    ]
    plain, banded = (layout_daylight(light, d) for d in designs)
    west0, west = plain.energy().groups[0], banded.energy().groups[0]
    assert west.dead_band == 0.5 and west0.dead_band == 0.0
    # The band holds the luminaires on longer: more energy, never less.
    assert west.energy_kwh > west0.energy_kwh
    # By hand from the sensor's daylight, the hours in order, each day starting on.
    year = banded.patches.year()
    ids = banded.groups.plan.sensors[0]
    day = banded.points.sky[:, ids, 0].mean(axis=1) @ year.exterior
    ref = _state_machine(day, 300.0, 0.5, year.day_starts)
    assert west.mean_level == pytest.approx(ref.mean())
    # The optimiser's batch (hour by hour with a band) against the layout's own year.
    problem = DesignProblem(designs[1], light)
    X = np.stack([problem.vars.initial(), problem.vars.initial() * 0.5])
    got = problem.evaluate(X).goals["min_annual_energy"]
    assert got[0] == pytest.approx(banded.energy().energy_kwh, rel=1e-6)
    half = layout_daylight(light, designs[1], problem.sources_at(X[1])).energy().energy_kwh
    assert got[1] == pytest.approx(half, rel=1e-6)
    # The report's control column and solve's text say the band.
    table = control_groups_table(daylight_section(banded, []))
    assert table.rows[0][:2] == ("west", "switching to 300 lux, off from 450 lux")
    summary = daylight_summary(light, designs[1], problem.solution(X[0]))
    head = dict(project="p", status="ok", method="vns", evaluations=1, seconds=0.0)
    text = solve_text({**head, "precompute_seconds": 0.0, "daylight": summary})
    assert "LENI" in text and "; switching to 300 lux, off from 450 lux" in text
    # level_sum with a band over the same year is the scan summed.
    b = banded.points.sky[:, ids, 0].mean(axis=1)[None]
    assert level_sum(SWITCHING, year, b, np.array([300.0]), 300.0, 0.1, None, 0.5)[0] == (
        pytest.approx(ref.sum())
    )


def test_the_cli_takes_a_band(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    schedule = _schedule(tmp_path, ["south"] * 3 + ["north"] * 3)
    argv = ["simulate", "office", "--resolution", "0.5", "--glazing", "roof=0.7"]
    argv += ["--weather", "builtin", "--workplane", "--luminaires", schedule]
    argv += ["--sensor", "south=0,0,12,4", "--sensor", "north=0,4,12,8", "--json"]
    runs = {}
    for band in ("", ":0.3"):
        assert cli.main([*argv, "--group-control", f"north=switching:500{band}"]) == 0
        out = json.loads(capsys.readouterr().out)["annual"]["control_groups"]["groups"]
        runs[band] = {g["name"]: g for g in out}
    plain, banded = runs[""]["north"], runs[":0.3"]["north"]
    assert (plain["dead_band"], banded["dead_band"]) == (0.0, 0.3)
    # On longer, never shorter: more energy.
    assert banded["mean_level"] >= plain["mean_level"]
    assert banded["energy_kwh"] > plain["energy_kwh"]
    assert runs[":0.3"]["south"] == runs[""]["south"]
    text = [*argv[:-1], "--group-control", "north=switching:500:0.3"]
    assert cli.main(text) == 0
    assert "control group north (switching to 500 lux, off from 650 lux)" in (
        capsys.readouterr().out
    )
    for bad in ("north=dimming:200:0.3", "north=switching:200:-1", "north=switching:200:x"):
        with pytest.raises(SystemExit):
            cli.main([*argv, "--group-control", bad])
        err = capsys.readouterr().err
        assert "dead band" in err, bad
