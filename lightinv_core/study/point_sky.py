"""Skies of one moment for ``simulate``: luminance by direction, the sun, the ground.

A ``PointSky`` gives the luminance (cd/m²) of the sky in any direction above the horizon
and of the ground below it (a Lambertian plane of reflectance rho_g lit by the global
horizontal illuminance: rho_g E_gh / pi), and the sun as a direction with its direct
normal illuminance (lux). Directions are compass axes (x east, y north, z up).

- ``overcast_sky``: the CIE standard overcast sky, no sun;
- ``clear_sky``: the CIE standard clear sky (type 12) with the sun at a given position;
- ``weather_hour_sky``: one hour of a weather file, the Perez all-weather sky.

Clear glazing reads the luminance ray by ray; diffusing glazing reads the illuminance
on its outside, ``plane_lux``, integrated on a fine grid.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import LightInvError

_ALT, _AZ = 180, 360
"""Steps of the numerical integration of a sky (0.5 x 1 degree)."""


@dataclass(frozen=True)
class PointSky:
    """The sky of one moment: ``relative(directions) -> luminance`` above the horizon
    times ``scale`` (cd/m²), the ground's luminance ``ground`` (cd/m²), the ``sun``
    (unit compass vector, or None) and its direct normal illuminance ``sun_lux``."""

    label: str
    relative: Callable[[np.ndarray], np.ndarray]
    scale: float
    ground: float
    sun: np.ndarray | None
    sun_lux: float

    def luminance(self, directions: np.ndarray) -> np.ndarray:
        """cd/m² in compass ``directions`` (m, 3): the sky above the horizon, the ground
        below."""
        d = np.asarray(directions, dtype=float).reshape(-1, 3)
        up = d[:, 2] > 0
        out = np.full(len(d), self.ground)
        if up.any():
            out[up] = self.scale * np.asarray(self.relative(d[up]), dtype=float)
        return out


def _hemisphere() -> tuple[np.ndarray, np.ndarray]:
    """Directions (k, 3) of the upper hemisphere and their solid angles (k,)."""
    alt = (np.arange(_ALT) + 0.5) * (math.pi / 2) / _ALT
    az = (np.arange(_AZ) + 0.5) * (2 * math.pi) / _AZ
    a, z = np.meshgrid(alt, az, indexing="ij")
    d = np.stack([np.cos(a) * np.sin(z), np.cos(a) * np.cos(z), np.sin(a)], axis=-1)
    solid = np.cos(a) * (math.pi / 2 / _ALT) * (2 * math.pi / _AZ)
    return d.reshape(-1, 3), solid.reshape(-1)


def _scaled(relative, horizontal_lux: float) -> float:
    """The factor making ``relative`` give ``horizontal_lux`` on open ground."""
    d, w = _hemisphere()
    h = float((np.asarray(relative(d)) * d[:, 2] * w).sum())
    return horizontal_lux / h if h > 0 else 0.0


def _check(lux: float, what: str) -> None:
    if not (0 <= lux <= 2e5 and math.isfinite(lux)):
        raise LightInvError(f"{what} must be from 0 to 200,000 lux, got {lux!r}")


def sun_vector(altitude_deg: float, azimuth_deg: float) -> np.ndarray:
    """Unit compass vector to the sun at ``altitude_deg`` above the horizon and compass
    ``azimuth_deg`` (clockwise from north)."""
    a, z = math.radians(altitude_deg), math.radians(azimuth_deg)
    return np.array([math.cos(a) * math.sin(z), math.cos(a) * math.cos(z), math.sin(a)])


def overcast_sky(horizontal_lux: float, ground_reflectance: float) -> PointSky:
    """The CIE overcast sky giving ``horizontal_lux`` on open ground."""
    from lightinv_core.climate.sky_luminance import cie_overcast

    _check(horizontal_lux, "exterior illuminance")
    scale = _scaled(cie_overcast, horizontal_lux)
    ground = ground_reflectance * horizontal_lux / math.pi
    return PointSky("CIE overcast", cie_overcast, scale, ground, None, 0.0)


def clear_sky(
    altitude_deg: float,
    azimuth_deg: float,
    diffuse_lux: float,
    sun_lux: float,
    ground_reflectance: float,
) -> PointSky:
    """The CIE standard clear sky (type 12) with the sun at ``altitude_deg`` /
    ``azimuth_deg`` (compass): the sky gives ``diffuse_lux`` on open ground, the sun
    ``sun_lux`` at normal incidence."""
    from lightinv_core.climate.sky_luminance import cie_clear

    if not 0 < altitude_deg <= 90:
        raise LightInvError(
            f"the sun's altitude must be above 0 and at most 90 deg, got {altitude_deg}"
        )
    _check(diffuse_lux, "the clear sky's diffuse horizontal illuminance")
    _check(sun_lux, "the sun's direct normal illuminance")
    sun = sun_vector(altitude_deg, azimuth_deg)

    def relative(d):
        return cie_clear(d, sun)

    scale = _scaled(relative, diffuse_lux)
    ground = ground_reflectance * (diffuse_lux + sun_lux * sun[2]) / math.pi
    return PointSky(
        f"CIE clear, sun at {altitude_deg:g} deg altitude, {azimuth_deg:g} deg azimuth",
        relative,
        scale,
        ground,
        sun,
        float(sun_lux),
    )


def weather_hour_sky(weather, sky, hour: int, ground_reflectance: float) -> PointSky:
    """Hour ``hour`` (0-based, of the file) of ``weather`` (``climate.weather.Weather``)
    with its sun and sky (``climate.transposition.SunAndSky``): the Perez all-weather
    sky scaled to the file's diffuse horizontal illuminance, the sun at mid-hour with
    the file's direct normal illuminance (none once it is below the horizon)."""
    from lightinv_core.climate.sky_luminance import perez_all_weather, perez_parameters

    if not 0 <= hour < weather.hours:
        raise LightInvError(f"hour {hour} is outside the weather file (0-{weather.hours - 1})")
    zen, az = float(sky.zenith[hour]), float(sky.azimuth[hour])
    sun = sun_vector(90.0 - zen, az)
    eps, delta = perez_parameters(
        np.array([weather.dhi[hour]]),
        np.array([weather.dni[hour]]),
        np.array([zen]),
        np.array([sky.dni_extra[hour]]),
    )

    def relative(d):
        return perez_all_weather(d, sun[None], np.array([zen]), eps, delta)[0]

    dh = float(weather.dh_lux[hour])
    up = zen < 90.0
    scale = _scaled(relative, dh) if dh > 0 else 0.0
    sun_lux = float(weather.dn_lux[hour]) if up else 0.0
    ground = ground_reflectance * float(weather.gh_lux[hour]) / math.pi
    when = weather.times[hour]
    return PointSky(
        f"{weather.name}, hour ending {when:%m-%d %H:%M} (Perez all-weather)",
        relative,
        scale,
        ground,
        sun if up else None,
        sun_lux,
    )


def plane_lux(sky: PointSky, outward: np.ndarray) -> np.ndarray:
    """Illuminance (lux) on the outside of planes facing compass unit ``outward``
    (m, 3): the sky and ground they face, plus the sun's beam when in front."""
    d, w = _hemisphere()
    out = np.asarray(outward, dtype=float).reshape(-1, 3)
    L = sky.luminance(d)
    result = np.empty(len(out))
    for i, n in enumerate(out):
        cos = d @ n
        sky_part = float((L * np.maximum(cos, 0.0) * w).sum())
        # The ground fills the lower hemisphere uniformly: its view factor from the plane.
        ground_part = sky.ground * math.pi * (1 - n[2]) / 2
        sun_part = 0.0
        if sky.sun is not None:
            sun_part = sky.sun_lux * max(float(sky.sun @ n), 0.0)
        result[i] = sky_part + ground_part + sun_part
    return result
