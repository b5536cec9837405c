"""Daylight-linked control groups in a project (issue #30 item 5, docs/daylight.md
"Control groups in a project").

References: a hand case (two groups, one sensor in the dark all year, one in daylight
above the target half the hours) counted by hand; the forward study
(``study.simulate`` with the same luminaires, groups and sensors, itself the
``lightinv-cli simulate --sensor`` path) on a side-lit room; the one-group path of
before (a design without groups keeps it; declaring the default group over the whole
plane gives the same energy); the optimiser's goal against the layout's own year. The
window's clicks are in tests/app/test_control_groups_gui.py.
"""

from __future__ import annotations

import copy
from dataclasses import replace

import numpy as np
import pytest

from lightinv_core.cli.solve import daylight_summary
from lightinv_core.cli.solve_text import solve_text
from lightinv_core.design.model import (
    ControlGroup,
    Daylight,
    Design,
    DesignError,
    Goal,
    LuminaireArray,
    Source,
    Workplane,
)
from lightinv_core.fields import ProjectError
from lightinv_core.light.arrays import array_luminaires
from lightinv_core.light.control_groups import (
    ControlPlan,
    GroupLight,
    control_plan,
    group_energies,
    group_levels,
)
from lightinv_core.light.daylight import ScenarioLight, layout_daylight
from lightinv_core.light.daylight_year import DaylightYear, SkyGroups
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.project import project_from_dict, project_to_dict
from lightinv_core.project.scene import SceneSpec
from lightinv_core.report.daylight import control_groups_table, daylight_section
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import SimulationSpec, simulate
from lightinv_core.transport.workplane import WorkPlane
from tests.core.test_project import VALID

PRODUCT = "Downlight 2000 lm 20 W"


# -- the project file -------------------------------------------------------------------


def test_groups_round_trip_and_bad_ones_are_refused():
    data = copy.deepcopy(VALID)
    p = project_from_dict(copy.deepcopy(data))
    groups = {g.name: g for g in p.design.control_groups}
    assert groups["window row"].sensor == (0.0, 0.0, 2.0, 2.0)
    assert groups["window row"].min_level == 0.2 and groups["inner"].workplane == "wp"
    assert p.design.source("L2").control_group == "window row"
    assert p.design.source("L1").control_group == "all"  # the default, not written
    assert "control_group" not in project_to_dict(p)["sources"][3]
    assert project_to_dict(p) == data
    cases = [
        ("sources", 4, "control_group", "nowhere", "no control group 'nowhere'"),
        ("sources", 0, "control_group", "inner", "only luminaires have this"),
        ("control_groups", 0, "sensor", [1, 1, 1, 3], "has no area"),
        ("control_groups", 1, "workplane", "high", "no work plane 'high'"),
        ("control_groups", 1, "name", "window row", "already used"),
        ("control_groups", 0, "min_level", 1.5, "expected a number >= 0 and <= 1"),
    ]
    for key, i, field, value, message in cases:
        bad = copy.deepcopy(data)
        bad[key][i][field] = value
        with pytest.raises(ProjectError, match=message):
            project_from_dict(bad)
    with pytest.raises(DesignError, match="has no area"):
        ControlGroup("g", sensor=(0, 0, 0, 1))


# -- a hand case ------------------------------------------------------------------------


def test_two_groups_one_dark_one_bright_by_hand():
    # 100 occupied hours of a 8,760-hour year: exterior 0 lux in the first 50, 10,000 in
    # the others. Points 0-1 see no daylight ("dark"), 2-3 see 10% of the exterior.
    T, q = 100, 4
    E = np.r_[np.zeros(50), np.full(50, 10000.0)][None]
    every = np.zeros((1, 8760))
    months = np.repeat(np.arange(1, 11), 10).astype(np.int8)
    mask = np.zeros(8760, bool)
    mask[:T] = True
    pd = pytest.importorskip("pandas")  # the climate extra's: weather times are pandas'
    times = pd.date_range("2001-01-01 01:00", periods=8760, freq="h")
    year = DaylightYear("hand", "", times, every, mask, E, months, None, None)
    d = Daylight(target_lux=500.0, min_level=0.1, standby_w=5.0)
    sky = np.array([0.0, 0.0, 0.1, 0.1])[None, :, None]
    points = ScenarioLight(
        d,
        SkyGroups((("s",),), np.zeros((1, 3)), (np.zeros(0),), np.ones(1)),
        np.zeros((q, 1)),
        sky,
        [year],
    )
    plan = ControlPlan(
        ("dark", "bright"),
        (np.array([0, 1]), np.array([2, 3])),
        (0.1, 0.3),
        (np.array([0]), np.array([1])),
        (np.zeros(0, int), np.zeros(0, int)),
    )
    # Each group's own light on its sensor at full output: 400 and 250 lux.
    own = np.array([[400.0, 400.0, 80.0, 80.0], [20.0, 20.0, 250.0, 250.0]])
    lit = GroupLight(plan, own, np.zeros((2, 1)), np.array([120.0, 60.0]), np.array([3, 2]))
    levels = group_levels(points, year, lit, d.target_lux)
    # Dark: (500 - 0) / 400 > 1, so full output every hour. Bright: full output while
    # dark (500 / 250 > 1), then (500 - 1000) / 250 < 0.3: its own floor, 0.3.
    assert np.array_equal(levels[0], np.ones(T))
    assert np.array_equal(levels[1], np.r_[np.ones(50), np.full(50, 0.3)])
    dark, bright = group_energies(levels, year, lit, floor_m2=50.0)
    assert dark.energy_kwh == pytest.approx(120.0 * 100 / 1000)  # 12 kWh
    assert bright.energy_kwh == pytest.approx(60.0 * (50 + 50 * 0.3) / 1000)  # 3.9 kWh
    assert (dark.mean_level, bright.mean_level) == (1.0, pytest.approx(0.65))
    assert bright.leni == pytest.approx(3.9 / 50.0) and bright.electric_lux == 250.0
    assert sum(bright.monthly_kwh) == pytest.approx(3.9)
    assert bright.monthly_kwh[9] == pytest.approx(60.0 * 10 * 0.3 / 1000)  # October


# -- against the forward study ---------------------------------------------------------


@pytest.fixture(scope="module")
def sidelit():
    # The side-lit room with a luminaire zone over its whole ceiling; the window's
    # patches black (the study's glazing is black inside; a design's diffusing window
    # keeps its surface's reflectance for the luminaires' light, docs/daylight.md).
    scene = SceneSpec(
        builtin="sidelit",
        resolution=1.0,
        reflectances=(("window", 0.0),),
        zones=(ZoneEdit("lums", "luminaire", "ceiling", (0, 0, 6, 8)),),
    ).load()
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=512)))


def _sidelit_design(light) -> Design:
    win = Source("W1", "window", "window", (0, 0, *light.zone_size("window")))
    front = LuminaireArray(
        "front", "lums", PRODUCT, (0, 6, 6, 8), columns=3, maintenance_factor=1.0,
        control_group="window row",
    )  # fmt: skip
    back = LuminaireArray(
        "back", "lums", PRODUCT, (0, 0, 6, 6), rows=3, columns=3, maintenance_factor=1.0
    )
    return Design(
        (win,),
        (Goal("min_annual_energy"),),
        daylight=Daylight(transmittance=0.7, standby_w=3.0),
        arrays=(front, back),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        control_groups=(
            ControlGroup("window row", sensor=(0, 0, 6, 2.5)),
            ControlGroup("all", sensor=(0, 2.5, 6, 8)),
        ),
    )


def test_each_group_as_the_study_counts_it(sidelit):
    light = sidelit
    design = _sidelit_design(light)
    e = layout_daylight(light, design).energy()
    lums = []
    for a, _, placed in array_luminaires(light.patches, design.arrays):
        lums += [replace(p, control=a.control_group) for p in placed]
    spec = SimulationSpec(
        scene=light.scene,
        luminaires=tuple(lums),
        glazing={"window": 0.7},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=design.daylight,
        sensors={g.name: g.sensor for g in design.control_groups},
    )
    got = simulate(spec)
    study = {g.name: g for g in got.control_groups}
    assert {g.name for g in e.groups} == set(study) == {"window row", "all"}
    for g in e.groups:
        s = study[g.name]
        assert (g.luminaires, g.sensor_points, g.watts) == (
            s.luminaires,
            s.sensor_points,
            s.installed_w,
        )
        assert g.energy_kwh == pytest.approx(s.energy_kwh, rel=0.01)
        assert g.mean_level == pytest.approx(s.mean_level, rel=0.01)
        assert g.electric_lux == pytest.approx(s.electric_lux, rel=0.01)
    assert e.energy_kwh == pytest.approx(got.control_total["energy_kwh"], rel=0.01)
    assert e.leni == pytest.approx(got.control_total["leni_kwh_m2"], rel=0.01)
    # The window row (daylit sensor) dims deeper than the inner rows.
    by = {g.name: g for g in e.groups}
    assert by["window row"].mean_level < by["all"].mean_level


def test_the_optimiser_scores_the_groups_total(sidelit):
    light = sidelit
    design = replace(_sidelit_design(light), arrays=tuple(
        replace(a, free=("columns",), columns_range=(1, 4)) for a in _sidelit_design(light).arrays
    ))  # fmt: skip
    problem = DesignProblem(design, light)
    x = problem.vars.initial()
    sol = problem.solution(x)  # judged with the arrays placed exactly
    layout = layout_daylight(light, design, sol.sources, sol.arrays).energy()
    assert sol.objectives["min_annual_energy"] == pytest.approx(layout.energy_kwh, rel=1e-6)
    # The search's batch reads the arrays from their lattice: close, not equal.
    blended = problem.evaluate(x[None]).goals["min_annual_energy"][0]
    assert blended == pytest.approx(layout.energy_kwh, rel=0.03)
    summary = daylight_summary(light, design, sol)
    assert [g["name"] for g in summary["control_groups"]] == ["window row", "all"]
    total = sum(g["energy_kwh"] for g in summary["control_groups"])
    assert total + 3.0 * 8.76 == pytest.approx(summary["energy_kwh"])
    head = dict(project="p", status="ok", method="vns", evaluations=1, seconds=0.0)
    text = solve_text({**head, "precompute_seconds": 0.0, "daylight": summary})
    assert "control group window row: 3 luminaires" in text
    section = daylight_section(layout_daylight(light, design, sol.sources, sol.arrays), [])
    table = control_groups_table(section)
    assert [r[0] for r in table.rows] == ["window row", "all"] and table.rows[0][2] == "3"
    target = f"{design.daylight.target_lux:g}"
    assert [r[1] for r in table.rows] == [f"dimming to {target} lux"] * 2


# -- the one group of before -----------------------------------------------------------


@pytest.fixture(scope="module")
def office():
    scene = builtin_scene("office", 0.5)
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=256)))


def _office_design() -> Design:
    sky = Source("S", "skylight", "skylight", (1.0, 0.5, 3.0, 1.5))
    lum = dict(kind="luminaire", rect=(0.5, 1.5, 1.5, 4.5), flux=8000.0, free=("flux",))
    return Design(
        (Source("L1", "lum_west", **lum), Source("L2", "lum_east", **lum), sky),
        (Goal("min_annual_energy"),),
        daylight=Daylight(transmittance=0.6, standby_w=2.0),
        workplanes=(Workplane("wp"),),
    )


def test_without_groups_the_one_group_of_before(office):
    light, design = office, _office_design()
    assert control_plan(design, None) is None
    one = layout_daylight(light, design)
    assert one.groups is None and one.energy().groups == ()
    # The default group declared, over the whole plane: the same year, now as a group.
    declared = replace(design, control_groups=(ControlGroup("all"),))
    again = layout_daylight(light, declared).energy()
    assert [g.name for g in again.groups] == ["all"]
    assert again.energy_kwh == pytest.approx(one.energy().energy_kwh, rel=1e-9)
    assert again.mean_level == pytest.approx(one.energy().mean_level, rel=1e-9)
    assert np.allclose(again.monthly_kwh, one.energy().monthly_kwh, rtol=1e-9)
    x = DesignProblem(design, light).vars.initial()[None]
    before = DesignProblem(design, light).evaluate(x).goals["min_annual_energy"]
    after = DesignProblem(declared, light).evaluate(x).goals["min_annual_energy"]
    assert after == pytest.approx(before, rel=1e-6)


def test_two_groups_in_the_optimiser_and_the_hour(office):
    light = office
    base = _office_design()
    design = replace(
        base,
        sources=(replace(base.sources[0], control_group="west"), *base.sources[1:]),
        control_groups=(ControlGroup("west", sensor=(0, 0, 6, 8), min_level=0.2),),
    )
    ld = layout_daylight(light, design)
    e = ld.energy()
    assert [g.name for g in e.groups] == ["west", "all"]
    assert e.energy_kwh == pytest.approx(sum(g.energy_kwh for g in e.groups) + 2.0 * 8.76)
    assert min(g.min_level for g in e.groups) == 0.1 and e.groups[0].min_level == 0.2
    problem = DesignProblem(design, light)
    X = np.stack([problem.vars.initial(), problem.vars.initial()])
    X[1, :] *= 0.5  # half the fluxes
    got = problem.evaluate(X).goals["min_annual_energy"]
    assert got[0] == pytest.approx(e.energy_kwh, rel=1e-6)
    half = layout_daylight(light, design, problem.sources_at(X[1])).energy().energy_kwh
    assert got[1] == pytest.approx(half, rel=1e-6)
    # The hour's light: each group at its own level, off when unoccupied.
    year = ld.patches.year()
    hour = int(np.flatnonzero(year.occupied)[300])
    levels = ld.group_levels_at(hour)
    assert levels.shape == (2,) and np.all((levels >= 0.1) & (levels <= 1.0))
    want = levels @ ld.groups.patches + ld.patches.hour_daylight(hour)
    assert np.allclose(ld.hour_lux(hour), want)
    night = int(np.flatnonzero(~year.occupied)[0])
    assert np.allclose(ld.hour_electric(night), 0.0)
    # A sensor on no grid point: the energy says so, the rest of the light stands.
    bad = replace(design, control_groups=(ControlGroup("west", sensor=(50, 50, 60, 60)),))
    held = layout_daylight(light, bad)
    with pytest.raises(DesignError, match="holds no point of work plane 'wp'"):
        held.energy()
    assert held.points.da(ld.grids.spans["wp"]).shape == (77, 1)


# -- editing (the window's rules, without a display) -----------------------------------


def test_editing_groups_renames_and_removes_with_their_luminaires():
    from lightinv_core.editing import DocumentModel, blank_project

    doc = DocumentModel()
    doc.set_project(blank_project("office", 0.7))
    edits = []
    doc.on_edit = lambda label, before, after: edits.append(label)
    lum = doc.add_source("lum_west")
    doc.set_workplanes((Workplane("wp"),), "add work plane wp")
    array = LuminaireArray("A1", "lum_east", PRODUCT, (0, 0, 2, 6), rows=2)
    doc.set_arrays((array,), "add array A1")
    assert doc.control_group_names() == ("all",)
    g = doc.add_control_group()
    assert g.name == "group 1" and doc.control_group_names() == ("all", "group 1")
    doc.set_luminaire_group(lum.name, "group 1")
    doc.set_luminaire_group("A1", "group 1")
    with pytest.raises(DesignError, match="no control group 'nope'"):
        doc.set_luminaire_group("A1", "nope")
    doc.update_control_group("group 1", name="window row", sensor=(0.0, 0.0, 4.0, 8.0))
    d = doc.design
    assert d.source(lum.name).control_group == d.array("A1").control_group == "window row"
    assert d.control_groups == (ControlGroup("window row", sensor=(0.0, 0.0, 4.0, 8.0)),)
    with pytest.raises(DesignError, match="'all' is used"):
        doc.update_control_group("window row", name="all")
    # With the light model, a sensor region on no grid point is refused, nothing changes.
    doc.set_operator(build_operator(doc.patches, OperatorSettings(rank=100, rays=128)))
    kept = doc.design
    with pytest.raises(DesignError, match="holds no point of work plane 'wp'"):
        doc.update_control_group("window row", sensor=(50.0, 50.0, 60.0, 60.0))
    assert doc.design is kept
    doc.remove_control_group("window row")
    d = doc.design
    assert not d.control_groups and d.array("A1").control_group == "all"
    assert d.source(lum.name).control_group == "all"
    assert edits[-4:] == [
        f"{lum.name}: control group group 1",
        "A1: control group group 1",
        "edit control group group 1",
        "remove control group window row",
    ]


@pytest.mark.slow  # a solve and a PDF report
def test_solve_and_report_a_project_with_two_groups(tmp_path, capsys):
    """``lightinv-cli solve --json`` carries each group, the saved project keeps them and
    ``lightinv-cli report`` prints their table: the integrated office with its west strip
    in a "window row" group read by the west third of the work plane."""
    import json
    import shutil
    import subprocess
    from pathlib import Path

    from lightinv_core import cli

    d = json.loads(Path("resources/projects/office-integrated.json").read_text())
    d["scene"]["resolution"] = 0.7
    d["control_groups"] = [{"name": "window row", "sensor": [0, 0, 4, 8]}]
    d["sources"][0]["control_group"] = "window row"  # L1, the west strip
    d["goals"] = [{"kind": "min_annual_energy"}]
    d["optimizer"] = {"method": "vns", "seed": 0, "max_evals": 150, "divisors": [1]}
    d["operator"] = {"rank": 120, "rays": 128}
    path, solved = tmp_path / "groups.json", tmp_path / "solved.json"
    path.write_text(json.dumps(d))
    assert cli.main(["solve", str(path), "--json", "-o", str(solved)]) == 0
    out = json.loads(capsys.readouterr().out)
    day = out["daylight"]
    groups = {g["name"]: g for g in day["control_groups"]}
    assert set(groups) == {"window row", "all"}
    assert groups["window row"]["luminaires"] == groups["all"]["luminaires"] == 1
    assert groups["window row"]["sensor_points"] < groups["all"]["sensor_points"]
    standby = d["daylight"]["standby_w"] * 8.76
    kwh = sum(g["energy_kwh"] for g in groups.values()) + standby
    assert kwh == pytest.approx(day["energy_kwh"], rel=1e-9)
    assert out["objective"] == pytest.approx(day["energy_kwh"], rel=1e-6)
    assert "control group window row: 1 luminaires" in solve_text(out)
    again = json.loads(solved.read_text())
    assert again["control_groups"] == d["control_groups"]
    assert cli.main(["report", str(solved), "-o", str(tmp_path / "r.pdf")]) == 0
    if shutil.which("pdftotext"):
        text = subprocess.run(
            ["pdftotext", str(tmp_path / "r.pdf"), "-"], capture_output=True, text=True
        ).stdout
        assert "Control groups" in text and "window row" in text
