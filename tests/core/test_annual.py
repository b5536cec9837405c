"""Annual daylight: the weather file, the Perez transposition against pvlib's own, the
coefficient method against a solve per hour (the oracle), the optimiser's year
statistics against the metrics of every hour, the metrics and dimming by definition."""

from __future__ import annotations

import json

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.climate.metrics import daylight_metrics, dimming_energy
from lightinv_core.climate.transposition import (
    orientation,
    plane_illuminance,
    plane_irradiance,
    sun_and_sky,
)
from lightinv_core.climate.weather import WeatherError, read_weather
from lightinv_core.design.model import Daylight
from lightinv_core.scene.builders import room_faces
from lightinv_core.scene.model import Scene, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study.annual import grid_year
from lightinv_core.transport.annual import orientation_coefficients, orientations, panes
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.glazing import glazing_emission
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors
from lightinv_core.transport.scene_light import light_grid, light_scene
from lightinv_core.transport.workplane import WorkPlane, work_plane_grid

pvlib = pytest.importorskip("pvlib")  # the climate extra; ./dev.sh installs it


@pytest.fixture(scope="module")
def weather():
    return read_weather("builtin")


def test_the_shipped_weather_file(weather):
    assert weather.hours == 8760 and weather.latitude == pytest.approx(36.1)
    # TMY3 illuminance comes in hundreds of lux: about 110 lm/W once multiplied.
    day = weather.ghi > 100
    assert 95 < np.median(weather.gh_lux[day] / weather.ghi[day]) < 125
    occupied = weather.occupied(8, 18)
    assert 2500 < occupied.sum() < 2700  # about 261 weekdays x 10 h
    hours = np.asarray((weather.times - np.timedelta64(30, "m")).hour)[occupied]
    assert hours.min() == 8 and hours.max() == 17


@pytest.mark.parametrize(
    "normal", [(0, 0, 1), (0, -1, 0), (1, 0, 0), (0, 1, 0), (-0.5, -0.5, 0.7071)]
)
def test_transposition_is_pvlibs_perez(weather, normal):
    sky = sun_and_sky(weather)
    tilt, azimuth = orientation(np.array(normal, float), north_deg=20.0)
    beam, diffuse, ground = plane_irradiance(weather, sky, tilt, azimuth, 0.2)
    total = pvlib.irradiance.get_total_irradiance(
        tilt,
        azimuth,
        sky.zenith,
        sky.azimuth,
        weather.dni,
        weather.ghi,
        weather.dhi,
        dni_extra=sky.dni_extra,
        airmass=sky.airmass,
        albedo=0.2,
        model="perez",
    )
    ref = np.asarray(total["poa_global"], dtype=float)
    known = np.isfinite(ref)  # pvlib leaves night hours NaN: ours are at most the ground's
    assert known.sum() > 4000 and np.all(weather.ghi[known] >= 0)
    assert np.all((beam + diffuse + ground)[~known] <= 0.2 * weather.ghi[~known] + 1e-9)
    np.testing.assert_allclose((beam + diffuse + ground)[known], ref[known], atol=1e-6)
    lux = plane_illuminance(weather, sky, np.array(normal, float), 0.2, 20.0)
    assert np.all(lux >= 0) and lux.max() > 10_000


def test_orientation_follows_the_compass():
    assert orientation(np.array([0.0, 1, 0]), 0.0) == pytest.approx((90.0, 0.0))  # north
    assert orientation(np.array([1.0, 0, 0]), 0.0) == pytest.approx((90.0, 90.0))  # east
    assert orientation(np.array([0.0, 1, 0]), 90.0) == pytest.approx((90.0, 90.0))
    assert orientation(np.array([0.0, 0, 1]), 0.0)[0] == pytest.approx(0.0)


def room() -> Scene:
    """5 x 4 x 3 m: a window in the south wall and a rooflight."""
    f = room_faces(0, 0, 0, 5, 4, 3)
    south, ceiling = f.pop("south"), f.pop("ceiling")
    surfaces = [Surface(k, k, 0.5, rect=r) for k, r in f.items()]
    surfaces += [
        Surface("s1", "walls", 0.5, rect=south.sub(0, 0, 1, 0.3)),
        Surface("win", "window", 0.5, rect=south.sub(0, 0.3, 1, 0.7)),
        Surface("s2", "walls", 0.5, rect=south.sub(0, 0.7, 1, 1)),
        Surface("c1", "ceiling", 0.8, rect=ceiling.sub(0, 0, 0.4, 1)),
        Surface("sky", "rooflight", 0.8, rect=ceiling.sub(0.4, 0, 0.6, 1)),
        Surface("c2", "ceiling", 0.8, rect=ceiling.sub(0.6, 0, 1, 1)),
    ]
    return Scene("room", surfaces, resolution=0.5)


def _room_light(glazing):
    p = mesh_patches(room())
    _, lit = glazing_emission(p, glazing, 0.0, 0.2)
    caster = RayCaster(p)
    F = form_factor_matrix(p, 256, seed=1, caster=caster)
    grid = work_plane_grid(p, caster, WorkPlane(0.8, 0.5))
    R = receiver_factors(grid.points, grid.normals, caster, p.n, 256, 2)
    return lit, F, caster, grid, R


def test_coefficients_match_a_solve_per_hour(weather):
    """The named oracle: relight the room for each of 12 hours with every pane at its
    hour's exterior illuminance, against coefficients x the optimiser's year."""
    glazing = {"window": 0.7, "rooflight": 0.6}
    lit, F, caster, grid, R = _room_light(glazing)
    orients = orientations(lit, glazing)
    assert [[q.group for q in o.panes] for o in orients] == [["window"], ["rooflight"]]
    coefficients = orientation_coefficients(lit, F, caster, orients, grid, R)
    got = grid_year(Daylight(weather="builtin", north_deg=30.0), orients, coefficients)
    lux = coefficients @ got.year.every  # every hour of the file, not only the occupied
    sky = sun_and_sky(weather)
    rng = np.random.default_rng(0)
    hours = rng.choice(np.flatnonzero(weather.ghi > 0), size=12, replace=False)
    for t in hours:
        E = np.zeros(lit.n)
        for pane in panes(lit, glazing):
            outside = plane_illuminance(weather, sky, pane.outward, 0.2, 30.0)[t]
            E[pane.idx] = pane.transmittance * outside
        direct = light_grid(grid, light_scene(lit, F, caster, E, []), caster, [], 1, factors=R)
        np.testing.assert_allclose(lux[:, t], direct.lux, rtol=1e-8, atol=1e-9)


@pytest.mark.parametrize("glazing", [{"rooflight": 0.6}, {"window": 0.7, "rooflight": 0.6}])
def test_year_statistics_equal_the_metrics_of_every_hour(glazing):
    """One sky group (sorted search) and two (hour by hour): the same DA300, UDI bands
    and sDA as ``daylight_metrics`` of the (points x occupied hours) illuminance."""
    lit, F, caster, grid, R = _room_light(glazing)
    orients = orientations(lit, glazing)
    coefficients = orientation_coefficients(lit, F, caster, orients, grid, R)
    got = grid_year(Daylight(weather="builtin", north_deg=30.0), orients, coefficients)
    assert (got.year.sorted is not None) == (len(glazing) == 1)
    hourly = daylight_metrics(got.lux)
    np.testing.assert_array_equal(got.metrics.da, hourly.da)
    np.testing.assert_array_equal(got.metrics.udi, hourly.udi)
    assert got.metrics.sda == hourly.sda and 0 < got.metrics.da.mean() < 1


def test_panes_facing_one_way_make_one_orientation():
    """Two glazing groups in one wall are one orientation: its coefficients are the sum of
    each group's, so the year has one sky group (the fast, sorted statistics)."""
    glazing = {"window": 0.7, "walls": 0.5}
    lit, F, caster, grid, R = _room_light(glazing)
    (both,) = orientations(lit, glazing)
    assert [q.group for q in both.panes] == ["window", "walls"]
    np.testing.assert_allclose(both.outward, [0.0, -1.0, 0.0], atol=1e-12)
    merged = orientation_coefficients(lit, F, caster, [both], grid, R)[:, 0]
    alone = [
        orientation_coefficients(lit, F, caster, orientations(lit, {g: t}), grid, R)[:, 0]
        for g, t in glazing.items()
    ]
    np.testing.assert_allclose(merged, alone[0] + alone[1], rtol=1e-10, atol=1e-12)


def test_metrics_and_dimming_by_definition():
    lux = np.array([[50.0, 150, 400, 5000], [350, 350, 350, 2000]])
    m = daylight_metrics(lux)
    np.testing.assert_allclose(m.da, [0.5, 1.0])
    np.testing.assert_allclose(m.udi[0], [0.25, 0.25, 0.25, 0.25])
    np.testing.assert_allclose(m.udi[1], [0.0, 0.0, 1.0, 0.0])
    assert m.sda == 1.0 and m.summary()["udi_100_3000"] == pytest.approx(0.75)
    d = dimming_energy(np.array([0.0, 250.0, 600.0]), 500.0, 500.0, 100.0, 20.0, 0.1, 2.0)
    np.testing.assert_allclose(d.levels, [1.0, 0.5, 0.1])
    assert d.energy_kwh == pytest.approx((100 * 1.6 + 2 * 8760) / 1000)
    assert d.leni == pytest.approx(d.energy_kwh / 20.0)


def test_bad_weather_files(tmp_path):
    with pytest.raises(WeatherError, match="does not exist"):
        read_weather(tmp_path / "none.epw")
    (tmp_path / "x.epw").write_text("not,a,weather\nfile\n")
    with pytest.raises(WeatherError, match=r"x\.epw: an EPW file starts with a LOCATION") as info:
        read_weather(tmp_path / "x.epw")
    assert "\n" not in str(info.value)


def test_cli_annual_daylight_and_dimming(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    from lightinv_core.luminaires.analytic import downlight
    from lightinv_core.luminaires.formats import write_photometry

    write_photometry(downlight(2000.0, watts=20.0), tmp_path / "d.ldt")
    (tmp_path / "l.csv").write_text(
        "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z\n"
        + "".join(
            f"D{k},{x},{y},2.95,d.ldt,0,0,-1,1,0,0\n"
            for k, (x, y) in enumerate([(2, 2), (6, 2), (10, 2), (2, 6), (6, 6), (10, 6)])
        )
    )
    argv = ["simulate", "office", "--resolution", "0.5", "--glazing", "roof=0.7"]
    argv += ["--weather", "builtin", "--workplane", "--luminaires", str(tmp_path / "l.csv")]
    argv += ["--grid-csv", str(tmp_path / "g.csv"), "--target-lux", "300", "--json"]
    assert cli.main(argv) == 0
    a = json.loads(capsys.readouterr().out)["annual"]
    assert 2500 < a["occupied_hours"] < 2700 and 0 <= a["sda300_50"] <= 1
    assert a["udi_n"] + a["udi_s"] + a["udi_a"] + a["udi_x"] == pytest.approx(1.0)
    d = a["dimming"]
    assert d["installed_w"] == pytest.approx(120.0) and 0 < d["energy_kwh"] < d["undimmed_kwh"]
    assert d["leni_kwh_m2"] == pytest.approx(d["energy_kwh"] / 96.0)
    header = (tmp_path / "g.csv").read_text().splitlines()[0]
    assert header == "x,y,z,lux,da300,udi_n,udi_s,udi_a,udi_x,da,udi,sda,ase"
    grid = np.loadtxt(tmp_path / "g.csv", delimiter=",", skiprows=1)
    assert np.array_equal(grid[:, 4], grid[:, 9])  # DA300 by its band and by the registry
    assert np.allclose(grid[:, 10], grid[:, 6] + grid[:, 7])  # UDI 100-3000 = UDI-s + UDI-a
    assert a["metrics"]["sda"]["mean"] == pytest.approx(a["sda300_50"])
    argv = ["simulate", "office", "--glazing", "roof=0.7", "--weather", "builtin"]
    assert cli.main(argv) == 2
    assert "add --workplane" in capsys.readouterr().err
