"""Annual daylight metrics are quantities with an ``HourBand``: the light model's fast
evaluation from sky-group coefficients (``ScenarioLight.band``) equals the hour-by-hour
definition (``HourBand.of_hours``) for the built-in metrics (DA300, UDI 100-3000,
sDA300/50%) and for bands a new metric could name, with one and two sky groups."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.design.model import Daylight
from lightinv_core.light.daylight import ScenarioLight
from lightinv_core.light.daylight_year import SkyGroups
from lightinv_core.quantities import HourBand, annual_metrics, quantity_spec
from tests.core.test_scenarios import _year


def _light(groups: int, seed: int = 5):
    rng = np.random.default_rng(seed)
    E = rng.gamma(1.5, 9000.0, size=(groups, 500))
    sky = rng.uniform(0, 0.08, size=(groups, 30, 4))
    sky[:, 0, 0] = 0.0  # a point no glazing reaches
    zones = tuple((f"z{g}",) for g in range(groups))
    sg = SkyGroups(
        zones, np.eye(3)[:groups], tuple(np.array([g]) for g in range(groups)), np.ones(groups)
    )
    light = ScenarioLight(Daylight(), sg, np.zeros((30, 4)), sky, [_year(E)])
    hourly = np.einsum("grm,gt->rmt", sky, E)  # daylight per point, layout and hour
    return light, hourly


BANDS = [
    HourBand(300.0),
    HourBand(100.0, 3000.0),
    HourBand(300.0, point_share=0.5),
    HourBand(1000.0, point_share=0.1),
    HourBand(50.0, 2000.0, point_share=0.25),
]


@pytest.mark.parametrize("groups", [1, 2])
@pytest.mark.parametrize("band", BANDS, ids=str)
def test_the_fast_band_equals_the_hourly_definition(groups, band):
    light, hourly = _light(groups)
    got = light.band(band)
    want = np.stack([band.of_hours(hourly[:, m]) for m in range(hourly.shape[1])], axis=1)
    assert got.shape == want.shape
    assert np.allclose(got, want, rtol=0, atol=1e-12)
    assert 0 < want.mean() < 1  # each case separates points


def test_the_built_in_annual_metrics_and_their_shortcuts():
    names = [str(q.name) for q in annual_metrics()]
    assert names == ["da", "udi", "sda", "ase"]
    light, hourly = _light(1)
    assert np.array_equal(light.da(), light.band(quantity_spec("da").hours))
    assert np.array_equal(light.udi(), light.band(quantity_spec("udi").hours))
    assert light.sda_mark().dtype == bool
    da = np.stack([HourBand(300.0).of_hours(hourly[:, m]) for m in range(4)], axis=1)
    assert np.array_equal(light.sda_mark(), da >= 0.5)
