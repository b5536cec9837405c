"""Geometry helpers for building scenes from axis-aligned rooms, boxes and panels.

All sizes in metres, z up. Rooms face inwards (normals into the room), solid
boxes face outwards.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import SceneError
from lightinv_core.scene.model import EmitterZone, Rect, Surface


@dataclass(frozen=True)
class Insert:
    """A sub-rectangle of a base rectangle, in metres along the base's (u, v) edges.

    ``group=None`` makes a hole (nothing is emitted there, e.g. where a column
    stands on the floor). ``zone`` names an emitter zone of kind ``zone_kind``.
    """

    name: str
    u0: float
    v0: float
    u1: float
    v1: float
    group: str | None = None
    reflectance: float | None = None
    zone_kind: str | None = None
    grid: tuple[int, int] | None = None


def split_rect(
    name: str, group: str, reflectance: float, rect: Rect, inserts: list[Insert] = ()
) -> tuple[list[Surface], list[EmitterZone]]:
    """Split ``rect`` into the inserts and the remaining cells around them.

    Each insert becomes one rectangular surface (so an emitter zone is a single
    regular grid); the rest of the base is cut along the inserts' edges into
    rectangles named ``name``, ``name.1``, ...
    """
    su, sv = rect.size
    for ins in inserts:
        if not (0 <= ins.u0 < ins.u1 <= su + 1e-9 and 0 <= ins.v0 < ins.v1 <= sv + 1e-9):
            raise SceneError(f"insert {ins.name!r} lies outside surface {name!r}")
    for a in range(len(inserts)):
        for b in range(a + 1, len(inserts)):
            p, q = inserts[a], inserts[b]
            if p.u0 < q.u1 and q.u0 < p.u1 and p.v0 < q.v1 and q.v0 < p.v1:
                raise SceneError(f"inserts {p.name!r} and {q.name!r} overlap in {name!r}")
    us = sorted({0.0, su, *[i.u0 for i in inserts], *[i.u1 for i in inserts]})
    vs = sorted({0.0, sv, *[i.v0 for i in inserts], *[i.v1 for i in inserts]})
    surfaces: list[Surface] = []
    zones: list[EmitterZone] = []
    for ins in inserts:
        if ins.group is None:
            continue
        sub = rect.sub(ins.u0 / su, ins.v0 / sv, ins.u1 / su, ins.v1 / sv)
        rho = reflectance if ins.reflectance is None else ins.reflectance
        surfaces.append(Surface(ins.name, ins.group, rho, rect=sub, grid=ins.grid))
        if ins.zone_kind is not None:
            zones.append(EmitterZone(ins.name, ins.zone_kind, ins.name))
    k = 0
    for a, b in itertools.pairwise(us):
        for c, d in itertools.pairwise(vs):
            if b - a < 1e-9 or d - c < 1e-9:
                continue
            um, vm = 0.5 * (a + b), 0.5 * (c + d)
            if any(i.u0 <= um <= i.u1 and i.v0 <= vm <= i.v1 for i in inserts):
                continue
            cell_name = name if k == 0 else f"{name}.{k}"
            surfaces.append(
                Surface(
                    cell_name, group, reflectance, rect=rect.sub(a / su, c / sv, b / su, d / sv)
                )
            )
            k += 1
    return surfaces, zones


def room_faces(x0: float, y0: float, z0: float, x1: float, y1: float, z1: float) -> dict[str, Rect]:
    """The six inward-facing faces of an axis-aligned room.

    Keys: floor, ceiling, south (y = y0), north (y = y1), west (x = x0), east (x = x1).
    For floor and ceiling, u runs along +x and v along y (so zone coordinates
    read like a plan view).
    """
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    return {
        "floor": Rect((x0, y0, z0), (dx, 0, 0), (0, dy, 0)),
        "ceiling": Rect((x0, y1, z1), (dx, 0, 0), (0, -dy, 0)),
        "south": Rect((x0, y0, z0), (0, 0, dz), (dx, 0, 0)),
        "north": Rect((x0, y1, z0), (dx, 0, 0), (0, 0, dz)),
        "west": Rect((x0, y0, z0), (0, dy, 0), (0, 0, dz)),
        "east": Rect((x1, y0, z0), (0, 0, dz), (0, dy, 0)),
    }


def box_faces(
    x0: float, y0: float, z0: float, x1: float, y1: float, z1: float, skip: tuple[str, ...] = ()
) -> dict[str, Rect]:
    """The outward-facing faces of a solid axis-aligned box (keys as ``room_faces``,
    with ``top`` and ``bottom``), leaving out the faces named in ``skip``."""
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    faces = {
        "bottom": Rect((x0, y0, z0), (0, dy, 0), (dx, 0, 0)),
        "top": Rect((x0, y0, z1), (dx, 0, 0), (0, dy, 0)),
        "south": Rect((x0, y0, z0), (dx, 0, 0), (0, 0, dz)),
        "north": Rect((x0, y1, z0), (0, 0, dz), (dx, 0, 0)),
        "west": Rect((x0, y0, z0), (0, 0, dz), (0, dy, 0)),
        "east": Rect((x1, y0, z0), (0, dy, 0), (0, 0, dz)),
    }
    return {k: v for k, v in faces.items() if k not in skip}


def box_surfaces(
    name: str,
    group: str,
    reflectance: float,
    lo,
    hi,
    skip: tuple[str, ...] = (),
    top_group: str | None = None,
) -> list[Surface]:
    """Surfaces of a solid box from corner ``lo`` to ``hi``; the top face may get its own group."""
    out = []
    for face, rect in box_faces(*lo, *hi, skip=skip).items():
        g = top_group if (face == "top" and top_group) else group
        out.append(Surface(f"{name}.{face}", g, reflectance, rect=rect))
    return out


def footprint_holes(
    prefix: str,
    boxes: list[tuple[np.ndarray, np.ndarray]],
    origin_xy: tuple[float, float],
    flip_y_from: float | None = None,
) -> list[Insert]:
    """Holes in a floor (or ceiling) under the footprints of boxes touching it.

    ``origin_xy`` is the floor rectangle's origin; for a ceiling whose v axis
    runs along -y from ``flip_y_from``, pass that y so the holes land right.
    """
    holes = []
    for k, (lo, hi) in enumerate(boxes):
        u0, u1 = lo[0] - origin_xy[0], hi[0] - origin_xy[0]
        if flip_y_from is None:
            v0, v1 = lo[1] - origin_xy[1], hi[1] - origin_xy[1]
        else:
            v0, v1 = flip_y_from - hi[1], flip_y_from - lo[1]
        holes.append(Insert(f"{prefix}{k}", u0, v0, u1, v1, group=None))
    return holes
