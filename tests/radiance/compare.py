"""Clear glazing beside Radiance at one moment: the comparison the tests run on a few
points with light settings and ``bench/peers.py`` runs on every point with the full
ones (its figures are the ones docs/daylight.md quotes)."""

from __future__ import annotations

import numpy as np

from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.study import SimulationSpec, simulate
from lightinv_core.transport.workplane import WorkPlane
from tests.radiance.run import POINT_PARAMS, point_lux
from tests.radiance.scene import sky_cie_clear, sky_sun_only

TAU = 0.7
ROOMS = {"sidelit": "window", "toplit": "rooflight"}
SUN = {"sidelit": (35.0, 190.0), "toplit": (55.0, 200.0)}
"""Sun positions (altitude, compass azimuth) that put a sun patch on each work plane."""

CASES = {
    # name: (diffuse lux, sun's direct normal lux, ground reflectance)
    "sun": (0.0, 80000.0, 0.0),
    "sky": (10000.0, 0.0, 0.0),
    "sky+sun+ground": (10000.0, 80000.0, 0.2),
}


def radiance_sky(case: str, sun) -> str:
    """The Radiance sky of a case (gensky's ground glows with the sun's light too, so
    the sky alone is compared without a ground)."""
    diffuse, sun_lux, rho_g = CASES[case]
    if case == "sun":
        return sky_sun_only(*sun, sun_lux)
    direct = sun_lux if sun_lux > 0 else None
    return sky_cie_clear(*sun, diffuse, rho_g, direct_normal_lux=direct)


def compare(room: str, case: str, every: int = 1, ab: int = 10, params: str = POINT_PARAMS) -> dict:
    """LightInv's work-plane lux and rtrace's at every ``every``-th point of ``room``
    under ``case``: both arrays, the relative errors and the sunlit points of each."""
    group, sun = ROOMS[room], SUN[room]
    diffuse, sun_lux, rho_g = CASES[case]
    res = simulate(
        SimulationSpec(
            builtin_scene(room, 0.5),
            glazing={group: TAU},
            glazing_kinds={group: "clear"},
            sky="cie-clear",
            sun=sun,
            exterior_lux=diffuse,
            sun_lux=sun_lux,
            ground_reflectance=rho_g,
            workplane=WorkPlane(0.8, 0.5),
            rays=2048,
        )
    )
    pick = slice(None, None, every)
    pts, nrm, ours = res.grid.points[pick], res.grid.normals[pick], res.grid_lux[pick]
    sky = radiance_sky(case, sun)
    theirs = point_lux(res.patches, {group: TAU}, sky, pts, nrm, ab=ab, params=params)
    err = np.abs(ours / theirs - 1)
    return {
        "ours": ours,
        "theirs": theirs,
        "error": err,
        "sunlit_ours": ours > 5000,
        "sunlit_theirs": theirs > 5000,
    }
