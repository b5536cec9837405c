"""Emitter zones drawn by the user, as pure functions of the scene.

A drawn zone (``ZoneEdit``) goes on a planar rectangular surface that is not already a
zone; the project stores the drawn zones with its scene, and the scene is rebuilt with
them. When a drawn zone goes (deleted, renamed), so do the sources placed in it and the
rules that name them (``rules.only_in_zones``).
"""

from __future__ import annotations

from collections.abc import Sequence

from lightinv_core.editing.rules import free_name
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.scene.model import Rect, Scene
from lightinv_core.scene.patches import Patches


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
