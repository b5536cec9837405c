"""The window's lists come from the registries: this module registers, from here alone, a
source type, a goal, an intention quantity, an import format and an optimisation method,
and finds each in the window as a user sees it, by its visible text — the kinds a zone
(and so a source) can have, Design > Goals and the run panel's goal list, the intention
dialog's quantities, File > Import model's file filter, the run panel's methods and the
result scatter's axes — then uses each once through the window. Everything is
unregistered after."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtCore, QtWidgets

from app.dialogs import ask
from app.dialogs.import_dialog import ImportDialog
from app.dialogs.intention_dialog import IntentionDialog
from app.dialogs.zone_dialog import ZoneDialog
from app.window.main_window import MainWindow
from lightinv_core.goals import GoalSpec, register_goal, unregister_goal
from lightinv_core.optimize import registry as methods
from lightinv_core.optimize.method import MethodSpec
from lightinv_core.optimize.registry import get_method
from lightinv_core.quantities import QuantitySpec, register_quantity, unregister_quantity
from lightinv_core.scene.importers import registry as importers
from lightinv_core.scene.importers.obj import load_obj
from lightinv_core.sources.types import (
    ZoneLuminaire,
    register_source_type,
    unregister_source_type,
)
from tests.app.conftest import wait_for_operator
from tests.core.test_optimizer_registry import random_search

MODEL = Path(__file__).resolve().parents[2] / "resources" / "models" / "meeting_room.obj"


class LedStrip(ZoneLuminaire):
    """A luminaire kind of its own: a line of LEDs, Lambertian like a luminaire panel."""

    kind = "led_strip"
    label = "LED strip"
    stem = "LS"


def _strips_lit(batch) -> np.ndarray:
    """The goal's batch value: the LED strips giving light, (m,)."""
    strips = [j for j, s in enumerate(batch.problem.design.sources) if s.kind == LedStrip.kind]
    return (batch.flux[:, strips] > 0).sum(axis=1).astype(float)


GOAL = GoalSpec(
    "min_strip_count",
    "LED strips lit",
    "Fewest LED strips",
    "fewest strips",
    "LED strips",
    value=_strips_lit,
    scale=lambda problem: max(len(problem.design.sources), 1),
)
QUANTITY = QuantitySpec(
    "luminance",
    "luminance",
    "luminance L (cd/m²)",
    "cd/m²",
    "luminance, cd/m²",
    high=1e6 / math.pi,
    from_lux=lambda lux, rho: lux * (rho[:, None] if lux.ndim == 2 else rho) / math.pi,
    needs_reflectance=True,
)
IMPORTER = importers.Importer("OBJ copy", (".objcopy",), load_obj, label="An OBJ copy")
METHOD = MethodSpec("random_gui", "Random search (a plug-in)", random_search)


@pytest.fixture
def registered():
    register_source_type(LedStrip())
    register_goal(GOAL)
    register_quantity(QUANTITY)
    importers.register(IMPORTER)
    methods.register(METHOD)
    yield
    methods.unregister(METHOD.name)
    importers.unregister(IMPORTER.name)
    unregister_quantity(QUANTITY.name)
    unregister_goal(GOAL.kind)
    unregister_source_type(LedStrip.kind)


@pytest.fixture
def window(qtbot, tmp_path, registered):
    """A window made after the registrations (its menus and lists are built then)."""
    settings = QtCore.QSettings(str(tmp_path / "settings.ini"), QtCore.QSettings.IniFormat)
    win = MainWindow(settings)
    win.ask_before_discard = False
    win.show()
    yield win
    win.close()


def texts(box: QtWidgets.QComboBox) -> list[str]:
    return [box.itemText(i) for i in range(box.count())]


def test_the_source_type_is_a_kind_of_zone_and_an_axis(qtbot, window):
    # Draw zone's kind in the toolbar, the drawn-zone dialog and the drawn zones panel.
    assert "led strip zone" in texts(window.zone_kind_box)
    window.zone_kind_box.setCurrentIndex(texts(window.zone_kind_box).index("led strip zone"))
    assert window.edits.draw_kind() == "led_strip"
    dialog = ZoneDialog("ceiling", "Z1", window)
    assert texts(dialog.kind)[-1] == "LED strip"
    assert texts(window.zone_panel.kind)[-1] == "LED strip"
    # The result scatter's axes: its area and its flux, summed over its sources.
    axes = texts(window.solutions_panel.x_axis)
    assert {"led strip area (m²)", "led strip flux (lm)"} <= set(axes)


def _choose(box: QtWidgets.QComboBox, text: str) -> None:
    box.setCurrentIndex(texts(box).index(text))


def _goal_through_the_window(qtbot, window) -> None:
    entry = next(a for a in window.goal_actions.values() if a.text() == "Fewest LED strips")
    entry.trigger()  # Design > Goals: the design gets the goal
    assert GOAL.kind in [g.kind for g in window.doc.design.goals]
    assert entry.isChecked()
    goals = window.run_panel.goal
    assert "fewest strips" in texts(goals)
    _choose(goals, "fewest strips")
    assert window.doc.design.goals[0].kind == GOAL.kind  # the goal a run optimises
    assert window.run_panel.goal_label() == "LED strips"
    assert "LED strips" in texts(window.solutions_panel.y_axis)


def test_the_goal_is_in_the_goals_menu_and_the_run_panel(qtbot, window):
    assert window.new_project("cornell", 0.5)
    wait_for_operator(qtbot, window)
    _choose(window.run_panel.method, get_method("vns").label)
    _goal_through_the_window(qtbot, window)


def test_the_goal_with_the_auto_method(qtbot, window):
    assert window.new_project("cornell", 0.5)
    wait_for_operator(qtbot, window)
    assert window.doc.project.optimizer.method == "auto"
    with qtbot.capture_exceptions() as raised:
        _goal_through_the_window(qtbot, window)
    assert not raised, raised[0][1]


def test_the_quantity_is_in_the_intention_dialog(qtbot, window):
    assert window.new_project("cornell", 0.5)
    wait_for_operator(qtbot, window)
    dialog = IntentionDialog("floor", window)
    assert "luminance L (cd/m²)" in texts(dialog.quantity)
    dialog.quantity.setCurrentIndex(texts(dialog.quantity).index("luminance L (cd/m²)"))
    dialog.set_values(min=None, max=None, uniformity=None, average=10.0)
    dialog.setResult(QtWidgets.QDialog.Accepted)
    assert window.edits.add_intention_on_group("floor", dialog)
    (intention,) = window.doc.design.intentions
    assert (intention.quantity, intention.average) == ("luminance", 10.0)
    tree = [window.tree.topLevelItem(i) for i in range(window.tree.topLevelItemCount())]
    rows = next(t for t in tree if t.text(0) == "Lighting intentions")
    assert "luminance" in rows.child(0).text(1)


def test_the_import_format_is_in_the_file_filter_and_imports(qtbot, window, tmp_path, monkeypatch):
    asked = []
    monkeypatch.setattr(ask, "open_file", lambda parent, title, filt: asked.append(filt) or "")
    window.act_import.trigger()  # File > Import model: the file dialog's filter
    models, *formats = asked[0].split(";;")
    assert "*.objcopy" in models
    assert "An OBJ copy (*.objcopy)" in formats
    # A file of that format imports through the import dialog.
    for name in ("meeting_room.mtl", "meeting_room-materials.json"):
        shutil.copy(MODEL.parent / name, tmp_path / name)
    path = tmp_path / "room.objcopy"
    shutil.copy(MODEL, path)
    dialog = ImportDialog(path, window)
    dialog.resolution.setValue(0.5)
    dialog.setResult(QtWidgets.QDialog.Accepted)
    assert window.files.import_obj_dialog(dialog)
    wait_for_operator(qtbot, window)
    assert window.doc.project.scene.obj == str(path.resolve())
    assert window.doc.patches.n > 0


def test_the_method_is_in_the_run_panel(qtbot, window):
    assert window.new_project("cornell", 0.5)
    wait_for_operator(qtbot, window)
    box = window.run_panel.method
    assert "Random search (a plug-in)" in texts(box)
    box.setCurrentIndex(texts(box).index("Random search (a plug-in)"))
    assert window.doc.project.optimizer.method == "random_gui"  # saved with the project
