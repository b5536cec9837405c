"""Radiance scene and sky descriptions written from LightInv's patches.

Radiance's frame is +X east, +Y north, +Z up; LightInv's scene axes are turned by the
project's ``north_deg`` (the compass bearing of the scene's +y axis), so the skies
written here are in Radiance's frame and ``tests.radiance.run`` turns them into the
scene's axes (``!xform -rz north_deg``: a counter-clockwise turn seen from above takes
the world's east, bearing 90, to the scene direction at bearing 90 - north_deg).

Sun positions are given as altitude (degrees above the horizon) and compass azimuth
(degrees clockwise from north, pvlib's convention, as LightInv's climate code);
gensky and gendaylit take the azimuth in degrees west of south, ``compass - 180``
(checked: ``gensky -ang 30 90`` puts the sun at (-0.866, 0, 0.5), due west).

Radiance works in radiometric units with a fixed luminous efficacy of 179 lm/W for
its white light: an irradiance (r, g, b) is ``179 * (0.265 r + 0.670 g + 0.065 b)``
lux, and a luminance of L cd/m2 is a radiance of L / 179 W/(m2 sr).
"""

from __future__ import annotations

import math
import subprocess
from pathlib import Path

import numpy as np

from lightinv_core.scene.patches import Patches

EFFICACY = 179.0
"""lm/W: Radiance's luminous efficacy of white light (its ``WHTEFFICACY``)."""

RGB_TO_LUX = EFFICACY * np.array([0.265, 0.670, 0.065])
"""Weights turning a Radiance irradiance (r, g, b) in W/m2 into lux."""

SUN_DIAMETER_DEG = 0.533
"""Apparent diameter of the sun disc written by ``sky_sun_only`` (gendaylit's)."""

SKY_GLOW = """
skyfunc glow sky_glow
0
0
4 1 1 1 0

sky_glow source sky
0
0
4 0 0 1 180

skyfunc glow ground_glow
0
0
4 1 1 1 0

ground_glow source ground
0
0
4 0 0 -1 180
"""
"""The sky and ground hemispheres glowing with the ``skyfunc`` written before them."""


def glass_transmissivity(transmittance: float) -> float:
    """Transmissivity tn for Radiance's ``glass`` from its normal transmittance Tn.

    The conversion given in Radiance's ``glass.c`` (refractive index 1.52):
    tn = (sqrt(0.8402528435 + 0.0072522239 Tn^2) - 0.9166530661) / 0.0036261119 / Tn;
    standard 88% glass gives 0.96.
    """
    t = float(transmittance)
    if not 0.0 < t < 0.92:
        raise ValueError(f"clear glass transmittance {t} outside (0, 0.92)")
    return (math.sqrt(0.8402528435 + 0.0072522239 * t * t) - 0.9166530661) / 0.0036261119 / t


def _radiance_env() -> dict:
    from tests.radiance.run import radiance_env

    return radiance_env()


def _gen(args: list[str]) -> str:
    """stdout of a Radiance generator (gensky, gendaylit), with its binaries on PATH."""
    out = subprocess.run(args, capture_output=True, text=True, env=_radiance_env(), check=False)
    if out.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} failed: {out.stderr.strip()}")
    return out.stdout


def _gensky_azimuth(compass_deg: float) -> float:
    """gensky/gendaylit azimuth (degrees west of south) from a compass azimuth."""
    return compass_deg % 360.0 - 180.0


def sun_direction(altitude_deg: float, azimuth_deg: float) -> np.ndarray:
    """Unit vector towards the sun in Radiance's frame (+X east, +Y north, +Z up) from
    its altitude and compass azimuth (degrees)."""
    a, z = math.radians(altitude_deg), math.radians(azimuth_deg)
    return np.array([math.cos(a) * math.sin(z), math.cos(a) * math.cos(z), math.sin(a)])


def sky_cie_clear(
    sun_altitude: float,
    sun_azimuth: float,
    horizontal_diffuse_lux: float,
    ground_reflectance: float,
    *,
    direct_normal_lux: float | None = None,
) -> str:
    """The CIE clear sky (``gensky``) for a sun at (altitude, compass azimuth) degrees.

    gensky ``-B`` sets the zenith luminance so that the sky's own numerical integral of
    the diffuse horizontal irradiance is ``horizontal_diffuse_lux / 179`` W/m2. Without
    ``direct_normal_lux`` the sky has no sun (``-s``); with it the sun disc (gensky's
    0.5 degrees) is added (``+s``) with its horizontal irradiance set by ``-R`` to
    ``direct_normal_lux * sin(altitude) / 179``. The ground below the horizon glows
    with gensky's ground brightness for ``ground_reflectance``.
    """
    args = ["gensky", "-ang", f"{sun_altitude:.6f}", f"{_gensky_azimuth(sun_azimuth):.6f}"]
    args += ["-s" if direct_normal_lux is None else "+s"]
    args += ["-B", f"{horizontal_diffuse_lux / EFFICACY:.8g}", "-g", f"{ground_reflectance:g}"]
    if direct_normal_lux is not None:
        sin_a = math.sin(math.radians(sun_altitude))
        args += ["-R", f"{direct_normal_lux * sin_a / EFFICACY:.8g}"]
    return _gen(args) + SKY_GLOW


def sky_cie_overcast(horizontal_lux: float, ground_reflectance: float) -> str:
    """The CIE overcast sky (``gensky -c``) whose horizontal illuminance is
    ``horizontal_lux`` (``-B``, as ``sky_cie_clear``); no sun."""
    args = ["gensky", "-ang", "45", "0", "-c", "-B", f"{horizontal_lux / EFFICACY:.8g}"]
    return _gen([*args, "-g", f"{ground_reflectance:g}"]) + SKY_GLOW


def sky_perez(
    sun_altitude: float,
    sun_azimuth: float,
    dni_w: float,
    dhi_w: float,
    ground_reflectance: float,
    *,
    solar: bool = False,
) -> str:
    """The Perez all-weather sky and sun (``gendaylit -ang ... -W DNI DHI -O 0``) from the
    direct normal and diffuse horizontal irradiance in W/m2; gendaylit turns them into
    visible light with the Perez luminous efficacy models and writes radiances in
    Radiance's 179 lm/W units. ``solar=True`` writes the solar radiance instead
    (``-O 1``): then "lux" from ``point_lux`` divided by 179 is the irradiance in W/m2."""
    args = ["gendaylit", "-ang", f"{sun_altitude:.6f}", f"{_gensky_azimuth(sun_azimuth):.6f}"]
    args += ["-W", f"{dni_w:g}", f"{dhi_w:g}", "-O", "1" if solar else "0"]
    args += ["-g", f"{ground_reflectance:g}"]
    return _gen(args) + SKY_GLOW


def sky_sun_only(sun_altitude: float, sun_azimuth: float, direct_normal_lux: float) -> str:
    """A sun disc of 0.533 degrees alone (no sky, no ground) whose illuminance on a plane
    facing it is ``direct_normal_lux``."""
    half = math.radians(SUN_DIAMETER_DEG / 2)
    solid_angle = 2 * math.pi * (1 - math.cos(half))
    radiance = direct_normal_lux / EFFICACY / solid_angle
    d = sun_direction(sun_altitude, sun_azimuth)
    return (
        f"void light solar\n0\n0\n3 {radiance:.8g} {radiance:.8g} {radiance:.8g}\n\n"
        f"solar source sun\n0\n0\n4 {d[0]:.9f} {d[1]:.9f} {d[2]:.9f} {SUN_DIAMETER_DEG}\n"
    )


def _polygon(points: np.ndarray) -> str:
    coords = "\n".join(f"  {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}" for p in points)
    return f"0\n0\n{3 * len(points)}\n{coords}\n"


def write_scene(
    patches: Patches,
    glazing: dict[str, float],
    path: str | Path,
    *,
    diffusing: set[str] | frozenset[str] = frozenset(),
    openings: set[str] | frozenset[str] = frozenset(),
    black: bool = False,
) -> Path:
    """Write ``patches`` as a Radiance scene file (.rad) and return its path.

    Every patch is a polygon whose vertex order gives its LightInv normal. Opaque
    patches are grey ``plastic`` of their reflectance (no specularity, no roughness;
    ``black=True`` makes them all 0). Each group named in ``glazing`` (name -> normal
    transmittance) is clear ``glass`` with the transmissivity of
    ``glass_transmissivity``; a group also in ``diffusing`` is instead a Lambertian
    transmitter (``trans`` with no specular part) whose total transmittance is the value
    and whose reflectance is its patches' ``rho``. Groups in ``openings`` are left out
    (empty holes: light passes unchanged).
    """
    path = Path(path)
    unknown = (set(glazing) | set(diffusing) | set(openings)) - set(patches.group_names)
    if unknown:
        raise ValueError(f"no groups {sorted(unknown)} in the patches")
    if not set(diffusing) <= set(glazing):
        raise ValueError("every diffusing group needs its transmittance in glazing")
    lines: list[str] = []
    material_of_group: dict[int, str] = {}
    for name, tau in glazing.items():
        g = patches.group_names.index(name)
        mat = f"glazing_{g}"
        material_of_group[g] = mat
        if name in diffusing:
            rhos = patches.rho[patches.group_id == g]
            rho = 0.0 if black else float(rhos.mean()) if len(rhos) else 0.0
            colour = rho + tau
            if colour > 1.0 + 1e-9:
                raise ValueError(f"group {name!r}: reflectance + transmittance > 1")
            frac = tau / colour if colour > 0 else 0.0
            c = f"{colour:.6g}"
            lines.append(f"void trans {mat}\n0\n0\n7 {c} {c} {c} 0 0 {frac:.8g} 0\n")
        else:
            tn = glass_transmissivity(tau)
            lines.append(f"void glass {mat}\n0\n0\n3 {tn:.8g} {tn:.8g} {tn:.8g}\n")
    rhos = np.zeros(patches.n) if black else np.round(np.asarray(patches.rho, float), 6)
    plastics = {r: f"grey_{k}" for k, r in enumerate(np.unique(rhos))}
    for r, mat in plastics.items():
        lines.append(f"void plastic {mat}\n0\n0\n5 {r:.6g} {r:.6g} {r:.6g} 0 0\n")
    o, e1, e2, nrm = patches.origin, patches.edge1, patches.edge2, patches.normal
    holes = [patches.group_names.index(g) for g in openings]
    for i in np.flatnonzero(~np.isin(patches.group_id, holes)):
        mat = material_of_group.get(int(patches.group_id[i])) or plastics[rhos[i]]
        if patches.is_triangle[i]:
            pts = np.array([o[i], o[i] + e1[i], o[i] + e2[i]])
        else:
            pts = np.array([o[i], o[i] + e1[i], o[i] + e1[i] + e2[i], o[i] + e2[i]])
        # Radiance's polygon normal follows the vertex order (right-hand rule).
        if np.dot(np.cross(e1[i], e2[i]), nrm[i]) < 0:
            pts = pts[::-1]
        lines.append(f"{mat} polygon p{i}\n{_polygon(pts)}")
    path.write_text("\n".join(lines))
    return path
