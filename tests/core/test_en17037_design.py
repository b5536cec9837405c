"""EN 17037 daylight provision in a project (issue #30, docs/daylight.md "EN 17037 in a
project"): the design's light model against the forward study (itself checked against
Radiance) on a clear window; diffusing glazing against the standard's arithmetic hour by
hour; the score's violation measure on a case worked by hand; the optimiser's batch."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.cli.solve_text import solve_text
from lightinv_core.climate.en17037 import daylight_hours, daylight_provision
from lightinv_core.climate.weather import load_weather
from lightinv_core.design.model import DesignError, Goal, Intention, Source
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.daylight_year import weather_path
from lightinv_core.light.en17037_plane import FLOOR, plane_figures, score_of, shortfall
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.quantities import level_name, quantity_spec
from lightinv_core.report.en17037 import en17037_table, required_level
from lightinv_core.study.clear_metrics import work_plane_metrics
from tests.core.test_clear_design import (  # noqa: F401 (fixtures)
    TAU,
    clear_window,
    sidelit,
    study,
    window_design,
)

LEVELS = ("minimum_300", "minimum_100", "medium_500", "medium_300", "high_750", "high_500")


def provision(level: float, name: str = "en") -> Intention:
    return Intention(name, grid="wp", quantity="en17037", min=level)


def test_a_clear_window_gives_the_studys_provision(sidelit, study):  # noqa: F811
    """The plane fractions of every criterion and the level through the design's light
    model equal the forward study's (``study.clear_metrics``: the CLI's figures) within
    2 points; the score says the level reached."""
    want = work_plane_metrics(study.clear_year)[0]["en17037_provision"]
    lay = layout_daylight(sidelit, window_design(sidelit))
    got = plane_figures(lay.points, lay.grids.spans["wp"])
    for key in LEVELS:
        assert got[key] == pytest.approx(want[key], abs=0.02), key
    assert got["level"] == want["level"] == "medium"  # high needs 500 lux on 95%
    assert got["horizontal_openings"] is False
    assert 2.0 < got["score"] < 3.0
    assert level_name(quantity_spec("en17037"), got["score"]) == "medium"
    q, _ = lay.quantity(provision(2.0))
    assert np.all(q == got["score"])


def test_diffusing_glazing_against_the_standards_arithmetic_hour_by_hour(sidelit):  # noqa: F811
    """A diffusing window (one sky group: the sorted-hour path): the fractions and the
    level equal ``climate.en17037.daylight_provision`` of the hourly light written out
    (coefficients x the exterior illuminance of each daylight hour)."""
    lay = layout_daylight(sidelit, replace(window_design(sidelit, "diffusing")))
    pts = lay.points
    span = lay.grids.spans["wp"]
    mask = daylight_hours(load_weather(weather_path(pts.daylight)).dh_lux)
    lux = pts.coefficients(span)[:, 0, :] @ pts.year().every[:, mask]
    ref = daylight_provision(lux).summary()
    got = plane_figures(pts, span)
    for key in LEVELS:
        assert got[key] == pytest.approx(ref[key], abs=1e-12), key
    assert got["level"] == ref["en17037_provision"]


def test_the_violation_measure_on_a_case_worked_by_hand():
    """Four points of equal area, a vertical window. Minimum: 300 lux reached half the
    time by 2 of 4 points (50%, met), 100 lux by all (met). Medium, 500 lux: 1 of 4
    (a = (0.5 - 0.25) / 0.5 = 0.5), the 2nd best point 0.4 of the hours (b = 0.2):
    0.01 + 0.99 x 0.35; 300 lux over 95%: 2 of 4 (a = 0.45 / 0.95), the 4th best 0.2
    (b = 0.6): 0.01 + 0.99 (a + b) / 2, the larger. Score 2 - that."""
    col = lambda *v: np.array(v, float)[:, None]  # noqa: E731
    shares = {
        100.0: col(1.0, 1.0, 1.0, 0.9),
        300.0: col(0.8, 0.6, 0.45, 0.2),
        500.0: col(0.55, 0.4, 0.3, 0.1),
        750.0: col(0.2, 0.1, 0.0, 0.0),
    }
    assert shortfall(shares[300.0], 0.5)[0] == 0.0
    assert shortfall(shares[500.0], 0.5)[0] == pytest.approx(0.01 + 0.99 * 0.35)
    worst = 0.01 + 0.99 * (0.45 / 0.95 + 0.6) / 2
    assert shortfall(shares[300.0], 0.95)[0] == pytest.approx(worst)
    assert score_of(shares, False)[0] == pytest.approx(2.0 - worst)
    # Exactly on the boundary (2 of 4 points at exactly half the hours): met.
    assert shortfall(col(0.5, 0.5, 0.49, 0.0), 0.5)[0] == 0.0
    # One hour short at one point is short by the floor and a little more, never 0.
    got = shortfall(col(0.5, 0.4999, 0.0, 0.0), 0.5)[0]
    assert FLOOR < got < FLOOR + 0.99 * (0.25 / 0.5 + 0.0002) / 2 + 1e-9
    # A rooflight (horizontal openings): only E_T over 95%; 300 lux at all four: minimum.
    # Medium, 500 lux over 95%: 1 of 4 (a = 0.7 / 0.95), the 4th best 0.1 (b = 0.8).
    roof = {**shares, 300.0: col(0.6, 0.6, 0.6, 0.55)}
    short = 0.01 + 0.99 * (0.7 / 0.95 + 0.8) / 2
    assert score_of(roof, True)[0] == pytest.approx(2.0 - short)
    # Every level met: 3.
    full = {e: col(1.0, 1.0, 1.0, 1.0) for e in shares}
    assert score_of(full, False)[0] == 3.0


def test_the_optimisers_batch_reads_the_layouts_score(sidelit):  # noqa: F811
    """``DesignProblem.evaluate`` judges "at least level high" with the layout's score:
    the relative violation (3 - score) / 3 and a penalty; "at least medium" is met. A
    free diffusing window's filter moves the score continuously: more glass, more."""
    design = replace(window_design(sidelit), intentions=(provision(3.0),))
    lay = layout_daylight(sidelit, design)
    score = plane_figures(lay.points, lay.grids.spans["wp"])["score"]
    problem = DesignProblem(design, sidelit)
    x = problem.vars.initial()[None]
    ev = problem.evaluate(x)
    assert ev.penalty[0] > 0
    ok = replace(design, intentions=(provision(2.0),))
    assert DesignProblem(ok, sidelit).evaluate(x).penalty[0] == 0.0
    g = ev.G[0, -1]
    assert g == pytest.approx((3.0 - score) / 3.0 - 1e-3, abs=1e-9)
    # A diffusing window with a free filter: the score rises with the filter.
    free = replace(
        window_design(sidelit, "diffusing"),
        sources=(clear_window(sidelit, free=("filter",), filter=0.5),),
        intentions=(provision(3.0),),
        goals=(Goal("min_glazing_area"),),
    )
    p2 = DesignProblem(free, sidelit)
    xs = np.repeat(p2.vars.initial()[None], 5, axis=0)
    assert [v.name for v in p2.vars.vars] == ["filter"]
    xs[:, 0] = [0.05, 0.1, 0.2, 0.4, 0.8]
    g2 = p2.evaluate(xs).G[:, -1]
    assert np.all(np.diff(g2) <= 0) and g2[0] > g2[-1]
    assert len(np.unique(np.round(g2, 6))) == 5  # it moves at every step


def test_the_intention_is_a_work_planes_and_takes_min_only():
    with pytest.raises(DesignError, match="one figure of a work plane"):
        Intention("e", group="floor", quantity="en17037", min=1.0)
    with pytest.raises(DesignError, match="`min` only"):
        Intention("e", grid="wp", quantity="en17037", min=1.0, max=3.0)
    with pytest.raises(DesignError, match="outside the range"):
        Intention("e", grid="wp", quantity="en17037", min=4.0)
    it = Intention("e", grid="wp", quantity="en17037", min=2.0, scenario="night")
    assert it.scenario == "annual"


def test_clear_and_diffusing_glazing_together_hour_by_hour(sidelit):  # noqa: F811
    """Half the window clear, half diffusing: the score's shares are the standard's
    arithmetic on the two lights added hour by hour, the clear blinds open."""
    w, h = sidelit.zone_size("window")
    clear = Source("W1", "window", "window", (0.0, 0.0, w, h / 2), glazing="clear")
    glow = Source("W2", "window", "window", (0.0, h / 2, w, h))
    design = replace(window_design(sidelit), sources=(clear, glow))
    pts = layout_daylight(sidelit, design).points
    mask = daylight_hours(load_weather(weather_path(pts.daylight)).dh_lux)
    c = pts.clear
    k = c.columns.count - 1  # the closed blinds' column left out
    open_sun = c.coefficients[:, :k] @ c.columns.every[:k][:, mask]
    open_sun += c.direct[0][:, mask]
    lux = pts.sky[0, :, 0][:, None] * pts.year().every[0, mask] + open_sun
    ref = daylight_provision(lux).summary()
    got = plane_figures(pts, slice(None))
    for key in LEVELS:
        assert got[key] == pytest.approx(ref[key], abs=1e-12), key


def test_the_report_and_solve_carry_each_criterion(sidelit, tmp_path, capsys):  # noqa: F811
    """The report's EN 17037 table lists every criterion with its share, requirement and
    pass/fail and the level against the one asked; ``lightinv-cli solve --json`` carries
    the figures and its text the level."""
    design = replace(window_design(sidelit), intentions=(provision(3.0),))
    lay = layout_daylight(sidelit, design)
    table = en17037_table(lay)
    got = plane_figures(lay.points, lay.grids.spans["wp"])
    assert len(table.rows) == 7  # two criteria at each of three levels, then the level
    assert table.rows[2][1].startswith("medium: 500 lux")
    assert table.rows[2][2] == f"{100 * got['medium_500']:.1f}%"
    assert table.rows[5][-1] == "FAIL" and table.flags[5] == "fail"  # 500 lux on 95%
    assert table.rows[-1][2:] == (f"medium (score {got['score']:.2f})", "high or better", "FAIL")
    assert required_level(design, "wp") == "high"
    assert required_level(window_design(sidelit), "wp") == "minimum"
    # solve: the integrated office (a diffusing rooflight) asks the minimum level.
    d = json.loads(Path("resources/projects/office-integrated.json").read_text())
    d["intentions"] += [{"name": "EN", "grid": "wp", "quantity": "en17037", "min": 1}]
    d["goals"] = [{"kind": "min_annual_energy"}]
    d["optimizer"] = {"method": "vns", "seed": 0, "max_evals": 100, "divisors": [1]}
    d["operator"] = {"rank": 120, "rays": 128}
    path = tmp_path / "en.json"
    path.write_text(json.dumps(d))
    assert cli.main(["solve", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    p = out["daylight"]["en17037_provision"]
    assert p["level"] in ("none", "minimum", "medium", "high")
    assert p["horizontal_openings"] is True and "minimum_100" not in p
    assert "EN 17037 daylight provision on wp: " in solve_text(out)
