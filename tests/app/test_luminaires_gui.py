"""The window's luminaires panel: catalogue and polar curves, arrays added and edited in
their dialog, luminaires drawn in the view, work planes with live EN 12464-1 values and
iso-lux lines, presets, undo, and a run that lays the arrays out."""

from __future__ import annotations

import numpy as np
import pytest

from app.dialogs.array_dialog import ArrayDialog
from app.dialogs.workplane_dialog import WorkplaneDialog
from lightinv_core.luminaires import builtin_catalogue
from tests.app.conftest import wait_for_operator


def _arrays_window(qtbot, window):
    assert window.new_project("office", 0.5)
    wait_for_operator(qtbot, window, timeout=120_000)
    return window.doc, window.luminaires_panel


def test_catalogue_shows_each_products_polar_curves(qtbot, window):
    panel = window.luminaires_panel
    assert panel.catalogue.rowCount() == len(builtin_catalogue())
    panel.catalogue.selectRow(1)
    assert "batwing" in panel.polar.getPlotItem().titleLabel.text.lower()
    c0, c90 = panel.polar.curves["C0"], panel.polar.curves["C90"]
    # The batwing is wider across (C90) than along (C0).
    assert np.abs(c90[:, 0]).max() > 1.3 * np.abs(c0[:, 0]).max()
    panel.grab().save("/tmp/luminaires-panel-catalogue.png")


def test_arrays_and_work_planes_are_edited_and_shown_live(qtbot, window, tmp_path):
    d, panel = _arrays_window(qtbot, window)
    base = d.lighting().copy()
    # A work plane first: no light from luminaires yet (the office has none lit).
    assert panel.add_workplane(WorkplaneDialog(list(d.patches.group_names), name="wp"))
    assert d.grid_stats()["wp"]["points"] > 20
    zones = {z: d.zone_size(z) for z in ("lum_west", "lum_east")}
    dialog = ArrayDialog(zones, name="A1")
    dialog.zone.setCurrentText("lum_west")
    dialog.product.setCurrentText("Linear batwing 4000 lm 32 W")
    dialog.rows.setValue(3)
    dialog.columns.setValue(1)
    dialog.rotation.setCurrentIndex(1)
    assert "3 luminaires" in dialog.summary.text()
    assert panel.add_array(dialog)
    assert [a.name for a in d.design.arrays] == ["A1"]
    em1 = d.grid_stats()["wp"]["Em"]
    assert em1 > 40 and d.lighting().max() > base.max()
    assert panel.arrays.item(0, 3).text() == "3 x 1"
    # Edit: six rows -> more light on the plane, the table follows.
    panel.arrays.selectRow(0)
    edit = ArrayDialog(zones, d.design.arrays[0])
    edit.rows.setValue(6)
    assert panel.edit_array(edit)
    em2 = d.grid_stats()["wp"]["Em"]
    assert em2 == pytest.approx(2 * em1, rel=0.1)
    assert panel.planes.item(0, 3).text() == f"{em2:.0f}"
    # The view draws the six luminaires and the plane's iso-lux lines.
    plotter = window.viewport.plotter
    assert "luminaires" in plotter.actors and "isolux" in plotter.actors
    # An EN 12464-1 preset becomes an intention on the plane; the Achieved tab shows it.
    assert panel.add_preset("filing")
    it = d.design.intentions[-1]
    assert (it.grid, it.average, it.uniformity) == ("wp", 300.0, 0.4)
    rows = window.achieved_panel.rows()
    assert any(r[0] == "filing" and r[1] == "average ≥" for r in rows)
    window.grab().save("/tmp/luminaires-window.png")
    panel.grab().save("/tmp/luminaires-panel.png")
    window.viewport.screenshot("/tmp/luminaires-view.png")
    # Undo takes the preset back, then the edit.
    window.act_undo.trigger()
    assert not any(i.grid for i in d.design.intentions)
    window.act_undo.trigger()
    assert d.design.arrays[0].rows == 3
    # Saved and opened again.
    assert window.save_to(tmp_path / "a.json")
    from lightinv_core.project import load_project

    again = load_project(tmp_path / "a.json")
    assert again.design.arrays[0].product == "Linear batwing 4000 lm 32 W"
    assert again.design.workplanes[0].name == "wp"


def test_a_bad_array_is_refused_with_a_message(qtbot, window, monkeypatch):
    d, panel = _arrays_window(qtbot, window)
    said = []
    monkeypatch.setattr("app.dialogs.ask.warn", lambda parent, msg: said.append(msg))
    dialog = ArrayDialog({"lum_west": d.zone_size("lum_west")}, name="A1")
    dialog.product.setCurrentText("no such product")
    assert "neither a catalogue luminaire" in dialog.summary.text()
    assert not panel.add_array(dialog)
    assert said and "neither a catalogue luminaire" in said[0]
    assert not d.design.arrays


def test_a_run_lays_the_arrays_out_and_loads_them(qtbot, window):
    """An optimisation of array rows, columns and dimming against an EN 12464-1 preset on the
    work plane: the best layout comes back into the design and the panel."""
    from tests.app.test_optimisation import run_and_wait

    d, panel = _arrays_window(qtbot, window)
    assert panel.add_workplane(WorkplaneDialog(list(d.patches.group_names), name="wp"))
    zones = {z: d.zone_size(z) for z in ("lum_west", "lum_east")}
    for name, zone in (("W", "lum_west"), ("E", "lum_east")):
        dialog = ArrayDialog(zones, name=name)
        dialog.zone.setCurrentText(zone)
        dialog.product.setCurrentText("Linear batwing 4000 lm 32 W")
        dialog.rotation.setCurrentIndex(1)
        dialog.rows.setValue(2)
        dialog.columns.setValue(1)
        for var, box in dialog.free.items():
            box.setChecked(var in ("rows", "columns", "dimming"))
        dialog.rows_range[1].setValue(5)
        dialog.cols_range[1].setValue(3)
        assert panel.add_array(dialog)
    assert panel.add_preset("archive")  # Em 200 lux, U0 0.4
    d.set_optimizer(method="vns", max_evals=3000)
    status = run_and_wait(qtbot, window, timeout=180_000)
    assert status == "feasible"
    best = d.project.runs[-1].solutions[0]
    assert best.arrays and d.design.arrays[0].rows == best.arrays[0].rows
    stats = d.grid_stats()["wp"]
    assert stats["Em"] >= 200 * 0.999 and stats["U0"] >= 0.4 * 0.999
    a = best.arrays[0]
    assert panel.arrays.item(0, 3).text() == f"{a.rows} x {a.columns}"
    window.grab().save("/tmp/luminaires-run.png")


def test_rules_on_arrays_are_added_in_the_rule_dialog_and_listed(qtbot, window):
    from PySide6 import QtWidgets

    from app.dialogs.rule_dialog import RuleDialog

    d, panel = _arrays_window(qtbot, window)
    zones = {z: d.zone_size(z) for z in ("lum_west", "lum_east")}
    assert panel.add_array(ArrayDialog(zones, name="A1"))
    dialog = RuleDialog([], window, ["A1"])
    # Only the array rules are offered without sources, and they list the arrays.
    assert [dialog.kind.itemData(i) for i in range(dialog.kind.count())] == ["shr", "clearance"]
    dialog.set_rule("shr", ["A1"], max=1.2)
    dialog.setResult(QtWidgets.QDialog.Accepted)
    assert window.edits.add_rule(dialog)
    clear = RuleDialog([], window, ["A1"])
    clear.set_rule("clearance", ["A1"], min=0.2)
    clear.setResult(QtWidgets.QDialog.Accepted)
    assert window.edits.add_rule(clear)
    kinds = [(r.kind, r.sources, r.min, r.max) for r in d.design.rules]
    assert kinds == [("shr", ("A1",), None, 1.2), ("clearance", ("A1",), 0.2, None)]
    texts = []
    root = window.tree.invisibleRootItem()
    for i in range(root.childCount()):
        item = root.child(i)
        texts += [item.child(j).text(1) for j in range(item.childCount())]
    assert "at most 1.2" in texts and "at least 0.2 m from the zone's edges" in texts
    # Removing the array takes its rules with it (one undoable step).
    panel.arrays.selectRow(0)
    panel.remove_array()
    assert not d.design.rules
    window.act_undo.trigger()
    assert len(d.design.rules) == 2


def _button(root, text: str):
    """The visible button of ``root`` whose text (without its '&' shortcut) is ``text``."""
    from PySide6 import QtWidgets

    found = [
        b
        for b in root.findChildren(QtWidgets.QAbstractButton)
        if b.text().replace("&", "") == text and b.isVisible()
    ]
    assert len(found) == 1, (text, [b.text() for b in root.findChildren(QtWidgets.QAbstractButton)])
    return found[0]


def _group(root, title: str):
    """The group box of ``root`` titled ``title``."""
    from PySide6 import QtWidgets

    (box,) = [g for g in root.findChildren(QtWidgets.QGroupBox) if g.title() == title]
    return box


def test_a_product_file_with_warnings_shows_them_in_the_dialog_panel_and_status_bar(
    qtbot, window, tmp_path, monkeypatch
):
    """Add array…, File… (a real IES file with a lamp-tilt table), OK: by clicks. The
    tilt table not applied is shown in the dialog, under the arrays and in the status
    bar's warnings; removing the array clears it, Undo brings it back."""
    from PySide6 import QtCore, QtWidgets

    from tests.core.test_luminaire_warnings import TILT_WARNING, tilted_file

    d, panel = _arrays_window(qtbot, window)
    path = tilted_file(tmp_path)
    monkeypatch.setattr("app.dialogs.ask.open_file", lambda *a, **k: str(path))
    shown: list[str] = []
    monkeypatch.setattr("app.dialogs.ask.inform", lambda parent, text: shown.append(text))
    before = list(window.warnings())
    seen: dict[str, str] = {}

    def fill_in() -> None:
        dialog = QtWidgets.QApplication.activeModalWidget()
        if not isinstance(dialog, ArrayDialog):
            QtCore.QTimer.singleShot(50, fill_in)  # not shown yet
            return
        try:
            qtbot.mouseClick(_button(dialog, "File…"), QtCore.Qt.LeftButton)
            seen["product"] = dialog.product.currentText()
            seen["summary"] = dialog.summary.text()
            qtbot.wait(50)  # the summary grows a line
            dialog.grab().save("/tmp/luminaires-array-dialog-warning.png")
            qtbot.mouseClick(_button(dialog, "OK"), QtCore.Qt.LeftButton)
        finally:
            if dialog.isVisible():
                dialog.reject()  # never leave the test waiting on a modal dialog

    QtCore.QTimer.singleShot(0, fill_in)
    qtbot.mouseClick(_button(panel, "Add array…"), QtCore.Qt.LeftButton)
    assert seen["product"] == str(path)
    assert "\u26a0" in seen["summary"] and "TILT=INCLUDE" in seen["summary"]
    assert [a.product for a in d.design.arrays] == [str(path)]
    line = f"{path}: {TILT_WARNING}"
    assert panel.array_warnings.isVisible() and panel.array_warnings.text() == f"\u26a0 {line}"
    assert window.warnings() == [*before, line], window._warnings
    assert window.warnings_button.isVisible()
    assert window.warnings_button.text().startswith(f"\u26a0 {len(before) + 1} warning")
    qtbot.mouseClick(window.warnings_button, QtCore.Qt.LeftButton)
    assert shown and line in shown[-1]
    window.grab().save("/tmp/luminaires-warnings.png")
    panel.grab().save("/tmp/luminaires-panel-warnings.png")
    # Removing the array takes its warning away; Undo brings both back.
    panel.arrays.selectRow(0)
    qtbot.mouseClick(_button(_group(panel, "Luminaire arrays"), "Remove"), QtCore.Qt.LeftButton)
    assert not d.design.arrays and window.warnings() == before
    assert not panel.array_warnings.isVisible()
    window.act_undo.trigger()
    assert window.warnings() == [*before, line]
