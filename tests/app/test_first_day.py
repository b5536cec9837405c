"""A designer's first day in the window (issue #29), done only as a user can: widgets
found by the text they show, mouse clicks and key presses on them, dialogs answered by
clicking OK, zones drawn with the mouse in the 3D view (tests/app/user.py). Nothing here
calls the document or a private method; what is checked is what the window shows.

The window is the one a 1366 x 768 laptop screen gives (pyproject.toml's xvfb size);
screenshots of each step go to /tmp/firstday for a person to look at."""

from __future__ import annotations

import re
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest
from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from app.window.main_window import MainWindow
from tests.app import user as u

DATA = Path(__file__).resolve().parents[1] / "data"
OBJ = DATA / "obj" / "classroom-window.obj"
IES = DATA / "photometry" / "rab-square-1.ies"
SHOTS = Path("/tmp/firstday")


@dataclass(frozen=True)
class Model:
    """A designer's model and where, in it, the scenario draws (m, the model's axes)."""

    name: str
    surfaces: set[str]  # the Surfaces branch of the tree once imported (names)
    skylight: tuple  # two opposite corners of the skylight rectangle, on the ceiling
    skylight_size: str  # as the tree shows it: "skylight, 1.50 x 2.00 m"
    polygon: list  # the luminaire polygon's corners, on the same ceiling
    polygon_size: str
    window: tuple | None  # corners of the wall window to draw from inside (Back view)
    window_zone: str  # its zone's name and tree text start
    window_size: str


OBJ_ROOM = Model(
    "classroom-window.obj",
    {"floor", "ceiling", "walls", "window"},
    ((1.0, 2.0, 3.0), (2.5, 4.0, 3.0)),
    "skylight, 1.50 x 2.00",
    [(3.5, 1.0, 3.0), (5.5, 1.0, 3.0), (5.5, 4.0, 3.0), (4.5, 4.5, 3.0), (3.5, 4.0, 3.0)],
    "luminaire, 2.00 x 3.50",
    # Inside the window's edges: the drag snaps to them (zone_drawing.SNAP_PIXELS).
    ((1.6, 0.0, 1.1), (4.4, 0.0, 2.1)),
    "south window",
    "window, 3.00 x 1.20",
)
# The IFC room (tests/core/test_ifc_import.py): x 0..6, y 0..4, roof slab's underside at
# 3 m with a skylight at x 2.5..3.5, y 1.5..2.5, a ceiling panel at x 4..6; its window
# is an IfcWindow, a glazing zone once imported.
IFC_ROOM = Model(
    "room.ifc",
    set(),
    ((0.5, 2.6, 3.0), (2.0, 3.6, 3.0)),
    "skylight, 1.50 x 1.00",
    [(0.5, 0.4, 3.0), (2.2, 0.4, 3.0), (2.2, 2.0, 3.0), (1.4, 2.3, 3.0), (0.5, 2.0, 3.0)],
    "luminaire, 1.70 x 1.90",
    None,
    "IfcWindow:W1",
    "window, 1.50 x 1.20",
)


def wait_for_light(win, timeout_s: float = 120) -> None:
    """Wait until the status bar names the operator's rank and no progress shows."""
    assert u.wait_for(
        lambda: "rank k" in win.status_rank.text() and not win.progress.isVisible(),
        int(timeout_s * 1000),
    ), win.status_rank.text()


def named(name: str):
    """An answer to the zone dialog: type the zone's name, click OK."""

    def respond(dialog):
        u.type_text(u.field(dialog, "Name"), name)
        u.ok(dialog)

    return respond


@pytest.fixture
def laptop(qtbot, tmp_path):
    """The window as it opens on the session's 1366 x 768 screen (not resized)."""
    settings = QtCore.QSettings(str(tmp_path / "settings.ini"), QtCore.QSettings.IniFormat)
    win = MainWindow(settings)
    win.ask_before_discard = False  # a failed test's teardown must not wait on a question
    qtbot.addWidget(win)
    win.show()
    QTest.qWaitForWindowExposed(win)
    assert win.frameGeometry().width() <= 1366 and win.frameGeometry().height() <= 768
    yield win
    win.close()


def test_first_day_on_an_obj_classroom(qtbot, laptop, tmp_path_factory):
    first_day(qtbot, laptop, OBJ, OBJ_ROOM, tmp_path_factory.mktemp("out"))


def test_first_day_on_an_ifc_room(qtbot, laptop, tmp_path_factory):
    pytest.importorskip("ifcopenshell")
    from tests.core.test_ifc_import import ifc_room

    model = ifc_room(tmp_path_factory.mktemp("ifc") / "room.ifc")
    first_day(qtbot, laptop, model, IFC_ROOM, tmp_path_factory.mktemp("out"))


def first_day(qtbot, win, path: Path, model: Model, out: Path) -> None:
    """The whole first day on the model file ``path``; PNGs of the steps in SHOTS."""
    vp = win.viewport
    shot = SHOTS / path.suffix[1:]

    # File > Import model..., the file typed in the file dialog, 0.5 m patches, OK.
    def half_metre(dialog):
        u.type_text(u.field(dialog, "Patch size"), "0.8")
        u.ok(dialog)

    seen = u.answer(lambda: u.menu(win, "File", "Import model..."), u.file_name(path), half_metre)
    assert seen == ["Import model", f"Import {path.name}"]
    wait_for_light(win)
    surfaces = set(u.tree_texts(win.tree, "Surfaces"))
    assert surfaces >= model.surfaces and len(surfaces) >= 4, surfaces
    u.screenshot(win, shot, "01-imported")

    # A skylight rectangle and a luminaire polygon on the same ceiling, from above.
    u.click(u.toolbar_button(win, "Top view"))
    u.choose(win.zone_kind_box, "skylight zone")
    u.click(u.toolbar_button(win, "Draw zone"))
    u.answer(lambda: u.view_drag(vp, *model.skylight), named("roof light"))
    wait_for_light(win)
    u.choose(win.zone_kind_box, "luminaire zone")
    u.click(u.toolbar_button(win, "Draw polygon"))

    def polygon():
        for c in model.polygon:
            u.view_click(vp, c)
            QTest.qWait(50)
        u.view_key(vp, QtCore.Qt.Key_Return)

    u.answer(polygon, named("lights"))
    wait_for_light(win)
    zones = u.tree_texts(win.tree, "Emitter zones")
    assert zones["roof light"].startswith(model.skylight_size), zones
    assert zones["lights"].startswith(model.polygon_size), zones
    u.screenshot(win, shot, "02-zones")

    # The wall's window made glazing: a window zone drawn over it, seen from inside the
    # room (Back view looks at the south wall); an IFC window is one once imported.
    u.click(u.toolbar_button(win, "Back view"))
    if model.window is not None:
        u.choose(win.zone_kind_box, "window (glazing) zone")
        u.click(u.toolbar_button(win, "Draw zone"))
        u.answer(lambda: u.view_drag(vp, *model.window), named(model.window_zone))
        wait_for_light(win)
    u.screenshot(win, shot, "02b-window")
    window_zone = u.tree_texts(win.tree, "Emitter zones")[model.window_zone]
    assert window_zone.startswith(model.window_size), window_zone

    # A panel luminaire of its own in the luminaire zone (Properties > Source).
    u.click(u.toolbar_button(win, "Iso view"))
    u.tab(win, "Properties")
    u.tab(win, "Source")
    props = win.findChild(QtWidgets.QDockWidget, "properties")
    u.choose(u.field(props, "New source in"), "lights")
    u.click(u.button(props, "Add source"))
    wait_for_light(win)
    sources = u.tree_texts(win.tree, "Sources")
    assert len(sources) == 1, sources

    # Luminaires: a catalogue product's array, and an array of an IES file from disk.
    u.tab(win, "Luminaires")
    dock = win.findChild(QtWidgets.QDockWidget, "luminaires")
    u.click_cell(win.luminaires_panel.catalogue, "Panel 600")
    u.answer(lambda: u.click(u.button(dock, "Add array...")), u.ok)

    def from_file(dialog):
        u.answer(lambda: u.click(u.button(dialog, "File...")), u.file_name(IES))
        assert u.field(dialog, "Product").currentText() == str(IES)
        u.ok(dialog)

    u.answer(lambda: u.click(u.button(dock, "Add array...")), from_file)
    u.answer(lambda: u.click(u.button(dock, "Add work plane...")), u.ok)
    u.choose(win.luminaires_panel.preset, "Classrooms")
    QTest.qWait(300)
    arrays = u.tree_texts(win.tree, "Luminaire arrays")
    assert arrays["A1"].startswith("2 x 2 = 4 Panel 600") and "rab-square-1.ies" in arrays["A2"]
    assert set(u.tree_texts(win.tree, "Work planes")) == {"wp"}
    # A new work plane follows EN 12464-1:2021, whose classrooms ask 500 lux.
    assert u.tree_texts(win.tree, "Lighting intentions")["classroom"].startswith(
        "work plane wp: average 500"
    )
    u.screenshot(win, shot, "03-luminaires")

    # Run from the Optimisation dock's Run tab: the default method and goal, and a
    # budget typed in as a designer trying the tool out would (the default 20,000
    # evaluations is a long wait in a test; the run's path is the same).
    u.tab(win, "Run")
    run_dock = win.findChild(QtWidgets.QDockWidget, "optimisation")
    budget = u.beside(run_dock, "Evaluations")
    u.type_text(budget, "600")
    u.press(budget, QtCore.Qt.Key_Tab)
    assert budget.value() == 600
    state = u.label(run_dock, "Ready")
    u.click(u.button(run_dock, "Run"))
    assert u.wait_for(lambda: state.text().startswith("Running"), 30_000), state.text()
    assert u.wait_for(lambda: not state.text().startswith(("Running", "Cancelling")), 600_000)
    assert "evaluations" in state.text(), state.text()
    # The typed budget ended it (a run may pass its budget by the last batch).
    evaluations = int(re.search(r"([\d,]+) evaluations", state.text()).group(1).replace(",", ""))
    assert evaluations < 1000, state.text()
    u.screenshot(win, shot, "04-run")

    # Load the best result from the Solutions table by clicking its row.
    u.tab(win, "Solutions")
    solutions = win.solutions_panel
    assert solutions.table.rowCount() >= 1
    u.click_cell(solutions.table, solutions.table.item(0, 0).text())
    QTest.qWait(300)
    assert "loaded" in win.statusBar().currentMessage().lower() or solutions.table.currentRow() == 0
    u.screenshot(win, shot, "05-loaded")

    # Drag the panel luminaire 0.5 m along the ceiling in Move mode, from the top, and
    # see the light change (its flux typed first: the optimiser may have dimmed it out).
    u.click(u.toolbar_button(win, "Top view"))
    (name,) = u.tree_texts(win.tree, "Sources")
    u.click_tree(win.tree, name)
    u.tab(win, "Properties")
    u.tab(win, "Source")
    flux = u.field(props, "flux")
    u.type_text(flux, "3000")
    u.press(flux, QtCore.Qt.Key_Return)
    wait_for_light(win)

    def desk() -> list[str]:
        """The work plane's row (Em, Emin, Emax, U0) as the Luminaires tab shows it."""
        u.tab(win, "Luminaires")
        table = win.luminaires_panel.planes
        row = [table.item(0, c).text() for c in range(3, 7)]
        u.tab(win, "Properties")
        return row

    lit = desk()
    corners = [u.field(props, c) for c in ("u0", "v0", "u1", "v1")]
    before = [c.value() for c in corners]
    u.click(u.toolbar_button(win, "Move"))
    centre = u.drawn_centre(vp, "current")
    middle = sum(c[0] for c in model.polygon) / len(model.polygon)
    step = 0.5 if centre[0] < middle else -0.5  # toward the middle of the polygon zone
    u.view_drag(vp, centre, (centre[0] + step, centre[1], centre[2]), steps=8)
    QTest.qWait(500)
    moved = u.drawn_centre(vp, "current")
    assert abs(moved[0] - centre[0] - step) < 0.1 and abs(moved[1] - centre[1]) < 0.1, moved
    shift = [c.value() - b for c, b in zip(corners, before, strict=True)]
    # One axis of the source's corners moved by the drag (within a pixel), the other not.
    moved_by = sorted(abs(d) for d in shift)
    assert moved_by[1] < 1e-6 and abs(moved_by[2] - 0.5) < 0.05 and abs(moved_by[3] - 0.5) < 0.05
    u.screenshot(win, shot, "06-dragged")
    assert desk() != lit, lit  # the light followed the drag

    # Export the report: File > Export report (PDF)..., a path typed in the file dialog.
    pdf = out / "classroom report.pdf"
    u.answer(lambda: u.menu(win, "File", "Export report (PDF)..."), u.file_name(pdf))
    assert u.wait_for(lambda: pdf.exists() and pdf.stat().st_size > 10_000, 120_000)
    text = subprocess.run(["pdftotext", str(pdf), "-"], capture_output=True, text=True).stdout
    assert "classroom" in text and ("pass" in text.lower() or "fail" in text.lower()), text[:500]

    # Save As, quit, open again in a new window: everything comes back.
    project = pdf.with_name("classroom.json")
    u.answer(lambda: u.menu(win, "File", "Save As..."), u.file_name(project))
    assert project.exists()
    shown = {
        b: u.tree_texts(win.tree, b)
        for b in ("Emitter zones", "Sources", "Luminaire arrays", "Work planes")
    }
    rows = solutions.table.rowCount()
    u.menu(win, "File", "Quit")
    assert u.wait_for(lambda: not win.isVisible(), 10_000)

    # LightInv started again: File > Open project..., the saved file typed.
    again = MainWindow(
        QtCore.QSettings(str(project.with_suffix(".ini")), QtCore.QSettings.IniFormat)
    )
    again.ask_before_discard = False
    qtbot.addWidget(again)
    again.show()
    QTest.qWaitForWindowExposed(again)
    u.answer(lambda: u.menu(again, "File", "Open project..."), u.file_name(project))
    wait_for_light(again)
    for branch, items in shown.items():
        assert u.tree_texts(again.tree, branch) == items, branch
    assert again.solutions_panel.table.rowCount() == rows
    assert again.windowTitle().startswith("classroom.json")
    u.screenshot(again, shot, "07-reopened")
    again.close()
