"""Work planes: horizontal calculation grids of receiver points, laid out by EN 12464-1.

A work plane lies ``height`` m above a floor group (default 0.8 m, the usual desk
height) over that floor's extent less a ``border`` band along the walls (default
0.5 m, the band EN 12464-1 leaves out of a room's calculation area). Its grid
follows by default EN 12464-1:2011, 4.4 (another edition's rule is passed in as
``counts``: ``GRID_RULES``): the largest spacing is

    p = 0.2 x 5^log10(d)    (m, and at most 10 m)

where d is the longer side of the calculation area, or the shorter if the longer is
twice it or more; each side gets ceil(side / p) points, at the centres of equal
cells. Points are kept where the floor group lies straight below them and
``border`` away in 16 directions (so L-shaped and round floors work),
and dropped where they sit inside a solid object (its back faces all around).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import LightInvError, SceneError
from lightinv_core.kinds import Edition
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.raycast import RayCaster

DEFAULT_HEIGHT = 0.8
DEFAULT_BORDER = 0.5
MAX_SPACING = 10.0
BORDER_DIRECTIONS = 16
"""Directions in which a point must have floor a border away: so it is at least
cos(pi / 16) = 0.98 of the border from any edge."""
UP = np.array([0.0, 0.0, 1.0])


def en12464_spacing(d: float) -> float:
    """Largest grid spacing (m) for a calculation area of characteristic size ``d`` m
    (EN 12464-1: p = 0.2 x 5^log10(d), at most 10 m)."""
    if not d > 0:
        raise LightInvError(f"a calculation area needs a positive size, got {d} m")
    return min(MAX_SPACING, 0.2 * 5 ** math.log10(d))


def grid_counts(width: float, depth: float) -> tuple[int, int, float]:
    """Points along each side of a ``width`` x ``depth`` m area and the spacing rule's p."""
    long_side, short_side = max(width, depth), min(width, depth)
    d = short_side if long_side >= 2 * short_side else long_side
    p = en12464_spacing(d)
    return max(1, math.ceil(width / p - 1e-9)), max(1, math.ceil(depth / p - 1e-9)), p


def grid_counts_2021(width: float, depth: float) -> tuple[int, int, float]:
    """EN 12464-1:2021's points along each side of a ``width`` x ``depth`` m area and its
    largest cell p (m): p from the longer side, side / p rounded (halves up), at least 1."""
    p = en12464_spacing(max(width, depth))
    return (
        max(1, math.floor(width / p + 0.5)),
        max(1, math.floor(depth / p + 0.5)),
        p,
    )


GRID_RULES: dict[str, Callable[[float, float], tuple[int, int, float]]] = {
    Edition.EN12464_2011: grid_counts,
    Edition.EN12464_2021: grid_counts_2021,
}
"""Each edition's grid rule: (width, depth) m -> (points along x, along y, p m)."""


@dataclass(frozen=True)
class WorkPlane:
    """What to lay a grid on: ``height`` m above floor group ``group``, ``border`` m
    left out along its edges; ``name`` names it in messages."""

    height: float = DEFAULT_HEIGHT
    border: float = DEFAULT_BORDER
    group: str = "floor"
    name: str = ""

    def __post_init__(self) -> None:
        for what, value in (("height", self.height), ("border", self.border)):
            if not (isinstance(value, int | float) and math.isfinite(value) and value >= 0):
                raise LightInvError(f"work plane {what} must be a number >= 0 m, got {value!r}")


@dataclass(frozen=True)
class Grid:
    """Receiver points of a work plane: ``points`` (m, 3) m, facing up; the cell
    spacing (dx, dy) m, the counts before points were dropped, and the rule's p."""

    points: np.ndarray
    spacing: tuple[float, float]
    counts: tuple[int, int]
    rule_spacing: float
    dropped: int

    @property
    def normals(self) -> np.ndarray:
        """(m, 3) unit normals: all +z."""
        return np.broadcast_to(UP, self.points.shape)


def _floor_below(caster: RayCaster, xy: np.ndarray, z: float, floor: np.ndarray) -> np.ndarray:
    """Whether a patch of ``floor`` (bool mask over patches) is straight below each
    point ``xy`` (m, 2), looking down from just above the floor level ``z``."""
    o = np.column_stack([xy, np.full(len(xy), z)])
    hit = caster.hit_patches(o, np.broadcast_to(-UP, o.shape))
    return (hit >= 0) & floor[np.maximum(hit, 0)]


def _room_top(patches: Patches, caster: RayCaster, xy: np.ndarray, z: float) -> float:
    """Height (m) of the highest first surface straight above points ``xy`` (m, 2) looking
    up from level ``z``: the top of the room over the floor (inf where nothing is above)."""
    o = np.column_stack([xy, np.full(len(xy), z)])
    hit = caster.hit_patches(o, np.broadcast_to(UP, o.shape))
    seen = hit >= 0
    if not seen.any():
        return math.inf
    hit, o = hit[seen], o[seen]
    n, at = patches.normal[hit], patches.origin[hit]
    nz = n[:, 2]
    tilted = np.abs(nz) > 1e-6
    # The height of the hit face's plane straight above the point (a wall: its centroid).
    rise = -np.einsum("ij,ij->i", n[:, :2], o[:, :2] - at[:, :2]) / np.where(tilted, nz, 1.0)
    z_hit = np.where(tilted, at[:, 2] + rise, patches.centroid[hit, 2])
    return float(z_hit.max())


def work_plane_grid(
    patches: Patches,
    caster: RayCaster,
    plane: WorkPlane,
    counts: Callable[[float, float], tuple[int, int, float]] = grid_counts,
) -> Grid:
    """The EN 12464-1 grid of ``plane`` over its floor group (see the module); ``counts``
    (width, depth m) -> (nx, ny, cell m) is the edition's rule (``GRID_RULES``;
    default the 2011 one, ``grid_counts``)."""
    try:
        idx = patches.group_index(plane.group)
    except LightInvError:
        raise LightInvError(
            f"no group {plane.group!r} for the work plane to lie over; groups: "
            f"{', '.join(patches.group_names)}"
        ) from None
    if np.any(patches.normal[idx] @ UP < 0.999):
        raise LightInvError(
            f"group {plane.group!r} is not a horizontal floor facing up; a work plane lies "
            "over a floor"
        )
    a = patches.area[idx]
    floor_z = float(patches.centroid[idx, 2] @ a / a.sum())
    corners = np.concatenate(
        [patches.origin[idx], patches.origin[idx] + patches.edge1[idx] + patches.edge2[idx]]
    )
    lo = corners[:, :2].min(axis=0) + plane.border
    hi = corners[:, :2].max(axis=0) - plane.border
    if np.any(hi - lo <= 0):
        raise LightInvError(
            f"the border of {plane.border} m leaves nothing of {plane.group!r} "
            f"({np.ptp(corners[:, 0]):.2f} x {np.ptp(corners[:, 1]):.2f} m); use a smaller border"
        )
    w, dpt = hi - lo
    nx, ny, p = counts(float(w), float(dpt))
    xs = lo[0] + (np.arange(nx) + 0.5) * w / nx
    ys = lo[1] + (np.arange(ny) + 0.5) * dpt / ny
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    floor = np.zeros(patches.n, bool)
    floor[idx] = True
    z_probe = floor_z + 4 * caster.offset
    keep = _floor_below(caster, xy, z_probe, floor)
    if plane.border > 0:
        for t in np.arange(BORDER_DIRECTIONS) * 2 * np.pi / BORDER_DIRECTIONS:
            step = plane.border * np.array([np.cos(t), np.sin(t)])
            keep &= _floor_below(caster, xy + step, z_probe, floor)
    top = _room_top(patches, caster, xy, z_probe)
    if floor_z + plane.height >= top - 1e-9:
        raise SceneError(
            f"{f'work plane {plane.name!r}' if plane.name else 'the work plane'} "
            f"{plane.height} m above {plane.group!r} (at z = "
            f"{floor_z + plane.height:.2f} m) is not inside its room, which spans z = "
            f"{floor_z:.2f} to {top:.2f} m ({top - floor_z:.2f} m high): give a height "
            f"below {top - floor_z:.2f} m"
        )
    pts = np.column_stack([xy, np.full(len(xy), floor_z + plane.height)])
    # Inside a solid object, looking up meets the back of a face: drop such points.
    up = np.broadcast_to(UP, pts.shape)
    inside = caster.occluded(pts, up, np.full(len(pts), 1e6)) & (caster.hit_patches(pts, up) < 0)
    keep &= ~inside
    if not keep.any():
        raise LightInvError(
            f"no grid point of the work plane at {plane.height} m lies over {plane.group!r} "
            f"with a border of {plane.border} m; check the height and the border"
        )
    return Grid(pts[keep], (float(w / nx), float(dpt / ny)), (nx, ny), p, int((~keep).sum()))


def grid_statistics(lux: np.ndarray) -> dict[str, float]:
    """EN 12464-1 values of a grid: mean Em, Emin, Emax (lux), U0 = Emin / Em."""
    lux = np.asarray(lux, dtype=float)
    em = float(lux.mean())
    return {
        "points": len(lux),
        "Em": em,
        "Emin": float(lux.min()),
        "Emax": float(lux.max()),
        "U0": float(lux.min() / em) if em > 0 else 0.0,
    }
