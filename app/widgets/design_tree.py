"""The scene and design tree: surfaces, emitter zones, sources, intentions, arrays, work
planes, observers, rules and goals, refreshed from the document; double-clicks and its
context menu ask the window to add or edit an intention or an observer, or delete one
(or a rule)."""

from __future__ import annotations

from PySide6 import QtCore, QtGui, QtWidgets

from app.dialogs.intention_dialog import intention_target
from app.document import Document
from lightinv_core.editing.rules import rule_text
from lightinv_core.goals import goal_spec
from lightinv_core.kinds import Bound


def arrays_text(arrays) -> str:
    """How many arrays and luminaires in all: "1 array, 6 luminaires"."""
    n, total = len(arrays), sum(a.count for a in arrays)
    return f"{n} array{'s' * (n != 1)}, {total} luminaire{'s' * (total != 1)}"


def goal_texts(goal) -> list[str]:
    """A goal's row: its name from the goals registry ("Least electric power", not
    the file's ``min_electric_power``), then the unit and the source kinds it counts."""
    try:
        spec = goal_spec(goal.kind)
    except KeyError:  # a kind no longer registered: its file name is all there is
        return [str(goal.kind), ", ".join(goal.kinds)]
    details = [f"in {spec.unit}"] if spec.unit else []
    if goal.kinds:
        details.append("of " + ", ".join(goal.kinds))
    return [spec.menu, ", ".join(details)]


class DesignTree(QtWidgets.QTreeWidget):
    """Surfaces (groups), emitter zones, sources, lighting intentions and goals."""

    groupActivated = QtCore.Signal(str)
    intentionActivated = QtCore.Signal(str)  # edit it
    workplaneActivated = QtCore.Signal(str)  # add an intention on its grid
    intentionDeleted = QtCore.Signal(str)
    ruleDeleted = QtCore.Signal(int)
    observerActivated = QtCore.Signal(str)  # edit it
    observerChosen = QtCore.Signal(str)  # clicked: picked, as in the view
    observerDeleted = QtCore.Signal(str)
    calcActivated = QtCore.Signal(str)  # edit a calculation object
    calcDeleted = QtCore.Signal(str)

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        self.setHeaderLabels(["item", "details"])
        self.setColumnWidth(0, 170)
        # Imported names differ at their end (IfcWallStandardCase:Wand-Ext-ERDG-1, -2,
        # ...): cut in the middle, every row of an IFC house read "IfcWallStandardCa...".
        self.setTextElideMode(QtCore.Qt.ElideMiddle)
        for sig in (doc.sceneChanged, doc.designChanged, doc.operatorChanged):
            sig.connect(self.refresh)
        self.itemClicked.connect(self._clicked)
        self.itemDoubleClicked.connect(self._double_clicked)
        self.setContextMenuPolicy(QtCore.Qt.CustomContextMenu)
        self.customContextMenuRequested.connect(self._context_menu)

    def refresh(self) -> None:
        self.clear()
        d, p = self.doc, self.doc.patches
        if p is None:
            return
        groups = QtWidgets.QTreeWidgetItem(self, ["Surfaces", f"{p.n:,} patches"])
        for k, g in enumerate(p.group_names):
            n = int((p.group_id == k).sum())
            QtWidgets.QTreeWidgetItem(groups, [g, f"{n:,} patches"]).setData(0, 256, ("group", g))
        zones = QtWidgets.QTreeWidgetItem(self, ["Emitter zones", str(len(d.scene.zones))])
        for z in d.scene.zones:
            w, h = d.zone_size(z.name)
            QtWidgets.QTreeWidgetItem(zones, [z.name, f"{z.kind}, {w:.2f} x {h:.2f} m"]).setData(
                0, 256, ("zone", z.name)
            )
        srcs = QtWidgets.QTreeWidgetItem(self, ["Sources", str(len(d.design.sources))])
        for s in d.design.sources:
            item = QtWidgets.QTreeWidgetItem(
                srcs, [s.name, f"{s.kind} in {s.zone}, {s.area:.2f} m²"]
            )
            item.setData(0, 256, ("source", s.name))
            if s.name == d.current_source:
                item.setSelected(True)
        its = QtWidgets.QTreeWidgetItem(
            self, ["Lighting intentions", str(len(d.design.intentions))]
        )
        for it in d.design.intentions:
            bounds = ", ".join(
                f"{k} {getattr(it, k):g}" for k in Bound if getattr(it, k) is not None
            )
            QtWidgets.QTreeWidgetItem(
                its, [it.name, f"{intention_target(it)}: {bounds} {it.quantity}, {it.scenario}"]
            ).setData(0, 256, ("intention", it.name))
        if d.design.arrays:
            # The count beside a heading is of the items under it (it showed the
            # luminaires, "Luminaire arrays 6" for one array of 2 x 3).
            arrays = QtWidgets.QTreeWidgetItem(
                self, ["Luminaire arrays", arrays_text(d.design.arrays)]
            )
            for a in d.design.arrays:
                QtWidgets.QTreeWidgetItem(
                    arrays,
                    [a.name, f"{a.rows} x {a.columns} = {a.count} {a.product} in {a.zone}"],
                )
        if d.design.workplanes:
            planes = QtWidgets.QTreeWidgetItem(self, ["Work planes", str(len(d.design.workplanes))])
            for w in d.design.workplanes:
                about = f"{w.height:g} m over {w.group}, border {w.border:g} m, {w.edition}"
                QtWidgets.QTreeWidgetItem(planes, [w.name, about]).setData(
                    0, 256, ("workplane", w.name)
                )
        if d.design.observers:
            eyes = QtWidgets.QTreeWidgetItem(self, ["Observers", str(len(d.design.observers))])
            for o in d.design.observers:
                view = f"azimuth {o.azimuth:g}°" if o.azimuth is not None else "direction"
                QtWidgets.QTreeWidgetItem(
                    eyes,
                    [o.name, f"({o.position[0]:g}, {o.position[1]:g}), eye {o.height:g} m, {view}"],
                ).setData(0, 256, ("observer", o.name))
        if d.design.calc_objects:
            objs = d.design.calc_objects
            calcs = QtWidgets.QTreeWidgetItem(self, ["Calculation objects", str(len(objs))])
            for c in objs:
                about = f"{c.spec.label} ({c.spec.symbol}): {c.spec.describe(c)}"
                QtWidgets.QTreeWidgetItem(calcs, [c.name, about]).setData(0, 256, ("calc", c.name))
        rules_item = QtWidgets.QTreeWidgetItem(self, ["Rules", str(len(d.design.rules))])
        for k, rule in enumerate(d.design.rules):
            what, bounds = rule_text(rule)
            QtWidgets.QTreeWidgetItem(rules_item, [what, bounds]).setData(0, 256, ("rule", k))
        goals = QtWidgets.QTreeWidgetItem(self, ["Goals", str(len(d.design.goals))])
        for g in d.design.goals:
            QtWidgets.QTreeWidgetItem(goals, goal_texts(g))
        self.expandAll()
        # The details column is cut in a narrow dock: each row's whole text on hover.
        for item in self.findItems("", QtCore.Qt.MatchContains | QtCore.Qt.MatchRecursive):
            item.setToolTip(1, item.text(1))
            item.setToolTip(0, item.text(0))

    def _clicked(self, item, _col) -> None:
        data = item.data(0, 256)
        if data and data[0] == "source":
            self.doc.set_current_source(data[1])
        elif data and data[0] == "observer":
            self.observerChosen.emit(data[1])

    def _double_clicked(self, item, _col) -> None:
        data = item.data(0, 256)
        if data and data[0] == "group":
            self.groupActivated.emit(data[1])
        elif data and data[0] == "intention":
            self.intentionActivated.emit(data[1])
        elif data and data[0] == "observer":
            self.observerActivated.emit(data[1])
        elif data and data[0] == "workplane":
            self.workplaneActivated.emit(data[1])
        elif data and data[0] == "calc":
            self.calcActivated.emit(data[1])

    def select_observer(self, name: str) -> None:
        """Make observer ``name``'s row the current one (picked in the view)."""
        for item in self.findItems(name, QtCore.Qt.MatchExactly | QtCore.Qt.MatchRecursive):
            if item.data(0, 256) == ("observer", name):
                self.setCurrentItem(item)
                self.scrollToItem(item)

    def intention_menu(self, name: str) -> QtWidgets.QMenu:
        """The menu of an intention's item: edit it, delete it."""
        menu = QtWidgets.QMenu(self)
        menu.addAction("Edit...", lambda: self.intentionActivated.emit(name))
        menu.addAction("Delete", lambda: self.intentionDeleted.emit(name))
        return menu

    def _context_menu(self, pos: QtCore.QPoint) -> None:
        item = self.itemAt(pos)
        data = item.data(0, 256) if item is not None else None
        if data and data[0] == "intention":
            self.intention_menu(data[1]).exec(self.viewport().mapToGlobal(pos))
        elif data and data[0] == "calc":
            menu = QtWidgets.QMenu(self)
            menu.addAction("Edit...", lambda: self.calcActivated.emit(data[1]))
            menu.addAction("Delete", lambda: self.calcDeleted.emit(data[1]))
            menu.exec(self.viewport().mapToGlobal(pos))
        elif data and data[0] == "rule":
            menu = QtWidgets.QMenu(self)
            menu.addAction("Delete", lambda: self.ruleDeleted.emit(data[1]))
            menu.exec(self.viewport().mapToGlobal(pos))
        elif data and data[0] == "observer":
            menu = QtWidgets.QMenu(self)
            menu.addAction("Edit...", lambda: self.observerActivated.emit(data[1]))
            menu.addAction("Delete", lambda: self.observerDeleted.emit(data[1]))
            menu.exec(self.viewport().mapToGlobal(pos))
        elif data and data[0] == "group":
            menu = QtWidgets.QMenu(self)
            menu.addAction("Add a lighting intention...", lambda: self.groupActivated.emit(data[1]))
            menu.exec(self.viewport().mapToGlobal(pos))
        elif data and data[0] == "workplane":
            menu = QtWidgets.QMenu(self)
            menu.addAction(
                "Add a lighting intention...", lambda: self.workplaneActivated.emit(data[1])
            )
            menu.exec(self.viewport().mapToGlobal(pos))

    def keyPressEvent(self, event: QtGui.QKeyEvent) -> None:
        """Delete removes the selected intention, rule or observer."""
        item = self.currentItem()
        data = item.data(0, 256) if item is not None else None
        deleting = event.key() in (QtCore.Qt.Key_Delete, QtCore.Qt.Key_Backspace)
        if deleting and data and data[0] == "intention":
            self.intentionDeleted.emit(data[1])
            return
        if deleting and data and data[0] == "calc":
            self.calcDeleted.emit(data[1])
            return
        if deleting and data and data[0] == "rule":
            self.ruleDeleted.emit(data[1])
            return
        if deleting and data and data[0] == "observer":
            self.observerDeleted.emit(data[1])
            return
        super().keyPressEvent(event)
