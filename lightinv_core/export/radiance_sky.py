"""Radiance's units, glass and skies, for the scenes ``radiance_scene`` writes and the
project's cross-checks with Radiance (``tests/radiance``).

Radiance's frame is +X east, +Y north, +Z up; LightInv's scene axes are turned by the
project's ``north_deg`` (the compass bearing of the scene's +y axis), so a sky is
written in Radiance's frame and turned into the scene's axes by ``xform -rz
north_deg`` (a counter-clockwise turn seen from above takes the world's east, bearing
90, to the scene direction at bearing 90 - north_deg).

Sun positions are altitude (degrees above the horizon) and compass azimuth (degrees
clockwise from north, pvlib's convention, as LightInv's climate code); gensky and
gendaylit take the azimuth in degrees west of south, ``compass - 180`` (checked:
``gensky -ang 30 90`` puts the sun at (-0.866, 0, 0.5), due west).

Radiance works in radiometric units with a fixed luminous efficacy of 179 lm/W for its
white light: an irradiance (r, g, b) is ``179 * (0.265 r + 0.670 g + 0.065 b)`` lux,
and a luminance of L cd/m² is a radiance of L / 179 W/(m² sr).

The sky functions return the generator's command line (``gensky ...``): a scene file
runs it itself (``!gensky ...``), so writing a scene needs no Radiance installed.
"""

from __future__ import annotations

import math

import numpy as np

EFFICACY = 179.0
"""lm/W: Radiance's luminous efficacy of white light (its ``WHTEFFICACY``)."""

RGB_TO_LUX = EFFICACY * np.array([0.265, 0.670, 0.065])
"""Weights turning a Radiance irradiance (r, g, b) in W/m² into lux."""

SUN_DIAMETER_DEG = 0.533
"""Apparent diameter of the sun disc written by ``sun_only`` (gendaylit's)."""

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


def gensky_azimuth(compass_deg: float) -> float:
    """gensky/gendaylit azimuth (degrees west of south) from a compass azimuth."""
    return compass_deg % 360.0 - 180.0


def sun_direction(altitude_deg: float, azimuth_deg: float) -> np.ndarray:
    """Unit vector towards the sun in Radiance's frame (+X east, +Y north, +Z up) from
    its altitude and compass azimuth (degrees)."""
    a, z = math.radians(altitude_deg), math.radians(azimuth_deg)
    return np.array([math.cos(a) * math.sin(z), math.cos(a) * math.cos(z), math.sin(a)])


def cie_clear_args(
    sun_altitude: float,
    sun_azimuth: float,
    horizontal_diffuse_lux: float,
    ground_reflectance: float,
    *,
    direct_normal_lux: float | None = None,
) -> list[str]:
    """``gensky`` for the CIE clear sky with a sun at (altitude, compass azimuth) deg.

    ``-B`` sets the zenith luminance so that the sky's own numerical integral of the
    diffuse horizontal irradiance is ``horizontal_diffuse_lux / 179`` W/m². Without
    ``direct_normal_lux`` the sky has no sun (``-s``); with it the sun disc (gensky's
    0.5 degrees) is added (``+s``) with its horizontal irradiance set by ``-R`` to
    ``direct_normal_lux * sin(altitude) / 179``. The ground below the horizon glows
    with gensky's ground brightness for ``ground_reflectance``.
    """
    args = ["gensky", "-ang", f"{sun_altitude:.6f}", f"{gensky_azimuth(sun_azimuth):.6f}"]
    args += ["-s" if direct_normal_lux is None else "+s"]
    args += ["-B", f"{horizontal_diffuse_lux / EFFICACY:.8g}", "-g", f"{ground_reflectance:g}"]
    if direct_normal_lux is not None:
        sin_a = math.sin(math.radians(sun_altitude))
        args += ["-R", f"{direct_normal_lux * sin_a / EFFICACY:.8g}"]
    return args


def cie_overcast_args(horizontal_lux: float, ground_reflectance: float) -> list[str]:
    """``gensky -c`` for the CIE overcast sky whose horizontal illuminance is
    ``horizontal_lux`` (``-B``, as ``cie_clear_args``); no sun."""
    args = ["gensky", "-ang", "45", "0", "-c", "-B", f"{horizontal_lux / EFFICACY:.8g}"]
    return [*args, "-g", f"{ground_reflectance:g}"]


def perez_args(
    sun_altitude: float,
    sun_azimuth: float,
    dni_w: float,
    dhi_w: float,
    ground_reflectance: float,
    *,
    solar: bool = False,
) -> list[str]:
    """``gendaylit -ang ... -W DNI DHI -O 0``: the Perez all-weather sky and sun from
    the direct normal and diffuse horizontal irradiance in W/m²; gendaylit turns them
    into visible light with the Perez luminous efficacy models and writes radiances in
    Radiance's 179 lm/W units. ``solar=True`` writes the solar radiance (``-O 1``)."""
    args = ["gendaylit", "-ang", f"{sun_altitude:.6f}", f"{gensky_azimuth(sun_azimuth):.6f}"]
    args += ["-W", f"{dni_w:g}", f"{dhi_w:g}", "-O", "1" if solar else "0"]
    return [*args, "-g", f"{ground_reflectance:g}"]


def sun_only(sun_altitude: float, sun_azimuth: float, direct_normal_lux: float) -> str:
    """A sun disc of 0.533 degrees alone (no sky, no ground) whose illuminance on a plane
    facing it is ``direct_normal_lux``, as Radiance text."""
    half = math.radians(SUN_DIAMETER_DEG / 2)
    solid_angle = 2 * math.pi * (1 - math.cos(half))
    radiance = direct_normal_lux / EFFICACY / solid_angle
    d = sun_direction(sun_altitude, sun_azimuth)
    return (
        f"void light solar\n0\n0\n3 {radiance:.8g} {radiance:.8g} {radiance:.8g}\n\n"
        f"solar source sun\n0\n0\n4 {d[0]:.9f} {d[1]:.9f} {d[2]:.9f} {SUN_DIAMETER_DEG}\n"
    )


def inline_sky(args: list[str], north_deg: float = 0.0) -> str:
    """A generator's sky as scene text that runs it (``!gensky ...``), turned into the
    scene's axes by ``north_deg``, with its sky and ground glows."""
    command = "!" + " ".join(args)
    if north_deg:
        command += f" | xform -rz {north_deg:.9g}"
    return command + "\n" + SKY_GLOW
