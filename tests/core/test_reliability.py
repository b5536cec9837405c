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
