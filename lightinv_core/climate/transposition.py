"""Hourly exterior illuminance on a glazing plane of any orientation (Perez sky).

For each hour of a ``Weather``: the sun's position at the middle of the hour
(pvlib, NREL SPA), then the irradiance on the plane in three parts,

- beam: DNI cos(angle of incidence), when the sun is in front of the plane;
- sky diffuse: the Perez 1990 model (pvlib.irradiance.perez, all-sites composite
  coefficients) from DHI, DNI, extraterrestrial DNI and the relative air mass;
- ground: GHI x ground reflectance x (1 - cos tilt) / 2;

each turned into illuminance with the file's own luminous efficacy of that component
that hour (direct normal lux / DNI, diffuse horizontal lux / DHI, global horizontal lux
/ GHI; the year's median where a component is below 1 W/m²). This is the usual way to
apply an irradiance transposition to illuminance: Perez's separate illuminance
coefficients are not in pvlib. The sum of the three irradiance parts is pvlib's own
``get_total_irradiance(model="perez")`` (tested).

Orientation: the scene's +z is up; ``north_deg`` is the compass bearing of the scene's
+y axis (0: +y is north, +x east; 90: +y is east).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from lightinv_core.climate.weather import Weather, WeatherError, require_pvlib

MIN_IRRADIANCE = 1.0
"""W/m²; below this a component's efficacy falls back to the year's median."""


@dataclass(frozen=True)
class SunAndSky:
    """The hourly inputs every plane shares: sun position (deg), extraterrestrial DNI
    (W/m²), relative air mass, and the luminous efficacy of each component (lm/W)."""

    zenith: np.ndarray
    apparent_zenith: np.ndarray
    azimuth: np.ndarray
    dni_extra: np.ndarray
    airmass: np.ndarray
    k_beam: np.ndarray
    k_diffuse: np.ndarray
    k_global: np.ndarray


def _efficacy(lux: np.ndarray, watts: np.ndarray) -> np.ndarray:
    ok = watts >= MIN_IRRADIANCE
    k = np.full(len(lux), np.median(lux[ok] / watts[ok]) if ok.any() else 110.0)
    k[ok] = lux[ok] / watts[ok]
    return k


def sun_and_sky(weather: Weather) -> SunAndSky:
    """Sun positions at mid-hour and the component efficacies of ``weather``."""
    pvlib = require_pvlib()
    mid = weather.midpoints
    with warnings.catch_warnings():
        # pvlib's own use of pandas APIs that pandas deprecates: not the user's concern.
        warnings.simplefilter("ignore", DeprecationWarning)
        pos = pvlib.solarposition.get_solarposition(
            mid, weather.latitude, weather.longitude, altitude=weather.altitude
        )
        extra = np.asarray(pvlib.irradiance.get_extra_radiation(mid), dtype=float)
    airmass = np.asarray(pvlib.atmosphere.get_relative_airmass(pos["apparent_zenith"]), dtype=float)
    return SunAndSky(
        np.asarray(pos["zenith"], dtype=float),
        np.asarray(pos["apparent_zenith"], dtype=float),
        np.asarray(pos["azimuth"], dtype=float),
        extra,
        np.nan_to_num(airmass, nan=0.0),
        _efficacy(weather.dn_lux, weather.dni),
        _efficacy(weather.dh_lux, weather.dhi),
        _efficacy(weather.gh_lux, weather.ghi),
    )


def orientation(normal: np.ndarray, north_deg: float = 0.0) -> tuple[float, float]:
    """(tilt, compass azimuth) in degrees of an outward unit ``normal`` in scene axes:
    tilt from the zenith, azimuth clockwise from north (pvlib's convention)."""
    n = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    tilt = math.degrees(math.acos(max(-1.0, min(1.0, n[2]))))
    if math.hypot(n[0], n[1]) < 1e-9:
        return tilt, 180.0  # horizontal: any azimuth; pvlib's default faces south
    bearing = math.degrees(math.atan2(n[0], n[1]))  # from +y towards +x
    return tilt, (bearing + north_deg) % 360.0


def plane_irradiance(
    weather: Weather, sky: SunAndSky, tilt: float, azimuth: float, ground_reflectance: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(beam, sky diffuse, ground) irradiance (W/m²) per hour on the plane."""
    pvlib = require_pvlib()
    if not 0 <= ground_reflectance < 1:
        raise WeatherError(
            f"ground reflectance must be from 0 to below 1, got {ground_reflectance}"
        )
    aoi = np.asarray(pvlib.irradiance.aoi(tilt, azimuth, sky.zenith, sky.azimuth), dtype=float)
    # As pvlib: no horizon test, since the file's DNI of an hour the sun rises in is
    # real even when the sun is still below the horizon at mid-hour.
    beam = weather.dni * np.maximum(np.cos(np.radians(aoi)), 0.0)
    diffuse = np.asarray(
        pvlib.irradiance.perez(
            tilt,
            azimuth,
            weather.dhi,
            weather.dni,
            sky.dni_extra,
            sky.zenith,
            sky.azimuth,
            sky.airmass,
        ),
        dtype=float,
    )
    diffuse = np.where(np.isfinite(diffuse), np.maximum(diffuse, 0.0), 0.0)
    ground = weather.ghi * ground_reflectance * (1 - math.cos(math.radians(tilt))) / 2
    return beam, diffuse, ground


def plane_illuminance(
    weather: Weather,
    sky: SunAndSky,
    normal: np.ndarray,
    ground_reflectance: float = 0.2,
    north_deg: float = 0.0,
) -> np.ndarray:
    """Exterior illuminance (lux) per hour on a plane with outward unit ``normal``."""
    tilt, azimuth = orientation(normal, north_deg)
    beam, diffuse, ground = plane_irradiance(weather, sky, tilt, azimuth, ground_reflectance)
    return sky.k_beam * beam + sky.k_diffuse * diffuse + sky.k_global * ground
