"""Luminaire arrays as design variables, work-plane grids as intention targets.

Checked against independent references: the light of the arrays at grid points and
patches against the reference solver with the luminaires placed exactly
(``transport.scene_light``); the lattice blend against exact placement off the nodes;
the rules against hand-computed layouts; the goals against counts and watts.
"""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.design.arrays import ArrayShapes, array_violations
from lightinv_core.design.model import (
    Design,
    DesignError,
    Goal,
    Intention,
    LuminaireArray,
    Rule,
    Workplane,
)
from lightinv_core.design.variables import Variables
from lightinv_core.light.arrays import (
    array_luminaires,
    arrays_field,
    caster_for,
    form_factors,
    resolve_product,
)
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.method import RunContext
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.registry import get_method
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.optimize.termination import StopRule
from lightinv_core.project import project_from_dict, project_to_dict
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.scene_light import light_grid, light_scene
from lightinv_core.transport.workplane import grid_statistics

BATWING = "Linear batwing 4000 lm 32 W"
DOWNLIGHT = "Downlight 2000 lm 20 W"


@pytest.fixture(scope="module")
def office():
    scene = builtin_scene("office", 0.5)
    patches = mesh_patches(scene)
    op = build_operator(patches, OperatorSettings(rays=256))
    return LightModel(scene, patches, op)


def _array(name, zone, **kw):
    base = dict(product=BATWING, rect=(0.0, 0.0, 2.0, 6.0), rows=3, columns=1, rotation=90)
    return LuminaireArray(name, zone, **{**base, **kw})


def _design(arrays, intentions=None, goals=("min_electric_power",), rules=()):
    return Design(
        sources=(),
        goals=tuple(Goal(g) for g in goals),
        arrays=tuple(arrays),
        workplanes=(Workplane("wp"),),
        intentions=intentions or (Intention("office", grid="wp", average=500.0, uniformity=0.6),),
        rules=tuple(rules),
    )


# -- the model ------------------------------------------------------------------------------


def test_array_positions_spacing_and_count():
    a = LuminaireArray("A", "z", DOWNLIGHT, (1.0, 0.0, 5.0, 3.0), rows=3, columns=2)
    assert a.count == 6
    assert a.spacing == (2.0, 1.0)
    assert a.positions() == [(2.0, 0.5), (4.0, 0.5), (2.0, 1.5), (4.0, 1.5), (2.0, 2.5), (4.0, 2.5)]


@pytest.mark.parametrize(
    "kw, message",
    [
        ({"rows": 0}, "rows must be an integer >= 1, got 0"),
        ({"rows": 2.5}, "rows must be an integer >= 1, got number 2.5"),
        ({"rotation": 45}, "rotation must be 0 or 90"),
        ({"dimming": 0}, "dimming must be a number > 0 and <= 1, got 0"),
        ({"free": ("flux",)}, r"free\[0\] must be one of 'u0'"),
        ({"rows_range": (4, 2)}, "min 4 is above max 2"),
        (
            {"maintenance_factor": 0.0},
            r"maintenance_factor must be a number > 0 and <= 1, got 0 \(typically",
        ),
    ],
)
def test_bad_arrays_are_refused_with_one_line(kw, message):
    with pytest.raises(DesignError, match=message):
        LuminaireArray("A", "z", DOWNLIGHT, (0, 0, 1, 1), **kw)


def test_rules_name_the_right_things():
    a = LuminaireArray("A", "z", DOWNLIGHT, (0, 0, 1, 1))
    with pytest.raises(DesignError, match="not luminaire arrays"):
        Design(
            (), (Goal("min_luminaire_count"),), rules=(Rule("shr", ("B",), max=1.5),), arrays=(a,)
        )
    with pytest.raises(DesignError, match="are arrays: they take shr and clearance"):
        Design(
            (), (Goal("min_luminaire_count"),), rules=(Rule("area", ("A",), max=1),), arrays=(a,)
        )
    with pytest.raises(DesignError, match="no work plane 'wp'"):
        Design((), (Goal("min_luminaire_count"),), (), (Intention("i", grid="wp", average=1),))
    with pytest.raises(DesignError, match="grid takes illuminance"):
        Intention("i", grid="wp", average=1, quantity="C")


def test_whole_number_variables_round_and_stay_in_range():
    a = LuminaireArray(
        "A",
        "z",
        DOWNLIGHT,
        (0, 0, 4, 4),
        rows=2,
        columns=2,
        free=("rows", "columns", "rotation", "dimming"),
        rows_range=(1, 5),
        columns_range=(2, 3),
    )
    d = Design((), (Goal("min_luminaire_count"),), arrays=(a,))
    v = Variables(d, {"z": (4.0, 4.0)})
    np.testing.assert_allclose(v.lo, [0.501, 1.501, -0.499, 0.1])
    np.testing.assert_allclose(v.hi, [5.499, 3.499, 1.499, 1.0])
    lay = v.decode_arrays(np.array([[0.501, 3.499, 1.2, 0.5], [5.499, 1.501, -0.4, 1.0]]))
    assert lay.rows.tolist() == [[1], [5]]
    assert lay.columns.tolist() == [[3], [2]]
    assert lay.rotation.tolist() == [[90], [0]]
    assert v.arrays_at(v.initial())[0] == a


def test_rules_on_hand_made_layouts():
    # A 4 x 2 m zone, downlights 0.15 m; two columns in [0, 4] -> spacing 2 m.
    a = LuminaireArray("A", "z", DOWNLIGHT, (0, 0, 4, 2), rows=1, columns=2)
    d = Design(
        (),
        (Goal("min_luminaire_count"),),
        rules=(Rule("shr", ("A",), max=1.0), Rule("clearance", ("A",), min=0.5)),
        arrays=(a,),
    )
    v = Variables(d, {"z": (4.0, 2.0)})
    shapes = ArrayShapes(np.array([[4.0, 2.0]]), np.array([[0.15, 0.15]]), np.array([2.5]))
    G = array_violations(d, v.decode_arrays(v.initial()[None]), shapes)
    # Inside; SHR 2 / 2.5 = 0.8 <= 1; clearance: 1 - 0.075 = 0.925 m from u edges,
    # 1 - 0.075 from v edges.
    np.testing.assert_allclose(G, 0.0)
    shapes_low = ArrayShapes(shapes.size, shapes.opening, np.array([1.6]))
    G = array_violations(d, v.decode_arrays(v.initial()[None]), shapes_low)
    assert G[0, 1] == pytest.approx((2 / 1.6 - 1.0) / 1.0)
    # A rectangle whose second luminaire (u = 4.5 m) is past the zone's edge, and
    # luminaires longer than their spacing.
    over = Design(
        (),
        (Goal("min_luminaire_count"),),
        arrays=(a.__class__(**{**a.__dict__, "rect": (0, 0, 6, 2)}),),
    )
    v2 = Variables(over, {"z": (4.0, 2.0)})
    assert array_violations(over, v2.decode_arrays(v2.initial()[None]), shapes)[0, 0] > 0
    wide = ArrayShapes(shapes.size, np.array([[0.15, 2.5]]), shapes.mount_height)
    assert array_violations(over, v2.decode_arrays(v2.initial()[None]), wide)[0, 0] > 0


def test_products_resolve_from_the_catalogue_or_files(tmp_path):
    p = resolve_product(BATWING)
    assert p.watts == 32.0 and p.lumens == pytest.approx(4000.0, rel=1e-3)
    assert p.opening == (0.15, 1.2) and not p.symmetric
    assert resolve_product(DOWNLIGHT).symmetric
    with pytest.raises(DesignError, match="neither a catalogue luminaire"):
        resolve_product("Nope")
    with pytest.raises(DesignError, match="no such photometric file"):
        resolve_product(str(tmp_path / "missing.ies"))


# -- light: against the reference solver with exact luminaires ------------------------------


def test_grid_light_matches_the_reference_solver(office):
    arrays = (_array("A1", "lum_west"), _array("A2", "lum_east", dimming=0.5))
    d = _design(arrays)
    pb = DesignProblem(d, office)
    x = pb.vars.initial()
    lv = pb.level(1)
    H = pb._light(*pb.vars.decode(x[None]), lv, pb.layout_of(x[None])).H
    grid_lux = H[-len(pb.grids.points) :, 0]
    # Reference: dense radiosity on the same form factors, luminaires placed exactly.
    patches = office.patches
    caster = caster_for(patches)
    F = form_factors(patches, office.op)
    lums = [lum for _, _, ps in array_luminaires(patches, arrays) for lum in ps]
    sl = light_scene(patches, F, caster, np.zeros(patches.n), lums)
    grid = pb.grids.grids["wp"]
    ref = light_grid(grid, sl, caster, lums, rays=256, seed=3).lux * 0.8
    assert grid_statistics(grid_lux)["Em"] == pytest.approx(grid_statistics(ref)["Em"], rel=0.02)
    err = np.abs(grid_lux - ref) / ref.mean()
    assert err.max() < 0.05, err.max()
    # Every group (exact placement through the operator) within 2% of the reference; per
    # patch, 95% within 5% (the rest are shadow edges, where the operator's 4 and the
    # reference's 16 direct-light samples per patch differ).
    Hp, _ = arrays_field(patches, office.op, arrays, maintained=False)
    for g in patches.group_names:
        idx = patches.group_index(g)
        a = patches.area[idx]
        assert Hp[idx] @ a == pytest.approx(sl.H[idx] @ a, rel=0.02), g
    lit = 0.05 * sl.H.max() < sl.H
    rel = np.abs(Hp - sl.H)[lit] / sl.H[lit]
    assert np.quantile(rel, 0.95) < 0.05


def test_lattice_blend_is_close_to_exact_placement_off_the_nodes(office):
    a = _array("A1", "lum_west", rect=(0.13, 0.37, 1.91, 5.53), rows=4, rotation=0)
    d = _design((a,))
    pb = DesignProblem(d, office)
    x = pb.vars.initial()
    lv = pb.level(1)
    H = pb._light(*pb.vars.decode(x[None]), lv, pb.layout_of(x[None])).H
    q = len(pb.grids.points)
    _, exact = arrays_field(office.patches, office.op, (a,), pb.grids.points)
    blend = H[-q:, 0]
    assert np.abs(blend - exact).max() / exact.mean() < 0.02


def test_arrays_field_keeps_its_responses_across_dimming_but_not_moves(office, monkeypatch):
    """A climate or dimming edit re-reads the arrays' light without tracing it again; a
    moved array or another product is traced afresh (and equals a cold trace)."""
    import dataclasses

    import lightinv_core.light.arrays as arrays_mod

    calls = []
    real = arrays_mod.luminaire_responses
    monkeypatch.setattr(
        arrays_mod, "luminaire_responses", lambda *a, **k: calls.append(1) or real(*a, **k)
    )
    a = _array("A1", "lum_west", rect=(0.2, 0.4, 1.8, 5.6), rows=3, rotation=0)
    pts = np.array([[2.0, 2.0, 0.8], [3.0, 4.0, 0.8]])
    H1, p1 = arrays_field(office.patches, office.op, (a,), pts)
    dimmed = dataclasses.replace(a, dimming=0.5)
    H2, p2 = arrays_field(office.patches, office.op, (dimmed,), pts)
    assert len(calls) == 1  # the dimming change read the kept responses
    assert np.allclose(H2, 0.5 * H1, rtol=1e-6) and np.allclose(p2, 0.5 * p1, rtol=1e-6)
    moved = dataclasses.replace(a, rect=(0.4, 0.4, 2.0, 5.6))
    H3, _ = arrays_field(office.patches, office.op, (moved,), pts)
    other = dataclasses.replace(a, product=DOWNLIGHT)
    H4, _ = arrays_field(office.patches, office.op, (other,), pts)
    assert len(calls) == 3 and not np.allclose(H3, H1) and not np.allclose(H4, H1)
    arrays_mod._FIELDS.clear()  # cold: the kept answer is the traced one
    H5, _ = arrays_field(office.patches, office.op, (moved,), pts)
    assert len(calls) == 4 and np.array_equal(H5, H3)


# -- goals and optimisation -----------------------------------------------------------------


def test_goals_count_power_and_dimming(office):
    arrays = (_array("A1", "lum_west", dimming=0.5), _array("A2", "lum_east", rows=2))
    d = _design(arrays, goals=("min_installed_power", "min_electric_power", "min_luminaire_count"))
    pb = DesignProblem(d, office)
    ev = pb.evaluate(pb.vars.initial()[None])
    assert ev.goals["min_luminaire_count"][0] == 5
    assert ev.goals["min_installed_power"][0] == pytest.approx(5 * 32.0)
    assert ev.goals["min_electric_power"][0] == pytest.approx(3 * 32.0 * 0.5 + 2 * 32.0)


def test_an_array_optimisation_meets_en12464_on_the_grid(office):
    # EN 12464-1 "filing, copying": Em 300 lux, U0 0.4, from the two ceiling strips.
    free = ("rows", "columns", "dimming")
    kw = dict(free=free, rows_range=(1, 5), columns_range=(1, 3))
    arrays = (_array("A1", "lum_west", **kw), _array("A2", "lum_east", **kw))
    rules = (Rule("shr", ("A1", "A2"), max=2.0), Rule("clearance", ("A1", "A2"), min=0.1))
    target = (Intention("filing", grid="wp", average=300.0, uniformity=0.4),)
    goals = ("min_electric_power", "min_luminaire_count")
    d = _design(arrays, intentions=target, rules=rules, goals=goals)
    pb = DesignProblem(d, office)
    res = get_method("vns").run(pb, RunContext(OptimizerSettings(seed=1), StopRule(3000), seed=1))
    sol = res.best
    assert sol.feasible, sol.violations
    # Judged again with the luminaires placed exactly (no lattice).
    _, exact = arrays_field(office.patches, office.op, sol.arrays, pb.grids.points)
    stats = grid_statistics(exact)
    assert stats["Em"] >= 300 * 0.98 and stats["U0"] >= 0.4 * 0.98
    # The least power is bought by dimming: at full output it would be over 500 lux.
    assert sol.objectives["min_electric_power"] < sum(a.count * 32.0 for a in sol.arrays) or all(
        a.dimming == 1.0 for a in sol.arrays
    )


def test_projects_round_trip_arrays_and_work_planes(tmp_path):
    from tests.core.test_project import VALID

    p = project_from_dict(VALID)
    assert p.design.arrays[0].rotation == 90
    assert p.design.workplanes[0].name == "wp"
    assert project_to_dict(p) == VALID


# -- presets, the CLI and the report --------------------------------------------------------


def test_en12464_presets_make_grid_intentions():
    from lightinv_core.design.en12464 import REQUIREMENTS, preset_intention

    it = preset_intention("office", "wp")
    assert (it.grid, it.average, it.uniformity) == ("wp", 500.0, 0.6)
    assert len({r.key for r in REQUIREMENTS}) == len(REQUIREMENTS)
    with pytest.raises(DesignError, match="no EN 12464-1:2011 preset 'gym'; presets: corridor"):
        preset_intention("gym", "wp")


def _arrays_project(tmp_path):
    import json

    from lightinv_core.project import save_project

    here = tmp_path / "p.json"
    d = _design(
        (_array("A1", "lum_west", free=("rows", "dimming")), _array("A2", "lum_east")),
        intentions=(Intention("filing", grid="wp", average=200.0, uniformity=0.3),),
        rules=(Rule("shr", ("A1", "A2"), max=2.0),),
    )
    from lightinv_core.project import Project, SceneSpec

    p = Project("arrays", SceneSpec(builtin="office", resolution=0.5), d)
    save_project(p, here)
    data = json.loads(here.read_text())
    data["operator"]["rays"] = 256
    here.write_text(json.dumps(data))
    return here


def test_cli_solve_prints_the_arrays_and_the_work_plane(tmp_path, capsys):
    from lightinv_core.cli import main

    path = _arrays_project(tmp_path)
    out = tmp_path / "solved.json"
    assert main(["solve", str(path), "--max-evals", "2000", "-o", str(out), "--json"]) == 0
    import json

    got = json.loads(capsys.readouterr().out)
    assert got["status"] == "feasible"
    assert [a["name"] for a in got["arrays"]] == ["A1", "A2"]
    assert got["arrays"][1]["count"] == 3
    wp = got["workplanes"]["wp"]
    assert wp["Em"] >= 200 * 0.999 and wp["U0"] >= 0.3 * 0.999
    # The saved solution keeps its arrays.
    from lightinv_core.project import load_project

    sol = load_project(out).solutions[0]
    assert sol.arrays[0].rows == got["arrays"][0]["rows"]


def test_report_has_the_schedule_polar_curves_and_work_planes(tmp_path):
    from lightinv_core.cli import main
    from lightinv_core.project import load_project
    from lightinv_core.report import write_report
    from lightinv_core.study import prepare

    path = _arrays_project(tmp_path)
    solved = tmp_path / "solved.json"
    assert main(["solve", str(path), "--max-evals", "1000", "-o", str(solved)]) == 0
    project = load_project(solved)
    info = write_report(project, prepare(project), tmp_path / "r.pdf", png_dir=tmp_path / "png")
    assert {"luminaires", "workplanes"} <= set(info.sections)
    assert all(p.stat().st_size > 10_000 for p in info.png_files)


# -- the editing model (the window's state) -------------------------------------------------


def test_the_editing_model_shows_arrays_and_work_plane_values(office, tmp_path):
    from lightinv_core.editing import DocumentModel
    from lightinv_core.project import Project, SceneSpec

    d = _design((_array("A1", "lum_west"),), rules=(Rule("shr", ("A1",), max=2.0),))
    m = DocumentModel()
    m.set_project(Project("p", SceneSpec(builtin="office", resolution=0.5), d))
    m.set_operator(office.op)
    one = m.grid_stats()["wp"]
    lit = m.lighting().copy()
    assert one["Em"] > 50 and lit.max() > 100
    m.set_arrays((_array("A1", "lum_west", rows=6, rotation=0), _array("A2", "lum_east")))
    two = m.grid_stats()["wp"]
    assert two["Em"] > 1.5 * one["Em"]
    # Exactly the arrays' light placed exactly, maintained.
    grids, lux = m.shown_grids()
    _, exact = arrays_field(office.patches, office.op, m.design.arrays, grids.points)
    np.testing.assert_allclose(lux, exact, rtol=1e-6)
    # Removing an array drops the rules on it; removing the work plane its intentions.
    m.set_arrays(m.design.arrays[1:])
    assert not m.design.rules
    m.set_workplanes(())
    assert not m.design.intentions and m.grid_stats() == {}


def test_the_array_precompute_reports_progress_and_cancels(office):
    from lightinv_core.errors import CancelledError

    # A product and zone no other test uses here: not in the precompute memo.
    d = _design((_array("D", "lum_east", product=DOWNLIGHT, rotation=0),))
    seen: list[float] = []
    pb = DesignProblem(d, office, progress=seen.append, cancel=lambda: len(seen) >= 1)
    assert not seen  # nothing is computed before the first evaluation
    with pytest.raises(CancelledError):
        pb.evaluate(pb.vars.initial()[None])
    done: list[float] = []
    pb = DesignProblem(d, office, progress=done.append)
    pb.evaluate(pb.vars.initial()[None])
    assert done[-1] == pytest.approx(1.0) and done == sorted(done)
