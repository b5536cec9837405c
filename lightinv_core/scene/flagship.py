"""The flagship office (issue #34): an open-plan office 15 x 9 x 3 m with clear windows
in deep reveals on its south façade, 15 desks and a suspended ceiling in two luminaire
zones (the window row and the inner rows), as a lighting designer would draw it.

Plan (x east along the 15 m façade, y north into the 9 m depth, z up; the weather's
north is +y):

- **Windows**: five 2.5 x 1.5 m panes (sill 1.0 m, head 2.5 m; sizes exact in binary,
  so a window source filling its zone lies exactly inside it) centred 3 m apart on the
  south wall (y = 0), each set ``REVEAL`` (1.2) m back in the façade: the opening's head, jambs
  and sill are surfaces (groups ``reveals``), its glass at the outer end is a window
  zone ``W1`` .. ``W5`` (group ``windows``). The head is a fixed overhang and the jambs
  fins: they keep the high summer sun off the work plane. The scene stays closed: the
  reveals face into the room and the glass closes the opening.
- **Ceiling** (group ``ceiling``, 0.8) in two luminaire zones: ``window_row`` the
  3 m band along the windows, ``inner_rows`` the 6 m beyond it. A luminaire array may
  go anywhere in its zone (its rectangle, rows and columns free: a suspended ceiling's
  grid). Ceiling zone axes: u = x, v = 9 - y (v runs from the north wall).
- **Desks**: 3 rows of 5 desks 1.6 x 0.8 m, tops at 0.75 m (group ``desks``, frames
  ``desk_frames``), in front of the windows and beyond.
- Reflectances: floor 0.3, walls and reveals 0.6, ceiling 0.8, desks 0.5 (EN 12464-1's
  usual ranges: ceiling 0.7-0.9, walls 0.5-0.8, floor 0.2-0.4).
"""

from __future__ import annotations

from lightinv_core.scene.builders import Insert, box_surfaces, room_faces, split_rect
from lightinv_core.scene.model import EmitterZone, Scene, Surface, check_resolution

LENGTH, DEPTH, HEIGHT = 15.0, 9.0, 3.0
"""Room size, m: along the façade (x), into the room (y), floor to ceiling (z)."""
FLOOR, WALL, CEILING, DESK = 0.3, 0.6, 0.8, 0.5
WINDOW_CENTRES = (1.5, 4.5, 7.5, 10.5, 13.5)
"""x of each window's centre, m."""
WINDOW_W, SILL, HEAD = 2.5, 1.0, 2.5
"""Window width, sill and head heights, m."""
REVEAL = 1.2
"""Depth of the window reveals (the glass set back in the façade), m."""
WINDOW_ROW = 3.0
"""Depth of the window row's ceiling zone from the façade, m."""
DESK_X = (1.75, 4.6, 7.5, 10.4, 13.25)
DESK_Y = (2.0, 4.5, 7.0)
DEFAULT_RESOLUTION = 0.3


def window_names() -> tuple[str, ...]:
    """The window zones, west to east: W1 .. W5."""
    return tuple(f"W{k + 1}" for k in range(len(WINDOW_CENTRES)))


def _window(name: str, xc: float) -> tuple[list[Surface], list[EmitterZone]]:
    """One window: its reveal (head, jambs, sill) from the façade's outer face at
    y = -REVEAL to the room at y = 0, and its glass at the outer end (a window zone)."""
    x0, x1 = xc - WINDOW_W / 2, xc + WINDOW_W / 2
    faces = room_faces(x0, -REVEAL, SILL, x1, 0.0, HEAD)
    surfaces = [
        Surface(f"{name}.{key}", "reveals", WALL, rect=faces[key])
        for key in ("floor", "ceiling", "west", "east")
    ]
    # The passage's south face (y = -REVEAL, facing +y into the room) is the glass.
    glass = Surface(name, "windows", WALL, rect=faces["south"])
    return [*surfaces, glass], [EmitterZone(name, "window", name)]


def flagship_office(resolution: float | None = None) -> Scene:
    """The flagship open-plan office 15 x 9 x 3 m (module docstring), ~5,800 patches at
    the default 0.3 m."""
    res = check_resolution(DEFAULT_RESOLUTION if resolution is None else resolution)
    faces = room_faces(0.0, 0.0, 0.0, LENGTH, DEPTH, HEIGHT)
    # Ceiling v runs along -y from y = DEPTH: the window row is v in [DEPTH - 3, DEPTH].
    ceiling = [
        Insert("inner_rows", 0.0, 0.0, LENGTH, DEPTH - WINDOW_ROW, "ceiling", None, "luminaire"),
        Insert("window_row", 0.0, DEPTH - WINDOW_ROW, LENGTH, DEPTH, "ceiling", None, "luminaire"),
    ]
    # South wall: u runs up (z), v along x; each window is a hole (its reveal fills it).
    holes = [
        Insert(f"{name}.opening", SILL, xc - WINDOW_W / 2, HEAD, xc + WINDOW_W / 2)
        for name, xc in zip(window_names(), WINDOW_CENTRES, strict=True)
    ]
    surfaces: list[Surface] = []
    zones: list[EmitterZone] = []
    parts = {
        "floor": ("floor", FLOOR, []),
        "ceiling": ("ceiling", CEILING, ceiling),
        "south": ("walls", WALL, holes),
        "north": ("walls", WALL, []),
        "west": ("walls", WALL, []),
        "east": ("walls", WALL, []),
    }
    for key, (group, rho, inserts) in parts.items():
        s, z = split_rect(key, group, rho, faces[key], inserts)
        surfaces += s
        zones += z
    for name, xc in zip(window_names(), WINDOW_CENTRES, strict=True):
        s, z = _window(name, xc)
        surfaces += s
        zones += z
    for row, yc in enumerate(DESK_Y):
        for col, xc in enumerate(DESK_X):
            lo, hi = (xc - 0.8, yc - 0.4, 0.71), (xc + 0.8, yc + 0.4, 0.75)
            surfaces += box_surfaces(
                f"desk{row}{col}", "desk_frames", DESK, lo, hi, top_group="desks"
            )
    return Scene(
        "flagship",
        tuple(surfaces),
        tuple(zones),
        res,
        "Open-plan office 15 x 9 x 3 m: five 2.5 x 1.5 m clear windows in 1.2 m deep "
        "reveals on the south façade (zones W1-W5), 15 desks, a suspended ceiling in two "
        "luminaire zones (window_row, the 3 m along the façade; inner_rows, the 6 m beyond).",
    )
