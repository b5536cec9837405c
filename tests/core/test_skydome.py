"""Tregenza and Reinhart sky patches: counts, solid angles against their closed forms
and a numerical integral, the patch lookup, and Radiance's own patch numbering
(``rcalc`` with Radiance's ``reinhartb.cal``, ``reinhart.cal`` and ``tregenza.cal``)."""

from __future__ import annotations

import math
import subprocess

import numpy as np
import pyradiance
import pytest

from lightinv_core.climate.skydome import altitude_azimuth, reinhart, tregenza
from lightinv_core.errors import LightInvError

RCALC = str(pyradiance.anci.BINPATH / "rcalc")


def _random_directions(n: int, seed: int) -> np.ndarray:
    v = np.random.default_rng(seed).normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def test_tregenza_bands_counts_and_edges() -> None:
    dome = tregenza()
    assert dome.count == 145
    lows = np.unique(dome.altitude[:, 0])
    np.testing.assert_allclose(lows, np.arange(0, 85, 12.0))
    per_band = [int((dome.altitude[:, 0] == lo).sum()) for lo in lows]
    assert per_band == [30, 30, 24, 24, 18, 12, 6, 1]
    # the first patch is centred due north at the horizon band's mid altitude (6 deg)
    np.testing.assert_allclose(dome.altitude[0], [0, 12])
    np.testing.assert_allclose(dome.azimuth[0], [-6, 6])
    np.testing.assert_allclose(
        dome.directions[0], [0, math.cos(math.radians(6)), math.sin(math.radians(6))]
    )
    # the second is east of it (compass azimuth 12)
    assert dome.directions[1, 0] > 0
    np.testing.assert_allclose(dome.directions[-1], [0, 0, 1])
    np.testing.assert_allclose(dome.altitude[-1], [84, 90])


@pytest.mark.parametrize("mf", [1, 2, 3, 4])
def test_solid_angles_closed_form_and_numerical(mf: int) -> None:
    dome = reinhart(mf)
    assert dome.count == 144 * mf * mf + 1
    assert dome.solid_angles.sum() == pytest.approx(2 * math.pi, rel=1e-12)
    assert dome.horizontal_solid_angles.sum() == pytest.approx(math.pi, rel=1e-12)
    n_in_band = np.array(
        [(dome.altitude[:, 0] == lo).sum() for lo in dome.altitude[:, 0]], dtype=float
    )
    s0, s1 = np.sin(np.radians(dome.altitude.T))
    np.testing.assert_allclose(dome.solid_angles, 2 * math.pi / n_in_band * (s1 - s0), rtol=1e-12)
    # numerical integral of cos(alt) d alt d az (and of sin(alt) cos(alt)) per patch,
    # by the midpoint rule on 200 altitude steps: independent of the closed forms
    t = (np.arange(200) + 0.5) / 200
    alt = np.radians(dome.altitude[:, :1] + (dome.altitude[:, 1:] - dome.altitude[:, :1]) * t)
    dalt = np.radians(dome.altitude[:, 1] - dome.altitude[:, 0]) / 200
    width = np.radians(dome.azimuth[:, 1] - dome.azimuth[:, 0])
    omega = width * (np.cos(alt).sum(axis=1) * dalt)
    proj = width * ((np.sin(alt) * np.cos(alt)).sum(axis=1) * dalt)
    np.testing.assert_allclose(dome.solid_angles, omega, rtol=1e-4)
    np.testing.assert_allclose(dome.horizontal_solid_angles, proj, rtol=1e-4)


@pytest.mark.parametrize("mf", [1, 2, 4])
def test_patch_of_centres_and_bounds(mf: int) -> None:
    dome = reinhart(mf)
    np.testing.assert_array_equal(dome.patch_of(dome.directions), np.arange(dome.count))
    d = _random_directions(20_000, mf)
    k = dome.patch_of(d)
    alt, az = altitude_azimuth(d)
    assert (k[alt <= 0] == -1).all()
    up = alt > 0
    kk = k[up]
    assert (kk >= 0).all()
    assert (dome.altitude[kk, 0] <= alt[up]).all() and (alt[up] < dome.altitude[kk, 1]).all()
    # azimuth inside [start, end) modulo 360 (the north patch starts below 0)
    rel = np.mod(az[up] - dome.azimuth[kk, 0], 360.0)
    assert (rel < dome.azimuth[kk, 1] - dome.azimuth[kk, 0] + 1e-9).all()


def _rcalc(cal: str, mf: int, expr: str, directions: np.ndarray) -> np.ndarray:
    # reinhart.cal needs the constant MF before it loads; reinhartb.cal sets MF = 1
    # itself, to be overridden after it
    before = cal == "reinhart.cal"
    load = ["-e", f"MF:{mf}", "-f", cal] if before else ["-f", cal, "-e", f"MF={mf}"]
    rows = "\n".join(f"{x:.10f} {y:.10f} {z:.10f}" for x, y, z in directions)
    out = subprocess.run(
        [RCALC, *load, "-e", "Dx=$1;Dy=$2;Dz=$3", "-e", f"$1={expr}"],
        input=rows,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    return np.array(out.split(), dtype=float).astype(int)


@pytest.mark.parametrize("mf", [1, 2, 4])
def test_patch_numbering_is_radiances(mf: int) -> None:
    """Radiance's reinhartb.cal (rbin: 0-based, -1 below the horizon) and reinhart.cal
    (rbin: 1-based, 0 the ground, as gendaymtx rows) number the same directions as we
    do: the centres, random directions, and subsamples near the patch edges."""
    dome = reinhart(mf)
    sub, _ = dome.subsamples(4)
    d = np.concatenate([dome.directions, _random_directions(3000, 10 + mf), sub.reshape(-1, 3)])
    ours = dome.patch_of(d)
    np.testing.assert_array_equal(_rcalc("reinhartb.cal", mf, "rbin", d), ours)
    np.testing.assert_array_equal(_rcalc("reinhart.cal", mf, "rbin", d), ours + 1)
    assert (dome.radiance_rows() == np.arange(dome.count) + 1).all()
    if mf == 1:
        np.testing.assert_array_equal(_rcalc("tregenza.cal", 1, "tbin", d), ours + 1)


@pytest.mark.parametrize("per_side", [1, 3, 5])
def test_subsamples_stay_in_their_patch_and_weigh_its_solid_angle(per_side: int) -> None:
    dome = reinhart(2)
    dirs, w = dome.subsamples(per_side)
    assert dirs.shape == (dome.count, per_side**2, 3) and w.shape == (dome.count, per_side**2)
    np.testing.assert_allclose(np.linalg.norm(dirs, axis=2), 1.0, atol=1e-12)
    np.testing.assert_allclose(w.sum(axis=1), dome.solid_angles, rtol=1e-12)
    owner = dome.patch_of(dirs.reshape(-1, 3)).reshape(dome.count, -1)
    np.testing.assert_array_equal(owner, np.arange(dome.count)[:, None] + 0 * owner)
    # a smooth integral over the hemisphere: the integral of sin^2(alt) d omega = 2 pi / 3
    z = dirs[..., 2]
    assert float((z**2 * w).sum()) == pytest.approx(2 * math.pi / 3, rel=2e-3 / per_side**2)


def test_bad_arguments() -> None:
    with pytest.raises(LightInvError):
        reinhart(0)
    with pytest.raises(LightInvError):
        tregenza().subsamples(0)
