"""Clear glazing in a forward simulation: the moment's sky and sun, and the year.

``simulate`` splits its glazing groups by kind (``kinds.GlazingKind``): diffusing
groups emit the light on their outside as before (``transport.glazing``); clear groups
are black inside and pass the sky and the sun by direction
(``transport.daylight_coefficients``). This module builds the moment's sky
(``study.point_sky``) and adds the clear groups' light to the patches and the work
plane.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.kinds import GlazingKind
from lightinv_core.study.point_sky import (
    PointSky,
    clear_sky,
    overcast_sky,
    plane_lux,
    weather_hour_sky,
)
from lightinv_core.transport.clear_glazing import to_geographic, to_scene
from lightinv_core.transport.daylight_coefficients import ClearDaylight

SKIES = ("cie-overcast", "cie-clear")
"""The point-in-time skies ``--sky`` names (a weather file's hour is ``--hour``)."""


def glazing_kind(name: str) -> str:
    """The glazing kind ``name`` (``kinds.GlazingKind``), or LightInvError listing them."""
    try:
        return str(GlazingKind(name))
    except ValueError:
        kinds = ", ".join(str(k) for k in GlazingKind)
        raise LightInvError(f"unknown glazing kind {name!r}: use one of {kinds}") from None


def split_glazing(
    glazing: dict[str, float], kinds: dict[str, str]
) -> tuple[dict[str, float], dict[str, float]]:
    """(diffusing, clear) glazing groups (name -> transmittance); a group not in
    ``kinds`` is diffusing."""
    unknown = sorted(set(kinds) - set(glazing))
    if unknown:
        raise LightInvError(f"glazing kind given for {unknown}, which are not glazing groups")
    clear = {g: t for g, t in glazing.items() if glazing_kind(kinds.get(g, "diffusing")) == "clear"}
    return {g: t for g, t in glazing.items() if g not in clear}, clear


def moment_sky(spec) -> PointSky | None:
    """The sky of one moment a ``SimulationSpec`` names: ``--sky`` or an ``--hour`` of
    its weather year; None when it names none."""
    if spec.hour is not None:
        if spec.annual is None:
            raise LightInvError("--hour is an hour of a weather file: give --weather FILE")
        if spec.sky:
            raise LightInvError("give either --sky or --hour, not both")
        from lightinv_core.climate.transposition import sun_and_sky
        from lightinv_core.climate.weather import load_weather
        from lightinv_core.light.daylight_year import weather_path

        weather = load_weather(weather_path(spec.annual))
        return weather_hour_sky(weather, sun_and_sky(weather), spec.hour, spec.ground_reflectance)
    if spec.sky == "cie-overcast":
        return overcast_sky(spec.exterior_lux, spec.ground_reflectance)
    if spec.sky == "cie-clear":
        if spec.sun is None:
            raise LightInvError("the CIE clear sky needs the sun: give --sun ALTITUDE,AZIMUTH")
        alt, az = spec.sun
        return clear_sky(alt, az, spec.exterior_lux, spec.sun_lux, spec.ground_reflectance)
    if spec.sky is not None:
        raise LightInvError(f"unknown sky {spec.sky!r}: use one of {', '.join(SKIES)}")
    return None


def outside_lux(sky: PointSky, north_deg: float):
    """A function of scene outward normals (m, 3) giving the lux on their outside."""

    def lux(normals: np.ndarray) -> np.ndarray:
        return plane_lux(sky, to_geographic(np.asarray(normals, float).reshape(-1, 3), north_deg))

    return lux


def clear_moment(
    clear: ClearDaylight, sky: PointSky, north_deg: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The clear glazing's light under ``sky``: (first-hit on the patches (n,), patches
    (n,), receivers (q,)) lux; the
    receivers' part is their direct view of the sky and sun only: the room's reflected
    light reaches them through the radiosity (its B gains rho x the patches' lux)."""

    def luminance(d):
        return sky.luminance(to_geographic(d, north_deg))

    sun = None if sky.sun is None else to_scene(sky.sun[None], north_deg)
    first, room = clear.room_under(luminance, sun, sky.sun_lux)
    points = clear.direct_under(luminance).sum(axis=0)
    if sun is not None and sky.sun_lux > 0:
        points = points + sky.sun_lux * clear.sun_direct(sun)[..., 0].sum(axis=0)
    return first, room, points


def clear_annual(spec, clear, orients, year):
    """The year through ``clear`` (a ``ClearDaylight`` on the work plane) with the
    diffusing glazing's ``orients`` and their ``GridYear`` ``year``: (``ClearYear``,
    summary for JSON, per-point columns), with glare at ``spec.views`` and EN 17037
    sunlight exposure at ``spec.sunlight_point`` when given."""
    from lightinv_core.study.clear_metrics import sunlight, view_metrics, work_plane_metrics
    from lightinv_core.study.clear_year import Receivers, clear_year
    from lightinv_core.study.daylight_criteria import judge
    from lightinv_core.transport.annual import orientation_coefficients
    from lightinv_core.transport.receivers import receiver_factors

    every = year.coefficients @ year.year.every if year is not None else None
    tilts = tuple(float(np.degrees(np.arccos(np.clip(o.outward[2], -1, 1)))) for o in orients)
    got = clear_year(clear, spec.annual, every, diffusing_tilts=tilts, sky_mf=spec.sky_mf)
    summary, columns = work_plane_metrics(got)
    if spec.views:
        v = np.asarray(spec.views, dtype=float)
        pts, nrm = v[:, :3], v[:, 3:] / np.linalg.norm(v[:, 3:], axis=1)[:, None]
        fac = receiver_factors(pts, nrm, clear.caster, clear.lit.n, spec.rays, spec.seed)
        views = ClearDaylight(clear.lit, clear.F, clear.caster, clear.glass, pts, nrm, fac)
        views.share_room(clear)
        other = None
        if orients:
            grid = Receivers(pts, nrm)
            c = orientation_coefficients(clear.lit, clear.F, clear.caster, orients, grid, fac)
            other = c @ year.year.every
        view_year = clear_year(views, spec.annual, other, diffusing_tilts=tilts, sky_mf=spec.sky_mf)
        rows = view_metrics(view_year, got)
        for row, view in zip(rows, spec.views, strict=True):
            row["view"] = list(view)
        summary["views"] = rows
    if spec.sunlight_point is not None:
        summary["en17037_sunlight"] = sunlight(
            spec.sunlight_point, clear, got, spec.sunlight_date, spec.sunlight_min_altitude
        )
    summary["criteria"] = [c.as_dict() for c in judge(summary)]
    return got, summary, columns


def clear_dimming(clear_year, electric: np.ndarray, watts: float, floor_m2: float, daylight):
    """Daylight-linked dimming (``climate.metrics.Dimming``) of luminaires giving
    ``electric`` (q,) lux at full output and drawing ``watts`` (W), on the mean daylight
    of the clear year's work plane in each occupied hour with the LM-83 blinds."""
    from lightinv_core.climate.metrics import dimming_energy
    from lightinv_core.study.clear_metrics import blinds

    cy = clear_year
    day = cy.total(blinds(cy))[:, cy.occupied].mean(axis=0)
    return dimming_energy(
        day,
        float(np.mean(electric)),
        daylight.target_lux,
        watts,
        floor_m2,
        daylight.min_level,
        daylight.standby_w,
        cy.open.shape[2],
    )
