"""Continuous daylight autonomy cDA300 of a layout over the occupied hours (issue #30):
the mean over the hours of min(E / 300 lux, 1) per receiver (Rogers 2006;
``climate.sun_metrics.continuous_da`` is the definition the tests compare with).

The light is what DA reads: each diffusing sky group's coefficients times the exterior
illuminance on its plane, plus the clear glazing's light with the LM-83 blinds. With one
sky group alone the year is not walked hour by hour: a receiver of coefficient a gets
a E(t) / 300 below the hour where a E = 300 and 1 above, so its sum is a prefix sum of
the sorted exterior illuminance up to one ``searchsorted``.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.climate.sun_metrics import CDA_THRESHOLD


def cda(light, idx=slice(None), threshold: float = CDA_THRESHOLD) -> np.ndarray:
    """(R', m) cDA (0-1) at receivers idx of ``light`` (a ``ScenarioLight``)."""
    a = light.coefficients(idx)  # (R', m, G)
    if not light.daylit:
        return np.zeros(a.shape[:2])
    year = light.year()
    fixed = light.clear_hours(idx)  # (R', T) or None
    if fixed is None and a.shape[-1] == 1 and year.sorted is not None:
        a0 = a[..., 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            cut = np.where(a0 > 0, threshold / np.where(a0 > 0, a0, 1.0), np.inf)
        k = np.searchsorted(year.sorted, cut, side="left")  # hours below the cut
        below = a0 * year.prefix[k] / threshold
        return (below + (year.hours - k)) / year.hours
    moving = fixed is not None and fixed.ndim == 3  # (R', m, T): clear shapes that move
    if a.shape[-1] == 0:  # clear glazing alone
        own = np.clip(fixed / threshold, 0.0, 1.0).mean(axis=-1)
        return own if moving else np.repeat(own[:, None], a.shape[1], axis=1)
    out = np.empty(a.shape[:2])
    for j in range(a.shape[1]):
        lux = a[:, j, :] @ year.exterior
        if fixed is not None:
            lux = lux + (fixed[:, j] if moving else fixed)
        out[:, j] = np.clip(lux / threshold, 0.0, 1.0).mean(axis=1)
    return out
