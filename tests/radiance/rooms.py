"""The small rooms the Radiance comparisons use, as LightInv patches.

Box rooms with Lambertian surfaces (walls 0.5, ceiling 0.7, floor 0.2 unless given),
the glazing an insert of group ``window`` or ``rooflight`` (reflectance 0: the glass
material of the Radiance scene, or LightInv's glazing, gives it its optics), and an
analysis grid at work-plane height.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.scene.builders import Insert, room_faces, split_rect
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches, mesh_patches

WALL, CEILING, FLOOR = 0.5, 0.7, 0.2


def box_room(
    size: tuple[float, float, float],
    *,
    window: tuple[float, float, float, float] | None = None,
    rooflight: tuple[float, float, float, float] | None = None,
    rho: tuple[float, float, float] = (WALL, CEILING, FLOOR),
    resolution: float = 0.5,
) -> Scene:
    """A room [0, dx] x [0, dy] x [0, dz] m (+y into the room from its south wall y = 0).

    ``window`` = (x0, z0, x1, z1) m on the south wall makes a glazing insert of group
    ``window``; ``rooflight`` = (x0, y0, x1, y1) m in plan on the ceiling one of group
    ``rooflight``; each is also an emitter zone of that name (kind window / skylight).
    ``rho`` = (walls, ceiling, floor) reflectances.
    """
    dx, dy, dz = size
    faces = room_faces(0, 0, 0, dx, dy, dz)
    walls, ceiling, floor = rho
    inserts: dict[str, list[Insert]] = {k: [] for k in faces}
    if window is not None:
        x0, z0, x1, z1 = window
        # The south face runs u along z, v along x.
        inserts["south"].append(Insert("window", z0, x0, z1, x1, "window", 0.0, "window"))
    if rooflight is not None:
        x0, y0, x1, y1 = rooflight
        # The ceiling runs u along x, v along -y from y = dy.
        ins = Insert("rooflight", x0, dy - y1, x1, dy - y0, "rooflight", 0.0, "skylight")
        inserts["ceiling"].append(ins)
    groups = {"floor": ("floor", floor), "ceiling": ("ceiling", ceiling)}
    surfaces, zones = [], []
    for key, rect in faces.items():
        group, r = groups.get(key, ("walls", walls))
        s, z = split_rect(key, group, r, rect, inserts[key])
        surfaces += s
        zones += z
    return Scene(
        "radiance_room",
        tuple(surfaces),
        tuple(zones),
        resolution,
        f"Box room {dx} x {dy} x {dz} m for the Radiance comparisons.",
    )


def window_office(resolution: float = 0.5) -> Patches:
    """The bench office: 4 m wide (x), 6 m deep (y), 3 m high, a 3 x 1.5 m clear window
    (sill 0.9 m) in its south wall (y = 0)."""
    return mesh_patches(
        box_room((4.0, 6.0, 3.0), window=(0.5, 0.9, 3.5, 2.4), resolution=resolution)
    )


def rooflight_room(resolution: float = 0.5) -> Patches:
    """The bench rooflight room: 4 x 6 x 3 m with a 1.5 x 1.5 m clear rooflight in the
    middle of its ceiling."""
    room = box_room((4.0, 6.0, 3.0), rooflight=(1.25, 2.25, 2.75, 3.75), resolution=resolution)
    return mesh_patches(room)


def work_plane(size: tuple[float, float], spacing: float = 1.0, height: float = 0.75):
    """Analysis points on a grid (cell centres of ``spacing`` m) over the floor
    [0, dx] x [0, dy] at ``height`` m, facing up: (points (q, 3), normals (q, 3))."""
    dx, dy = size
    xs = np.arange(spacing / 2, dx, spacing)
    ys = np.arange(spacing / 2, dy, spacing)
    x, y = np.meshgrid(xs, ys, indexing="ij")
    points = np.column_stack([x.ravel(), y.ravel(), np.full(x.size, height)])
    normals = np.tile([0.0, 0.0, 1.0], (len(points), 1))
    return points, normals
