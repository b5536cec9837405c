"""Clear glazing in a design: its daylight as fixed sky and sun columns (issue #30).

A clear skylight or window (``Source.glazing == "clear"``) passes the sky's luminance
pattern and the sun's beam by direction (``transport.clear_glazing``: Radiance's glass).
This version keeps clear glazing fixed (a clear source frees no variable), so its light
at the receivers is the same for every candidate: ``light.clear_build`` computes it
once per light model, clear sources, work planes and daylight settings.

Its light at a receiver in hour t is ``sum_k c_k w_k(t)`` over K columns, a block per
clear source (it has its own blinds):

- the sky patches (Tregenza's 145; Reinhart's 577 or 2,305 by
  ``daylight.sky_subdivision``), w_k(t) the patch's Perez luminance of the hour (cd/m²,
  scaled to the file's diffuse horizontal illuminance), and the ground, w = rho_g E_gh / pi;
- the sun's light reflected in the room, on a Reinhart MF:2 basis of sun positions
  (about 6 degrees; a bin's direction is the mean of its hours' suns), w = the hour's
  direct normal illuminance in its bin's column, 0 in the others;
- the sun's direct light: at the patches on the same bins; at work-plane points traced
  at each hour's own sun (``ClearLight.direct``, as ``study.clear_year`` does);
- its closed blinds (IES LM-83): the source glowing as diffusing glazing of
  ``BLIND_TRANSMITTANCE`` x its transmittance, w = the exterior lux on its plane.

``every`` holds the weights with the blinds open; ``blinds`` the weights as the LM-83
schedule sets them (the open columns 0 in the hours the blinds are closed, the closed
column 0 in the others). Annual light and dimming read ``blinds``, ASE the direct sun
with the blinds open. ``overcast`` (K,) is the CIE overcast sky per horizontal lux
(blinds open, no sun): the ``overcast`` and ``design`` scenarios light clear glazing
with it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from lightinv_core.design.model import Daylight, Design
from lightinv_core.kinds import GlazingKind
from lightinv_core.transport.clear_glazing import MAX_CLEAR_TRANSMITTANCE

BLIND_TRANSMITTANCE = 0.2
"""Share of a clear source's transmittance its closed blinds pass as a diffusing glow
(as ``study.clear_year``: LM-83 leaves the blind's optics to the modeller)."""


def is_clear(source) -> bool:
    """Whether ``source`` is clear glazing (a daylit source whose glazing is clear)."""
    return getattr(source, "glazing", None) == GlazingKind.CLEAR


def clear_sources(design: Design) -> tuple:
    """The design's clear glazing sources, in order."""
    return tuple(s for s in design.sources if is_clear(s))


def clear_transmittance(daylight: Daylight) -> float:
    """The clear glass's normal transmittance: ``daylight.transmittance``, capped (with a
    warning) at what glass can pass (``MAX_CLEAR_TRANSMITTANCE``)."""
    import warnings

    t = float(daylight.transmittance)
    if t > MAX_CLEAR_TRANSMITTANCE:
        warnings.warn(
            f"clear glazing: glass passes at most {MAX_CLEAR_TRANSMITTANCE:.3f} at normal "
            f"incidence; the transmittance {t:g} is taken as {MAX_CLEAR_TRANSMITTANCE:.3f}",
            stacklevel=2,
        )
    return min(t, MAX_CLEAR_TRANSMITTANCE)


@dataclass(frozen=True, eq=False)
class ClearColumns:
    """The K columns of the clear glazing's light: ``every`` (K, H) weights for every
    hour of the weather file with the blinds open, ``blinds`` (K, H) with the LM-83
    blinds, ``overcast`` (K,) the CIE overcast sky per horizontal lux, ``sun_direct``
    the indices of the sun's direct columns, ``closed`` (G, H) each source's blinds,
    ``outward`` (G, 3) each source's unit normal away from the room (None: unknown).
    The last G columns are the closed blinds' glow."""

    every: np.ndarray
    blinds: np.ndarray
    overcast: np.ndarray
    sun_direct: np.ndarray
    closed: np.ndarray
    outward: np.ndarray | None = None

    @property
    def count(self) -> int:
        """Number of columns K."""
        return self.every.shape[0]


@dataclass(frozen=True, eq=False)
class ClearLight:
    """The clear glazing's daylight at R receivers: ``coefficients`` (R, K) lux per unit
    of each column (``columns``), and ``direct`` (G, R_d, H) lux, each source's direct
    sun traced hour by hour at the last R_d receivers (work-plane points, whose sun
    columns are 0; None when none is traced)."""

    columns: ClearColumns
    coefficients: np.ndarray
    direct: np.ndarray | None = None
    _memo: dict = field(default_factory=dict, repr=False)

    def hours(self, idx, mask: np.ndarray, sun_only: bool = False) -> np.ndarray:
        """(R', T) lux at receivers idx in the hours of ``mask`` (the direct sun alone
        with ``sun_only``), remembered: every candidate reads the same."""
        key = (_index_key(idx), mask.tobytes(), sun_only)
        if key not in self._memo:
            if len(self._memo) >= 32:
                self._memo.clear()
            got = self.sun(idx, mask) if sun_only else self.lux(idx, mask)
            self._memo[key] = np.ascontiguousarray(got)
        return self._memo[key]

    def band(self, band, idx, mask: np.ndarray) -> np.ndarray:
        """(R',) an annual metric (``quantities.HourBand``) of this light alone."""
        key = (_index_key(idx), mask.tobytes(), band)
        if key not in self._memo:
            self._memo[key] = band.of_hours(self.hours(idx, mask, band.direct_sun))
        return self._memo[key]

    def open_hours(self, idx, mask: np.ndarray) -> np.ndarray:
        """(R', T) lux at receivers idx in the hours of ``mask`` with every blind open
        all year (EN 17037 counts the daylight available), remembered."""
        key = (_index_key(idx), mask.tobytes(), "open")
        if key not in self._memo:
            if len(self._memo) >= 32:
                self._memo.clear()
            c = self.columns
            k = c.count - c.closed.shape[0]  # without the closed blinds' glow
            out = self.coefficients[idx][:, :k] @ c.every[:k][:, mask]
            traced = self._traced(idx, mask, False)
            self._memo[key] = np.ascontiguousarray(out if traced is None else out + traced)
        return self._memo[key]

    def overcast(self, idx=slice(None)) -> np.ndarray:
        """(R',) lux per horizontal exterior lux under the CIE overcast sky."""
        return self.coefficients[idx] @ self.columns.overcast

    def _traced(self, idx, hours, blinds: bool) -> np.ndarray | None:
        """(R', h) the hour-by-hour direct sun at receivers idx (0 where not traced),
        with each source's blinds (closed: no beam) or open."""
        if self.direct is None:
            return None
        R, off = len(self.coefficients), len(self.coefficients) - self.direct.shape[1]
        rows = np.arange(R)[idx]
        h = np.arange(self.columns.every.shape[1])[hours]
        out = np.zeros((len(rows), len(h)))
        on = rows >= off
        for g, d in enumerate(self.direct):
            sun = d[rows[on] - off][:, h]
            out[on] += sun * ~self.columns.closed[g, h] if blinds else sun
        return out

    def sun(self, idx=slice(None), hours=slice(None)) -> np.ndarray:
        """(R', h) the direct sun alone (lux) in ``hours``, blinds open (ASE)."""
        c = self.columns
        out = self.coefficients[idx][:, c.sun_direct] @ c.every[c.sun_direct][:, hours]
        traced = self._traced(idx, hours, False)
        return out if traced is None else out + traced

    def lux(self, idx=slice(None), hours=slice(None)) -> np.ndarray:
        """(R', h) the clear glazing's daylight (lux) in ``hours``, sun included, with
        the LM-83 blinds."""
        out = self.coefficients[idx] @ self.columns.blinds[:, hours]
        traced = self._traced(idx, hours, True)
        return out if traced is None else out + traced


def stacked(patches: ClearLight, rows: np.ndarray, points: ClearLight | None) -> ClearLight:
    """The clear light at patches ``rows`` followed by the work-plane points (an
    optimisation level's receivers)."""
    coeffs = [patches.coefficients[rows]]
    direct = None
    if points is not None:
        coeffs.append(points.coefficients)
        direct = points.direct
    return ClearLight(patches.columns, np.concatenate(coeffs), direct)


def _index_key(idx) -> tuple:
    """A hashable key of receivers idx (a slice or an index array)."""
    if isinstance(idx, slice):
        return ("slice", idx.start, idx.stop, idx.step)
    a = np.asarray(idx)
    return ("rows", a.dtype.str, a.tobytes())


@dataclass(frozen=True, eq=False)
class ClearDesignLight:
    """The clear glazing of a design at its ``patches`` (n receivers) and its work-plane
    ``points`` (None without work planes), and the build's ``seconds``."""

    patches: ClearLight
    points: ClearLight | None
    seconds: float
