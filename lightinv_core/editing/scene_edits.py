"""The scene as the user edits it: picked patches, drawn emitter zones, reflectances.

``SceneEdits`` is the document's concern for the scene (a mixin over
``state.DocumentState``). Drawing a zone or changing a reflectance changes the patches,
so the project is re-meshed (``set_project(..., rebuild=True)``) and the operator is
built again or loaded from the cache; the rules of drawn zones are in zones.py.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from lightinv_core.editing import rules
from lightinv_core.editing import zones as _zones
from lightinv_core.editing.state import DocumentState
from lightinv_core.errors import DesignError
from lightinv_core.project import Project
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.scene.model import Rect


class SceneEdits(DocumentState):
    """Pick patches, draw and remove emitter zones, change a group's reflectance."""

    def set_selection(self, patch_ids) -> None:
        """Replace the picked patches (ids, any order, repeats dropped)."""
        self.selection = np.unique(np.asarray(patch_ids, dtype=np.int64))
        self._emit_selection()

    # -- emitter zones drawn by the user ------------------------------------------------------
    @property
    def user_zones(self) -> tuple[ZoneEdit, ...]:
        """Zones the project adds to its scene."""
        return self._project.scene.zones

    def drawable_surface(self, patch: int) -> tuple[str, Rect] | None:
        """(surface name, Rect) under a patch if a zone may be drawn there, else None."""
        return _zones.drawable_surface(self.scene, self.patches, patch)

    def zone_surface(
        self, kind: str, origin, direction, seen: int | None = None
    ) -> tuple[str, Rect]:
        """(surface name, Rect) a zone of ``kind`` drawn along a view ray goes on: the
        patch ``seen`` under the cursor's surface if it suits, else the first along the
        ray (``zones.zone_surface``), named as the drawn zones name it (a piece a drawn
        zone left: the surface it was cut from); DesignError saying where such zones go
        if none."""
        return _zones.zone_surface(
            self.scene, self.patches, kind, origin, direction, seen, self.user_zones
        )

    def face_zone(self, patch: int) -> tuple[str, tuple[float, float, float, float]]:
        """(surface name, rect) of a zone covering the whole face under ``patch``, as the
        drawn zones name it (``zones.face_zone``); DesignError if it cannot be one."""
        return _zones.face_zone(self.scene, self.patches, patch, self.user_zones)

    def new_zone_name(self) -> str:
        """A free name for a drawn zone (Z1, Z2, ...)."""
        return _zones.new_zone_name(self.scene)

    def set_user_zones(self, zones) -> None:
        """Replace the drawn zones: the scene is rebuilt and re-meshed (the operator must
        be built again) and sources in a zone that goes are removed with their rules.
        SceneError on a bad zone, leaving the project unchanged."""
        zones = tuple(zones)
        names = _zones.zone_names_after(self.scene, self.user_zones, zones)
        project = replace(
            self._project,
            scene=replace(self._project.scene, zones=zones),
            design=rules.only_in_zones(self.design, names),
        )
        self._remesh(project, "drawn zones")

    def add_user_zone(self, name: str, kind: str, surface: str, rect) -> ZoneEdit:
        """Draw a new zone ``name`` of ``kind`` on ``surface`` at ``rect`` (u0, v0, u1, v1)
        metres of the surface; SceneError on a bad zone, leaving the project unchanged."""
        edit = ZoneEdit(name, kind, surface, tuple(rect))
        self.set_user_zones((*self.user_zones, edit))
        return edit

    # -- materials ------------------------------------------------------------------------------
    def reflectance(self, group: str) -> float:
        """The area-weighted reflectance of a lighting group's surfaces (0 to 1)."""
        surfaces = [x for x in self.scene.surfaces if x.group == group]
        if not surfaces:
            raise DesignError(f"no lighting group {group!r} in the scene")
        area = sum(x.area for x in surfaces)
        return sum(x.reflectance * x.area for x in surfaces) / area

    def set_reflectance(self, group: str, value: float | None) -> None:
        """Give a lighting group's surfaces ``value`` (None: the scene's own again). The
        patches change, so the operator is built again (or loaded from the cache);
        SceneError or ProjectError on a bad value, leaving the project unchanged."""
        current = dict(self._project.scene.reflectances)
        if value is None:
            current.pop(group, None)
        else:
            current[group] = float(value)
        spec = replace(self._project.scene, reflectances=tuple(sorted(current.items())))
        if spec == self._project.scene:
            return
        self._remesh(replace(self._project, scene=spec), f"reflectance of {group}")

    def _remesh(self, project: Project, label: str) -> None:
        """Make ``project``, this one with another scene, current (an edit called
        ``label``): its scene is loaded first, so an error changes nothing."""
        before = self._project
        self.set_project(project, self.path, rebuild=True)
        self.mark_dirty()
        self._edited(label, before)
