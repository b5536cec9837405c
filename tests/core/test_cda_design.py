"""cDA300 in a project (issue #30): the design's light model against the definition
(``climate.sun_metrics.continuous_da``) on the hourly light written out, for a diffusing
window (the prefix-sum path), and against the forward study on a clear window."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.climate.sun_metrics import continuous_da
from lightinv_core.design.model import Intention
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.study.clear_metrics import work_plane_metrics
from tests.core.test_clear_design import (  # noqa: F401 (fixtures)
    TAU,
    clear_window,
    sidelit,
    study,
    window_design,
)


def test_a_diffusing_window_against_the_definition(sidelit):  # noqa: F811
    pts = layout_daylight(sidelit, window_design(sidelit, "diffusing")).points
    year = pts.year()
    lux = pts.coefficients()[:, 0, :] @ year.exterior
    want = continuous_da(lux)
    assert pts.cda()[:, 0] == pytest.approx(want, abs=1e-12)
    assert 0.3 < want.mean() < 1.0
    # The optimiser's batch: a free filter, the intention's average read the same way.
    design = replace(
        window_design(sidelit, "diffusing"),
        sources=(clear_window(sidelit, free=("filter",), filter=0.4),),
        intentions=(Intention("c", grid="wp", quantity="cda", average=0.99),),
    )
    problem = DesignProblem(design, sidelit)
    x = problem.vars.initial()[None]
    got = layout_daylight(sidelit, design).points.cda()[:, 0].mean()
    assert problem.evaluate(x).G[0, -1] == pytest.approx((0.99 - got) / 0.99 - 1e-3)


def test_a_clear_window_against_the_study(sidelit, study):  # noqa: F811
    want = work_plane_metrics(study.clear_year)[0]["cda300_mean"]
    pts = layout_daylight(sidelit, window_design(sidelit)).points
    got = float(pts.cda()[:, 0].mean())
    assert got == pytest.approx(want, abs=0.02)
    assert pts.cda()[:, 0] == pytest.approx(continuous_da(pts.clear_hours()), abs=1e-12)
    assert np.all(pts.quantity(Intention("c", grid="wp", quantity="cda", min=0.1)) <= 1.0)
