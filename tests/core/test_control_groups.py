"""Several daylight-linked control groups, each dimmed by its own sensor region."""

from __future__ import annotations

import json

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.study.control_groups import sensor_mask

ROWS = [(2, 2), (6, 2), (10, 2), (2, 6), (6, 6), (10, 6)]


def _schedule(tmp_path, groups: list[str] | None) -> str:
    from lightinv_core.luminaires.analytic import downlight
    from lightinv_core.luminaires.formats import write_photometry

    write_photometry(downlight(2000.0, watts=20.0), tmp_path / "d.ldt")
    head = "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z" + (",control" if groups else "")
    rows = [
        f"D{k},{x},{y},2.95,d.ldt,0,0,-1,1,0,0" + (f",{groups[k]}" if groups else "")
        for k, (x, y) in enumerate(ROWS)
    ]
    path = tmp_path / f"l{len(groups or [])}.csv"
    path.write_text("\n".join([head, *rows]) + "\n")
    return str(path)


def _run(capsys, schedule: str, extra: list[str]) -> dict:
    argv = ["simulate", "office", "--resolution", "0.5", "--glazing", "roof=0.7"]
    argv += ["--weather", "builtin", "--workplane", "--luminaires", schedule]
    argv += ["--target-lux", "300", "--standby-w", "2", "--json", *extra]
    assert cli.main(argv) == 0
    payload = json.loads(capsys.readouterr().out)
    return {**payload["annual"], "grid_points": payload["grid"]["points"]}


def test_control_groups_by_sensor_region(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    one = _run(capsys, _schedule(tmp_path, None), ["--sensor", "all=-100,-100,100,100"])
    # One group reading the whole grid is the single dimming: the same energy.
    g = one["control_groups"]
    assert len(g["groups"]) == 1 and g["groups"][0]["name"] == "all"
    assert g["total"]["energy_kwh"] == pytest.approx(one["dimming"]["energy_kwh"], rel=1e-9)
    assert g["total"]["leni_kwh_m2"] == pytest.approx(one["dimming"]["leni_kwh_m2"], rel=1e-9)

    groups = ["south"] * 3 + ["north"] * 3
    two = _run(
        capsys,
        _schedule(tmp_path, groups),
        ["--sensor", "south=0,0,12,4", "--sensor", "north=0,4,12,8"],
    )
    g = two["control_groups"]
    by = {x["name"]: x for x in g["groups"]}
    assert set(by) == {"south", "north"}
    for x in by.values():
        assert x["luminaires"] == 3 and x["installed_w"] == pytest.approx(60.0)
        assert 0 < x["sensor_points"] < 100 and 0.1 <= x["mean_level"] <= 1.0
    assert by["south"]["sensor_points"] + by["north"]["sensor_points"] == two["grid_points"]
    standby = 2 * 8760 / 1000
    assert g["total"]["standby_kwh"] == pytest.approx(standby)
    assert g["total"]["energy_kwh"] == pytest.approx(
        by["south"]["energy_kwh"] + by["north"]["energy_kwh"] + standby
    )
    assert g["total"]["leni_kwh_m2"] == pytest.approx(g["total"]["energy_kwh"] / 96.0)
    assert by["south"]["leni"] + by["north"]["leni"] == pytest.approx(
        (g["total"]["energy_kwh"] - standby) / 96.0
    )
    assert {(x["mode"], x["target_lux"]) for x in by.values()} == {("dimming", 300.0)}

    # --group-control: the north row switched at its own 200 lux; the south row as before.
    sensors = ["--sensor", "south=0,0,12,4", "--sensor", "north=0,4,12,8"]
    switched = _run(
        capsys, _schedule(tmp_path, groups), [*sensors, "--group-control", "north=switching:200"]
    )
    after = {x["name"]: x for x in switched["control_groups"]["groups"]}
    assert (after["north"]["mode"], after["north"]["target_lux"]) == ("switching", 200.0)
    assert after["south"] == by["south"]
    # Switching is on full or off: its mean level is the share of hours it is on, which
    # a lower target can only cut, and it never runs below dimming's floor while on.
    assert after["north"]["mean_level"] != by["north"]["mean_level"]
    assert after["north"]["energy_kwh"] == pytest.approx(
        after["north"]["mean_level"] * 60.0 * switched["occupied_hours"] / 1000.0, rel=1e-9
    )


def test_sensor_regions_and_their_errors(tmp_path, capsys, monkeypatch):
    pts = np.array([[0.5, 0.5, 0.8], [2.0, 3.0, 0.8], [5.0, 5.0, 0.8]])
    assert sensor_mask(pts, (3, 4, 0, 0)).tolist() == [True, True, False]
    # Regions sharing an edge share no point: the upper edges are out.
    assert sensor_mask(pts, (0, 0, 2, 3)).tolist() == [True, False, False]
    assert sensor_mask(pts, None).all()
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    schedule = _schedule(tmp_path, ["a"] * 6)
    argv = ["simulate", "office", "--resolution", "0.5", "--glazing", "roof=0.7"]
    argv += ["--weather", "builtin", "--workplane", "--luminaires", schedule]
    assert cli.main([*argv, "--sensor", "b=0,0,1,1"]) == 2
    assert "no luminaire belongs to" in capsys.readouterr().err
    assert cli.main([*argv, "--sensor", "a=50,50,60,60"]) == 2
    assert "holds no work-plane point" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        cli.main([*argv, "--sensor", "a=0,0,0,1"])
    assert "non-zero size" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        cli.main([*argv, "--group-control", "a=blinking"])
    assert "MODE one of dimming, switching" in capsys.readouterr().err
    assert cli.main([*argv, "--group-control", "b=switching"]) == 2
    assert "no luminaire belongs to" in capsys.readouterr().err
