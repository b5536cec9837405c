"""Clear glazing through ``simulate``: the overcast sky through a rooflight against an
exact quadrature, one weather hour against the year's hour, the CLI's options and
figures."""

from __future__ import annotations

import gzip
import json
import math
import shutil

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.climate.sky_luminance import cie_overcast
from lightinv_core.design.model import Daylight
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.study import SimulationSpec, simulate
from lightinv_core.transport.clear_glazing import glass_transmittance
from lightinv_core.transport.workplane import WorkPlane

from .test_daylight import black_room_with_a_rooflight


@pytest.fixture(scope="module")
def chicago(tmp_path_factory):
    path = tmp_path_factory.mktemp("weather") / "chicago.epw"
    with gzip.open("tests/data/weather/chicago.epw.gz", "rb") as src, open(path, "wb") as dst:
        shutil.copyfileobj(src, dst)
    return path


def test_the_overcast_sky_through_a_clear_rooflight_matches_quadrature():
    spec = SimulationSpec(
        black_room_with_a_rooflight(),
        glazing={"rooflight": 0.6},
        glazing_kinds={"rooflight": "clear"},
        sky="cie-overcast",
        exterior_lux=10000.0,
        workplane=WorkPlane(0.8, 0.5),
        rays=256,
    )
    res = simulate(spec)
    # Exact: the overcast luminance through the glass, on a 200 x 400 grid of the pane.
    L_z = 10000.0 * 9 / (7 * math.pi)  # E_h = 7 pi L_z / 9
    xs, ys = 2 + (np.arange(200) + 0.5) / 100, (np.arange(400) + 0.5) / 100
    X, Y = np.meshgrid(xs, ys)
    want = []
    for q in res.grid.points:
        v = np.stack([X - q[0], Y - q[1], np.full_like(X, 3 - q[2])], -1)
        r = np.linalg.norm(v, axis=-1)
        c = v[..., 2] / r
        L = L_z * (1 + 2 * c) / 3  # sin(altitude) = cos(zenith) = c here
        want.append((L * glass_transmittance(0.6, c) * c * c / r**2 * 1e-4).sum())
    want = np.array(want)
    err = res.grid_lux / want - 1
    assert np.abs(err).mean() < 0.005 and np.abs(err).max() < 0.015
    assert cie_overcast(np.array([[0, 0, 1.0]]))[0] == pytest.approx(1.0)
    # The daylight factor is the same light over 10,000 lux.
    assert res.df_grid == pytest.approx(100 * res.grid_lux / 10000.0)


def test_one_hour_of_the_year_is_the_years_hour(chicago):
    """The year's hour from the daylight coefficients (patch-constant sky, binned sun
    reflections) against that hour computed alone (the sky's luminance ray by ray, the
    sun's own position): the discretisation costs little."""
    base = dict(
        scene=builtin_scene("sidelit", 0.5),
        glazing={"window": 0.7},
        glazing_kinds={"window": "clear"},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=Daylight(weather=str(chicago)),
    )
    year = simulate(SimulationSpec(**base)).clear_year
    lux = year.total()
    # A sunny winter noon (the sun deep in the room) and an overcast-ish hour.
    sunny = int(np.argmax(np.where(year.sun_up, year.direct_sun.sum(axis=(0, 1)), 0)))
    for hour in (sunny, (sunny + 24 * 30) % 8760):
        one = simulate(SimulationSpec(**base, hour=hour))
        direct = year.direct_sun[0][:, hour]
        assert one.grid_lux.mean() == pytest.approx(lux[:, hour].mean(), rel=0.03)
        sunlit = direct > 0
        if sunlit.any():  # the beam itself is the same ray each way
            assert np.all(one.grid_lux[sunlit] >= direct[sunlit])
    assert year.direct_sun[:, :, sunny].max() > 10000


def test_cli_clear_glazing_year_and_options(tmp_path, capsys, chicago):
    argv = ["simulate", "sidelit", "--resolution", "0.5", "--glazing", "window=0.7:clear"]
    argv += ["--weather", str(chicago), "--workplane", "--grid-csv", str(tmp_path / "g.csv")]
    assert cli.main([*argv, "--json"]) == 0
    a = json.loads(capsys.readouterr().out)["annual"]
    for key in ("da300_mean", "cda300_mean", "udi_n", "udi_100_3000", "udi_x", "sda300_50"):
        assert 0 <= a[key] <= 1, key
    assert 0 < a["ase1000_250"] <= 1  # a clear south window in Chicago lets the sun in
    assert a["cda300_mean"] >= a["da300_mean"]
    assert a["udi_n"] + a["udi_100_3000"] + a["udi_x"] == pytest.approx(1.0)
    assert a["glazing_kinds"] == {"window": "clear"} and a["weekdays_only"] is True
    assert a["blinds_closed_hours"]["window"] > 0
    header = (tmp_path / "g.csv").read_text().splitlines()[0].split(",")
    assert {"da300", "cda300", "ase_hours"} <= set(header)
    # Every day of the week: 365 days x 10 h. Weekdays only: 52 weeks of five days and
    # up to four more (a typical year mixes the years of its months), 10 h each.
    assert cli.main([*argv, "--all-days", "--json"]) == 0
    every = json.loads(capsys.readouterr().out)["annual"]
    assert every["occupied_hours"] == 3650 and every["weekdays_only"] is False
    assert 2600 <= a["occupied_hours"] <= 2640 and a["occupied_hours"] % 10 == 0
    # The CIE clear sky with the sun, and its errors.
    moment = ["simulate", "sidelit", "--resolution", "0.5", "--glazing", "window=0.7:clear"]
    moment += ["--workplane", "--json", "--sky", "cie-clear", "--sun", "30,180"]
    assert cli.main(moment) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["moment_sky"].startswith("CIE clear") and out["grid"]["Emax"] > 10000
    assert cli.main(moment[:-2]) == 2
    assert "needs the sun" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        cli.main([*moment[:5], "window=0.7:frosted"])
    assert "clear" in capsys.readouterr().err


def test_clear_glazing_with_dimmed_luminaires_and_a_year_without_sun(tmp_path, capsys, chicago):
    from lightinv_core.luminaires.analytic import downlight
    from lightinv_core.luminaires.formats import write_photometry

    write_photometry(downlight(2000.0, watts=20.0), tmp_path / "d.ldt")
    rows = [(1.5, 2, "front"), (4.5, 2, "front"), (1.5, 6, "back"), (4.5, 6, "back")]
    (tmp_path / "l.csv").write_text(
        "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z,control\n"
        + "".join(f"D{k},{x},{y},2.95,d.ldt,0,0,-1,1,0,0,{g}\n" for k, (x, y, g) in enumerate(rows))
    )
    argv = ["simulate", "sidelit", "--resolution", "0.5", "--glazing", "window=0.7:clear"]
    argv += ["--workplane", "--luminaires", str(tmp_path / "l.csv"), "--json"]
    argv += ["--sensor", "front=0,0,6,4", "--sensor", "back=0,4,6,8"]
    assert cli.main([*argv, "--weather", str(chicago)]) == 0
    a = json.loads(capsys.readouterr().out)["annual"]
    d = a["dimming"]
    assert d["installed_w"] == pytest.approx(80.0) and 0 < d["energy_kwh"] < d["undimmed_kwh"]
    g = {x["name"]: x for x in a["control_groups"]["groups"]}
    # The row by the window has more daylight, so it dims deeper than the back row.
    assert g["front"]["mean_level"] < g["back"]["mean_level"]
    # A file whose direct light is all zero: no sun to trace, no crash, no ASE.
    lines = chicago.read_text().splitlines()
    dark = []
    for line in lines:
        f = line.split(",")
        if len(f) > 30 and f[0].strip().isdigit() and len(lines) - len(dark) <= 8760:
            f[14], f[17] = "0", "0"  # direct normal irradiance and illuminance
        dark.append(",".join(f))
    (tmp_path / "dark.epw").write_text("\n".join(dark) + "\n")
    assert cli.main([*argv, "--weather", str(tmp_path / "dark.epw")]) == 0
    a = json.loads(capsys.readouterr().out)["annual"]
    assert a["ase1000_250"] == 0 and a["blinds_closed_hours"]["window"] == 0
    assert a["lm83"]["hours"] == 3650
