"""Built-in parametric scenes: cornell, office, patio, corridor, building, the two
daylight rooms sidelit and toplit, and the flagship office (``scene/flagship.py``).

Each takes ``resolution`` (target patch edge in metres; ``None`` for the
scene's default) and returns a closed ``Scene`` with named groups and emitter
zones. Closed means every ray leaving a front face hits another front face, so
form-factor rows sum to 1 (the tests rely on it).

Reflectances are typical interior values: floors 0.3, walls 0.6, ceilings 0.8.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable

import numpy as np

from lightinv_core.errors import SceneError
from lightinv_core.scene.builders import (
    Insert,
    box_surfaces,
    footprint_holes,
    room_faces,
    split_rect,
)
from lightinv_core.scene.building import building
from lightinv_core.scene.flagship import flagship_office
from lightinv_core.scene.model import EmitterZone, Rect, Scene, Surface, check_resolution

FLOOR, WALL, CEILING = 0.3, 0.6, 0.8


def _room(faces: dict[str, Rect], parts: dict[str, tuple[str, float, list[Insert]]]):
    """Split each named room face with its inserts; returns (surfaces, zones)."""
    surfaces, zones = [], []
    for key, (group, rho, inserts) in parts.items():
        s, z = split_rect(key, group, rho, faces[key], inserts)
        surfaces += s
        zones += z
    return surfaces, zones


def cornell(resolution: float | None = None) -> Scene:
    """A closed 2 m Cornell-style box with two blocks and a ceiling light zone (~1,000 patches)."""
    res = check_resolution(0.16 if resolution is None else resolution)
    faces = room_faces(0, 0, 0, 2, 2, 2)
    short = (np.array([0.3, 0.35, 0.0]), np.array([0.9, 0.95, 0.6]))
    tall = (np.array([1.1, 1.0, 0.0]), np.array([1.7, 1.6, 1.2]))
    light = Insert("light", 0.75, 0.75, 1.25, 1.25, group="light", zone_kind="luminaire")
    surfaces, zones = _room(
        faces,
        {
            "floor": ("floor", 0.75, footprint_holes("floor.hole", [short, tall], (0, 0))),
            "ceiling": ("ceiling", 0.75, [light]),
            "north": ("back_wall", 0.75, []),
            "south": ("front_wall", 0.75, []),
            "west": ("red_wall", 0.2, []),
            "east": ("green_wall", 0.3, []),
        },
    )
    for name, (lo, hi) in (("short_block", short), ("tall_block", tall)):
        surfaces += box_surfaces(name, "blocks", 0.75, lo, hi, skip=("bottom",))
    return Scene(
        "cornell",
        tuple(surfaces),
        tuple(zones),
        res,
        "Closed 2 x 2 x 2 m box, red and green side walls, two blocks, ceiling light zone.",
    )


def office(resolution: float | None = None) -> Scene:
    """An open office 12 x 8 x 3 m: 8 desks (tops at 0.75 m), a roof skylight zone and
    two ceiling luminaire strips (~5,000 patches)."""
    res = check_resolution(0.25 if resolution is None else resolution)
    faces = room_faces(0, 0, 0, 12, 8, 3)
    # Ceiling zone coordinates: u = x, v = 8 - y (the ceiling's v axis runs along -y).
    ceiling = [
        Insert("skylight", 4.0, 3.0, 8.0, 5.0, group="roof", zone_kind="skylight"),
        Insert("lum_west", 1.0, 1.0, 3.0, 7.0, group="ceiling", zone_kind="luminaire"),
        Insert("lum_east", 9.0, 1.0, 11.0, 7.0, group="ceiling", zone_kind="luminaire"),
    ]
    surfaces, zones = _room(
        faces,
        {
            "floor": ("floor", FLOOR, []),
            "ceiling": ("ceiling", CEILING, ceiling),
            "north": ("walls", WALL, []),
            "south": ("walls", WALL, []),
            "west": ("walls", WALL, []),
            "east": ("walls", WALL, []),
        },
    )
    for row, yc in enumerate((2.5, 5.5)):
        for col, xc in enumerate((1.9, 4.6, 7.4, 10.1)):
            lo = np.array([xc - 0.8, yc - 0.4, 0.71])
            hi = np.array([xc + 0.8, yc + 0.4, 0.75])
            surfaces += box_surfaces(
                f"desk{row}{col}", "desk_frames", 0.5, lo, hi, top_group="desks"
            )
    return Scene(
        "office",
        tuple(surfaces),
        tuple(zones),
        res,
        "Open office 12 x 8 x 3 m, 8 desks with work surfaces at 0.75 m, a 4 x 2 m "
        "roof skylight zone and two 2 x 6 m ceiling luminaire zones.",
    )


PATIO_RES = 0.245


def patio(resolution: float | None = None) -> Scene:
    """A 20 x 20 m hall around a covered courtyard (~24,000 patches).

    The courtyard (12 x 12 m, 8 m high) has a roof that is one emitter zone,
    meshed as a 32 x 32 grid at the default resolution (the paper's 1,024 roof
    quads; the grid scales with the resolution). A 4 m high gallery runs
    around it behind 16 columns joined by beams (the arcade).
    """
    res = check_resolution(PATIO_RES if resolution is None else resolution)
    ng = max(4, round(32 * PATIO_RES / res))
    lower = room_faces(0, 0, 0, 20, 20, 4)
    upper = room_faces(4, 4, 4, 16, 16, 8)
    cols, beams = [], []
    pos = [3.6, 6.6, 9.6, 12.6, 16.0]  # column x-starts along one side, 0.4 m square
    for p in pos:
        for q in (3.6, 16.0):
            cols.append((np.array([p, q, 0.0]), np.array([p + 0.4, q + 0.4, 4.0])))
            if p not in (3.6, 16.0):
                cols.append((np.array([q, p, 0.0]), np.array([q + 0.4, p + 0.4, 4.0])))
    gap = 0.01  # beams stop 1 cm short of the columns so every face stays a front face
    for a, b in itertools.pairwise(pos):
        for q in (3.6, 16.0):
            beams.append((np.array([a + 0.4 + gap, q, 3.4]), np.array([b - gap, q + 0.4, 4.0])))
            beams.append((np.array([q, a + 0.4 + gap, 3.4]), np.array([q + 0.4, b - gap, 4.0])))
    courtyard_hole = Insert("ceiling.courtyard", 4.0, 4.0, 16.0, 16.0, group=None)
    surfaces, zones = _room(
        lower,
        {
            "floor": ("floor", FLOOR, footprint_holes("floor.hole", cols, (0, 0))),
            "ceiling": (
                "ceiling",
                CEILING,
                [courtyard_hole, *footprint_holes("ceiling.hole", cols + beams, (0, 0), 20.0)],
            ),
            "north": ("walls", WALL, []),
            "south": ("walls", WALL, []),
            "west": ("walls", WALL, []),
            "east": ("walls", WALL, []),
        },
    )
    for key in ("north", "south", "west", "east"):
        surfaces.append(Surface(f"courtyard_wall.{key}", "walls", WALL, rect=upper[key]))
    surfaces.append(
        Surface("courtyard_roof", "roof", CEILING, rect=upper["ceiling"], grid=(ng, ng))
    )
    zones.append(EmitterZone("ceiling", "skylight", "courtyard_roof"))
    for k, (lo, hi) in enumerate(cols):
        surfaces += box_surfaces(f"column{k}", "columns", WALL, lo, hi, skip=("bottom", "top"))
    for k, (lo, hi) in enumerate(beams):
        surfaces += box_surfaces(f"arch{k}", "arches", WALL, lo, hi, skip=("top",))
    return Scene(
        "patio",
        tuple(surfaces),
        tuple(zones),
        res,
        "Hall 20 x 20 x 4 m around a 12 x 12 x 8 m covered courtyard; the courtyard "
        f"roof is one {ng} x {ng} emitter grid; 16 columns and arcade beams.",
    )


def corridor(resolution: float | None = None) -> Scene:
    """The paper's experiment-5 corridor, 36 x 4 x 3.5 m (~16,700 patches).

    Roof skylight zones S1, S2, S3 (6 x 2 m on the centre line; S1 and S3
    mirror-symmetric about x = 18 m, S2 centred on it), ceiling luminaire zones
    A1, A2, A3 (3 x 0.6 m strips by the north wall) and three 3 x 1.5 m wall
    panels (group ``panels``) on the north wall below them.
    """
    res = check_resolution(0.182 if resolution is None else resolution)
    faces = room_faces(0, 0, 0, 36, 4, 3.5)
    ceiling, panels = [], []
    for k, xc in enumerate((8.0, 18.0, 28.0), start=1):
        # Ceiling v runs along -y from y = 4: v in [1, 3] is y in [1, 3], v in [0.2, 0.8]
        # is y in [3.2, 3.8] (by the north wall).
        ceiling.append(
            Insert(f"S{k}", xc - 3, 1.0, xc + 3, 3.0, group="roof", zone_kind="skylight")
        )
        ceiling.append(
            Insert(f"A{k}", xc - 1.5, 0.2, xc + 1.5, 0.8, group="ceiling", zone_kind="luminaire")
        )
        panels.append(
            Insert(f"panel{k}", xc - 1.5, 1.0, xc + 1.5, 2.5, group="panels", reflectance=0.7)
        )
    surfaces, zones = _room(
        faces,
        {
            "floor": ("floor", FLOOR, []),
            "ceiling": ("ceiling", CEILING, ceiling),
            "north": ("walls", WALL, panels),
            "south": ("walls", WALL, []),
            "west": ("walls", WALL, []),
            "east": ("walls", WALL, []),
        },
    )
    return Scene(
        "corridor",
        tuple(surfaces),
        tuple(zones),
        res,
        "Corridor 36 x 4 x 3.5 m with roof skylight zones S1-S3, ceiling luminaire "
        "zones A1-A3 and three wall panels.",
    )


def _daylit_room(name: str, size, parts, about: str, resolution: float | None) -> Scene:
    res = check_resolution(0.25 if resolution is None else resolution)
    surfaces, zones = _room(room_faces(0, 0, 0, *size), parts)
    return Scene(name, tuple(surfaces), tuple(zones), res, about)


def sidelit(resolution: float | None = None) -> Scene:
    """A deep room 6 x 8 x 3 m lit by one 4.8 x 1.6 m window (sill 0.9 m) in its south
    wall (y = 0), group ``window``: the daylight rooms' side-lit case (~2,900 patches)."""
    window = Insert("window", 0.9, 0.6, 2.5, 5.4, group="window", zone_kind="window")
    parts = {
        "floor": ("floor", FLOOR, []),
        "ceiling": ("ceiling", CEILING, []),
        "south": ("walls", WALL, [window]),
        "north": ("walls", WALL, []),
        "west": ("walls", WALL, []),
        "east": ("walls", WALL, []),
    }
    about = "Room 6 x 8 x 3 m, a 4.8 x 1.6 m window (group window) in the south wall."
    return _daylit_room("sidelit", (6, 8, 3), parts, about, resolution)


def toplit(resolution: float | None = None) -> Scene:
    """A room 8 x 8 x 4 m lit by one 2 x 2 m rooflight in the middle of its flat roof,
    group ``rooflight``: the daylight rooms' top-lit case (~4,100 patches)."""
    roof = Insert("rooflight", 3.0, 3.0, 5.0, 5.0, group="rooflight", zone_kind="skylight")
    parts = {
        "floor": ("floor", FLOOR, []),
        "ceiling": ("ceiling", CEILING, [roof]),
        "south": ("walls", WALL, []),
        "north": ("walls", WALL, []),
        "west": ("walls", WALL, []),
        "east": ("walls", WALL, []),
    }
    about = "Room 8 x 8 x 4 m, a 2 x 2 m rooflight (group rooflight) in the middle of the roof."
    return _daylit_room("toplit", (8, 8, 4), parts, about, resolution)


BUILTIN_SCENES: dict[str, Callable[..., Scene]] = {
    "cornell": cornell,
    "office": office,
    "patio": patio,
    "corridor": corridor,
    "building": building,  # scene/building.py: 4 storeys, ~200,000 patches
    "sidelit": sidelit,
    "toplit": toplit,
    "flagship": flagship_office,  # scene/flagship.py: the flagship office (issue #34)
}


def builtin_scene(name: str, resolution: float | None = None) -> Scene:
    """Build the built-in scene ``name`` at ``resolution`` m (None: its default)."""
    try:
        factory = BUILTIN_SCENES[name]
    except KeyError:
        known = ", ".join(BUILTIN_SCENES)
        raise SceneError(f"no built-in scene {name!r} (built-in scenes: {known})") from None
    return factory(resolution)
