"""EN 17037 daylight provision on the "hours" basis in a project (issue #30,
``daylight.en17037_basis``, docs/daylight.md "EN 17037's hours basis in a project"):
against ``climate.en17037.daylight_provision(..., basis="hours")`` of the hourly light
written out, for a diffusing window (the sorted-threshold path) and a clear one (hour
by hour); its shortfall on a case worked by hand; the optimiser's batch; the field."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.climate.en17037 import daylight_hours, daylight_provision
from lightinv_core.climate.weather import load_weather
from lightinv_core.design.model import Daylight, DesignError, Goal, Intention
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.daylight_year import weather_path
from lightinv_core.light.en17037_plane import FLOOR, hours_shortfall, plane_figures, score_of
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.report.en17037 import en17037_table
from tests.core.test_clear_design import TAU, clear_window, sidelit, window_design  # noqa: F401

LEVELS = ("minimum_300", "minimum_100", "medium_500", "medium_300", "high_750", "high_500")


def hours_design(light, glazing: str, **kw):
    base = window_design(light, glazing)
    return replace(base, daylight=Daylight(transmittance=TAU, en17037_basis="hours"), **kw)


def written_out(lay) -> np.ndarray:
    """(points, daylight hours) lux of the control plane, every blind open."""
    pts, span = lay.points, lay.grids.spans["wp"]
    mask = daylight_hours(load_weather(weather_path(pts.daylight)).dh_lux)
    lux = pts.coefficients(span)[:, 0, :] @ pts.year().every[:, mask]
    if pts.clear is not None:
        lux = lux + pts.clear.open_hours(span, mask)
    return lux


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
@pytest.mark.parametrize("glazing", ["diffusing", "clear"])
def test_against_the_standards_arithmetic_hour_by_hour(sidelit, glazing):  # noqa: F811
    """Each criterion's share of the daylight hours and the level equal the standard's
    arithmetic on the hours basis; the points basis of the same light differs (the two
    readings are not the same figure)."""
    lay = layout_daylight(sidelit, hours_design(sidelit, glazing))
    lux = written_out(lay)
    ref = daylight_provision(lux, basis="hours").summary()
    got = plane_figures(lay.points, lay.grids.spans["wp"])
    assert got["basis"] == "hours"
    for key in LEVELS:
        assert got[key] == pytest.approx(ref[key], abs=1e-12), key
    assert got["level"] == ref["en17037_provision"]
    points = daylight_provision(lux, basis="points").summary()
    assert any(abs(points[k] - ref[k]) > 0.01 for k in LEVELS)
    # The report says which share it is: of the hours, on the plane fraction.
    rows = {r[1]: r for r in en17037_table(lay).rows if r[0] == "wp"}
    row = rows["medium: 500 lux on 50% of the plane"]
    assert row[2:4] == (f"{100 * ref['medium_500']:.1f}%", "≥ 50%")
    assert "'hours' basis" in en17037_table(lay).note


def test_the_shortfall_on_a_case_worked_by_hand():
    """Four daylight hours, a vertical window; per hour the share of the plane reaching
    each illuminance. 300 lux over 50% of the plane in 2 of 4 hours: met. 500 lux over
    50%: 1 of 4 hours (a = (0.5 - 0.25) / 0.5 = 0.5), the 2nd best hour's share 0.45
    (b = (0.5 - 0.45) / 0.5 = 0.1): 0.01 + 0.99 x 0.3. 100 lux over 95% in 2 of 4: met;
    300 lux over 95%: no hour (a = 1), the 2nd best 0.5 (b = 0.45 / 0.95)."""
    col = lambda *v: np.array(v, float)[:, None]  # noqa: E731
    shares = {
        100.0: col(1.0, 1.0, 0.9, 0.8),
        300.0: col(0.6, 0.5, 0.4, 0.2),
        500.0: col(0.55, 0.45, 0.3, 0.1),
        750.0: col(0.2, 0.1, 0.0, 0.0),
    }
    assert hours_shortfall(shares[300.0], 0.5)[0] == 0.0
    assert hours_shortfall(shares[100.0], 0.95)[0] == 0.0
    assert hours_shortfall(shares[500.0], 0.5)[0] == pytest.approx(0.01 + 0.99 * 0.3)
    worst = 0.01 + 0.99 * (1.0 + 0.45 / 0.95) / 2
    assert hours_shortfall(shares[300.0], 0.95)[0] == pytest.approx(worst)
    assert score_of(shares, False, "hours")[0] == pytest.approx(2.0 - worst)
    assert hours_shortfall(col(0.5, 0.4999, 0.0, 0.0), 0.5)[0] > FLOOR


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_the_optimisers_batch_on_the_hours_basis(sidelit):  # noqa: F811
    """Half the window clear (fixed), half diffusing with a free filter, "at least
    high" on the hours basis: the batch's violation is (3 - score) / 3 of each layout's
    own score, which rises with the filter, and differs a little from the points
    basis's."""
    from lightinv_core.design.model import Source

    w, h = sidelit.zone_size("window")
    clear = Source("W1", "window", "window", (0.0, 0.0, w, h / 2), glazing="clear")
    glow = Source("W2", "window", "window", (0.0, h / 2, w, h), free=("filter",), filter=0.5)
    it = Intention("en", grid="wp", quantity="en17037", min=3.0)
    design = hours_design(
        sidelit, "clear", sources=(clear, glow), intentions=(it,), goals=(Goal("min_glazing_area"),)
    )
    problem = DesignProblem(design, sidelit)
    filters = np.array([[0.0], [0.5], [1.0]])
    G = problem.evaluate(filters).G[:, -1]
    scores = []
    for f in filters[:, 0]:
        layout = replace(glow, filter=float(f), free=())
        lay = layout_daylight(sidelit, replace(design, sources=(clear, layout)))
        scores.append(plane_figures(lay.points, lay.grids.spans["wp"])["score"])
    np.testing.assert_allclose(G, (3.0 - np.array(scores)) / 3.0 - 1e-3, atol=1e-9)
    assert scores[0] < scores[1] < scores[2]
    points = replace(design, daylight=replace(design.daylight, en17037_basis="points"))
    G_points = DesignProblem(points, sidelit).evaluate(filters).G[:, -1]
    # Close (the sun patches reorder the points a little; one diffusing group alone
    # would give equal scores, below) but not the same figure.
    assert np.abs(G_points - G).max() > 1e-3


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_one_diffusing_group_scores_the_same_on_both_bases(sidelit):  # noqa: F811
    """With one diffusing sky group and no clear glazing, E_p(t) = a_p E(t) ranks the
    points the same in every hour, so the k-th best point's time share is the share of
    hours in which k points reach, and the median hour's plane share is the share of
    points reaching in half the hours: the two bases' shortfalls swap their terms and
    the scores are equal, though the figures each reports differ."""
    window = clear_window(sidelit, filter=0.5)
    design = hours_design(sidelit, "diffusing", sources=(window,))
    got = {}
    for basis in ("hours", "points"):
        d = replace(design, daylight=replace(design.daylight, en17037_basis=basis))
        lay = layout_daylight(sidelit, d)
        got[basis] = plane_figures(lay.points, lay.grids.spans["wp"])
    assert got["hours"]["score"] == pytest.approx(got["points"]["score"], abs=1e-12)
    assert 2.0 < got["hours"]["score"] < 3.0
    assert any(abs(got["hours"][k] - got["points"][k]) > 0.05 for k in LEVELS)
    # The optimiser scores this case on the points basis's path: the same value.
    it = Intention("en", grid="wp", quantity="en17037", min=3.0)
    problem = DesignProblem(replace(design, intentions=(it,)), sidelit)
    g = problem.evaluate(problem.vars.initial()[None]).G[0, -1]
    assert g == pytest.approx((3.0 - got["hours"]["score"]) / 3.0 - 1e-3, abs=1e-9)


def test_the_field():
    assert Daylight().en17037_basis == "points"
    with pytest.raises(DesignError, match="en17037_basis"):
        Daylight(en17037_basis="minutes")
