"""EN 17037 sunlight exposure at the design's observers (issue #30, docs/daylight.md
"EN 17037 in a project").

An observer's eye is the reference point the designer places (put it just inside the
window, 1.2 m up, as the standard's reference point). On ``daylight.sunlight_date`` the
sun is followed minute by minute (``climate.en17037.sunlight_exposure``: pvlib's sun at
the weather file's site, local standard time of its time zone) and counted while it is
above ``daylight.sunlight_min_altitude`` and seen from the eye through the design's
clear glazing with nothing in the way inside or out (``transport.clear_glazing.
exit_pane``: the ray leaves through a clear pane, unobstructed beyond). Diffusing
glazing shows no sun. The hours do not depend on the candidates (the clear glazing is
fixed), so they are computed once per design and remembered.
"""

from __future__ import annotations

import datetime
import weakref

import numpy as np

from lightinv_core.climate.en17037 import sunlight_exposure
from lightinv_core.design.model import Design, DesignError
from lightinv_core.light.arrays import caster_for
from lightinv_core.light.clear_build import clear_glass
from lightinv_core.light.clear_glazing import clear_sources
from lightinv_core.light.daylight_year import weather_path
from lightinv_core.light.glare import observer_eyes
from lightinv_core.transport.clear_glazing import exit_pane, to_scene

STEP_MINUTES = 1.0
"""The time step the sun is followed in (the test against a closed form: within 1 min)."""

_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def sunlight_day(design: Design) -> datetime.date:
    """The day of ``daylight.sunlight_date`` (DesignError when it is not MM-DD)."""
    text = design.daylight.sunlight_date
    try:
        month, day = (int(p) for p in str(text).split("-"))
        return datetime.date(2001, month, day)
    except ValueError:
        raise DesignError(
            f"daylight sunlight_date must be MM-DD (02-01 to 03-21), got {text!r}"
        ) from None


def observer_sunlight(light, design: Design) -> dict[str, dict]:
    """{observer: {"hours", "level", "sun_hours", "date", "min_altitude_deg"}} at every
    observer of ``design`` on ``light`` (a ``LightModel``), remembered per design."""
    memo = _CACHE.setdefault(light.op, {})
    key = (design.observers, clear_sources(design), design.daylight)
    if key not in memo:
        memo.clear()
        memo[key] = _compute(light, design)
    return memo[key]


def _compute(light, design: Design) -> dict[str, dict]:
    from lightinv_core.climate.weather import load_weather
    from lightinv_core.light.clear_glazing import clear_transmittance

    d = design.daylight
    if d.sunlight_min_altitude is None:
        raise DesignError(
            "EN 17037 sunlight exposure counts the sun above the site's minimum altitude "
            "(the standard's national value): set daylight sunlight_min_altitude (degrees)"
        )
    day = sunlight_day(design)
    eyes = observer_eyes(light.patches, design.observers)
    weather = load_weather(weather_path(d))
    sources = clear_sources(design)
    if sources:
        glass = clear_glass(light, sources, clear_transmittance(d))
        caster = caster_for(light.patches)
    out = {}
    for name, eye in zip(eyes.names, eyes.points, strict=True):

        def visible(directions, eye=eye):
            if not sources:
                return np.zeros(len(directions), bool)  # no clear glass: no sun seen
            dirs = to_scene(np.asarray(directions, float).reshape(-1, 3), d.north_deg)
            got, _ = exit_pane(np.broadcast_to(eye, dirs.shape), dirs, light.patches, glass, caster)
            return got >= 0

        try:
            got = sunlight_exposure(
                visible,
                weather.latitude,
                weather.longitude,
                day,
                min_altitude_deg=float(d.sunlight_min_altitude),
                step_minutes=STEP_MINUTES,
                utc_offset_h=weather.utc_offset_h,
            )
        except DesignError:
            raise
        except Exception as exc:  # the date outside 1 February - 21 March, a bad site
            raise DesignError(f"EN 17037 sunlight exposure: {exc}") from None
        out[name] = {
            "hours": float(got.hours),
            "level": got.level,
            "sun_hours": float(got.sun_hours),
            "date": got.date.isoformat()[5:],
            "min_altitude_deg": got.min_altitude_deg,
        }
    return out


def sunlight_values(light, design: Design, names) -> np.ndarray:
    """(k,) hours of sunlight exposure at the observers ``names``."""
    got = observer_sunlight(light, design)
    return np.array([got[n]["hours"] for n in names], dtype=float)
