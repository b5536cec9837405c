"""The real main window under Xvfb: scene, precompute, picking, intentions, sources,
saving, cancelling — asserted on the model and on the viewport's pixels."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6 import QtCore, QtGui, QtWidgets

from app.dialogs.intention_dialog import IntentionDialog
from lightinv_core.project import load_project
from tests.app.conftest import wait_for_operator
from tests.app.user import view_pixel


def send_mouse(
    widget, kind, pos: QtCore.QPointF, button=QtCore.Qt.LeftButton, modifiers=QtCore.Qt.NoModifier
):
    buttons = QtCore.Qt.NoButton if kind == QtCore.QEvent.Type.MouseButtonRelease else button
    event = QtGui.QMouseEvent(kind, pos, widget.mapToGlobal(pos), button, buttons, modifiers)
    QtWidgets.QApplication.sendEvent(widget, event)


to_qt = view_pixel
"""Widget coordinates of a world point (tests/app/user.py's ``view_pixel``)."""


def image(win) -> np.ndarray:
    return win.viewport.screenshot().astype(float)


@pytest.fixture
def cornell(qtbot, window):
    assert window.new_project("cornell", 0.25)
    wait_for_operator(qtbot, window)
    return window


def test_opens_a_scene_precomputes_and_shows_light(qtbot, cornell):
    win = cornell
    assert win.doc.patches.n > 0 and win.doc.operator is not None
    assert "rank k" in win.status_rank.text()
    dark = image(win)
    win.doc.add_source("light")
    lux = win.doc.lighting()
    assert lux is not None and lux.max() > 0
    lit = image(win)
    assert lit.std() > 10  # not blank
    assert np.abs(lit - dark).mean() > 1.0  # the light shows
    assert "lighting" in win.status_eval.text()


def test_pick_patches_by_clicking_and_add_an_intention(qtbot, cornell):
    win = cornell
    win.viewport.camera("top")
    win.set_mode("select")
    iw = win.viewport.plotter.interactor
    centre = QtCore.QPointF(iw.width() / 2, iw.height() / 2)
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonPress, centre)
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, centre)
    picked = win.doc.selection
    assert len(picked) == 1
    # Seen from above with the ceiling culled, the centre of the view is on the floor.
    assert win.doc.patches.group_names[win.doc.patches.group_id[picked[0]]] == "floor"
    # Rubber band with shift adds a block of patches.
    a = QtCore.QPointF(iw.width() * 0.4, iw.height() * 0.4)
    b = QtCore.QPointF(iw.width() * 0.6, iw.height() * 0.6)
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonPress, a)
    send_mouse(iw, QtCore.QEvent.Type.MouseMove, b)
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, b, modifiers=QtCore.Qt.ShiftModifier)
    assert len(win.doc.selection) > 5 and set(picked) <= set(win.doc.selection)
    assin = win.viewport.plotter.actors.get("selection")
    assert assin is not None
    dialog = IntentionDialog("picked", win)
    dialog.set_values(min=100.0, average=None, uniformity=None)
    dialog.setResult(QtWidgets.QDialog.Accepted)
    assert win.edits.add_intention_on_selection(dialog)
    (it,) = win.doc.design.intentions
    assert it.min == 100.0 and set(it.patches) == set(win.doc.selection)
    assert win.tree.findItems(it.name, QtCore.Qt.MatchRecursive)


def test_add_and_drag_a_source_relights_the_view(qtbot, cornell):
    win = cornell
    win.viewport.camera("top")
    src = win.doc.add_source("light")  # fills the 0.5 m light zone: make it smaller
    win.doc.update_source(src.name, rect=(0.2, 0.2, 0.45, 0.45))
    before_img = image(win)
    before_rect = win.doc.design.source(src.name).rect
    frame = win.viewport.frames["light"]
    win.set_mode("move")
    iw = win.viewport.plotter.interactor
    start = to_qt(win.viewport, frame.to_world(0.3, 0.3))
    end = to_qt(win.viewport, frame.to_world(0.1, 0.1))
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonPress, start)
    send_mouse(iw, QtCore.QEvent.Type.MouseMove, end)
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, end)
    after_rect = win.doc.design.source(src.name).rect
    moved = np.subtract(after_rect, before_rect)
    assert np.all(moved < -0.05)  # dragged towards the zone origin
    assert min(after_rect) >= 0.0  # kept inside the zone
    assert np.abs(image(win) - before_img).mean() > 0.2
    # Numeric editing through the source panel.
    win.source_panel.corners[2].setValue(0.4)
    assert win.doc.design.source(src.name).rect[2] == pytest.approx(0.4)
    assert win.windowTitle().endswith("*")


def test_save_and_reopen_gives_the_same_project(qtbot, cornell, tmp_path):
    win = cornell
    win.doc.add_source("light")
    win.doc.set_selection([1, 2, 3])
    dialog = IntentionDialog("three", win)
    dialog.setResult(QtWidgets.QDialog.Accepted)
    assert win.edits.add_intention_on_selection(dialog)
    path = tmp_path / "p.json"
    assert win.save_to(path)
    saved = win.doc.project
    assert not win.windowTitle().endswith("*")
    assert win.open_path(path)
    wait_for_operator(qtbot, win)
    assert win.doc.project == saved == load_project(path)
    assert win.recent_files()[0] == str(path.resolve())


def test_cancel_precompute_leaves_no_operator_and_no_thread(qtbot, window):
    window.doc.new_from_scene  # noqa: B018 - the window opens the scene itself
    window.stop_worker()
    assert window.new_project("office", 0.35)  # starts a precompute (not cached)
    assert window.worker is not None
    with qtbot.waitSignal(window.worker.cancelled, timeout=30_000):
        window.cancel_precompute()
    qtbot.waitUntil(lambda: window.worker is None, timeout=30_000)
    assert window.doc.operator is None
    assert window.act_precompute.isEnabled() and not window.act_cancel.isEnabled()


def test_bad_project_file_shows_an_error_and_keeps_the_open_one(
    qtbot, cornell, tmp_path, monkeypatch
):
    shown = []
    monkeypatch.setattr(
        QtWidgets.QMessageBox, "critical", lambda *a: shown.append(a[2]) or QtWidgets.QMessageBox.Ok
    )
    bad = tmp_path / "bad.json"
    bad.write_text('{"schema": 9, "name": "x"}')
    before = cornell.doc.project
    assert not cornell.open_path(bad)
    assert "schema 9" in shown[0] and cornell.doc.project is before


def test_draw_a_zone_on_the_ceiling_and_place_a_source_in_it(qtbot, window):
    from dataclasses import replace

    from app.dialogs.zone_dialog import ZoneDialog
    from lightinv_core.editing import blank_project
    from lightinv_core.project import OperatorSettings

    # The office at 0.5 m with 256 rays: each zone edit rebuilds the operator (three
    # builds), and what is checked is where the zone lands, not how exact the light is.
    office = blank_project("office", 0.5)
    assert window.load_project(replace(office, operator=OperatorSettings(rays=256)))
    wait_for_operator(qtbot, window)
    win = window
    win.set_mode("zone")
    iw = win.viewport.plotter.interactor
    # The ceiling faces down: look up at it from inside the room, below a clear strip
    # between the skylight zone and the north wall (y 7.3 to 7.7 m, x 5.5 to 6.5 m).
    win.viewport.plotter.camera_position = [(6.0, 7.5, 0.3), (6.0, 7.5, 3.0), (0, 1, 0)]
    win.viewport.render_now()
    dialog = ZoneDialog("ceiling", "Z1", win)
    dialog.kind.setCurrentIndex(dialog.kind.findData("luminaire"))
    dialog.setResult(QtWidgets.QDialog.Accepted)
    drawn = []
    win.viewport.zoneDrawn.disconnect(win.edits.zone_drawn)
    win.viewport.zoneDrawn.connect(lambda *a: drawn.append(a))
    start = to_qt(win.viewport, (5.5, 7.7, 3.0))
    end = to_qt(win.viewport, (6.5, 7.3, 3.0))
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonPress, start)
    send_mouse(iw, QtCore.QEvent.Type.MouseMove, end)
    send_mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, end)
    ((surface, u0, v0, u1, v1),) = drawn
    rect = win.doc.scene.surface(surface).rect
    assert win.doc.scene.surface(surface).group == "ceiling"
    corners = [
        rect.point(0, 0) + a * rect.u / rect.size[0] + b * rect.v / rect.size[1]
        for a, b in ((u0, v0), (u1, v1))
    ]
    np.testing.assert_allclose(sorted(c[0] for c in corners), [5.5, 6.5], atol=0.03)
    np.testing.assert_allclose(sorted(c[1] for c in corners), [7.3, 7.7], atol=0.03)
    assert win.edits.zone_drawn(surface, u0, v0, u1, v1, dialog)
    assert "Z1" in {z.name for z in win.doc.scene.zones}
    assert win.doc.project.scene.zones[0].name == "Z1" and win.doc.dirty
    wait_for_operator(qtbot, win)
    win.doc.add_source("Z1")
    assert win.doc.lighting().max() > 0
    # Rename and delete through the zone panel.
    win.zone_panel.name.setText("Z9")
    win.zone_panel.apply()
    wait_for_operator(qtbot, win)
    assert "Z9" in {z.name for z in win.doc.scene.zones}
    win.zone_panel.delete()
    assert win.doc.project.scene.zones == () and win.doc.design.sources == ()
    win.stop_worker()


def test_mirror_and_centre_rules_from_the_source_panel(qtbot, window):
    assert window.new_project("office", 0.5)
    wait_for_operator(qtbot, window)
    d = window.doc
    a = d.add_source("lum_west")
    b = d.add_source("lum_east")
    d.update_source(a.name, rect=(0.2, 1.0, 0.8, 2.0))
    d.set_current_source(b.name)
    window.source_panel.mirror.setCurrentIndex(window.source_panel.mirror.findData(a.name))
    assert d.mirror_of(b.name) == (a.name, "u")
    east = {s.name: s for s in d.effective_sources()}[b.name]
    assert east.u_range == pytest.approx((2.0 - 0.8, 2.0 - 0.2))  # the 2 m wide zone, flipped
    window.source_panel.centred.setChecked(True)
    assert d.centred(b.name)


def test_export_report_from_the_window(qtbot, window, tmp_path):
    from lightinv_core.study import solve

    assert window.new_project("cornell", 0.25)
    wait_for_operator(qtbot, window)
    d = window.doc
    d.add_source("light")
    from dataclasses import replace

    result = solve(d.project, d.prepared(), max_evals=300)
    d.project = replace(d.project, solutions=(result.best,))
    pdf = tmp_path / "report.pdf"
    assert window.export_report(pdf)
    with qtbot.waitSignal(window.worker.finished, timeout=60_000):
        pass
    qtbot.waitUntil(lambda: window.worker is None, timeout=10_000)
    assert pdf.exists() and pdf.read_bytes()[:4] == b"%PDF"
