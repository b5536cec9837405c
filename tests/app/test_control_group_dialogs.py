"""The dialogs that carry a luminaire array's control group and a group's sensor: an
array edited in its dialog keeps its group (or takes another), and the control group
dialog builds the group as entered. The clicks are in test_control_groups_gui.py."""

from __future__ import annotations

from app.dialogs.array_dialog import ArrayDialog
from app.dialogs.control_group_dialog import ControlGroupDialog
from lightinv_core.design.model import ControlGroup, LuminaireArray


def test_the_array_dialog_keeps_and_changes_the_group(qtbot):
    base = LuminaireArray(
        "A1", "lum", "Downlight 2000 lm 20 W", (0, 0, 2, 2), control_group="window row"
    )
    dialog = ArrayDialog({"lum": (2.0, 2.0)}, base, groups=("all", "window row", "inner"))
    qtbot.addWidget(dialog)
    assert dialog.array().control_group == "window row"
    dialog.control.setCurrentText("inner")
    assert dialog.array().control_group == "inner"


def test_the_group_dialog_builds_what_is_entered(qtbot):
    dialog = ControlGroupDialog(["wp", "high"], ControlGroup("g"), (1.0, 1.0, 11.0, 7.0))
    qtbot.addWidget(dialog)
    assert dialog.group() == ControlGroup("g")  # the whole control plane, its floor
    dialog.whole.setChecked(False)
    dialog.plane.setCurrentIndex(2)
    dialog.own_floor.setChecked(True)
    dialog.floor.setValue(0.25)
    got = dialog.group()
    assert got.sensor == (1.0, 1.0, 11.0, 7.0) and got.workplane == "high"
    assert got.min_level == 0.25


def test_the_group_dialog_takes_a_mode_and_an_own_target(qtbot):
    base = ControlGroup("g", mode="switching", target_lux=300.0)
    dialog = ControlGroupDialog(["wp"], base, target_lux=500.0)
    qtbot.addWidget(dialog)
    assert dialog.group() == base  # shown as it is: switching, its own 300 lux
    labels = [dialog.mode.itemText(i) for i in range(dialog.mode.count())]
    assert labels[:2] == ["dimming (continuous)", "switching (on/off)"]
    dialog.mode.setCurrentIndex(0)
    dialog.own_target.setChecked(False)
    assert dialog.group() == ControlGroup("g")  # dimming to the daylight's target
    fresh = ControlGroupDialog(["wp"], ControlGroup("h"), target_lux=450.0)
    qtbot.addWidget(fresh)
    assert fresh.target.value() == 450.0 and not fresh.target.isEnabled()  # proposed
