"""EN 17037 daylight provision and sunlight exposure (climate/en17037.py).

Provision: constructed fields exactly on the boundaries (half the points at 300 lux for
exactly half the hours), a field on which the two readings of the criteria disagree,
and a realistic field (daylight factors times the shipped TMY3's diffuse horizontal
illuminance) checked against the standard's daylight-factor method, which it must
equal because the field is proportional to one exterior illuminance.

Sunlight exposure: with the sun always seen, the time above the minimum altitude must
match the closed form cos H = (sin h - sin phi sin delta) / (cos phi cos delta) with
the declination from NOAA's solar calculator equations (Meeus), independent of
pvlib's SPA; with the sun seen only
within 45 degrees of south, the same closed form split at the hour angle where the
azimuth (tan A = sin H / (sin phi cos H - cos phi tan delta)) reaches 45 degrees."""

from __future__ import annotations

import datetime as dt
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from lightinv_core.climate.en17037 import (
    daylight_hours,
    daylight_provision,
    sun_directions,
    sunlight_exposure,
    sunlight_level,
)
from lightinv_core.errors import LightInvError


def _boundary_field() -> np.ndarray:
    """4 points, 10 hours: all at 100 lux in hours 0-4, points 0 and 1 at 300 lux."""
    lux = np.zeros((4, 10))
    lux[:, :5] = 100.0
    lux[:2, :5] = 300.0
    return lux


def test_provision_met_exactly_at_the_boundaries():
    result = daylight_provision(_boundary_field())
    assert result.level == "minimum"
    target, minimum = result.checks[0].criteria
    assert (target.lux, target.achieved, target.required) == (300.0, 0.5, 0.5)
    assert (minimum.lux, minimum.achieved, minimum.required) == (100.0, 1.0, 0.95)
    assert not result.checks[1].met  # 500 lux is never reached
    assert result.summary()["minimum_300"] == 0.5


def test_provision_fails_just_below_each_boundary():
    lux = _boundary_field()
    lux[1, 4] = 299.99  # point 1 now reaches 300 lux in 4 of 10 hours
    assert daylight_provision(lux).level == "none"
    assert daylight_provision(lux).checks[0].criteria[0].achieved == 0.25
    lux = _boundary_field()
    lux[3, 4] = 99.0  # one point of four below 100 lux half the time: 75% < 95%
    assert daylight_provision(lux).checks[0].criteria[1].achieved == 0.75
    assert daylight_provision(lux).level == "none"


def test_horizontal_openings_need_the_target_over_95_percent():
    assert daylight_provision(_boundary_field(), horizontal_openings=True).level == "none"
    lux = np.zeros((20, 6))
    lux[:19, :3] = 750.0  # 19 of 20 points (95%) at 750 lux half the time
    result = daylight_provision(lux, horizontal_openings=True)
    assert result.level == "high"
    assert all(len(c.criteria) == 1 for c in result.checks)
    lux[18, 2] = 0.0  # 18 of 20: 90%
    assert daylight_provision(lux, horizontal_openings=True).level == "none"


def test_the_two_readings_can_disagree():
    # 4 points, 3 hours: hour 0 lights points 0-1, hour 1 points 2-3, hour 2 none;
    # 100 lux everywhere always. Each hour 0 and 1 has 50% of the plane at 300 lux (2
    # hours of 3: the "hours" reading passes); no point is at 300 lux half the time.
    lux = np.full((4, 3), 100.0)
    lux[:2, 0] = 300.0
    lux[2:, 1] = 300.0
    assert daylight_provision(lux, basis="points").level == "none"
    by_hours = daylight_provision(lux, basis="hours")
    assert by_hours.level == "minimum"
    assert by_hours.checks[0].criteria[0].achieved == pytest.approx(2 / 3)


def test_provision_rejects_bad_input():
    with pytest.raises(LightInvError):
        daylight_provision(np.ones(4))
    with pytest.raises(LightInvError):
        daylight_provision(np.ones((2, 2)), basis="area")


@pytest.fixture(scope="module")
def greensboro():
    from lightinv_core.climate.weather import read_weather

    return read_weather("builtin")


def test_daylight_hours_brightest_half(greensboro):
    assert daylight_hours(np.array([5.0, 1.0, 4.0, 2.0, 3.0, 0.0])).tolist() == [
        True,
        False,
        True,
        False,
        True,
        False,
    ]
    assert daylight_hours(np.ones(4)).tolist() == [True, True, False, False]  # ties: earlier
    dh = greensboro.dh_lux
    mask = daylight_hours(dh)
    assert mask.sum() == 4380
    assert dh[mask].min() >= dh[~mask].max()
    alt = np.array([-3.0, 0.0, 0.1, 45.0])
    assert daylight_hours(None, "sun-up", alt).tolist() == [False, False, True, True]


def test_realistic_field_equals_the_daylight_factor_method(greensboro):
    dh = greensboro.dh_lux[daylight_hours(greensboro.dh_lux)]
    depth = np.linspace(0.5, 6.0, 23)
    df = np.repeat(0.06 * np.exp(-depth / 3.0), 2)  # two columns of a side-lit room
    lux = df[:, None] * dh[None, :]
    result = daylight_provision(lux)
    # A point reaches E_T in at least half of the 4380 hours iff DF x (the 2190th
    # highest exterior value) >= E_T: the DF method's D_T = E_T / E_v,d,med.
    e_med = np.sort(dh)[::-1][dh.size // 2 - 1]
    for check, (target, minimum) in zip(
        result.checks, ((300, 100), (500, 300), (750, 500)), strict=True
    ):
        assert check.criteria[0].achieved == pytest.approx(np.mean(df * e_med >= target))
        assert check.criteria[1].achieved == pytest.approx(np.mean(df * e_med >= minimum))
    assert result.level == "minimum"


def _declination(day: dt.date, longitude: float) -> float:
    """The sun's declination (radians) at local solar noon of ``day``."""
    return _declination_jd(day.toordinal() + 1721424.5 + 0.5 - longitude / 360.0)


def _declination_jd(jd: float) -> float:
    """The sun's declination (radians) at Julian day ``jd``: NOAA's solar calculator
    equations (Meeus, Astronomical Algorithms, chapter 25, low precision, ~0.01 deg)."""
    t = (jd - 2451545.0) / 36525.0
    l0 = (280.46646 + t * (36000.76983 + 0.0003032 * t)) % 360.0
    m = math.radians(357.52911 + t * (35999.05029 - 0.0001537 * t))
    c = (
        math.sin(m) * (1.914602 - t * (0.004817 + 0.000014 * t))
        + math.sin(2 * m) * (0.019993 - 0.000101 * t)
        + math.sin(3 * m) * 0.000289
    )
    omega = math.radians(125.04 - 1934.136 * t)
    lam = math.radians(l0 + c - 0.00569 - 0.00478 * math.sin(omega))
    seconds = 21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))
    eps = math.radians(23.0 + (26.0 + seconds / 60.0) / 60.0 + 0.00256 * math.cos(omega))
    return math.asin(math.sin(eps) * math.sin(lam))


def test_reference_declination_reproduces_meeus_example_25a():
    # Meeus, Astronomical Algorithms (2nd ed.), example 25.a: 1992 October 13.0 TD,
    # apparent declination -7.78507 deg.
    assert math.degrees(_declination_jd(2448908.5)) == pytest.approx(-7.78507, abs=2e-4)


def _hour_angle_above(lat: float, dec: float, h_min: float) -> float:
    """Half the time (as an hour angle, radians) the sun is above h_min."""
    phi, h = math.radians(lat), math.radians(h_min)
    c = (math.sin(h) - math.sin(phi) * math.sin(dec)) / (math.cos(phi) * math.cos(dec))
    return math.acos(max(-1.0, min(1.0, c)))


def _hour_angle_at_azimuth(lat: float, dec: float, from_south: float) -> float:
    """Hour angle at which the sun's azimuth is ``from_south`` (radians) west of south."""
    phi = math.radians(lat)

    def f(h):
        return (
            math.atan2(math.sin(h), math.sin(phi) * math.cos(h) - math.cos(phi) * math.tan(dec))
            - from_south
        )

    return brentq(f, 0.0, math.pi - 1e-9)


def _always(d):
    assert np.allclose(np.linalg.norm(d, axis=1), 1.0)
    return np.ones(len(d), dtype=bool)


SITES = [
    (48.21, 16.37, "2026-03-21", 10.0),  # Vienna
    (55.68, 12.57, "2026-02-01", 10.0),  # Copenhagen
    (41.90, 12.50, "2026-02-15", 15.0),  # Rome
    (60.17, 24.94, "2026-03-01", 0.0),  # Helsinki
]


@pytest.mark.parametrize(("lat", "lon", "date", "h_min"), SITES)
def test_sun_always_seen_matches_the_closed_form(lat, lon, date, h_min):
    result = sunlight_exposure(_always, lat, lon, date, min_altitude_deg=h_min)
    dec = _declination(dt.date.fromisoformat(date), lon)
    expected = 2 * math.degrees(_hour_angle_above(lat, dec, h_min)) / 15.0
    assert result.hours == pytest.approx(expected, abs=2 / 60)  # within 2 minutes
    assert result.sun_hours == result.hours


def _south_45(d):
    az = np.degrees(np.arctan2(d[:, 0], d[:, 1])) % 360.0
    return np.abs(az - 180.0) <= 45.0


@pytest.mark.parametrize(("lat", "lon", "date", "h_min"), SITES)
def test_sun_seen_within_45_degrees_of_south_matches_the_closed_form(lat, lon, date, h_min):
    result = sunlight_exposure(_south_45, lat, lon, date, min_altitude_deg=h_min)
    dec = _declination(dt.date.fromisoformat(date), lon)
    h_alt = _hour_angle_above(lat, dec, h_min)
    h_az = _hour_angle_at_azimuth(lat, dec, math.radians(45.0))
    expected = 2 * math.degrees(min(h_alt, h_az)) / 15.0
    assert result.hours == pytest.approx(expected, abs=2 / 60)
    assert result.hours < result.sun_hours or h_az >= h_alt


def test_levels_and_nothing_seen():
    assert [sunlight_level(h) for h in (0.0, 1.49, 1.5, 2.99, 3.0, 3.99, 4.0)] == [
        "none",
        "none",
        "minimum",
        "minimum",
        "medium",
        "medium",
        "high",
    ]
    dark = sunlight_exposure(
        lambda d: np.zeros(len(d), bool), 50.0, 10.0, "2026-03-01", min_altitude_deg=10.0
    )
    assert (dark.hours, dark.level) == (0.0, "none")
    assert dark.sun_hours > 8


def test_date_window_and_bad_input():
    for date in ("2026-02-01", "2026-03-21", dt.date(2026, 2, 28)):
        sunlight_exposure(_always, 50.0, 10.0, date, min_altitude_deg=10.0, step_minutes=10.0)
    for date in ("2026-01-31", "2026-03-22", "2026-06-21"):
        with pytest.raises(LightInvError, match="1 February to 21 March"):
            sunlight_exposure(_always, 50.0, 10.0, date, min_altitude_deg=10.0)
    with pytest.raises(LightInvError, match="one bool per direction"):
        sunlight_exposure(lambda d: np.ones(3, bool), 50.0, 10.0, "2026-03-01", min_altitude_deg=5)
    with pytest.raises(LightInvError):
        sunlight_exposure(_always, 50.0, 10.0, "2026-03-01", min_altitude_deg=10.0, step_minutes=7)


def test_sun_directions_are_geographic():
    # Around solar noon in the northern winter the sun is due south: -y, and up.
    d, alt = sun_directions(48.0, 0.0, "2026-03-01", step_minutes=60.0, utc_offset_h=0.0)
    noon = d[12]  # 12:30 UTC at longitude 0
    assert noon[1] < -0.5 and noon[2] > 0.5 and abs(noon[0]) < 0.2
    assert alt[0] < 0 and alt[12] > 30
