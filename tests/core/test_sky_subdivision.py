"""Finer skies in projects (issue #30, docs/daylight.md "Finer skies in projects;
switching with a dead band"): ``daylight.sky_subdivision`` (Reinhart MF 1, 2, 4) used by
a project's fixed clear glazing.

References: the forward study at the same subdivision (``simulate --sky-subdivision 2``,
``study.clear_year``, itself checked against Radiance) on the same room; the project at
MF:1 (the annual figures move by little, ASE, direct sun traced by direction, not at
all); solve's JSON and text; the project file's field and its refusals; the traced
light rebuilt on an edit.
"""

from __future__ import annotations

import copy
from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.cli.solve import daylight_summary
from lightinv_core.cli.solve_text import solve_text
from lightinv_core.design.model import Daylight, Intention
from lightinv_core.fields import ProjectError
from lightinv_core.light.clear_build import clear_light_key
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.project import project_from_dict, project_to_dict
from lightinv_core.study import SimulationSpec, simulate
from lightinv_core.study.clear_metrics import blinds, work_plane_metrics
from lightinv_core.transport.workplane import WorkPlane
from tests.core.test_clear_design import TAU, sidelit, window_design  # noqa: F401
from tests.core.test_project import VALID


def _mean(got, q: str) -> float:
    it = Intention("q", grid="wp", quantity=q, max=1.0)
    return float(got.points.quantity(it)[:, 0].mean())


def _design(light, mf: int):
    design = window_design(light)
    return replace(design, daylight=replace(design.daylight, sky_subdivision=mf))


@pytest.mark.slow  # the study's MF:2 year and two builds: about 17 s
def test_a_project_at_mf2_gives_the_studys_mf2_year(sidelit):  # noqa: F811
    spec = SimulationSpec(
        scene=sidelit.scene,
        glazing={"window": TAU},
        glazing_kinds={"window": "clear"},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=Daylight(transmittance=TAU),
        sky_mf=2,
    )
    year = simulate(spec).clear_year
    got = layout_daylight(sidelit, _design(sidelit, 2))
    # 577 sky patches and the ground, per source, in the project's columns.
    cols = got.points.clear.columns
    B = cols.count - 1  # one source: its block, then its closed blinds' column
    assert B > 578 and (B - 578) % 2 == 0  # sky and ground, then the sun's two halves
    want, _ = work_plane_metrics(year)
    for q, key in (("da", "da300_mean"), ("udi", "udi_100_3000"), ("sda", "sda300_50")):
        assert _mean(got, q) == pytest.approx(want[key], abs=0.02), q
    assert _mean(got, "ase") == pytest.approx(want["ase1000_250"], abs=0.02)
    # The hourly light per point over the year: the same to a few per cent.
    occ = year.occupied
    ratio = got.points.clear_hours().mean(axis=1) / year.total(blinds(year))[:, occ].mean(axis=1)
    assert np.abs(ratio - 1).mean() < 0.03

    # Against MF:1: the sky's light moves by little; the sun's direct light not at all.
    one = layout_daylight(sidelit, _design(sidelit, 1))
    assert one.points.clear.columns.count < cols.count
    for q in ("da", "udi", "sda"):
        assert _mean(one, q) == pytest.approx(_mean(got, q), abs=0.01), q
    assert _mean(one, "ase") == _mean(got, "ase")
    assert np.array_equal(one.points.clear.direct, got.points.clear.direct)
    a, b = one.points.clear_hours().mean(axis=1), got.points.clear_hours().mean(axis=1)
    assert 0 < np.abs(a / b - 1).mean() < 0.02

    # lightinv-cli solve says which sky the clear glazing was traced on.
    design = _design(sidelit, 2)
    problem = DesignProblem(design, sidelit)
    summary = daylight_summary(sidelit, design, problem.solution(problem.vars.initial()))
    assert summary["sky_patches"] == 577
    assert summary["ase1000_250"] == pytest.approx(_mean(got, "ase"))
    head = dict(project="p", status="ok", method="vns", evaluations=1, seconds=0.0)
    text = solve_text({**head, "precompute_seconds": 0.0, "daylight": summary})
    assert "(clear glazing, sky in 577 patches)" in text


def test_the_project_field():
    assert Daylight().sky_subdivision == 1
    assert Daylight(sky_subdivision=4).sky_subdivision == 4
    data = copy.deepcopy(VALID)
    data["daylight"]["sky_subdivision"] = 2
    assert project_from_dict(data).design.daylight.sky_subdivision == 2
    back = project_to_dict(project_from_dict(data))
    assert back["daylight"]["sky_subdivision"] == 2
    # The default is not written: files saved before read and write as they were.
    assert "sky_subdivision" not in project_to_dict(project_from_dict(VALID))["daylight"]
    for bad in (3, 2.0, "2", 0):
        data["daylight"]["sky_subdivision"] = bad
        with pytest.raises(ProjectError, match="sky_subdivision: expected one of 1, 2, 4"):
            project_from_dict(data)


def test_an_edit_of_the_subdivision_traces_the_glazing_again(sidelit):  # noqa: F811
    one, two = _design(sidelit, 1), _design(sidelit, 2)
    assert clear_light_key(one) != clear_light_key(two)
    # The dimming's target does not: it stays out of the key.
    three = replace(one, daylight=replace(one.daylight, target_lux=300.0))
    assert clear_light_key(three) == clear_light_key(one)
