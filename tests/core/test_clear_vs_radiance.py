"""Clear glazing side by side with Radiance (``rtrace``, tests/radiance): work-plane
illuminance in the two daylight rooms (a clear south window, a clear rooflight; glass of
transmittance 0.7) under the sun alone, the CIE clear sky alone, and both with the
ground, against ``rtrace -ab 10``.

Targets (issue #30): within 5% per point on average for the sun, 3% for the sky. Here a
few points keep it to seconds: the sun's with 4,096 hemisphere samples, the sky's with
16,384, as ``bench/peers.py`` runs every point (the figures docs/daylight.md quotes): at
4,096 the reference's own noise moved the side-lit room's sky mean error from 1.2% to
3.4% run to run, at 16,384 0.7-1.4% (eight and four runs).
"""

from __future__ import annotations

import pytest

from tests.radiance.compare import CASES, ROOMS, compare
from tests.radiance.run import POINT_PARAMS

ALLOWED = {"sun": 0.05, "sky": 0.03}
"""The sun and the sky apart in each room; ``bench/peers.py`` also runs them together
with the ground."""
PARAMS = {"sun": POINT_PARAMS.replace("-ad 16384", "-ad 4096"), "sky": POINT_PARAMS}


@pytest.mark.parametrize("case", ALLOWED)
@pytest.mark.parametrize("room", ROOMS)
def test_work_plane_light_against_rtrace(room, case):
    got = compare(room, case, every=6, params=PARAMS[case])
    if CASES[case][1]:  # both suns are points (the harness traces -dj 0)
        assert (got["sunlit_ours"] == got["sunlit_theirs"]).all()
    assert got["error"].mean() < ALLOWED[case], (got["error"].mean(), got["error"].max())
