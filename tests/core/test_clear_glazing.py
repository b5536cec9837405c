"""Clear glazing: the glass's angular transmittance, the sky seen through a rooflight
against an exact quadrature, the sun's patch against its geometric projection, and the
flux entering the room against the glass's hemispherical transmittance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.clear_glazing import (
    clear_glass,
    glass_transmittance,
    room_sky_rays,
    sun_on_room,
    to_geographic,
    to_scene,
    transmissivity,
)
from lightinv_core.transport.daylight_coefficients import ClearDaylight, bounce
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.glazing import glazing_emission
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors
from lightinv_core.transport.solver import solve_dense
from lightinv_core.transport.workplane import WorkPlane, work_plane_grid

from .test_daylight import black_room_with_a_rooflight

TAU = 0.6


@pytest.fixture(scope="module")
def rooflight():
    p = mesh_patches(black_room_with_a_rooflight())
    _, lit = glazing_emission(p, {"rooflight": TAU}, 0.0, 0.2)
    caster = RayCaster(p)
    F = form_factor_matrix(p, 256, seed=1, caster=caster)
    grid = work_plane_grid(p, caster, WorkPlane(0.8, 0.5))
    factors = receiver_factors(grid.points, grid.normals, caster, p.n, 256, 0)
    glass = clear_glass(p, {"rooflight": TAU})
    return (
        lit,
        caster,
        F,
        grid,
        ClearDaylight(lit, F, caster, glass, grid.points, grid.normals, factors),
    )


def test_glass_transmittance_is_radiance_glass():
    for t in (0.2, 0.6, 0.88):
        # Radiance's conversion constants are given to 10 digits.
        assert glass_transmittance(t, 1.0) == pytest.approx(t, rel=1e-6)
    # Lossless glass of n = 1.52 passes (1 - r) / (1 + r) at normal incidence.
    r = ((1.52 - 1) / (1.52 + 1)) ** 2
    lossless = (1 - r) / (1 + r)
    assert transmissivity(lossless) == pytest.approx(1.0, abs=1e-6)
    cos = np.linspace(1, 0, 50)
    t = glass_transmittance(0.6, cos)
    assert np.all(np.diff(t) <= 1e-12) and t[-1] == pytest.approx(0, abs=1e-6)
    assert np.allclose(glass_transmittance(0.6, -cos), t)
    # Fresnel at 60 degrees for lossless glass (s and p reflectances by hand).
    ci, ct = 0.5, math.sqrt(1 - 0.75 / 1.52**2)
    rs = ((ci - 1.52 * ct) / (ci + 1.52 * ct)) ** 2
    rp = ((ct - 1.52 * ci) / (ct + 1.52 * ci)) ** 2
    want = 0.5 * ((1 - rs) / (1 + rs) + (1 - rp) / (1 + rp))
    assert glass_transmittance(lossless, 0.5) == pytest.approx(want, rel=1e-6)


def test_compass_frame_round_trip():
    d = np.array([[0, 1.0, 0], [1.0, 0, 0], [0.3, -0.4, 0.866]])
    east = to_geographic(np.array([[0, 1.0, 0]]), 90.0)  # +y points east
    assert east[0] == pytest.approx([1, 0, 0], abs=1e-12)
    assert to_scene(to_geographic(d, 33.0), 33.0) == pytest.approx(d)


def _quadrature(points: np.ndarray, luminance) -> np.ndarray:
    """Exact-ish illuminance through the 2 x 4 m rooflight at z = 3 by a 400 x 800 grid."""
    xs = 2 + (np.arange(400) + 0.5) / 400 * 2
    ys = (np.arange(800) + 0.5) / 800 * 4
    X, Y = np.meshgrid(xs, ys)
    dA = (2 / 400) * (4 / 800)
    out = []
    for q in points:
        v = np.stack([X - q[0], Y - q[1], np.full_like(X, 3 - q[2])], -1)
        r = np.linalg.norm(v, axis=-1)
        c = v[..., 2] / r
        L = luminance((v / r[..., None]).reshape(-1, 3)).reshape(X.shape)
        out.append((L * glass_transmittance(TAU, c) * c * c / r**2 * dA).sum())
    return np.array(out)


def test_the_sky_through_a_black_rooms_rooflight_matches_quadrature(rooflight):
    *_, grid, clear = rooflight

    def sky(d):  # a sky brighter towards +x, so direction matters
        return 1000.0 * (1.0 + 0.8 * d[:, 0])

    got = clear.under(sky)[0]
    want = _quadrature(grid.points, sky)
    err = np.abs(got / want - 1)
    assert err.mean() < 0.003 and err.max() < 0.01
    # Binned daylight coefficients reproduce it when the sky is constant per bin.
    coeff = clear.sky(lambda d: (d[:, 0] > 0).astype(int), 2)[0]
    half = coeff @ np.array([1.0, 3.0])
    assert half == pytest.approx(
        _quadrature(grid.points, lambda d: 1 + 2.0 * (d[:, 0] > 0)), rel=0.01
    )


def test_the_sun_patch_is_the_rooflights_projection(rooflight):
    _, _, _, grid, clear = rooflight
    alt, az = math.radians(60.0), math.radians(30.0)
    sun = np.array([[math.cos(alt) * math.sin(az), math.cos(alt) * math.cos(az), math.sin(alt)]])
    got = clear.sun_direct(sun)[0, :, 0]
    # Where the ray from each point to the sun crosses z = 3.
    t = (3 - grid.points[:, 2]) / sun[0, 2]
    x, y = grid.points[:, 0] + t * sun[0, 0], grid.points[:, 1] + t * sun[0, 1]
    inside = (x > 2) & (x < 4) & (y > 0) & (y < 4)
    assert inside.sum() > 5 and (~inside).sum() > 5
    assert np.all(got[~inside] == 0)
    assert got[inside] == pytest.approx(glass_transmittance(TAU, math.sin(alt)) * math.sin(alt))


def test_the_flux_entering_is_the_glass_hemispherical_transmittance(rooflight):
    lit, caster, *_ = rooflight
    glass = clear_glass(lit, {"rooflight": TAU})
    rays = room_sky_rays(lit, glass, caster, rays=256)
    flux = float((rays.weight * lit.area[rays.target]).sum())  # lm per cd/m² of sky
    theta = (np.arange(2000) + 0.5) / 2000 * math.pi / 2
    hemi = (
        2
        * float((glass_transmittance(TAU, np.cos(theta)) * np.cos(theta) * np.sin(theta)).sum())
        * (math.pi / 2 / 2000)
    )
    assert flux == pytest.approx(math.pi * 8.0 * hemi, rel=0.005)
    # The sun's beam lands whole in the closed room: A cos T(theta) lumens per lux.
    sun = np.array([[0.3, 0.2, math.sqrt(1 - 0.13)]])
    H = sun_on_room(lit, glass, caster, sun)[0, :, 0]
    assert float(H @ lit.area) == pytest.approx(
        8.0 * sun[0, 2] * glass_transmittance(TAU, sun[0, 2])
    )


def test_bounce_is_the_radiosity_solve(cornell_patches, cornell_F):
    rng = np.random.default_rng(0)
    H = rng.random((cornell_patches.n, 3))
    B = bounce(cornell_F, cornell_patches.rho, H)
    for c in range(3):
        ref = solve_dense(cornell_F, cornell_patches.rho, cornell_patches.rho * H[:, c])
        assert B[:, c] == pytest.approx(ref.B, rel=1e-9)
