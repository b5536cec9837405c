"""Drawing new emitter zones on the planar rectangles of a scene.

A ``ZoneEdit`` is a rectangle an architect draws on a rectangular surface (a ceiling,
a roof) where skylights or luminaires may go. ``apply_zone_edits`` cuts each drawn
rectangle out of the scene as a new rectangular surface of the surface's group and
reflectance, registers it as an ``EmitterZone``, and replaces the rest of every surface
it covers with remainder rectangles (``split_rect``). The pieces tile the originals
exactly, so the total area is unchanged and a closed scene stays closed; the patch count
changes only by grid rounding.

Coordinates are metres along the named surface's own ``Rect`` edges u and v from its
origin (for the built-in room ceilings: u = x, v = room depth - y). Built-in faces are
already cut into cells around their zones (the office ``ceiling`` is the 1 x 1 m corner
cell, ``ceiling.1`` ... the others), so a rectangle may go past the named surface onto
the coplanar cells of the same group and reflectance that continue it, in the named
surface's coordinates: on the office ceiling, (4, 5.5)-(8, 7) lies between the existing
zones. It may not cover an existing emitter zone, a hole or anything else.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import SceneError
from lightinv_core.kinds import source_kind_names
from lightinv_core.scene.builders import Insert, split_rect
from lightinv_core.scene.model import EmitterZone, Rect, Scene, Surface
from lightinv_core.scene.zone_outline import bounds as outline_bounds
from lightinv_core.scene.zone_outline import check_outline

EDGE_SNAP = 1e-6  # m: rectangle edges this close to the surface's edges are put on them


def _fmt(x: float) -> str:
    return f"{x:g}"


@dataclass(frozen=True)
class ZoneEdit:
    """A new emitter zone ``name`` of ``kind`` ("skylight", "window", "luminaire", ...)
    drawn on the rectangular surface ``surface``.

    ``rect`` is (u0, v0, u1, v1) in metres along the surface's u and v edges from its
    origin; the corners may be given in any order and are stored as
    (min u, min v, max u, max v). A zone of any other shape is given by ``outline``,
    its polygon's corners (u, v) in the same metres (stored counter-clockwise): the
    zone's surface is then the polygon's bounding rectangle, and sources placed in the
    zone must lie inside the polygon (``EmitterZone.outline``). With an outline,
    ``rect`` may be left out; if given, it must be the outline's bounding rectangle.
    """

    name: str
    kind: str
    surface: str
    rect: tuple[float, float, float, float] | None = None
    outline: tuple[tuple[float, float], ...] | None = None

    def __post_init__(self) -> None:
        for key in ("name", "surface"):
            value = getattr(self, key)
            if not isinstance(value, str) or not value.strip():
                raise SceneError(f"new emitter zone: {key} must be a non-empty string")
        where = f"new emitter zone {self.name!r} on surface {self.surface!r}"
        if self.kind not in source_kind_names():
            raise SceneError(f"{where}: kind {self.kind!r} is not one of {source_kind_names()}")
        given = self.rect
        if self.outline is not None:
            outline = check_outline(self.outline, where)
            object.__setattr__(self, "outline", tuple((float(u), float(v)) for u, v in outline))
            if self.rect is None:
                object.__setattr__(self, "rect", outline_bounds(outline))
        elif self.rect is None:
            raise SceneError(f"{where}: give its rectangle (rect) or its outline (corners)")
        try:
            items = list(self.rect)
            values = [float(x) for x in items if not isinstance(x, bool | str)]
        except (TypeError, ValueError, OverflowError):
            items, values = [], []
        if len(values) != 4 or len(items) != 4 or not all(map(math.isfinite, values)):
            raise SceneError(
                f"{where}: rect must be 4 finite numbers (u0, v0, u1, v1) in metres, "
                f"got {self.rect!r}"
            )
        u0, v0, u1, v1 = values
        rect = (min(u0, u1), min(v0, v1), max(u0, u1), max(v0, v1))
        width, height = rect[2] - rect[0], rect[3] - rect[1]
        if not (width > 0 and height > 0 and math.isfinite(width) and math.isfinite(height)):
            raise SceneError(
                f"{where}: the rectangle has zero width or height "
                f"({_fmt(width)} x {_fmt(height)} m); give two opposite corners"
            )
        if self.outline is not None and given is not None:
            box = outline_bounds(np.array(self.outline))
            if max(abs(a - b) for a, b in zip(box, rect, strict=True)) > EDGE_SNAP:
                raise SceneError(
                    f"{where}: rect ({', '.join(map(_fmt, rect))}) is not the bounding "
                    f"rectangle of the outline, ({', '.join(map(_fmt, box))}); leave rect out"
                )
            rect = box
        object.__setattr__(self, "rect", rect)

    @property
    def size(self) -> tuple[float, float]:
        """Width along u and height along v, in metres."""
        u0, v0, u1, v1 = self.rect
        return u1 - u0, v1 - v0


def rect_surfaces(scene: Scene) -> list[tuple[str, Rect]]:
    """The surfaces a new zone may be drawn on, as (name, rectangle): planar rectangles
    that are not already emitter zones and have no fixed grid."""
    taken = {z.surface for z in scene.zones}
    return [
        (s.name, s.rect)
        for s in scene.surfaces
        if s.rect is not None and s.grid is None and s.name not in taken
    ]


def _unknown_surface(scene: Scene, edit: ZoneEdit, where: str) -> SceneError:
    names = [name for name, _ in rect_surfaces(scene)]
    close = difflib.get_close_matches(edit.surface, names, n=1)
    shown = ", ".join(names[:8]) + (f" and {len(names) - 8} more" if len(names) > 8 else "")
    hint = f"; did you mean {close[0]!r}?" if close else ""
    return SceneError(
        f"{where}: scene {scene.name!r} has no surface {edit.surface!r} "
        f"(rectangular surfaces: {shown or 'none'}){hint}"
    )


def _where(edit: ZoneEdit) -> str:
    return f"new emitter zone {edit.name!r} on surface {edit.surface!r}"


def _check_surface(scene: Scene, edit: ZoneEdit) -> Surface:
    where = _where(edit)
    surf = next((s for s in scene.surfaces if s.name == edit.surface), None)
    if surf is None:
        raise _unknown_surface(scene, edit, where)
    if surf.rect is None:
        raise SceneError(f"{where}: the surface is not a planar rectangle (it is triangles)")
    for z in scene.zones:
        if z.surface == surf.name:
            raise SceneError(
                f"{where}: the surface is already emitter zone {z.name!r}; "
                "draw new zones on a surface that is not a zone"
            )
    if surf.grid is not None:
        raise SceneError(
            f"{where}: the surface has a fixed {surf.grid[0]} x {surf.grid[1]} grid "
            "and cannot be split"
        )
    return surf


class _Frame:
    """The (u, v) metre coordinates of a rectangle's plane."""

    def __init__(self, rect: Rect):
        self.rect = rect
        self.origin = rect.origin
        su, sv = rect.size
        self.eu, self.ev, self.n = rect.u / su, rect.v / sv, rect.normal

    def extent(self, r: Rect) -> tuple[float, float, float, float] | None:
        """(u0, v0, u1, v1) of ``r`` in this frame, or None if ``r`` is not a coplanar,
        same-facing rectangle with edges along this frame's axes."""
        if abs(float(r.normal @ self.n) - 1.0) > 1e-9:
            return None
        if abs(float((r.origin - self.origin) @ self.n)) > EDGE_SNAP:
            return None
        ru = r.u / np.linalg.norm(r.u)
        if min(abs(abs(float(ru @ self.eu)) - 1.0), abs(abs(float(ru @ self.ev)) - 1.0)) > 1e-9:
            return None
        corners = np.array([r.origin, r.origin + r.u, r.origin + r.v, r.origin + r.u + r.v])
        uu, vv = (corners - self.origin) @ self.eu, (corners - self.origin) @ self.ev
        return float(uu.min()), float(vv.min()), float(uu.max()), float(vv.max())

    def point(self, u: float, v: float) -> np.ndarray:
        return self.origin + u * self.eu + v * self.ev


def _snap(x: float, edges: list[float]) -> float:
    near = [e for e in edges if abs(e - x) <= EDGE_SNAP]
    return min(near, key=lambda e: abs(e - x)) if near else x


def _local_box(frame: _Frame, box, cell: Rect) -> tuple[float, float, float, float]:
    """``box`` (u0, v0, u1, v1 in ``frame``) in ``cell``'s own metre coordinates."""
    u0, v0, u1, v1 = box
    pts = np.array([frame.point(u, v) for u in (u0, u1) for v in (v0, v1)]) - cell.origin
    cu, cv = cell.size
    s, t = pts @ (cell.u / cu), pts @ (cell.v / cv)
    out = []
    for x, size in ((s.min(), cu), (t.min(), cv), (s.max(), cu), (t.max(), cv)):
        x = 0.0 if x <= EDGE_SNAP else (size if x >= size - EDGE_SNAP else float(x))
        out.append(x)
    return out[0], out[1], out[2], out[3]


def _apply_one(scene: Scene, edit: ZoneEdit, base: Surface, used: set[str]) -> Scene:
    """``scene`` with ``edit`` cut out; ``base`` is the named surface as it was first."""
    where = _where(edit)
    frame = _Frame(base.rect)
    zone_of = {z.surface: z.name for z in scene.zones}
    hits = []  # (index, surface, intersection box in frame)
    u0, v0, u1, v1 = edit.rect
    exts = [None if s.rect is None else frame.extent(s.rect) for s in scene.surfaces]
    near = [
        e
        for e in exts
        if e is not None
        and e[0] < u1 + EDGE_SNAP
        and u0 - EDGE_SNAP < e[2]
        and e[1] < v1 + EDGE_SNAP
        and v0 - EDGE_SNAP < e[3]
    ]
    edges_u = [x for e in near for x in (e[0], e[2])]
    edges_v = [x for e in near for x in (e[1], e[3])]
    u0, u1 = _snap(u0, edges_u), _snap(u1, edges_u)
    v0, v1 = _snap(v0, edges_v), _snap(v1, edges_v)
    covered = 0.0
    for i, (s, ext) in enumerate(zip(scene.surfaces, exts, strict=True)):
        if ext is None:
            continue
        box = (max(u0, ext[0]), max(v0, ext[1]), min(u1, ext[2]), min(v1, ext[3]))
        if box[2] - box[0] <= EDGE_SNAP or box[3] - box[1] <= EDGE_SNAP:
            continue
        if s.name in zone_of:
            raise SceneError(f"{where}: the rectangle overlaps emitter zone {zone_of[s.name]!r}")
        if s.grid is not None:
            raise SceneError(
                f"{where}: the rectangle covers surface {s.name!r}, which has a fixed grid"
            )
        if s.group != base.group or s.reflectance != base.reflectance:
            raise SceneError(
                f"{where}: the rectangle runs onto surface {s.name!r} of group {s.group!r} "
                f"(reflectance {s.reflectance:g}) at ({_fmt(box[0])}, {_fmt(box[1])})-"
                f"({_fmt(box[2])}, {_fmt(box[3])}) m on the surface; a zone must lie on "
                f"surfaces of group {base.group!r} with reflectance {base.reflectance:g}: "
                "draw it beside that one (between rafters, beams or panels)"
            )
        covered += (box[2] - box[0]) * (box[3] - box[1])
        hits.append((i, s, box))
    area = (u1 - u0) * (v1 - v0)
    if abs(covered - area) > 1e-9 * max(1.0, area):
        su, sv = base.rect.size
        raise SceneError(
            f"{where}: the rectangle ({_fmt(u0)}, {_fmt(v0)})-({_fmt(u1)}, {_fmt(v1)}) m "
            f"lies (partly) outside the surface, which runs from (0, 0) to "
            f"({_fmt(su)}, {_fmt(sv)}) m, and outside the coplanar {base.group!r} surfaces "
            "that continue it"
        )
    zone_rect = Rect(frame.point(u0, v0), (u1 - u0) * frame.eu, (v1 - v0) * frame.ev)
    outline = None
    if edit.outline is not None:  # in the zone's own metres, on its rectangle
        outline = np.clip(np.array(edit.outline) - (u0, v0), 0.0, (u1 - u0, v1 - v0))
    zone_surface = Surface(edit.name, base.group, base.reflectance, rect=zone_rect)
    replaced: dict[int, list[Surface]] = {}
    for k, (i, s, box) in enumerate(hits):
        hole = Insert(f"{edit.name} hole", *_local_box(frame, box, s.rect), group=None)
        cells, _ = split_rect(s.name, s.group, s.reflectance, s.rect, [hole])
        root = s.name.split("~")[0]
        pieces = [zone_surface] if k == 0 else []
        n = 0
        for cell in cells:
            n += 1
            while f"{root}~{n}" in used:
                n += 1
            used.add(f"{root}~{n}")
            pieces.append(Surface(f"{root}~{n}", s.group, s.reflectance, rect=cell.rect))
        replaced[i] = pieces
    surfaces = []
    for i, s in enumerate(scene.surfaces):
        surfaces += replaced.get(i, [s])
    return Scene(
        scene.name,
        tuple(surfaces),
        (*scene.zones, EmitterZone(edit.name, edit.kind, edit.name, outline)),
        scene.resolution,
        scene.description,
        dict(scene.info),
    )


def apply_zone_edits(scene: Scene, edits: Sequence[ZoneEdit]) -> Scene:
    """A new scene with each edit's rectangle cut out as a new emitter zone.

    The zone's surface is named like the zone and has the group and reflectance of the
    named surface; the rest of every surface the rectangle covers becomes rectangles
    named ``"<surface>~1"``, ``"<surface>~2"``, ... (numbers skipping names in use).
    Edits are applied in order, each in the coordinates of its named surface as it was
    in ``scene``, so several zones may be drawn on the same surface. Raises
    ``SceneError`` naming the zone and the surface for an unknown or unsuitable
    surface, a rectangle outside it, overlapping zones, or a zone name already used.
    """
    edits = tuple(edits)
    surface_names = {s.name for s in scene.surfaces}
    zone_names = {z.name for z in scene.zones}
    seen: set[str] = set()
    bases = []
    for edit in edits:
        if not isinstance(edit, ZoneEdit):
            raise SceneError(f"expected ZoneEdit values, got {type(edit).__name__}")
        where = _where(edit)
        if edit.name in zone_names:
            raise SceneError(f"{where}: scene {scene.name!r} already has a zone {edit.name!r}")
        if edit.name in seen:
            raise SceneError(f"{where}: the zone name {edit.name!r} is used twice")
        if edit.name in surface_names:
            raise SceneError(
                f"{where}: scene {scene.name!r} already has a surface called {edit.name!r}; "
                "the zone's surface takes the zone's name, so choose another name"
            )
        seen.add(edit.name)
        bases.append(_check_surface(scene, edit))
    used = surface_names | seen
    for edit, base in zip(edits, bases, strict=True):
        scene = _apply_one(scene, edit, base, used)
    return scene
