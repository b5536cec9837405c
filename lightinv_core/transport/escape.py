"""Luminaires whose light mostly leaves the model: outside the room, inside a solid, or
behind a surface that faces away from them.

Light a luminaire sends towards nothing, or onto the back of a face, is lost to the
model: such a luminaire lights little or nothing, which the user must hear about rather
than read as a dark result. ``escaping_fraction`` traces rays from a luminaire's
photometric centre in ``ESCAPE_RAYS`` directions of equal solid angle (a Fibonacci
sphere) and weighs each by the intensity sent that way: the result is the share of its
flux that meets no front face. ``luminaire_escape_warnings`` names every luminaire of which more
than ``ESCAPE_LIMIT`` is lost; the command line, the window and the report show them.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from lightinv_core.transport.luminaires import PlacedLuminaire
from lightinv_core.transport.raycast import RayCaster

ESCAPE_RAYS = 4096
"""Directions traced per luminaire (equal solid angle each)."""
ESCAPE_LIMIT = 0.5
"""A luminaire losing more than this share of its flux is named in a warning."""


def sphere_directions(n: int = ESCAPE_RAYS) -> np.ndarray:
    """(n, 3) unit directions spread evenly over the sphere (Fibonacci lattice), each
    standing for 4 pi / n sr."""
    k = np.arange(n) + 0.5
    z = 1.0 - 2.0 * k / n
    r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    phi = np.pi * (3.0 - np.sqrt(5.0)) * k
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def escaping_fraction(lum: PlacedLuminaire, caster: RayCaster, n: int = ESCAPE_RAYS) -> float:
    """Share of ``lum``'s flux that meets no surface or only a surface's back (0 to 1);
    0 for a luminaire that emits nothing."""
    d = sphere_directions(n)
    weight = np.asarray(lum.intensity(d), dtype=float)
    total = float(weight.sum())
    if not total > 0:
        return 0.0
    hit = caster.hit_patches(np.broadcast_to(lum.position, d.shape), d)
    return float(weight[hit < 0].sum() / total)


def luminaire_warning(lum: PlacedLuminaire, lost: float) -> str | None:
    """The warning for ``lum`` losing share ``lost`` of its flux, or None if it keeps
    at least half of it."""
    if not lost > ESCAPE_LIMIT:
        return None
    x, y, z = (float(c) for c in lum.position)
    return (
        f"luminaire {lum.name!r} at ({x:.2f}, {y:.2f}, {z:.2f}) m: {100 * lost:.0f}% of its "
        "light leaves the model or meets the back of a surface; it lights little or "
        "nothing. Is it outside the room, inside a solid or behind a surface facing away?"
    )


def luminaire_escape_warnings(
    luminaires: Iterable[PlacedLuminaire], caster: RayCaster
) -> list[str]:
    """A warning naming each of ``luminaires`` whose light mostly leaves the model."""
    out = []
    for lum in luminaires:
        msg = luminaire_warning(lum, escaping_fraction(lum, caster))
        if msg:
            out.append(msg)
    return out
