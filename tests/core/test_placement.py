"""Any placement of a model gives the same light: georeferenced models sit kilometres
from the origin, where float32 ray casting in absolute coordinates leaks light."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builders import room_faces
from lightinv_core.scene.builtin import BUILTIN_SCENES, builtin_scene
from lightinv_core.scene.model import Rect, Scene, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import form_factor_matrix, lost_fraction
from lightinv_core.transport.solver import energy_balance, solve

SHIFTS = {"3 km": np.array([3000.0, 3000.0, 0.0]), "500 km": np.array([5.0e5, 5.2e6, 120.0])}
"""3 km in x and y (the probe's case) and UTM-like coordinates (easting, northing, altitude)."""


def moved(scene: Scene, shift: np.ndarray) -> Scene:
    """``scene`` with every surface translated by ``shift`` (m)."""
    surfaces = []
    for s in scene.surfaces:
        if s.rect is not None:
            r = s.rect
            s = dataclasses.replace(s, rect=Rect(r.origin + shift, r.u, r.v))
        else:
            s = dataclasses.replace(s, triangles=s.triangles + shift)
        surfaces.append(s)
    return dataclasses.replace(scene, surfaces=tuple(surfaces))


def _lux(scene: Scene, rays: int = 256) -> tuple[np.ndarray, float, float]:
    """Per-patch illuminance (lux) with every patch of the first group emitting 1000 lm,
    the lost fraction and the energy imbalance."""
    p = mesh_patches(scene)
    F = form_factor_matrix(p, rays, seed=3)
    emitting = p.group_id == 0
    E = np.where(emitting, 1000.0 / p.area[emitting].sum(), 0.0)
    sol = solve(F, p.rho, E)
    return sol.H, lost_fraction(F, p), energy_balance(p, sol)["imbalance"]


@pytest.mark.parametrize("shift", SHIFTS, ids=list(SHIFTS))
@pytest.mark.parametrize("name", list(BUILTIN_SCENES))
def test_every_builtin_scene_gives_the_same_light_far_from_the_origin(name, shift):
    scene = builtin_scene(name, 1.0 if name == "building" else 0.5)  # building: 14,000
    H0, lost0, imb0 = _lux(scene)
    H1, lost1, imb1 = _lux(moved(scene, SHIFTS[shift]))
    # Same rays up to float64 round-off of the shifted coordinates: a handful of grazing
    # rays may land on the neighbouring patch, nothing more.
    assert abs(lost1 - lost0) < 1e-4
    assert abs(imb1 - imb0) < 1e-4
    assert np.abs(H1 - H0).max() <= 0.02 * H0.max()
    assert abs(np.mean(H1) - np.mean(H0)) <= 1e-3 * np.mean(H0)


def test_closed_box_far_away_stays_closed_on_the_operator_path():
    """The probe's 4 x 3 x 2.5 m closed box moved 3 km gave walls 0 lux and claimed the
    room was open at UTM-like coordinates."""
    faces = room_faces(0, 0, 0, 4.0, 3.0, 2.5)
    box = Scene("box", [Surface(k, k, 0.5, rect=r) for k, r in faces.items()], resolution=0.5)
    settings = OperatorSettings(rays=128, rank=16)
    near = build_operator(mesh_patches(box), settings)
    for shift in SHIFTS.values():
        far = build_operator(mesh_patches(moved(box, shift)), settings)
        assert far.info["lost_fraction"] < 1e-4
        E = np.zeros(near.n)
        E[:4] = 100.0
        np.testing.assert_allclose(far.illuminance(E), near.illuminance(E), rtol=0.02, atol=0.05)
