"""The window's actions, menus and toolbar: one function per menu.

``create_actions`` makes the ``QAction``s as attributes of the window (``act_open``,
``act_run``, ``mode_actions``, ...), which tests and scripts reach; the menu functions
only place them. Slots are the window's public methods, so a menu entry and a script do
the same thing.
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6 import QtGui, QtWidgets

from app.window import help_pages
from lightinv_core.export import exporters
from lightinv_core.goals import goal_spec, goal_specs
from lightinv_core.scene.builtin import BUILTIN_SCENES
from lightinv_core.sources.types import source_types

MODES = (
    ("navigate", "Navigate"),
    ("select", "Select patches"),
    ("move", "Move source, observer or sensor"),
    ("zone", "Draw zone"),
    ("polygon", "Draw polygon zone"),
)
CAMERAS = ("iso", "top", "front", "back", "left", "right")
TOOLBAR_CAMERAS = ("iso", "top", "front", "back")
"""The cameras on the toolbar (all are in the View menu): what fits a 1366 px screen."""


def action(
    parent: QtWidgets.QWidget, text: str, slot: Callable, shortcut=None, checkable=False
) -> QtGui.QAction:
    """A ``QAction`` calling ``slot`` when triggered."""
    act = QtGui.QAction(text, parent)
    if shortcut:
        act.setShortcut(shortcut)
    act.setCheckable(checkable)
    act.triggered.connect(slot)
    return act


def create_actions(win) -> None:
    """Every action of the main window ``win``, as its attributes."""
    ks = QtGui.QKeySequence
    files, edits = win.files, win.edits
    win.act_open = action(win, "&Open project...", files.open_dialog, ks.Open)
    win.act_save = action(win, "&Save", win.save, ks.Save)
    win.act_save_as = action(win, "Save &As...", files.save_as_dialog, ks.SaveAs)
    win.act_import = action(win, "&Import model...", lambda _=False: files.import_obj_dialog())
    win.act_png = action(win, "Export viewport &PNG...", files.export_png_dialog)
    win.act_report = action(win, "Export &report (PDF)...", files.export_report_dialog)
    # One entry per registered export format (lightinv_core.export.registry).
    win.export_actions = {
        e.name: action(
            win, f"{e.label}...", lambda _=False, n=e.name: files.export_design_dialog(n)
        )
        for e in exporters()
    }
    win.act_quit = action(win, "&Quit", win.close, ks.Quit)
    win.act_precompute = action(win, "Precompute", win.start_precompute)
    win.act_cancel = action(win, "Cancel", win.cancel_precompute)
    win.act_cancel.setEnabled(False)
    # The run controller is made after the actions: look it up when triggered.
    win.act_run = action(win, "&Run optimisation", lambda: win.runs.start(), "F5")
    win.act_cancel_run = action(win, "Cancel optimisation", lambda: win.runs.cancel())
    win.act_cancel_run.setEnabled(False)
    win.act_intention = action(
        win, "Add intention on selection...", lambda _=False: edits.add_intention_on_selection()
    )
    win.act_clear = action(win, "Clear selection", lambda: win.doc.set_selection([]))
    win.mode_group = QtGui.QActionGroup(win)
    win.mode_actions = {}
    for mode, text in MODES:
        act = action(win, text, lambda _=False, m=mode: win.set_mode(m), checkable=True)
        win.mode_group.addAction(act)
        win.mode_actions[mode] = act
    win.mode_actions["navigate"].setChecked(True)
    # What Draw zone makes: it decides the surface too (a luminaire zone drawn in Top
    # view goes on the ceiling the view looks through, not on the floor it sees).
    win.zone_kind_box = QtWidgets.QComboBox()
    for t in source_types():
        win.zone_kind_box.addItem(f"{t.label.lower()} zone", str(t.kind))
    win.zone_kind_box.setToolTip("The kind of zone Draw zone makes")
    win.camera_actions = {
        name: action(win, f"{name.title()} view", lambda _=False, n=name: win.viewport.camera(n))
        for name in CAMERAS
    }


def file_menu(win, bar: QtWidgets.QMenuBar) -> None:
    """File: new from a built-in scene, import, open, recent, save, export, quit."""
    file = bar.addMenu("&File")
    new = file.addMenu("&New from built-in scene")
    for name in BUILTIN_SCENES:
        new.addAction(action(win, name, lambda _=False, n=name: win.new_project(n)))
    for act in (win.act_import, win.act_open):
        file.addAction(act)
    win.recent_menu = file.addMenu("Open &recent")
    file.addSeparator()
    for act in (win.act_save, win.act_save_as, win.act_png, win.act_report):
        file.addAction(act)
    export = file.addMenu("Export &design")
    for act in win.export_actions.values():
        export.addAction(act)
    file.addSeparator()
    file.addAction(win.act_quit)


def edit_menu(win, bar: QtWidgets.QMenuBar) -> None:
    """Edit: undo and redo every edit of the design, the drawn zones and the run settings."""
    edit = bar.addMenu("&Edit")
    win.act_undo = win.undo_stack.createUndoAction(win, "&Undo")
    win.act_undo.setShortcut(QtGui.QKeySequence.Undo)
    win.act_redo = win.undo_stack.createRedoAction(win, "&Redo")
    win.act_redo.setShortcut(QtGui.QKeySequence.Redo)
    edit.addAction(win.act_undo)
    edit.addAction(win.act_redo)


def view_menu(win, bar: QtWidgets.QMenuBar) -> None:
    """View: the camera presets, then every panel and the toolbar (shown when ticked,
    so a closed panel comes back from here)."""
    view = bar.addMenu("&View")
    for act in win.camera_actions.values():
        view.addAction(act)
    view.addSeparator()
    win.panel_actions = {}
    for dock in win.findChildren(QtWidgets.QDockWidget):
        act = dock.toggleViewAction()
        act.setText(f"{dock.windowTitle()} panel")
        win.panel_actions[dock.objectName()] = act
        view.addAction(act)
    view.addSeparator()
    win.act_restore_layout = action(win, "Restore the panel layout", win.restore_layout)
    view.addAction(win.act_restore_layout)


def help_menu(win, bar: QtWidgets.QMenuBar) -> None:
    """Help: the user guide, the documentation folder, about."""
    help_ = bar.addMenu("&Help")
    win.help_actions = {
        "guide": action(
            win, "User guide (the window)", lambda _=False: help_pages.open_doc(win, "app.md")
        ),
        "docs": action(win, "All documentation", lambda _=False: help_pages.open_doc(win, "")),
        "inputs": action(
            win,
            "Messages and what they mean",
            lambda _=False: help_pages.open_doc(win, "bad-input.md"),
        ),
        "about": action(win, "About LightInv", lambda _=False: help_pages.about(win)),
    }
    for act in win.help_actions.values():
        help_.addAction(act)


def design_menu(win, bar: QtWidgets.QMenuBar) -> None:
    """Design: intentions on the selection, rules, goals, the viewport's modes."""
    design = bar.addMenu("&Design")
    for act in (win.act_intention, win.act_clear):
        design.addAction(act)
    win.act_add_rule = action(win, "Add a geometric &rule...", lambda _=False: win.edits.add_rule())
    design.addAction(win.act_add_rule)
    win.act_add_observer = action(
        win, "Add &observer (glare, UGR)...", lambda _=False: win.edits.add_observer()
    )
    design.addAction(win.act_add_observer)
    win.act_glare_limit = action(
        win, "Add UGR &limit at the observers...", lambda _=False: win.edits.add_glare_limit()
    )
    design.addAction(win.act_glare_limit)
    win.act_add_calc = action(
        win, "Add &calculation object...", lambda _=False: win.edits.add_calc_object()
    )
    design.addAction(win.act_add_calc)
    # Two goals make a Pareto front: both power goals, or annual energy and glazing area.
    # Every registered goal is offered; one the design cannot take (a match without a
    # target lighting) is refused with the model's reason.
    menu = design.addMenu("&Goals (two: a Pareto front)")
    win.goal_actions = {}
    climate = False
    for spec in sorted(goal_specs(), key=lambda s: s.annual):  # the climate goals last
        if spec.annual and not climate:
            climate = True
            menu.addSection("Climate (a weather file and a work plane)")
        kind = str(spec.kind)
        act = action(
            win,
            goal_menu_text(kind),
            lambda on, k=kind: win.edits.set_goal(k, on),
            checkable=True,
        )
        win.goal_actions[kind] = act
        menu.addAction(act)
    design.addSeparator()
    for act in win.mode_actions.values():
        design.addAction(act)


def goal_menu_text(kind: str) -> str:
    """The Design > Goals entry of a goal, with its units."""
    spec = goal_spec(kind)
    return spec.with_units(spec.menu)


def check_goals(win) -> None:
    """Tick the Design > Goals entries as the design has them."""
    kinds = {g.kind for g in win.doc.design.goals} if win.doc.project is not None else set()
    for kind, act in getattr(win, "goal_actions", {}).items():
        act.blockSignals(True)
        act.setChecked(kind in kinds)
        act.blockSignals(False)


def compute_menu(win, bar: QtWidgets.QMenuBar) -> None:
    """Compute: precompute the operator, run the optimisation, and cancel either."""
    compute = bar.addMenu("&Compute")
    for act in (win.act_precompute, win.act_cancel, win.act_run, win.act_cancel_run):
        compute.addAction(act)


def toolbar_text(win) -> tuple:
    """(action, short toolbar label) pairs."""
    m = win.mode_actions
    return (
        (m["select"], "Select"),
        (m["move"], "Move"),
        (m["polygon"], "Draw polygon"),
        (win.act_run, "Run"),
        (win.act_cancel_run, "Cancel run"),
        (win.act_intention, "Add intention"),
    )


def main_toolbar(win) -> QtWidgets.QToolBar:
    """The toolbar: files, precompute, run, modes (and the kind of zone drawn),
    intention, cameras."""
    tools = win.addToolBar("Main")
    tools.setObjectName("main toolbar")
    groups = (
        (win.act_open, win.act_save, win.act_precompute, win.act_cancel),
        (win.act_run, win.act_cancel_run),
        (*win.mode_actions.values(), win.zone_kind_box, win.act_intention),
        tuple(win.camera_actions[c] for c in TOOLBAR_CAMERAS),
    )
    # Short toolbar labels (the menus keep the full names), so the camera buttons still
    # fit a 1366 px wide screen.
    for act, short in toolbar_text(win):
        act.setIconText(short)
        act.setToolTip(act.text().replace("&", "").rstrip("."))
    for i, group in enumerate(groups):
        if i:
            tools.addSeparator()
        for item in group:
            if isinstance(item, QtWidgets.QWidget):
                tools.addWidget(item)
            else:
                tools.addAction(item)
    return tools


def build_menus(win) -> None:
    """The menu bar and the toolbar of ``win`` (its actions made first)."""
    bar = win.menuBar()
    tools = main_toolbar(win)
    for menu in (file_menu, edit_menu, view_menu, design_menu, compute_menu, help_menu):
        menu(win, bar)
    win.panel_actions["toolbar"] = tools.toggleViewAction()
    win.panel_actions["toolbar"].setText("Toolbar")
    view = next(a.menu() for a in bar.actions() if a.text() == "&View")
    view.insertAction(win.act_restore_layout, win.panel_actions["toolbar"])


def fill_recent(win, paths: list[str]) -> None:
    """The File > Open recent entries."""
    win.recent_menu.clear()
    for p in paths:
        win.recent_menu.addAction(action(win, p, lambda _=False, q=p: win.open_path(q)))
    win.recent_menu.setEnabled(bool(paths))
