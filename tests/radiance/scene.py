"""Radiance scene and sky descriptions written from LightInv's patches, for the
cross-checks: the scene writer, units, glass and sky command lines are the core's
exporter (``lightinv_core.export.radiance_sky``, ``radiance_scene.write_patches``);
here the sky generators are run at once, so a bad sky fails where it is made.

Sky functions return Radiance text in Radiance's frame (+X east, +Y north);
``tests.radiance.run`` turns them into the scene's axes (``!xform -rz north_deg``).
"""

from __future__ import annotations

import subprocess

from lightinv_core.export.radiance_scene import write_patches
from lightinv_core.export.radiance_sky import (
    EFFICACY,
    RGB_TO_LUX,
    SKY_GLOW,
    SUN_DIAMETER_DEG,
    cie_clear_args,
    cie_overcast_args,
    glass_transmissivity,
    perez_args,
    sun_direction,
    sun_only,
)

__all__ = [
    "EFFICACY",
    "RGB_TO_LUX",
    "SKY_GLOW",
    "SUN_DIAMETER_DEG",
    "glass_transmissivity",
    "sky_cie_clear",
    "sky_cie_overcast",
    "sky_perez",
    "sky_sun_only",
    "sun_direction",
    "write_scene",
]

write_scene = write_patches
"""Patches as a Radiance scene file (``radiance_scene.write_patches``)."""


def _radiance_env() -> dict:
    from tests.radiance.run import radiance_env

    return radiance_env()


def _gen(args: list[str]) -> str:
    """stdout of a Radiance generator (gensky, gendaylit), with its binaries on PATH."""
    out = subprocess.run(args, capture_output=True, text=True, env=_radiance_env(), check=False)
    if out.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} failed: {out.stderr.strip()}")
    return out.stdout


def sky_cie_clear(
    sun_altitude: float,
    sun_azimuth: float,
    horizontal_diffuse_lux: float,
    ground_reflectance: float,
    *,
    direct_normal_lux: float | None = None,
) -> str:
    """The CIE clear sky (``gensky``, ``radiance_sky.cie_clear_args``) and its glows."""
    args = cie_clear_args(
        sun_altitude, sun_azimuth, horizontal_diffuse_lux, ground_reflectance,
        direct_normal_lux=direct_normal_lux,
    )  # fmt: skip
    return _gen(args) + SKY_GLOW


def sky_cie_overcast(horizontal_lux: float, ground_reflectance: float) -> str:
    """The CIE overcast sky (``gensky -c``) of ``horizontal_lux``; no sun."""
    return _gen(cie_overcast_args(horizontal_lux, ground_reflectance)) + SKY_GLOW


def sky_perez(
    sun_altitude: float,
    sun_azimuth: float,
    dni_w: float,
    dhi_w: float,
    ground_reflectance: float,
    *,
    solar: bool = False,
) -> str:
    """The Perez all-weather sky and sun (``gendaylit``, ``radiance_sky.perez_args``)."""
    args = perez_args(sun_altitude, sun_azimuth, dni_w, dhi_w, ground_reflectance, solar=solar)
    return _gen(args) + SKY_GLOW


def sky_sun_only(sun_altitude: float, sun_azimuth: float, direct_normal_lux: float) -> str:
    """A sun disc of 0.533 degrees alone (``radiance_sky.sun_only``)."""
    return sun_only(sun_altitude, sun_azimuth, direct_normal_lux)
