"""Radiance scene export (lightinv_core/export/radiance_scene.py) checked with Radiance
itself: rtrace on the exported scene against LightInv's own illuminance."""

from __future__ import annotations

import subprocess

import numpy as np
import pytest

pytest.importorskip("pyradiance")

from lightinv_core.export.radiance_scene import write_radiance
from lightinv_core.export.radiance_sky import RGB_TO_LUX
from lightinv_core.light.arrays import caster_for
from lightinv_core.transport.luminaires import PlacedLuminaire
from tests.export.office import BATWING, exported, office_project
from tests.radiance.run import radiance_env

FAST = "-aa 0 -lw 1e-4 -dj 0 -ds 0 -dt 0 -dc 1 -dr 0 -st 0 -ss 0"


def rtrace(folder, rad: str, points, ab: int, ad: int = 256) -> np.ndarray:
    """Illuminance (lux) at ``points`` facing up, by rtrace on the exported scene."""
    env = radiance_env()
    oct_ = folder / "scene.oct"
    with open(oct_, "wb") as fh:
        subprocess.run(["oconv", rad], cwd=folder, env=env, stdout=fh, check=True)
    rays = "".join(f"{p[0]:.9g} {p[1]:.9g} {p[2]:.9g} 0 0 1\n" for p in points).encode()
    args = ["rtrace", "-h", "-I+", "-ov", "-ab", str(ab), "-ad", str(ad), *FAST.split()]
    out = subprocess.run(
        [*args, oct_.name], input=rays, cwd=folder, env=env, capture_output=True, check=True
    )
    return np.array(out.stdout.split(), float).reshape(-1, 3) @ RGB_TO_LUX


@pytest.mark.parametrize("product", [None, BATWING], ids=["rab-downlight", "linear-batwing"])
def test_exported_luminaires_light_as_lightinv_direct(tmp_path, product):
    """Direct light only (-ab 0) of an array turned 90 degrees: a real round IES
    downlight and an asymmetric 1.2 m batwing (six point sources, C0 along v): every
    work-plane point within 2% of LightInv's own point-source sum."""
    ex = exported(office_project(panel=False, skylight=False, product=product))
    write_radiance(ex, tmp_path / "night.rad", sky="none")
    plane = ex.planes[0]
    pts = plane.points[::3]
    up = np.tile([0.0, 0.0, 1.0], (len(pts), 1))
    caster = caster_for(ex.patches)
    own = sum(
        f.maintenance
        * PlacedLuminaire(f.name, f.position, f.photometry, f.aim, f.c0, f.dimming).illuminance(
            pts, up, caster
        )
        for f in ex.fixtures
    )
    got = rtrace(tmp_path, "night.rad", pts, ab=0)
    assert own.min() > 1.0
    np.testing.assert_allclose(got, own, rtol=0.02)


def test_exported_scene_with_interreflections_matches_the_work_plane(tmp_path):
    """The array and the Lambertian panel with -ab 4: the work plane's illuminance
    (interreflections by LightInv's operator) within 10% on average at 6 points."""
    ex = exported(office_project(skylight=False))
    write_radiance(ex, tmp_path / "night.rad", sky="auto")
    plane = ex.planes[0]
    pick = np.linspace(0, len(plane.points) - 1, 6).astype(int)
    got = rtrace(tmp_path, "night.rad", plane.points[pick], ab=4, ad=512)
    err = np.abs(got / plane.lux[pick] - 1)
    print("rtrace", got.round(1), "lightinv", plane.lux[pick].round(1), "mean error", err.mean())
    assert err.mean() < 0.10, (got.round(), plane.lux[pick].round())
