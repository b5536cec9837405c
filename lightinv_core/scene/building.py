"""A multi-storey office building: the whole-building scene (~200,000 patches at 0.25 m).

Every storey has two rows of cellular offices on either side of a central corridor,
doors from each office to the corridor, and the corridor opening at both ends into a
stair void: a shaft through every storey with landings at and between floor levels.
Walls are solid (``WALL`` thick), so each opening is a short passage (its reveals are
surfaces); the scene is closed, like every built-in scene. Emitter zones: a ceiling
luminaire band across every office and along every corridor, a roof skylight band in
every top-floor office and a skylight over each stair void.

Plan (y up the page; ``rooms`` offices per row, x from 0 to the building length):

    north offices   y = D + 2t + c ... 2D + 2t + c
    corridor        y = D + t ... D + t + c       (stair voids beyond both ends)
    south offices   y = 0 ... D

Names: office ``F{f}.{S|N}{i}`` (storey f from 0, row, index i from 0), corridor
``F{f}.corridor``, stair voids ``stair_west`` and ``stair_east``; zones
``F{f}.{S|N}{i}.lum``, ``F{f}.corridor.lum``, ``F{top}.{S|N}{i}.sky`` and
``stair_west.sky`` / ``stair_east.sky``. Groups: floor, ceiling, walls, desks,
desk_frames, corridor_floor, stairs, roof (skylight zones).
"""

from __future__ import annotations

from lightinv_core.errors import SceneError
from lightinv_core.scene.builders import Insert, box_surfaces, room_faces, split_rect
from lightinv_core.scene.model import EmitterZone, Rect, Scene, Surface, check_resolution

FLOOR, WALLS, CEILING, DESK, STAIRS = 0.3, 0.6, 0.8, 0.5, 0.4
STOREY = 3.3  # floor to floor, m
HEIGHT = 3.0  # floor to ceiling, m
WALL = 0.2  # wall thickness, m
ROOM_W, ROOM_D = 7.2, 6.0  # an office, along x and y, m
CORRIDOR = 2.0  # corridor width, m
SHAFT_W, SHAFT_D = 4.0, 6.0  # a stair void, along x and y, m
DOOR_AT, DOOR_W, DOOR_H = 0.6, 1.0, 2.1  # door offset from the office's west wall, size, m
GAP = 0.05  # m between a landing and the walls, so every face stays a front face
DEFAULT_RESOLUTION = 0.25


Parts = dict[str, tuple[str, float, list[Insert]]]


def _faces(
    prefix: str, faces: dict[str, Rect], parts: Parts
) -> tuple[list[Surface], list[EmitterZone]]:
    """The named faces of a box, each split around its inserts (doors, zones)."""
    surfaces, zones = [], []
    for key, (group, rho, inserts) in parts.items():
        s, z = split_rect(f"{prefix}.{key}", group, rho, faces[key], inserts)
        surfaces += s
        zones += z
    return surfaces, zones


def _passage(prefix: str, lo: tuple, hi: tuple, open_axis: str) -> list[Surface]:
    """The four inward faces of an opening through a wall (floor, head, two reveals);
    the two ends along ``open_axis`` ("x" or "y") are open."""
    faces = room_faces(*lo, *hi)
    ends = ("west", "east") if open_axis == "x" else ("south", "north")
    groups = {"floor": ("floor", FLOOR), "ceiling": ("walls", WALLS)}
    return [
        Surface(f"{prefix}.{key}", *groups.get(key, ("walls", WALLS)), rect=rect)
        for key, rect in faces.items()
        if key not in ends
    ]


def _office(f: int, row: str, i: int, top: bool) -> tuple[list[Surface], list[EmitterZone]]:
    """Office i of row S or N on storey f: ceiling bands, a door to the corridor, two desks."""
    z0 = f * STOREY
    x0 = i * (ROOM_W + WALL)
    y0 = 0.0 if row == "S" else ROOM_D + 2 * WALL + CORRIDOR
    name = f"F{f}.{row}{i}"
    faces = room_faces(x0, y0, z0, x0 + ROOM_W, y0 + ROOM_D, z0 + HEIGHT)
    # The ceiling's v runs along -y from the office's north wall: bands across the office.
    if top:
        ceiling = [
            Insert(f"{name}.lum", 0.0, 0.75, ROOM_W, 3.0, group="ceiling", zone_kind="luminaire"),
            Insert(f"{name}.sky", 0.0, 3.5, ROOM_W, 5.0, group="roof", zone_kind="skylight"),
        ]
    else:
        ceiling = [
            Insert(f"{name}.lum", 0.0, 1.5, ROOM_W, 4.5, group="ceiling", zone_kind="luminaire")
        ]
    door = f"{name}.door"
    if row == "S":  # door in the north wall (u along x, v up)
        walls = {"north": [Insert(door, DOOR_AT, 0.0, DOOR_AT + DOOR_W, DOOR_H)], "south": []}
    else:  # door in the south wall (u up, v along x)
        walls = {"south": [Insert(door, 0.0, DOOR_AT, DOOR_H, DOOR_AT + DOOR_W)], "north": []}
    parts: Parts = {
        "floor": ("floor", FLOOR, []),
        "ceiling": ("ceiling", CEILING, ceiling),
        **{k: ("walls", WALLS, v) for k, v in walls.items()},
        "west": ("walls", WALLS, []),
        "east": ("walls", WALLS, []),
    }
    surfaces, zones = _faces(name, faces, parts)
    for d, xc in enumerate((x0 + ROOM_W / 3, x0 + 2 * ROOM_W / 3)):
        yc = y0 + ROOM_D / 2
        lo, hi = (xc - 0.8, yc - 0.4, z0 + 0.71), (xc + 0.8, yc + 0.4, z0 + 0.75)
        surfaces += box_surfaces(f"{name}.desk{d}", "desk_frames", DESK, lo, hi, top_group="desks")
    return surfaces, zones


def _corridor(f: int, rooms: int) -> tuple[list[Surface], list[EmitterZone]]:
    """The corridor of storey f: open at both ends, a door opening per office, a
    luminaire band along its ceiling, and the passages through its walls."""
    z0 = f * STOREY
    y0, y1 = ROOM_D + WALL, ROOM_D + WALL + CORRIDOR
    length = rooms * ROOM_W + (rooms - 1) * WALL
    name = f"F{f}.corridor"
    doors = [i * (ROOM_W + WALL) + DOOR_AT for i in range(rooms)]
    south = [Insert(f"{name}.dS{i}", 0.0, x, DOOR_H, x + DOOR_W) for i, x in enumerate(doors)]
    north = [Insert(f"{name}.dN{i}", x, 0.0, x + DOOR_W, DOOR_H) for i, x in enumerate(doors)]
    band = Insert(f"{name}.lum", 0.0, 0.5, length, 1.5, group="ceiling", zone_kind="luminaire")
    faces = room_faces(0.0, y0, z0, length, y1, z0 + HEIGHT)
    parts: Parts = {
        "floor": ("corridor_floor", FLOOR, []),
        "ceiling": ("ceiling", CEILING, [band]),
        "south": ("walls", WALLS, south),
        "north": ("walls", WALLS, north),
    }
    surfaces, zones = _faces(name, faces, parts)
    for i, x in enumerate(doors):
        for row, (a, b) in (("S", (ROOM_D, y0)), ("N", (y1, y1 + WALL))):
            lo, hi = (x, a, z0), (x + DOOR_W, b, z0 + DOOR_H)
            surfaces += _passage(f"{name}.pass{row}{i}", lo, hi, "y")
    for end, (a, b) in (("west", (-WALL, 0.0)), ("east", (length, length + WALL))):
        surfaces += _passage(f"{name}.pass_{end}", (a, y0, z0), (b, y1, z0 + HEIGHT), "x")
    return surfaces, zones


def _stair(side: str, floors: int, length: float) -> tuple[list[Surface], list[EmitterZone]]:
    """A stair void beyond one end of the corridors, through every storey: an opening
    from each corridor, landings at each floor level and half-way up, a roof skylight."""
    name = f"stair_{side}"
    yc = ROOM_D + WALL + CORRIDOR / 2
    ys0, ys1 = yc - SHAFT_D / 2, yc + SHAFT_D / 2
    top = (floors - 1) * STOREY + HEIGHT
    if side == "west":
        x0, x1, wall = -WALL - SHAFT_W, -WALL, "east"
    else:
        x0, x1, wall = length + WALL, length + WALL + SHAFT_W, "west"
    c0, c1 = yc - CORRIDOR / 2 - ys0, yc + CORRIDOR / 2 - ys0  # opening, along the wall
    if wall == "east":  # u up, v along y
        openings = [
            Insert(f"{name}.o{f}", f * STOREY, c0, f * STOREY + HEIGHT, c1) for f in range(floors)
        ]
    else:  # u along y, v up
        openings = [
            Insert(f"{name}.o{f}", c0, f * STOREY, c1, f * STOREY + HEIGHT) for f in range(floors)
        ]
    sky_u = (SHAFT_W / 2 - 1.0, SHAFT_W / 2 + 1.0)
    sky = Insert(f"{name}.sky", sky_u[0], 1.5, sky_u[1], 4.5, group="roof", zone_kind="skylight")
    other = "west" if wall == "east" else "east"
    parts: Parts = {
        "floor": ("stairs", STAIRS, []),
        "ceiling": ("ceiling", CEILING, [sky]),
        "south": ("walls", WALLS, []),
        "north": ("walls", WALLS, []),
        other: ("walls", WALLS, []),
        wall: ("walls", WALLS, openings),
    }
    surfaces, zones = _faces(name, room_faces(x0, ys0, 0.0, x1, ys1, top), parts)
    near = (x1 - 1.5, x1 - GAP) if wall == "east" else (x0 + GAP, x0 + 1.5)
    far = (x0 + GAP, x0 + 1.5) if wall == "east" else (x1 - 1.5, x1 - GAP)
    landings = [(near, f * STOREY) for f in range(1, floors)]
    landings += [(far, f * STOREY + STOREY / 2) for f in range(floors - 1)]
    for j, ((a, b), z) in enumerate(landings):
        lo, hi = (a, ys0 + GAP, z - 0.25), (b, ys1 - GAP, z)
        surfaces += box_surfaces(f"{name}.landing{j}", "stairs", STAIRS, lo, hi)
    return surfaces, zones


def building(resolution: float | None = None, floors: int = 4, rooms: int = 7) -> Scene:
    """A ``floors``-storey office building with ``rooms`` offices on each side of every
    corridor and a stair void at each end (module docstring); at the default 0.25 m,
    4 storeys of 7 + 7 offices make about 200,000 patches."""
    res = check_resolution(DEFAULT_RESOLUTION if resolution is None else resolution)
    if not (isinstance(floors, int) and 1 <= floors <= 50):
        raise SceneError(f"a building has 1 to 50 storeys, got {floors!r}")
    if not (isinstance(rooms, int) and 1 <= rooms <= 100):
        raise SceneError(f"a building has 1 to 100 offices per row, got {rooms!r}")
    length = rooms * ROOM_W + (rooms - 1) * WALL
    surfaces: list[Surface] = []
    zones: list[EmitterZone] = []
    for f in range(floors):
        for row in ("S", "N"):
            for i in range(rooms):
                s, z = _office(f, row, i, top=f == floors - 1)
                surfaces += s
                zones += z
        s, z = _corridor(f, rooms)
        surfaces += s
        zones += z
    for side in ("west", "east"):
        s, z = _stair(side, floors, length)
        surfaces += s
        zones += z
    return Scene(
        "building",
        tuple(surfaces),
        tuple(zones),
        res,
        f"Office building of {floors} storeys, {2 * rooms} offices ({ROOM_W:g} x {ROOM_D:g} m, "
        f"two desks each) per storey on a {CORRIDOR:g} m corridor, stair voids at both ends; "
        "ceiling luminaire bands in every office and corridor, roof skylight bands on the "
        "top storey and over the stairs.",
    )
