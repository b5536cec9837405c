"""The docks and the main window on a 1366 x 768 laptop (issue #29, minor items), used as
a designer does: the example meeting room imported by File > Import model..., panels
reached by clicking their tabs, buttons clicked, keys pressed, dialogs answered by
their buttons.

- every button of Properties and Luminaires is on screen without scrolling;
- the Source page names the selected source's own zone, apart from where a new one goes;
- the polar curve fills its box however the dock is resized;
- the tree counts one array as one ("Luminaire arrays 6" before) and names goals;
- undoing every edit leaves the project clean: no "*", no question on closing;
- file dialogs start in the last-used folder, else the project's, else home;
- status messages fit (elided, whole in the tooltip); the title keeps the name.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from app.dialogs import ask
from app.window.main_window import MainWindow
from tests.app.conftest import wait_for_operator
from tests.app.test_dialog_buttons import answer, button, click, menu_action
from tests.app.test_laptop_screen import click_tab

MODELS = Path(__file__).resolve().parents[2] / "resources" / "models"
SHOTS = Path("/tmp/lightinv-docks")
LAPTOP = (1366, 768)


def laptop(window) -> None:
    """The window at a 1366 x 768 laptop screen's size, active (for its shortcuts)."""
    window.resize(*LAPTOP)
    window.activateWindow()
    QTest.qWaitForWindowActive(window)
    QTest.qWait(100)


def import_meeting_room(qtbot, window, monkeypatch, tmp_path) -> Path:
    """File > Import model..., the example meeting room (a copy) chosen, OK clicked."""
    for f in MODELS.glob("meeting_room*"):
        shutil.copy(f, tmp_path)
    path = tmp_path / "meeting_room.obj"
    monkeypatch.setattr(ask, "open_file", lambda *a, **k: str(path))
    seen = answer(menu_action(window, "File/Import model...").trigger, click("OK"))
    assert seen["dialog"] == "ImportDialog"
    wait_for_operator(qtbot, window, timeout=120_000)
    report = getattr(window, "import_report", None)
    if report is not None:
        report.close()
    return path


def whole(widget: QtWidgets.QWidget) -> bool:
    """Whether all of ``widget`` is drawn (not clipped by a scroll area or the window)."""
    return widget.isVisible() and widget.visibleRegion().boundingRect().size() == widget.size()


def scrolled(dock: QtWidgets.QDockWidget) -> list[str]:
    """The scroll areas of ``dock`` that show a scroll bar (by their object's class)."""
    return [
        type(a.widget()).__name__
        for a in dock.findChildren(QtWidgets.QScrollArea)
        if a.isVisible()
        and (a.verticalScrollBar().isVisible() or a.horizontalScrollBar().isVisible())
    ]


def add_array(window) -> None:
    """Luminaires: Add array…, OK (the dialog's 2 x 3 layout typed in)."""
    click_tab(window, "Luminaires")
    add = button(window.luminaires_panel, "Add array…")
    seen = answer(lambda: QTest.mouseClick(add, QtCore.Qt.LeftButton), click("OK"))
    assert seen["dialog"] == "ArrayDialog"


def test_every_button_of_the_side_docks_is_on_screen_at_1366_x_768(
    qtbot, window, monkeypatch, tmp_path
):
    import_meeting_room(qtbot, window, monkeypatch, tmp_path)
    laptop(window)
    click_tab(window, "Properties")
    click_tab(window, "Source")
    QTest.mouseClick(button(window.source_panel, "Add source"), QtCore.Qt.LeftButton)
    add_array(window)
    SHOTS.mkdir(exist_ok=True)
    properties = window.findChild(QtWidgets.QDockWidget, "properties")
    for page in ("Source", "Drawn zones", "Materials and view"):
        click_tab(window, "Properties")
        click_tab(window, page)
        buttons = [b for b in properties.findChildren(QtWidgets.QPushButton) if b.isVisible()]
        assert buttons, page
        assert {b.text(): whole(b) for b in buttons} == {b.text(): True for b in buttons}
        assert scrolled(properties) == [], page
        window.grab().save(str(SHOTS / f"properties-{page.split()[0].lower()}.png"))
    click_tab(window, "Luminaires")
    luminaires = window.findChild(QtWidgets.QDockWidget, "luminaires")
    buttons = [b for b in luminaires.findChildren(QtWidgets.QPushButton) if b.isVisible()]
    assert {"Add array…", "Edit…", "Remove", "Add work plane…"} <= {b.text() for b in buttons}
    window.grab().save(str(SHOTS / "luminaires.png"))
    assert all(whole(b) for b in buttons), [(b.text(), whole(b)) for b in buttons]
    assert scrolled(luminaires) == []
    # The polar curve whole in its box (squeezed below its minimum, it was cut off).
    polar = window.luminaires_panel.polar
    assert polar.parentWidget().rect().contains(polar.geometry())
    assert polar.height() >= polar.minimumHeight()


def test_the_source_page_names_the_selected_sources_own_zone(qtbot, window, monkeypatch, tmp_path):
    import_meeting_room(qtbot, window, monkeypatch, tmp_path)
    laptop(window)
    click_tab(window, "Properties")
    click_tab(window, "Source")
    panel = window.source_panel
    # A new source goes in the zone chosen beside Add source: the skylight zone.
    panel.zone.setCurrentIndex(panel.zone.findData("skylight"))
    QTest.mouseClick(button(panel, "Add source"), QtCore.Qt.LeftButton)
    assert panel.name.text().startswith("S1 (skylight)")
    assert panel.own_zone.text().startswith("skylight (skylight zone, 2.00 x 1.00 m)")
    # Then the downlights zone: the new one is selected and its own zone named...
    panel.zone.setCurrentIndex(panel.zone.findData("downlights"))
    QTest.mouseClick(button(panel, "Add source"), QtCore.Qt.LeftButton)
    assert panel.own_zone.text().startswith("downlights (luminaire zone")
    # ... and choosing the skylight again in the tree shows its zone, whatever the
    # new-source box says.
    tree = window.tree
    item = tree.findItems("S1", QtCore.Qt.MatchExactly | QtCore.Qt.MatchRecursive)[0]
    tree.scrollToItem(item)
    QTest.mouseClick(tree.viewport(), QtCore.Qt.LeftButton, pos=tree.visualItemRect(item).center())
    assert panel.name.text().startswith("S1") and panel.own_zone.text().startswith("skylight (")
    assert panel.zone.currentData() == "downlights"
    labels = [w.text() for w in panel.findChildren(QtWidgets.QLabel) if w.isVisible()]
    assert "In zone" in labels and "New source in" in labels and "Zone" not in labels


def on_screen(polar, rect: QtCore.QRectF) -> QtCore.QRectF:
    """``rect`` (cd/klm) in the polar plot's pixels."""
    view = polar.getPlotItem().getViewBox()
    return view.mapViewToScene(rect).boundingRect()


def test_the_polar_curve_fills_its_box_when_the_dock_is_resized(qtbot, window):
    laptop(window)
    click_tab(window, "Luminaires")
    panel = window.luminaires_panel
    cat = panel.catalogue
    QTest.mouseClick(
        cat.viewport(), QtCore.Qt.LeftButton, pos=cat.visualItemRect(cat.item(1, 0)).center()
    )
    assert panel.polar.curves
    dock = window.findChild(QtWidgets.QDockWidget, "luminaires")
    # As dragging its edge does: narrow, wide, then floating and tall.
    for width in (330, 640):
        window.resizeDocks([dock], [width], QtCore.Qt.Horizontal)
        QTest.qWait(100)
    dock.setFloating(True)
    for size in ((420, 900), (900, 500)):
        dock.resize(*size)
        QTest.qWait(100)
    polar = panel.polar
    SHOTS.mkdir(exist_ok=True)
    polar.grab().save(str(SHOTS / "polar-900x500.png"))
    view = polar.getPlotItem().getViewBox().sceneBoundingRect()
    drawn = on_screen(polar, polar.box)
    assert view.adjusted(-2, -2, 2, 2).contains(drawn), (drawn, view)
    # The diagram fills the shorter side of its box (it shrank in a wider dock)...
    assert min(drawn.width(), drawn.height()) > 0.85 * min(view.width(), view.height())
    # ... and holds the curves.
    xy = np.vstack(list(polar.curves.values()))
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    curves = on_screen(polar, QtCore.QRectF(lo[0], lo[1], hi[0] - lo[0], hi[1] - lo[1]))
    assert drawn.adjusted(-1, -1, 1, 1).contains(curves)
    assert curves.height() > 0.3 * view.height()
    dock.setFloating(False)


def test_the_tree_counts_arrays_and_names_goals(qtbot, window, monkeypatch, tmp_path):
    import_meeting_room(qtbot, window, monkeypatch, tmp_path)
    laptop(window)
    add_array(window)
    (array,) = window.doc.design.arrays
    tree = window.tree
    item = tree.findItems("Luminaire arrays", QtCore.Qt.MatchExactly)[0]
    assert item.text(1) == f"1 array, {array.count} luminaire{'s' * (array.count != 1)}"
    assert item.childCount() == 1
    goals = tree.findItems("Goals", QtCore.Qt.MatchExactly)[0]
    assert goals.child(0).text(0) == "Least electric power"
    every = tree.findItems("", QtCore.Qt.MatchContains | QtCore.Qt.MatchRecursive)
    assert not any("min_electric_power" in i.text(0) + i.text(1) for i in every)


def test_undoing_every_edit_leaves_the_project_clean(qtbot, window, monkeypatch, tmp_path):
    import_meeting_room(qtbot, window, monkeypatch, tmp_path)
    laptop(window)
    # Save it (Ctrl+S, the file name given to the save dialog), then two edits.
    saved = tmp_path / "room.json"
    monkeypatch.setattr(ask, "save_file", lambda *a, **k: str(saved))
    QTest.mouseClick(window.tree.viewport(), QtCore.Qt.LeftButton)
    QTest.keyClick(window, QtCore.Qt.Key_S, QtCore.Qt.ControlModifier)
    assert saved.exists() and not window.windowTitle().endswith("*")
    click_tab(window, "Properties")
    click_tab(window, "Source")
    QTest.mouseClick(button(window.source_panel, "Add source"), QtCore.Qt.LeftButton)
    u1 = window.source_panel.corners[2]
    QTest.mouseClick(u1, QtCore.Qt.LeftButton)
    QTest.keyClick(u1, QtCore.Qt.Key_A, QtCore.Qt.ControlModifier)
    QTest.keyClicks(u1, "1.2")
    QTest.keyClick(u1, QtCore.Qt.Key_Return)
    assert window.windowTitle().endswith("*") and window.undo_stack.count() == 2
    # Ctrl+Z twice, from the tree (a spin box would undo its own typing).
    QTest.mouseClick(window.tree.viewport(), QtCore.Qt.LeftButton)
    QTest.keyClick(window.tree, QtCore.Qt.Key_Z, QtCore.Qt.ControlModifier)
    assert window.windowTitle().endswith("*")
    QTest.keyClick(window.tree, QtCore.Qt.Key_Z, QtCore.Qt.ControlModifier)
    assert window.doc.design.sources == () and not window.windowTitle().endswith("*")
    # Redo: unsaved again; undo: clean again.
    QTest.keyClick(
        window.tree, QtCore.Qt.Key_Z, QtCore.Qt.ControlModifier | QtCore.Qt.ShiftModifier
    )
    assert window.windowTitle().endswith("*")
    QTest.keyClick(window.tree, QtCore.Qt.Key_Z, QtCore.Qt.ControlModifier)
    assert not window.windowTitle().endswith("*")
    # Quitting does not ask to save.
    asked = []
    monkeypatch.setattr(ask, "ask_unsaved", lambda *a: asked.append(a) or "cancel")
    window.ask_before_discard = True
    assert window.close() and asked == []


def file_dialog_folder(trigger) -> str:
    """The folder the file dialog ``trigger`` opens starts in (then Cancel)."""
    seen = {}

    def look(dialog):
        seen["folder"] = dialog.directory().absolutePath()
        QTest.keyClick(dialog, QtCore.Qt.Key_Escape)

    answer(trigger, look)
    return seen["folder"]


@pytest.fixture
def home(tmp_path, monkeypatch) -> Path:
    """A home folder of the test's own."""
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.setattr(Path, "home", classmethod(lambda cls: home))
    return home


def test_file_dialogs_start_in_the_last_used_folder(qtbot, tmp_path, home):
    settings = QtCore.QSettings(str(tmp_path / "settings.ini"), QtCore.QSettings.IniFormat)
    open_project = None

    def start():
        nonlocal open_project
        win = MainWindow(settings)
        win.ask_before_discard = False
        win.show()
        open_project = menu_action(win, "File/Open project...")
        return win

    win = start()
    # Nothing used yet, no project: the home folder, not the installation's.
    assert file_dialog_folder(open_project.trigger) == str(home)
    # A project opened by typing its path in the dialog: its folder is the next start.
    folder = tmp_path / "projects"
    folder.mkdir()
    project = folder / "office.json"
    shutil.copy(
        Path(__file__).resolve().parents[2] / "resources/projects/office-demo.json", project
    )

    def type_path(dialog):  # the path pasted in the file name box, then Open clicked
        dialog.findChild(QtWidgets.QLineEdit, "fileNameEdit").setText(str(project))
        QTest.mouseClick(button(dialog, "Open"), QtCore.Qt.LeftButton)

    answer(open_project.trigger, type_path)
    assert win.doc.path == project
    assert file_dialog_folder(menu_action(win, "File/Import model...").trigger) == str(folder)
    win.close()
    # Remembered across sessions (the settings), until the folder is gone: then the
    # open project's folder, then home.
    win = start()
    assert file_dialog_folder(open_project.trigger) == str(folder)
    win.close()
    settings.setValue("lastFolder", str(tmp_path / "gone"))
    win = start()
    assert file_dialog_folder(open_project.trigger) == str(home)
    other = tmp_path / "elsewhere"
    other.mkdir()
    shutil.copy(project, other / "copy.json")
    assert win.open_path(other / "copy.json")
    assert file_dialog_folder(open_project.trigger) == str(other)
    win.close()


def test_status_messages_fit_and_the_title_keeps_the_name(qtbot, window, monkeypatch, tmp_path):
    import_meeting_room(qtbot, window, monkeypatch, tmp_path)
    laptop(window)
    bar = window.statusBar()
    text = (
        "Precomputing the luminaire arrays' light for the 3 arrays of the design: 45% "
        "(12 s); the search starts after it, and then every candidate layout is lit "
        "from the precomputed light in a few milliseconds"
    )
    bar.showMessage(text, 10_000)
    shown = bar.currentMessage()
    assert shown != text and shown.endswith("…")
    assert bar.fontMetrics().horizontalAdvance(shown) <= bar.room() and bar.toolTip() == text
    # The window made wider: the whole message shows, with no tooltip.
    window.resize(2600, 768)
    QTest.qWait(100)
    assert bar.currentMessage() == text and bar.toolTip() == ""
    laptop(window)
    # A project saved deep down: its name first in the title, the folder shortened.
    deep = tmp_path.joinpath(*[f"folder-with-a-long-name-{k}" for k in range(6)])
    deep.mkdir(parents=True)
    monkeypatch.setattr(ask, "save_file", lambda *a, **k: str(deep / "classroom.json"))
    QTest.mouseClick(window.tree.viewport(), QtCore.Qt.LeftButton)
    QTest.keyClick(window, QtCore.Qt.Key_S, QtCore.Qt.ControlModifier)
    title = window.windowTitle()
    assert title.startswith("classroom.json - ") and title.endswith(" - LightInv")
    assert "…" in title and len(title) < 80


def test_a_line_too_long_for_its_panel_is_elided_and_whole_on_hover(qtbot):
    from app.widgets.elided_label import ElidedLabel

    text = "Precomputing the luminaire arrays' light: 45% (12 s); the search starts after it"
    label = ElidedLabel(text + "\nrun 1 of 3")
    qtbot.addWidget(label)
    label.resize(200, 60)
    label.show()
    first, second = label.text().split("\n")
    assert first.endswith("…") and label.fontMetrics().horizontalAdvance(first) <= 200
    assert second == "run 1 of 3" and label.toolTip() == text + "\nrun 1 of 3"
    label.resize(900, 60)
    assert label.text() == label.full_text() == text + "\nrun 1 of 3" and label.toolTip() == ""
