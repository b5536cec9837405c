"""Emitter zones drawn by the user, as pure functions of the scene.

A drawn zone (``ZoneEdit``) goes on a planar rectangular surface that is not already a
zone; the project stores the drawn zones with its scene, and the scene is rebuilt with
them. When a drawn zone goes (deleted, renamed), so do the sources placed in it and the
rules that name them (``rules.only_in_zones``).

Which surface a zone is drawn on (``zone_surface``): rooms face inwards and the viewport
culls back faces, so from above (Top view) the ceiling is invisible and the floor, or a
wall near the edge, is what is seen; a luminaire zone drawn there used to land on the
floor. Zones go where their source type's ``placement`` allows (``sources.types``): a
kind placed on ceilings takes the first surface facing down (a ceiling or roof, seen
from below or looked through from above) that the view ray crosses before it reaches
what is seen; failing that, the surface seen if its class (ceiling, wall, floor, by its
front normal) is in the placement: a luminaire also goes on a wall, a window (glazing)
on any planar face, a skylight only overhead. z is up.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from lightinv_core.editing.rules import free_name
from lightinv_core.errors import DesignError
from lightinv_core.scene.edits import ZoneEdit, rect_surfaces
from lightinv_core.scene.model import Rect, Scene
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.types import (
    CEILING,
    WALL,
    placement_text,
    source_type,
    surface_class,
)

HEAD_ON = 0.05
"""How much more squarely (cosine of the view ray to its normal) the surface seen must
face the view than the ceiling the ray crosses to take a zone of a kind that may go on
either."""


def placement(kind: str) -> frozenset[str]:
    """The classes of surface (``sources.types.CEILING``, ``WALL``, ``FLOOR``) a zone of
    source kind ``kind`` may go on: its type's ``placement`` (DesignError for an unknown
    kind)."""
    return frozenset(source_type(kind).placement)


def on_walls(kind: str) -> bool:
    """Whether a zone of source kind ``kind`` may go on a wall seen (its type's
    placement holds walls: a luminaire or a window may, a skylight may not)."""
    return WALL in placement(kind)


def drawable_surface(scene: Scene, patches: Patches, patch: int) -> tuple[str, Rect] | None:
    """(surface name, its Rect) under ``patch`` if a zone may be drawn there: a planar
    rectangle that is not an emitter zone and not a gridded mesh; else None."""
    name = patches.surface_names[patches.surface_id[patch]]
    surface = scene.surface(name)
    zone_surfaces = {z.surface for z in scene.zones}
    if surface.rect is None or name in zone_surfaces or surface.grid is not None:
        return None
    return name, surface.rect


def zone_names_after(
    scene: Scene, drawn_before: Sequence[ZoneEdit], drawn_after: Sequence[ZoneEdit]
) -> set[str]:
    """The emitter zones a scene will have once its drawn zones ``drawn_before`` are
    replaced by ``drawn_after``: its own zones and the new drawn ones."""
    old = {z.name for z in drawn_before}
    return {z.name for z in scene.zones if z.name not in old} | {z.name for z in drawn_after}


def new_zone_name(scene: Scene) -> str:
    """A free name for a new zone: Z1, Z2, ..."""
    return free_name("Z", {z.name for z in scene.zones})


def surfaces_on_ray(scene: Scene, origin, direction) -> list[tuple[float, str]]:
    """(distance along the ray in units of ``direction``, surface name) of every planar
    rectangle the ray from ``origin`` meets in front of it, either side, nearest first."""
    p0, d = np.asarray(origin, float), np.asarray(direction, float)
    hits = []
    for surface in scene.surfaces:
        r = surface.rect
        if r is None:
            continue
        t = _plane_distance(r.origin, r.normal, p0, d)
        if t is None:
            continue
        q = p0 + t * d - r.origin
        s, w = float(q @ r.u) / float(r.u @ r.u), float(q @ r.v) / float(r.v @ r.v)
        if -1e-9 <= s <= 1 + 1e-9 and -1e-9 <= w <= 1 + 1e-9:
            hits.append((t, surface.name))
    return sorted(hits)


def _plane_distance(point, normal, p0, d) -> float | None:
    """Where the ray p0 + t d meets the plane through ``point`` (t > 0), or None."""
    den = float(d @ normal)
    if abs(den) < 1e-12:
        return None  # the ray runs along the plane
    t = float((np.asarray(point, float) - p0) @ normal) / den
    return t if t > 0 else None


def drawn_on(scene: Scene, drawn: Sequence[ZoneEdit], name: str, rect: Rect) -> tuple[str, Rect]:
    """(surface name, Rect) a new zone drawn on surface ``name`` of ``scene`` is given as.

    The drawn zones ``drawn`` are applied to the scene as loaded, where the pieces a
    zone leaves of a surface (``"ceiling~3"``) do not exist: a zone drawn on such a piece
    names the surface it came from (``"ceiling"``), in that surface's metres. Its
    rectangle is the extent of the pieces and the drawn zones cut from it (they tile it,
    and each keeps its u and v directions). Any other surface is returned as it is."""
    root = name.split("~")[0]
    cut = {z.name for z in drawn if z.surface == root}
    if root == name or not cut:
        return name, rect
    eu, ev = rect.u / np.linalg.norm(rect.u), rect.v / np.linalg.norm(rect.v)
    corners = [
        p
        for s in scene.surfaces
        if s.rect is not None and (s.name.split("~")[0] == root or s.name in cut)
        for p in (s.rect.origin, s.rect.origin + s.rect.u + s.rect.v)
    ]
    u = [float((p - rect.origin) @ eu) for p in corners]
    v = [float((p - rect.origin) @ ev) for p in corners]
    origin = rect.origin + min(u) * eu + min(v) * ev
    return root, Rect(origin, (max(u) - min(u)) * eu, (max(v) - min(v)) * ev)


def zone_surface(
    scene: Scene,
    patches: Patches,
    kind: str,
    origin,
    direction,
    seen: int | None = None,
    drawn: Sequence[ZoneEdit] = (),
) -> tuple[str, Rect]:
    """(surface name, its Rect) on which a zone of ``kind`` drawn along the view ray
    (``origin``, ``direction``) goes, ``seen`` being the patch under the cursor (None:
    nothing). For a kind placed on ceilings (``placement``), the first drawable surface
    facing down that the ray crosses up to the one seen (a ceiling seen from below, or
    looked through from above); the drawable surface seen, if its class (a wall for a
    luminaire; any planar face for a window) is in the kind's placement, instead when it
    faces the view more squarely (by ``HEAD_ON``) than that ceiling. A surface a
    drawn zone (of ``drawn``) has cut is named as it was drawn on (``drawn_on``). A
    DesignError says where such zones go when there is none."""
    where = placement(kind)  # DesignError for an unknown kind
    p0, d = np.asarray(origin, float), np.asarray(direction, float)
    limit = np.inf
    if seen is not None:
        t = _plane_distance(patches.origin[seen], patches.normal[seen], p0, d)
        limit = np.inf if t is None else t * (1 + 1e-6) + 1e-9
    found = []
    if CEILING in where:
        drawable = dict(rect_surfaces(scene))
        for t, name in surfaces_on_ray(scene, p0, d):
            rect = drawable.get(name)
            if t <= limit and rect is not None and surface_class(rect.normal) == CEILING:
                found.append((name, rect))
                break
    if seen is not None:
        face = drawable_surface(scene, patches, seen)
        if face is not None and surface_class(face[1].normal) in where:
            found.append(face)
    if found:
        # The ceiling the ray crosses, unless the surface seen faces the view more
        # squarely: from above (Top view) the wall seen at the edge is grazed and the
        # ceiling meant; looking at a wall from the side, the ceiling crossed near its
        # edge is grazed and the wall meant.
        square = [abs(float(r.normal @ d)) / float(np.linalg.norm(d)) for _, r in found]
        best = found[-1] if square[-1] > square[0] + HEAD_ON else found[0]
        return drawn_on(scene, drawn, *best)
    raise DesignError(
        f"{kind} zones are drawn on {placement_text(where)}, on a planar rectangle that "
        "is not a zone yet; there is none under the cursor"
    )


def surface_label(name: str) -> str:
    """A surface's name for people: the pieces a drawn zone leaves (``"ceiling~3"``)
    are the surface they came from, an imported group's rectangles (``"walls.rect2"``)
    its faces: ``"ceiling"``, ``"walls, face 2"``."""
    root = name.split("~")[0]
    group, dot, number = root.rpartition(".rect")
    return f"{group}, face {number}" if dot and number.isdigit() else root


def zone_size(rect=None, outline=None) -> tuple[float, float, float]:
    """(width, height, area) of a drawn zone, m and m²: its rectangle (u0, v0, u1, v1),
    or its polygon's bounds and area."""
    if outline is not None:
        p = np.asarray(outline, float)
        w, h = np.ptp(p, axis=0)
        x, y = p[:, 0], p[:, 1]
        area = 0.5 * abs(float(x @ np.roll(y, -1) - y @ np.roll(x, -1)))
        return float(w), float(h), area
    u0, v0, u1, v1 = (float(c) for c in rect)
    return abs(u1 - u0), abs(v1 - v0), abs(u1 - u0) * abs(v1 - v0)


def face_zone(
    scene: Scene, patches: Patches, patch: int, drawn: Sequence[ZoneEdit] = ()
) -> tuple[str, tuple[float, float, float, float]]:
    """(surface name, rect) of a zone covering the whole planar face under ``patch``:
    the face picked in the view made a zone (a window on a wall, say). A piece a drawn
    zone left is given in the metres of the surface it was cut from (``drawn_on``).
    DesignError when the face is no drawable rectangle (a zone already, or curved)."""
    found = drawable_surface(scene, patches, patch)
    if found is None:
        name = patches.surface_names[patches.surface_id[patch]]
        raise DesignError(
            f"the picked face ({surface_label(name)}) cannot become a zone: it is a zone "
            "already, or not a planar rectangle; draw the zone on it instead"
        )
    name, rect = found
    root, frame = drawn_on(scene, drawn, name, rect)
    eu, ev = frame.u / np.linalg.norm(frame.u), frame.v / np.linalg.norm(frame.v)
    corners = [rect.origin, rect.origin + rect.u + rect.v]
    u = [float((c - frame.origin) @ eu) for c in corners]
    v = [float((c - frame.origin) @ ev) for c in corners]
    return root, (min(u), min(v), max(u), max(v))
