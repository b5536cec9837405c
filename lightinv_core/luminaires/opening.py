"""A luminous opening as point sources: where a large luminaire's light leaves it.

The inverse-square law of a photometric table holds beyond about five times the
luminous opening (the "five-times rule"). Nearer, a large opening is modelled as
several point sources, each carrying an equal share of the intensity: the opening is
cut into cells of equal area no wider than ``segment`` and each cell's point is its
centroid. The shape follows IES LM-63's codes for (width, length) (docs/photometry.md):

- a **rectangle** (width and length >= 0): ``ceil(side / segment)`` equal parts along
  each side, points at the parts' centres. A horizontal cylinder (one of width and length
  negative) is its footprint ``|width| x |length|``.
- a **circle or ellipse** (width and length both negative: diameters ``|length|`` along
  C0 and ``|width|`` along C90; also LM-63's spheres and vertical cylinders, seen from
  below): a centre disc and ``m`` rings of 6, 12, ..., 6m equal sectors, 1 + 3m(m + 1)
  cells of equal area; ring radii follow from the areas, each point is its sector's
  centroid; ``m`` is the fewest rings whose outer sectors' arcs are at most ``segment``
  (0.3175 m: 7 points, 0.6 m: 19, 1 m: 37). An ellipse is the circle's pattern
  stretched, which keeps the areas equal. A diameter up to ``segment`` is one point, as
  a rectangle's side is.

The points' offsets are in the opening's own frame (along C0, along C90), metres; the
caller places them (``transport.luminaires.PlacedLuminaire.segments``).
"""

from __future__ import annotations

import math

import numpy as np


def is_round(opening: tuple[float, ...]) -> bool:
    """Whether LM-63's (width, length, height) codes a circle or ellipse (both negative)."""
    return opening[0] < 0 and opening[1] < 0


def opening_points(opening: tuple[float, ...], segment: float) -> np.ndarray:
    """(k, 2) offsets (m) along C0 and C90 of the k equal-area point sources of the
    luminous ``opening`` (width, length, ...) in LM-63's codes (see the module); each
    carries 1/k of the intensity. Their mean is the opening's centre."""
    width, length = float(opening[0]), float(opening[1])
    if is_round(opening):
        unit = _disc_points(_rings(max(-width, -length), segment))
        return unit * np.array([-length / 2.0, -width / 2.0])
    return _rectangle_points(abs(width), abs(length), segment)


def _rectangle_points(width: float, length: float, segment: float) -> np.ndarray:
    n_len = max(1, math.ceil(length / segment - 1e-9))
    n_wid = max(1, math.ceil(width / segment - 1e-9))
    a = ((np.arange(n_len) + 0.5) / n_len - 0.5) * length
    b = ((np.arange(n_wid) + 0.5) / n_wid - 0.5) * width
    ga, gb = np.meshgrid(a, b, indexing="ij")
    return np.column_stack([ga.reshape(-1), gb.reshape(-1)])


def _rings(diameter: float, segment: float) -> int:
    """Rings around the centre disc: none up to ``segment``, else the fewest whose
    outer sectors' arcs (pi D / 6m) are at most ``segment``."""
    if diameter <= segment * (1 + 1e-9):
        return 0
    return max(1, math.ceil(math.pi * diameter / (6.0 * segment) - 1e-9))


def _disc_points(m: int) -> np.ndarray:
    """Centroids of the 1 + 3m(m + 1) equal-area cells of the unit disc: the centre
    disc and ring j = 1..m of 6j sectors, the sectors centred at half-steps of angle
    (so the set is mirror symmetric about both axes, like quadrant-symmetric tables)."""
    total = 1 + 3 * m * (m + 1)
    points = [np.zeros((1, 2))]
    for j in range(1, m + 1):
        r1 = math.sqrt((1 + 3 * (j - 1) * j) / total)  # cells inside ring j
        r2 = math.sqrt((1 + 3 * j * (j + 1)) / total)
        n = 6 * j
        half = math.pi / n  # half a sector's angle
        rho = 2.0 / 3.0 * (r2**3 - r1**3) / (r2**2 - r1**2) * math.sin(half) / half
        phi = (np.arange(n) + 0.5) * (2.0 * half)
        points.append(rho * np.column_stack([np.cos(phi), np.sin(phi)]))
    return np.vstack(points)
