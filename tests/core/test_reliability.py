"""Reliability: input that used to give silent zeros or NaNs is refused or warned about
(luminaires outside the model, work planes outside their room, intention bounds out of
their quantity's range, bad fixed sources, absurd numbers, duplicate results)."""

from __future__ import annotations

import pytest

from lightinv_core import cli
from lightinv_core.errors import SceneError
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.workplane import WorkPlane, work_plane_grid
from tests.core.test_bad_input import build_problem, with_array


@pytest.fixture(scope="module")
def office():
    patches = mesh_patches(builtin_scene("office"))
    return patches, RayCaster(patches)


# --- work planes must lie inside their room ----------------------------------------------


@pytest.mark.parametrize("height", [3.0, 5.0])
def test_a_work_plane_at_or_above_the_ceiling_is_refused(office, height):
    patches, caster = office
    with pytest.raises(SceneError) as err:
        work_plane_grid(patches, caster, WorkPlane(height, 0.5, "floor", "desk"))
    msg = str(err.value)
    assert "work plane 'desk'" in msg and f"{height} m above 'floor'" in msg
    assert "spans z = 0.00 to 3.00 m" in msg


def test_a_work_plane_just_below_the_ceiling_is_kept(office):
    patches, caster = office
    assert len(work_plane_grid(patches, caster, WorkPlane(2.9, 0.5)).points) == 77


def test_a_design_work_plane_above_the_room_is_refused(tmp_path):
    def change(data):
        with_array()(data)
        data["workplanes"] = [{"name": "desks", "height": 5}]

    with pytest.raises(SceneError, match=r"work plane 'desks' 5.0 m above 'floor'.*2.50 m"):
        build_problem(tmp_path, change)


def test_cli_refuses_a_work_plane_above_the_box(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    argv = ["simulate", "cornell", "--emit", "light=100", "--workplane", "4", "--rays", "16"]
    assert cli.main(argv) == 2
    assert "is not inside its room" in capsys.readouterr().err


# --- intention bounds within their quantity's range --------------------------------------


@pytest.mark.parametrize(
    "intention, message",
    [
        ({"quantity": "da", "average": 1.5}, "average 1.5 is outside the range of da"),
        ({"quantity": "udi", "min": 2}, "min 2 is outside the range of udi"),
        ({"quantity": "df", "min": 150}, "min 150 is outside the range of df"),
        ({"max": 1e300}, "max 1e+300 is outside the range of lux"),
        ({"min": -5}, "expected a number >= 0"),
        ({"uniformity": 1.5}, "expected a number >= 0 and <= 1, got 1.5"),
    ],
)
def test_intention_bounds_out_of_their_quantitys_range_are_refused(tmp_path, intention, message):
    from lightinv_core.project import ProjectError

    def change(data):
        data["intentions"] = [{"name": "it", "group": "floor", **intention}]

    with pytest.raises(ProjectError) as err:
        build_problem(tmp_path, change)
    assert "intentions[0]" in str(err.value) and message in str(err.value)


def test_a_design_intention_out_of_range_names_it():
    from lightinv_core.design.model import DesignError, Intention

    with pytest.raises(DesignError, match=r"intention 'da': average 1.5 .* 0 to 1"):
        Intention("da", group="floor", quantity="da", average=1.5)
    assert Intention("da", group="floor", quantity="da", average=0.5).average == 0.5


# --- an objective given twice in the results ---------------------------------------------


def test_an_objective_given_twice_in_the_results_is_refused(tmp_path):
    from lightinv_core.project import ProjectError
    from tests.core.test_bad_input import duplicate_objective

    err = duplicate_objective(tmp_path)
    assert isinstance(err, ProjectError)
    assert "results.solutions[0].objectives: objective 'max_light_power' is given twice" in str(err)


# --- luminaires whose light leaves the model ---------------------------------------------


def _down(name, z, aim=(0.0, 0.0, -1.0)):
    from lightinv_core.luminaires.analytic import downlight
    from lightinv_core.transport.luminaires import PlacedLuminaire

    return PlacedLuminaire(name, (3.0, 2.0, z), downlight(2000.0, watts=20.0), aim)


def test_a_luminaire_outside_the_room_or_behind_a_surface_is_named(office):
    from lightinv_core.transport.escape import escaping_fraction, luminaire_escape_warnings

    _, caster = office
    inside, above, behind = _down("in", 2.95), _down("out", 5.0), _down("back", 3.05)
    assert escaping_fraction(inside, caster) < 0.01
    assert escaping_fraction(above, caster) > 0.99
    assert escaping_fraction(behind, caster) > 0.99  # sees the ceiling's back
    warnings = luminaire_escape_warnings([inside, above, behind], caster)
    assert len(warnings) == 2
    assert warnings[0].startswith("luminaire 'out' at (3.00, 2.00, 5.00) m: 100% of its light")
    assert "luminaire 'back'" in warnings[1]


def test_cli_warns_of_a_luminaire_outside_the_box(tmp_path, capsys, monkeypatch):
    import json

    from lightinv_core.luminaires.analytic import downlight
    from lightinv_core.luminaires.formats import write_photometry
    from tests.core.test_obj_import import BOX

    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    (tmp_path / "room.obj").write_text(BOX)
    write_photometry(downlight(2000.0, watts=20.0), tmp_path / "down.ldt")
    (tmp_path / "lums.csv").write_text(
        "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z\n"
        "UP,2,1.5,5,down.ldt,0,0,-1,1,0,0\nIN,2,1.5,2.4,down.ldt,0,0,-1,1,0,0\n"
    )
    argv = ["simulate", str(tmp_path / "room.obj"), "--resolution", "0.5", "--rays", "64"]
    argv += ["--luminaires", str(tmp_path / "lums.csv"), "--workplane", "0.8"]
    assert cli.main([*argv, "--json"]) == 0
    got = capsys.readouterr()
    warnings = json.loads(got.out)["warnings"]
    assert [w.split(" at ")[0] for w in warnings] == ["luminaire 'UP'"]
    assert "luminaire 'UP'" in got.err
    assert cli.main(argv) == 0
    assert "lightinv-cli: luminaire 'UP' at (2.00, 1.50, 5.00) m: 100%" in capsys.readouterr().err


def test_the_luminaire_schedule_notes_the_luminaires_lost_to_the_model(tmp_path):
    from lightinv_core.light.arrays import array_escape_warnings
    from lightinv_core.report.luminaires import luminaire_table

    problem = build_problem(tmp_path, with_array())
    arrays = problem.design.arrays
    assert array_escape_warnings(problem.light.patches, arrays) == []
    note = luminaire_table(arrays, ["luminaire 'A1.1' at (0, 0, 9) m: lost"]).note
    assert "Warning: luminaire 'A1.1' at (0, 0, 9) m: lost" in note


# --- every physical number in a project file has a sane range ----------------------------


@pytest.mark.parametrize(
    "path, value, message",
    [
        ("sources.0.flux_range", [0, 1e308], "sources[0].flux_range[1]: expected a number >= 0"),
        ("daylight", {"exterior_lux": 1e300}, "daylight.exterior_lux: expected a number >= 0"),
        ("daylight", {"target_lux": 1e7}, "daylight.target_lux: expected a number >= 0"),
        ("daylight", {"standby_w": 1e12}, "daylight.standby_w: expected a number >= 0"),
    ],
)
def test_absurd_numbers_in_a_project_file_are_refused(tmp_path, path, value, message):
    from lightinv_core.project import ProjectError
    from tests.core.test_bad_input import project_error, setter

    err = project_error(tmp_path, setter(path, value))
    assert isinstance(err, ProjectError) and message in str(err)
