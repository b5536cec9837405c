"""Radiance as the independent reference for LightInv's daylight (issue #30, item 7).

A test and bench helper, never needed at run time: it needs the ``pyradiance`` wheel
(dev extra), whose Radiance binaries it runs. See ``docs/daylight.md``, "Radiance as
the reference (issue #30)".

- ``scene``: ``write_scene`` (patches -> .rad), ``glass_transmissivity`` and the skies
  ``sky_cie_clear``, ``sky_cie_overcast``, ``sky_perez``, ``sky_sun_only``;
- ``run``: ``point_lux`` (rtrace) and ``annual_lux`` (two-phase daylight coefficients);
- ``rooms``: the small box rooms with a window or a rooflight and their work plane.
"""

from tests.radiance.rooms import box_room, rooflight_room, window_office, work_plane
from tests.radiance.run import annual_lux, point_lux, radiance_env, read_matrix
from tests.radiance.scene import (
    EFFICACY,
    glass_transmissivity,
    sky_cie_clear,
    sky_cie_overcast,
    sky_perez,
    sky_sun_only,
    sun_direction,
    write_scene,
)

__all__ = [
    "EFFICACY",
    "annual_lux",
    "box_room",
    "glass_transmissivity",
    "point_lux",
    "radiance_env",
    "read_matrix",
    "rooflight_room",
    "sky_cie_clear",
    "sky_cie_overcast",
    "sky_perez",
    "sky_sun_only",
    "sun_direction",
    "window_office",
    "work_plane",
    "write_scene",
]
