"""Cooperative cancel inside the long steps (issue #30, docs/daylight.md "Opening and
cancelling without freezing (issue #30)"): the clear build reflects its first-hit light a
block of columns at a time with a progress call between blocks, and ``layout_daylight``
reports between its steps and between the luminaires of its arrays; a progress callback
that raises stops either there. On the flagship office meshed at 1 m.

Checked against the light made in one go: the blocks' reflections equal one product over
every column, and ``layout_daylight``'s electric light (its arrays placed once for the
patches and the grid points) equals the two calls it made before (``arrays_field`` on the
patches, ``grid_light`` at the points)."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import lightinv_core.light.arrays as arrays_mod
import lightinv_core.light.clear_build as clear_build
from lightinv_core.errors import CancelledError
from lightinv_core.light.arrays import arrays_field
from lightinv_core.light.clear_build import clear_light, clear_light_ready
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.grids import design_receivers, grid_light
from lightinv_core.project import load_project
from lightinv_core.study import prepare

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-flagship.json"


@pytest.fixture(scope="module")
def flagship(tmp_path_factory):
    data = json.loads(PROJECT.read_text(encoding="utf-8"))
    data["scene"]["resolution"] = 1.0
    data["operator"] = {"rank": 120, "rays": 128}
    path = tmp_path_factory.mktemp("flagship") / "flagship.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    project = load_project(path)
    return project, prepare(project)


class Stop:
    """A progress callback that records its fractions and raises CancelledError at the
    ``at``-th call whose fraction lies in (low, high)."""

    def __init__(self, low: float = 2.0, high: float = 2.0, at: int = 1):
        self.low, self.high, self.at = low, high, at
        self.seen: list[float] = []
        self.inside = 0

    def __call__(self, fraction: float) -> None:
        self.seen.append(fraction)
        if self.low < fraction < self.high:
            self.inside += 1
            if self.inside == self.at:
                raise CancelledError("stopped by the test")


def test_the_reflections_in_blocks_are_the_light_in_one_go(flagship, monkeypatch):
    _, prepared = flagship
    light = prepared.light
    rng = np.random.default_rng(3)
    H = rng.random((light.n, 300)) * 100.0
    rho = light.patches.rho.copy()
    whole = clear_build._reflected(light, rho, H)
    monkeypatch.setattr(clear_build, "reflect_columns", lambda _light: 64)
    stop = Stop()
    blocks = clear_build._reflections(light, rho, H, stop)
    assert stop.seen == pytest.approx([64 / 300, 128 / 300, 192 / 300, 256 / 300, 1.0])
    # Each column reflects alone, but the operator's products are float32 and OpenBLAS
    # 0.3.31 rounds a column differently with the columns computed beside it (2.8e-7
    # relative at most here; older builds gave the same bits): float32 rounding.
    np.testing.assert_allclose(blocks, whole, rtol=1e-6, atol=1e-6 * np.abs(whole).max())
    assert np.abs(whole).max() > 1.0  # light was reflected


def test_a_cancel_inside_the_reflections_stops_the_build_there(flagship, monkeypatch):
    project, prepared = flagship
    light, design = prepared.light, project.design
    assert clear_build.reflect_columns(light) < 1725  # this room's columns: two blocks or more
    calls = []
    reflected = clear_build._reflected
    monkeypatch.setattr(clear_build, "_reflected", lambda *a: calls.append(1) or reflected(*a))
    stop = Stop(0.22, 0.55)  # the reflections report between 0.22 and 0.55
    with pytest.raises(CancelledError):
        clear_light(light, design, stop)
    assert len(calls) == 1  # stopped after the first block, not at the step's end
    assert not clear_light_ready(light, design)  # nothing kept
    assert stop.seen == sorted(stop.seen)


def test_layout_daylight_reports_and_stops_between_luminaires(flagship):
    project, prepared = flagship
    light = prepared.light
    # Its arrays, groups and work plane, without its clear windows (no trace needed
    # here) and intentions (the observers' light is placed by other modules).
    design = replace(project.design, sources=(), intentions=())
    assert design.arrays and design.workplanes
    arrays_mod._FIELDS.clear()  # the arrays' responses traced here, not kept from before
    stop = Stop()
    ld = layout_daylight(light, design, progress=stop)
    assert stop.seen == sorted(stop.seen) and stop.seen[-1] == 1.0
    # Asked while its arrays are placed (at 0.1 until they are), not only after.
    assert stop.seen.count(0.1) >= 4
    # The light as the two calls it replaces made it, exactly.
    grids = design_receivers(light, design)
    Hp, _ = arrays_field(light.patches, light.op, design.arrays)
    field = light.field((), design.daylight).illuminance
    np.testing.assert_array_equal(ld.patches.electric[:, 0], field + Hp)
    at_points = grid_light(light, grids, (), design.arrays, design.daylight)
    np.testing.assert_array_equal(ld.points.electric[:, 0], at_points)
    assert at_points.mean() > 100.0  # lux of the arrays on the work plane

    # A cancel while its arrays are placed stops it there (kept responses are read at
    # once: none to place).
    arrays_mod._FIELDS.clear()
    stop = Stop(0.09, 0.11, at=3)
    with pytest.raises(CancelledError):
        layout_daylight(light, design, progress=stop)
    assert max(stop.seen) == 0.1
