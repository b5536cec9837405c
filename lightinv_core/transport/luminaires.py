"""Direct light of photometric luminaires: point sources with an intensity table,
oriented in the room, seen through shadow rays.

A luminaire sits at ``position`` (its photometric centre, m). Its ``aim`` is the
direction of gamma = 0 (straight down for a downlight) and ``c0`` the direction of
the C = 0 half-plane (along a linear luminaire); C = 90 lies along ``-aim x c0``,
so C grows counter-clockwise seen from the side the light leaves from, as in
IES LM-63 and EULUMDAT. The illuminance it gives a surface point ``p`` with unit
normal ``n`` is ``I(C, gamma) cos(theta) / d²`` (lux) if the segment between them is
clear, with ``d`` the distance, ``theta`` the angle of incidence and ``I`` in cd
times the luminaire's ``dimming``.

The point-source law holds beyond about five times the luminous opening (the
"five-times rule"). A luminaire whose opening is longer or wider than ``SEGMENT`` is
therefore split into cells of equal area, each a point source with its share of the
intensity (as lighting programs do for linear luminaires): a 1.2 m batwing becomes 6
sources 0.2 m apart, exact beyond 1 m; a round opening (IES width and length
negative) becomes points on its disc, a 0.6 m one 19 (``luminaires.opening``). Place
the photometric centre at least a centimetre off the mounting surface: a point source
on a surface lights it at grazing angles.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.luminaires.opening import opening_points
from lightinv_core.luminaires.photometry import Photometry
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.raycast import RayCaster, patch_points

MIN_DISTANCE = 1e-3
"""Metres; nearer points are treated as this far, so the 1/d² law stays finite."""
SEGMENT = 0.2
"""Metres; the longest piece of a luminous opening treated as one point source."""
DIRECT_SAMPLES = 16
"""Points per patch at which direct light is sampled (stratified; a 4 x 4 grid)."""


def _unit(v, what: str) -> np.ndarray:
    try:
        a = np.asarray(v, dtype=float).reshape(3)
    except (TypeError, ValueError):
        raise LightInvError(f"{what} must be three numbers, got {v!r}") from None
    norm = float(np.linalg.norm(a))
    if not np.isfinite(norm) or norm == 0.0:
        raise LightInvError(f"{what} must be a non-zero finite direction, got {a.tolist()}")
    return a / norm


@dataclass(frozen=True, eq=False)
class PlacedLuminaire:
    """A photometric luminaire in the room (see the module for the conventions).

    ``c0`` need not be exactly perpendicular to ``aim``: its part along ``aim`` is
    removed. ``dimming`` scales the intensities (1 = the photometric file's values).
    """

    name: str
    position: np.ndarray
    photometry: Photometry
    aim: np.ndarray = (0.0, 0.0, -1.0)
    c0: np.ndarray = (1.0, 0.0, 0.0)
    dimming: float = 1.0
    control: str = ""  # its daylight-linked control group ("": the one default group)

    def __post_init__(self) -> None:
        where = f"luminaire {self.name!r}"
        pos = np.asarray(self.position, dtype=float).reshape(-1)
        if pos.shape != (3,) or not np.all(np.isfinite(pos)):
            raise LightInvError(f"{where}: position must be three finite numbers (m)")
        aim = _unit(self.aim, f"{where}: aim")
        c0 = _unit(self.c0, f"{where}: c0")
        c0 = c0 - (c0 @ aim) * aim
        if np.linalg.norm(c0) < 1e-6:
            raise LightInvError(
                f"{where}: c0 {np.round(self.c0, 6).tolist()} is parallel to the aim; give "
                "the direction of the C = 0 plane across the aim (e.g. along the luminaire)"
            )
        if not (isinstance(self.dimming, int | float) and 0.0 <= self.dimming <= 1.0):
            raise LightInvError(f"{where}: dimming must be from 0 to 1, got {self.dimming!r}")
        object.__setattr__(self, "position", pos)
        object.__setattr__(self, "aim", aim)
        object.__setattr__(self, "c0", c0 / np.linalg.norm(c0))

    @property
    def c90(self) -> np.ndarray:
        """Unit direction of the C = 90 half-plane: ``-aim x c0``."""
        return np.cross(-self.aim, self.c0)

    @property
    def segments(self) -> np.ndarray:
        """(k, 3) positions (m) of the point sources the opening is split into (see
        the module and ``luminaires.opening``); each carries 1/k of the intensity."""
        offsets = opening_points(self.photometry.opening, SEGMENT)
        return self.position + offsets[:, :1] * self.c0 + offsets[:, 1:] * self.c90

    @property
    def lumens(self) -> float:
        """Luminous flux it emits (lm), dimming included."""
        return self.dimming * self.photometry.flux()

    def angles(self, directions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(C, gamma) in degrees of unit ``directions`` (..., 3) leaving the luminaire."""
        d = np.asarray(directions, dtype=float)
        gamma = np.degrees(np.arccos(np.clip(d @ self.aim, -1.0, 1.0)))
        c = np.degrees(np.arctan2(d @ self.c90, d @ self.c0)) % 360.0
        return c, gamma

    def intensity(self, directions: np.ndarray) -> np.ndarray:
        """Intensity (cd) towards unit ``directions`` (..., 3), dimming included."""
        c, gamma = self.angles(directions)
        return self.dimming * self.photometry.intensity(c, gamma)

    def illuminance(
        self, points: np.ndarray, normals: np.ndarray, caster: RayCaster | None
    ) -> np.ndarray:
        """Direct illuminance (lux) at ``points`` (..., 3) facing unit ``normals``;
        with ``caster``, what a segment of the luminaire cannot see gets none of its
        light (shadow rays)."""
        points = np.asarray(points, dtype=float)
        normals = np.asarray(normals, dtype=float)
        segments = self.segments
        total = np.zeros(points.shape[:-1])
        for source in segments:
            total += self._point_source(source, points, normals, caster)
        return total / len(segments)

    def _point_source(
        self, source: np.ndarray, points: np.ndarray, normals: np.ndarray, caster
    ) -> np.ndarray:
        v = points - source
        dist = np.maximum(np.linalg.norm(v, axis=-1), MIN_DISTANCE)
        w = v / dist[..., None]
        cos_in = -np.einsum("...i,...i->...", w, normals)
        lux = np.where(cos_in > 0, self.intensity(w) * np.maximum(cos_in, 0) / dist**2, 0.0)
        if caster is None:
            return lux
        lit = np.flatnonzero(lux.reshape(-1) > 0)
        if len(lit):
            start = points.reshape(-1, 3)[lit] + caster.offset * normals.reshape(-1, 3)[lit]
            to_lum = source - start
            length = np.linalg.norm(to_lum, axis=1)
            # Stop short of the luminaire: its own mounting surface must not shade it.
            blocked = caster.occluded(
                start, to_lum / length[:, None], np.maximum(length - 2 * caster.offset, 0.0)
            )
            flat = lux.reshape(-1)
            flat[lit[blocked]] = 0.0
        return lux


def direct_on_patches(
    patches: Patches,
    luminaires: list[PlacedLuminaire],
    caster: RayCaster,
    samples: int = DIRECT_SAMPLES,
    seed: int = 0,
) -> np.ndarray:
    """Mean direct illuminance (lux) over each patch from all ``luminaires``, sampled
    at ``samples`` stratified points per patch with shadow rays. Cost: n * samples
    shadow rays per luminaire (lit points only)."""
    rng = np.random.default_rng(seed)
    H0 = np.zeros(patches.n)
    rows = np.arange(patches.n)
    block = max(1, 2**18 // samples)
    for start in range(0, patches.n, block):
        r = rows[start : start + block]
        pts = patch_points(patches, r, samples, rng)
        nrm = np.broadcast_to(patches.normal[r][:, None], pts.shape)
        for lum in luminaires:
            H0[r] += lum.illuminance(pts, nrm, caster).mean(axis=1)
    return H0


def direct_at_points(
    points: np.ndarray,
    normals: np.ndarray,
    luminaires: list[PlacedLuminaire],
    caster: RayCaster,
) -> np.ndarray:
    """Direct illuminance (lux) at receiver ``points`` (m, 3) facing ``normals``."""
    total = np.zeros(len(points))
    for lum in luminaires:
        total += lum.illuminance(np.asarray(points, float), np.asarray(normals, float), caster)
    return total
