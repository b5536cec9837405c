"""Editing the design from the window: what the viewport's picks, drags and drawn zones
do, and the edits that ask a dialog first (intentions, rules, goals).

``DesignEdits`` turns the viewport's signals into document edits and asks the editing
dialogs; every edit goes through the document (Edit > Undo takes it back), an edit the
model refuses is shown and nothing changes. Each ``dialog=`` argument replaces the
dialog that would be shown (tests, scripts): a dialog whose result is set already is
not shown.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from PySide6 import QtCore

from app.dialogs import ask
from app.dialogs.calc_dialog import CalcObjectDialog
from app.dialogs.intention_dialog import IntentionDialog, intention_target
from app.dialogs.observer_dialog import ObserverDialog
from app.dialogs.rule_dialog import RuleDialog
from app.dialogs.zone_dialog import ZoneDialog
from app.view import observer_overlay
from app.view.observer_drag import ObserverDrag
from app.view.zone_frame import ZoneFrame
from app.window import actions
from lightinv_core.design.preset_glare import strictest_preset
from lightinv_core.errors import LightInvError
from lightinv_core.light.glare import observer_eyes
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.scene.model import Rect

MIN_ZONE = 0.05  # m: a drawn zone narrower than this is a slip of the mouse


def surface_frame_of(zone: ZoneFrame, edit: ZoneEdit) -> ZoneFrame:
    """The frame of the surface a drawn zone was cut from (its corners are measured along
    it): the zone's own axes, its origin moved back by the zone's first corner."""
    u0, v0, u1, v1 = edit.rect
    origin = zone.origin - u0 * zone.u - v0 * zone.v
    return ZoneFrame(None, edit.surface, rect=Rect(origin, u1 * zone.u, v1 * zone.v))


class DesignEdits(QtCore.QObject):
    """The design edits of a main window (``window``)."""

    def __init__(self, window):
        super().__init__(window)
        self.win, self.doc = window, window.doc
        self.current_observer: str | None = None  # picked in the view, drawn green
        # Observers: picked and dragged in the view (Move mode), edited and deleted from
        # the view or the tree; wired here, beside the edits they make.
        self.observer_drag = ObserverDrag(window.viewport, self.observer_eyes)
        self.observer_drag.picked.connect(self.observer_picked)
        self.observer_drag.dragged.connect(self.observer_dragged)
        self.observer_drag.activated.connect(self.edit_observer)
        window.tree.observerActivated.connect(self.edit_observer)
        window.tree.observerChosen.connect(self.observer_picked)
        window.tree.observerDeleted.connect(self.delete_observer)

    def _say(self, message: str, ms: int = 4000) -> None:
        self.win.statusBar().showMessage(message, ms)

    # -- the viewport's picks, drags and zones -------------------------------------------------
    def picked(self, ids: np.ndarray, add: bool) -> None:
        """Patches picked in the view: the selection (``add``: added to it)."""
        ids = np.union1d(self.doc.selection, ids) if add else ids
        self.doc.set_selection(ids)
        self._say(f"{len(ids)} patches selected")

    def dragged(self, du: float, dv: float) -> None:
        """The current source dragged by (du, dv) m in its zone."""
        if self.doc.current_source is not None:
            self.doc.move_source(self.doc.current_source, du, dv)

    def surface_frame(self, seen: int | None, near, far) -> ZoneFrame | None:
        """The surface a zone of the kind being drawn goes on, for the view ray near ->
        far through the cursor (``seen``: the patch under it, if any)."""
        try:
            name, rect = self.doc.zone_surface(self.draw_kind(), near, far - near, seen)
        except LightInvError as exc:
            self._say(str(exc), 6000)
            return None
        self._say(f"Drawing a {self.draw_kind()} zone on {name}")
        return ZoneFrame(None, name, rect=rect)

    def draw_kind(self) -> str:
        """The kind of zone Draw zone makes (the toolbar's choice)."""
        return self.win.zone_kind_box.currentData()

    def zone_drawn(self, surface, u0, v0, u1, v1, dialog: ZoneDialog | None = None) -> bool:
        """Ask for the new zone's name and kind, then rebuild the scene with it."""
        if abs(u1 - u0) < MIN_ZONE or abs(v1 - v0) < MIN_ZONE:
            self._say("Zone too small: drag a larger rectangle")
            return False
        return self._add_zone(surface, dialog, rect=(u0, v0, u1, v1))

    def polygon_drawn(self, surface: str, corners, dialog: ZoneDialog | None = None) -> bool:
        """Ask for the new polygon zone's name and kind, then rebuild the scene with it."""
        pts = np.asarray(corners, float)
        span = pts.max(axis=0) - pts.min(axis=0) if len(pts) else np.zeros(2)
        if len(pts) < 3 or span.min() < MIN_ZONE:
            self._say("Zone too small: click at least 3 corners apart")
            return False
        return self._add_zone(surface, dialog, outline=tuple(map(tuple, pts)))

    def _add_zone(self, surface: str, dialog: ZoneDialog | None, **shape) -> bool:
        """Ask for a drawn zone's name and kind, then rebuild the scene with it
        (``shape``: its ``rect`` or its ``outline``); errors shown, nothing changed."""
        if dialog is None:
            dialog = ZoneDialog(surface, self.doc.new_zone_name(), self.win, **shape)
            dialog.kind.setCurrentIndex(max(0, dialog.kind.findData(self.draw_kind())))
        if not ask.accepted(dialog):
            return False
        try:
            name, kind = dialog.name.text().strip(), dialog.kind.currentData()
            edit = ZoneEdit(name, kind, surface, **shape)  # a bad name stops nothing
            self.win.stop_worker()
            self.doc.set_user_zones((*self.doc.user_zones, edit))
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
            return False
        return True

    # -- intentions ----------------------------------------------------------------------------
    def add_intention_on_selection(self, dialog: IntentionDialog | None = None) -> bool:
        """Ask for bounds and add an intention on the picked patches."""
        if len(self.doc.selection) == 0:
            ask.inform(self.win, "Select patches first (Select patches mode).")
            return False
        label = f"{len(self.doc.selection)} patches"
        return self._add_intention(label, None, self.doc.selection, dialog)

    def add_intention_on_group(self, group: str, dialog: IntentionDialog | None = None) -> bool:
        """Ask for bounds and add an intention on a group's patches."""
        return self._add_intention(group, group, None, dialog)

    def add_intention_on_grid(self, plane: str, dialog: IntentionDialog | None = None) -> bool:
        """Ask for bounds and add an intention on a work plane's grid points."""
        dialog = dialog or IntentionDialog(f"work plane {plane}", self.win, on_grid=True)
        return self._add_intention(plane, None, None, dialog, grid=plane)

    def _add_intention(self, label, group, patches, dialog, grid=None) -> bool:
        dialog = dialog or IntentionDialog(label, self.win)
        if not ask.accepted(dialog):
            return False
        try:
            self.doc.add_intention(dialog.intention(group=group, patches=patches, grid=grid))
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
            return False
        return True

    def edit_intention(self, name: str, dialog: IntentionDialog | None = None) -> bool:
        """Change an intention's name, quantity or bounds in the intention dialog."""
        old = next((i for i in self.doc.design.intentions if i.name == name), None)
        if old is None:
            return False
        if dialog is None:
            dialog = IntentionDialog(
                intention_target(old), self.win, old.observers is not None, old.grid is not None
            )
            dialog.load(old)
        if not ask.accepted(dialog):
            return False
        try:
            new = dialog.intention(
                group=old.group, patches=old.patches, grid=old.grid, observers=old.observers
            )
            self.doc.replace_intention(name, replace(new, weight=old.weight))
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
            return False
        return True

    def delete_intention(self, name: str) -> None:
        """Remove a lighting intention (Edit > Undo brings it back)."""
        self.doc.remove_intention(name)
        self._say(f"Deleted intention {name} (Edit > Undo to restore)", 6000)

    # -- observers -----------------------------------------------------------------------------
    def observer_eyes(self) -> dict[str, np.ndarray]:
        """{name: eye (x, y, z) m} of the design's observers inside the room (as drawn)."""
        d = self.doc
        if d.project is None or d.patches is None:
            return {}
        out = {}
        for ob in d.design.observers:
            try:
                out[ob.name] = observer_eyes(d.patches, (ob,)).points[0]
            except LightInvError:
                continue  # outside the room: not drawn, not picked
        return out

    def observer_picked(self, name: str) -> None:
        """An observer's ball pressed in the view: draw it green, say what can be done."""
        self.current_observer = name
        d, vp = self.doc, self.win.viewport
        observer_overlay.draw(vp.plotter, d.patches, d.design.observers, name)
        vp.request_render()
        self.win.tree.select_observer(name)
        self._say(
            f"Observer {name}: drag its ball to move it; double-click it, or its row under "
            "Observers, to edit it; Delete there removes it",
            8000,
        )

    def observer_dragged(self, name: str, dx: float, dy: float) -> None:
        """An observer dragged by (dx, dy) m in plan (one undo step per drag)."""
        try:
            self.doc.move_observer(name, dx, dy)
        except LightInvError as exc:
            self._say(str(exc), 6000)

    def edit_observer(self, name: str, dialog: ObserverDialog | None = None) -> bool:
        """Change an observer's name, place, eye height, view or floor group in the
        observer dialog (its limits follow a new name)."""
        old = next((o for o in self.doc.design.observers if o.name == name), None)
        if old is None:
            return False
        if dialog is None:
            groups = list(self.doc.patches.group_names) if self.doc.patches is not None else []
            dialog = ObserverDialog(groups or [old.group], name, old.position, self.win)
            dialog.load(old)
        if not ask.accepted(dialog):
            return False
        picked = self.current_observer
        try:
            new = dialog.observer()
            if picked == name:
                self.current_observer = new.name  # drawn green under its new name
            self.doc.replace_observer(name, new)
        except LightInvError as exc:
            self.current_observer = picked
            ask.warn(self.win, str(exc))
            return False
        return True

    def delete_observer(self, name: str) -> None:
        """Remove an observer; a limit at it alone goes too (Edit > Undo brings both back)."""
        self.doc.remove_observer(name)
        self._say(f"Deleted observer {name} (Edit > Undo to restore)", 6000)

    def add_observer(self, dialog: ObserverDialog | None = None) -> bool:
        """Ask for an observer (an eye the glare rating is judged from) and, ticked, a
        UGR limit at it; add both."""
        if self.doc.project is None:
            return False
        d = self.doc.design
        if dialog is None:
            patches = self.doc.patches
            centre = (0.0, 0.0)
            if patches is not None:
                lo, hi = patches.centroid.min(axis=0), patches.centroid.max(axis=0)
                centre = (round(float(lo[0] + hi[0]) / 2, 2), round(float(lo[1] + 0.1), 2))
            groups = list(patches.group_names) if patches is not None else ["floor"]
            name = next(
                f"observer {k}"
                for k in range(1, 999)
                if f"observer {k}" not in {o.name for o in d.observers}
            )
            preset = strictest_preset(d)
            limit = {} if preset is None else {"limit": preset.ugr_l, "limit_source": preset.label}
            dialog = ObserverDialog(groups, name, centre, self.win, **limit)
        if not ask.accepted(dialog):
            return False
        try:
            taken = {i.name for i in d.intentions}
            self.doc.add_observer(dialog.observer(), dialog.intention(taken))
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
            return False
        return True

    def add_calc_object(self, dialog: CalcObjectDialog | None = None) -> bool:
        """Ask for a calculation object (a task area, a wall or ceiling surface,
        cylindrical or free points) and, ticked, an intention on it; add both."""
        if self.doc.project is None:
            return False
        d = self.doc.design
        if dialog is None:
            patches = self.doc.patches
            groups = list(patches.group_names) if patches is not None else ["floor"]
            taken = {c.name for c in d.calc_objects} | {w.name for w in d.workplanes}
            name = next(f"object {k}" for k in range(1, 999) if f"object {k}" not in taken)
            dialog = CalcObjectDialog(groups, name, self.win)
        if not ask.accepted(dialog):
            return False
        try:
            taken = {i.name for i in d.intentions}
            self.doc.add_calc_object(dialog.calc_object(), dialog.intention(taken))
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
            return False
        return True

    def edit_calc_object(self, name: str, dialog: CalcObjectDialog | None = None) -> bool:
        """Ask again for calculation object ``name`` (its dialog filled) and replace it."""
        old = next((c for c in self.doc.design.calc_objects if c.name == name), None)
        if old is None:
            return False
        if dialog is None:
            groups = list(self.doc.patches.group_names)
            dialog = CalcObjectDialog(groups, name, self.win, old)
        if not ask.accepted(dialog):
            return False
        try:
            self.doc.replace_calc_object(name, dialog.calc_object())
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
            return False
        return True

    def delete_calc_object(self, name: str) -> None:
        """Remove a calculation object and its intentions (Edit > Undo brings them back)."""
        self.doc.remove_calc_object(name)
        self._say(f"Deleted calculation object {name} (Edit > Undo to restore)", 6000)

    def add_glare_limit(self, dialog: IntentionDialog | None = None) -> bool:
        """Ask for a UGR limit at every observer of the design (the intention dialog,
        UGR chosen) and add it."""
        names = [o.name for o in self.doc.design.observers] if self.doc.project else []
        if not names:
            ask.inform(self.win, "Add an observer first (Design > Add observer).")
            return False
        dialog = dialog or IntentionDialog("observers " + ", ".join(names), self.win, True)
        dialog.name.setText("glare")
        if not ask.accepted(dialog):
            return False
        try:
            self.doc.add_intention(dialog.intention(observers=names))
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
            return False
        return True

    # -- rules and goals -----------------------------------------------------------------------
    def add_rule(self, dialog: RuleDialog | None = None) -> bool:
        """Ask for a geometric rule (area, aspect, spacing, align; spacing-to-height and
        clearance on luminaire arrays) and add it."""
        d = self.doc.design if self.doc.project else None
        names = [x.name for x in d.sources] if d is not None else []
        arrays = [a.name for a in d.arrays] if d is not None else []
        if not names and not arrays:
            ask.inform(self.win, "Add sources or luminaire arrays first: rules bind them.")
            return False
        dialog = dialog or RuleDialog(names, self.win, arrays)
        if not ask.accepted(dialog):
            return False
        try:
            self.doc.add_rule(dialog.rule())
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
            return False
        return True

    def delete_rule(self, index: int) -> None:
        """Remove a geometric rule (Edit > Undo brings it back)."""
        self.doc.remove_rule(index)
        self._say("Deleted a rule (Edit > Undo to restore)", 6000)

    def set_goal(self, kind: str, on: bool) -> None:
        """Add or remove a goal (Design > Goals); two goals give a Pareto front."""
        try:
            self.doc.set_goal(kind, on)
        except LightInvError as exc:
            ask.warn(self.win, str(exc))
        actions.check_goals(self.win)
