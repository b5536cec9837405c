"""File > Export design: one entry per registered export format, each a save dialog
then the export of the design on screen, driven by clicks at 1366 x 768."""

from __future__ import annotations

from pathlib import Path

import pytest
import trimesh
from PySide6 import QtCore, QtWidgets

from lightinv_core.export import exporters
from lightinv_core.project import save_project
from tests.app import user as u
from tests.app.conftest import wait_for_operator
from tests.export.office import office_project

SHOTS = Path("/tmp/shots-export")


def test_export_design_from_the_file_menu(window, qtbot, tmp_path):
    pytest.importorskip("ifcopenshell")
    win = window
    win.resize(1366, 768)
    result = tmp_path / "result.json"
    save_project(office_project(), result)
    u.answer(lambda: u.menu(win, "File", "Open project..."), u.file_name(result))
    wait_for_operator(qtbot, win)

    # The submenu lists every registered format, from the registry.
    u.menu(win, "File", "Export design")
    sub = next(m for m in win.findChildren(QtWidgets.QMenu) if m.title() == "Export &design")
    assert u.wait_for(sub.isVisible, 5000)
    texts = [u.plain(a.text()) for a in sub.actions()]
    assert texts == [f"{e.label}..." for e in exporters()]
    SHOTS.mkdir(parents=True, exist_ok=True)
    sub.grab().save(str(SHOTS / "export-design-menu.png"))
    u.press(sub, QtCore.Qt.Key_Escape)
    u.press(win.menuBar(), QtCore.Qt.Key_Escape)

    for e in exporters():
        # A folder each: typed into the dialog beside the files of the format before
        # (design_lum.cal, ...), a name was now and then completed into another.
        (tmp_path / e.name).mkdir()
        target = tmp_path / e.name / f"design{e.suffixes[0]}"
        titles = u.answer(
            lambda e=e: u.menu(win, "File", "Export design", f"{e.label}..."), u.file_name(target)
        )
        assert titles == [f"Export design: {e.label}"]
        assert u.wait_for(lambda t=target: t.exists() and win.worker is None, 60_000), e.name
        assert "Design exported" in win.statusBar().currentMessage()
    u.screenshot(win, SHOTS, "after-export")

    ifc = (tmp_path / "ifc" / "design.ifc").read_text()
    assert ifc.count("IFCLIGHTFIXTURE(") == 4 and "IFCWINDOW(" in ifc
    assert "lum_mult" in (tmp_path / "radiance" / "design.rad").read_text()
    glb = trimesh.load(tmp_path / "gltf" / "design.glb", force="scene")
    assert len(glb.geometry) == 6
