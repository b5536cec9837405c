"""The sky hemisphere split into patches: Tregenza's 145 and Reinhart's subdivisions.

Frame: geographic, x east, y north, z up. Azimuth is the compass bearing, clockwise
from north (pvlib's convention); altitude is above the horizon. A direction is

    (cos(alt) sin(az), cos(alt) cos(az), sin(alt)).

Reinhart's subdivision with factor ``mf`` (Tregenza when mf = 1) has ``7 mf`` bands of
``alpha = 90 / (7 mf + 0.5)`` degrees from the horizon up, band ``r`` holding
``mf * (30, 30, 24, 24, 18, 12, 6)[r // mf]`` patches, and a zenith cap of half a
band (84 to 90 degrees for Tregenza): ``144 mf^2 + 1`` patches in all.

Patch order is Radiance's (``reinhart.cal`` / ``reinhartb.cal`` / ``tregenza.cal`` and
``gendaymtx``): from the horizon band up, and within a band from the patch centred due
north, turning east (clockwise seen from above); the cap is last. Patch ``k`` here is
``rbin = k`` of ``reinhartb.cal`` and row ``k + 1`` of a ``gendaymtx`` sky vector
(whose row 0 is the ground), so ``vector[1:]`` lines up with the dome.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import LightInvError

_TREGENZA_ROW_COUNTS = (30, 30, 24, 24, 18, 12, 6)


def unit_directions(altitude_deg: np.ndarray, azimuth_deg: np.ndarray) -> np.ndarray:
    """Unit vectors (..., 3) for compass azimuths and altitudes in degrees."""
    alt = np.radians(altitude_deg)
    az = np.radians(azimuth_deg)
    return np.stack([np.cos(alt) * np.sin(az), np.cos(alt) * np.cos(az), np.sin(alt)], axis=-1)


def altitude_azimuth(directions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Altitude (degrees, -90..90) and compass azimuth (degrees, 0..360) of unit
    ``directions`` (m, 3)."""
    d = np.asarray(directions, dtype=float)
    alt = np.degrees(np.arcsin(np.clip(d[..., 2], -1.0, 1.0)))
    az = np.mod(np.degrees(np.arctan2(d[..., 0], d[..., 1])), 360.0)
    return alt, az


@dataclass(frozen=True)
class SkyDome:
    """Patches of the upper hemisphere (see the module docstring for the order)."""

    directions: np.ndarray
    """(K, 3) unit vectors to the patch centres (mid altitude, mid azimuth; the cap's
    centre is the zenith)."""
    solid_angles: np.ndarray
    """(K,) sr; they sum to 2 pi."""
    altitude: np.ndarray
    """(K, 2) lower and upper altitude of each patch, degrees."""
    azimuth: np.ndarray
    """(K, 2) start and end compass azimuth, degrees; the patch centred due north
    starts below 0 (e.g. -6..6), the zenith cap is 0..360."""
    mf: int
    """Reinhart's subdivision factor (1: Tregenza)."""

    @property
    def count(self) -> int:
        return int(self.solid_angles.shape[0])

    @property
    def horizontal_solid_angles(self) -> np.ndarray:
        """(K,) the integral of sin(alt) d omega over each patch (sr): the patch's
        solid angle projected on the horizontal; they sum to pi."""
        s0 = np.sin(np.radians(self.altitude[:, 0]))
        s1 = np.sin(np.radians(self.altitude[:, 1]))
        width = np.radians(self.azimuth[:, 1] - self.azimuth[:, 0])
        return 0.5 * width * (s1**2 - s0**2)

    def radiance_rows(self) -> np.ndarray:
        """(K,) the row of each patch in a Radiance ``gendaymtx`` sky vector (row 0 is
        the ground); equal to the ``rbin`` of ``reinhartb.cal`` plus one."""
        return np.arange(self.count) + 1

    def patch_of(self, directions: np.ndarray) -> np.ndarray:
        """(m,) patch index of unit ``directions`` (m, 3); -1 at or below the horizon
        (as ``reinhartb.cal``, whose rbin is -1 for altitude <= 0)."""
        alt, az = altitude_azimuth(np.atleast_2d(directions))
        rows = 7 * self.mf
        alpha = 90.0 / (rows + 0.5)
        counts, first = _row_tables(self.mf)
        row = np.minimum(np.floor(alt / alpha).astype(int), rows)
        row = np.clip(row, 0, rows)
        n = counts[row]
        inc = 360.0 / n
        col = np.floor(np.mod(az + 0.5 * inc, 360.0) / inc).astype(int)
        col = np.minimum(col, n - 1)  # rounding at 360 exactly
        return np.where(alt > 0.0, first[row] + col, -1)

    def subsamples(self, per_side: int) -> tuple[np.ndarray, np.ndarray]:
        """Directions (K, s, 3) stratified inside each patch, s = per_side**2, and their
        solid-angle weights (K, s) summing to each patch's solid angle.

        Each patch is cut into per_side x per_side cells of equal sin(altitude) and
        azimuth steps, which have equal solid angles; a cell is represented by its
        centre in (sin(alt), azimuth)."""
        if per_side < 1:
            raise LightInvError(f"per_side must be at least 1, got {per_side}")
        u = (np.arange(per_side) + 0.5) / per_side
        s0 = np.sin(np.radians(self.altitude[:, :1]))
        s1 = np.sin(np.radians(self.altitude[:, 1:]))
        sin_alt = s0 + (s1 - s0) * u[None, :]  # (K, p)
        az = self.azimuth[:, :1] + (self.azimuth[:, 1:] - self.azimuth[:, :1]) * u
        sa = np.repeat(sin_alt, per_side, axis=1)  # (K, p*p): altitude major
        zz = np.tile(az, (1, per_side))
        ca = np.sqrt(np.maximum(1.0 - sa**2, 0.0))
        azr = np.radians(zz)
        dirs = np.stack([ca * np.sin(azr), ca * np.cos(azr), sa], axis=-1)
        weights = np.repeat(self.solid_angles[:, None] / per_side**2, per_side**2, 1)
        return dirs, weights


def _row_tables(mf: int) -> tuple[np.ndarray, np.ndarray]:
    """Patches per row (7 mf bands then the cap) and the index of each row's first
    patch."""
    counts = [mf * _TREGENZA_ROW_COUNTS[r // mf] for r in range(7 * mf)] + [1]
    counts_a = np.asarray(counts, dtype=int)
    first = np.concatenate([[0], np.cumsum(counts_a)[:-1]])
    return counts_a, first


def reinhart(mf: int) -> SkyDome:
    """Reinhart's subdivision: 144 mf^2 + 1 patches (mf = 1 is Tregenza's 145)."""
    if not (isinstance(mf, int) and 1 <= mf <= 64):
        raise LightInvError(f"Reinhart subdivision must be an integer 1..64, got {mf}")
    rows = 7 * mf
    alpha = 90.0 / (rows + 0.5)
    counts, _ = _row_tables(mf)
    alt_lo, alt_hi, az_lo, az_hi = [], [], [], []
    for r, n in enumerate(counts[:-1]):
        inc = 360.0 / n
        centres = np.arange(n) * inc
        alt_lo.append(np.full(n, r * alpha))
        alt_hi.append(np.full(n, (r + 1) * alpha))
        az_lo.append(centres - 0.5 * inc)
        az_hi.append(centres + 0.5 * inc)
    alt_lo.append(np.array([rows * alpha]))
    alt_hi.append(np.array([90.0]))
    az_lo.append(np.array([0.0]))
    az_hi.append(np.array([360.0]))
    altitude = np.stack([np.concatenate(alt_lo), np.concatenate(alt_hi)], axis=1)
    azimuth = np.stack([np.concatenate(az_lo), np.concatenate(az_hi)], axis=1)
    width = np.radians(azimuth[:, 1] - azimuth[:, 0])
    solid = width * (np.sin(np.radians(altitude[:, 1])) - np.sin(np.radians(altitude[:, 0])))
    centre_alt = altitude.mean(axis=1)
    centre_alt[-1] = 90.0
    centre_az = azimuth.mean(axis=1)
    centre_az[-1] = 0.0
    directions = unit_directions(centre_alt, centre_az)
    directions[-1] = (0.0, 0.0, 1.0)  # exactly the zenith
    return SkyDome(directions, solid, altitude, azimuth, mf)


def tregenza() -> SkyDome:
    """Tregenza's 145 patches: 7 bands of 12 degrees (30, 30, 24, 24, 18, 12, 6
    patches) and a zenith cap above 84 degrees."""
    return reinhart(1)


SUN_BASIS_MF = 2
"""Reinhart subdivision of the sun positions whose inter-reflected light is solved (a
study's clear year and a project's clear glazing alike)."""


def sun_bins(geo: np.ndarray, up: np.ndarray, mf: int = SUN_BASIS_MF):
    """The sun positions binned on Reinhart MF:``mf``: (S, 3) mean geographic direction
    of each bin some hour's sun falls in, and each hour's bin (H,) (-1 where ``up`` is
    False: the sun below the horizon). ``geo`` (H, 3) unit sun directions."""
    b = np.full(len(geo), -1)
    b[up] = reinhart(mf).patch_of(geo[up])
    used, inverse = np.unique(b[up], return_inverse=True)
    mean = np.zeros((len(used), 3))
    np.add.at(mean, inverse, geo[up])
    mean /= np.linalg.norm(mean, axis=1)[:, None]
    hour_bin = np.full(len(geo), -1)
    hour_bin[up] = inverse
    return mean, hour_bin
