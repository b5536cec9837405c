"""A designer's first day in the window (issue #29), done only as a user can: widgets
found by the text they show, mouse clicks and key presses on them, dialogs answered by
clicking OK, zones drawn with the mouse in the 3D view (tests/app/user.py). Nothing here
calls the document or a private method; what is checked is what the window shows.

Steps that another helper of issue #29 is making possible are behind the module
constants below; the lead turns each on once that work is merged."""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from tests.app import user as u

WALL_GLAZING_READY = False
"""A skylight (glazing) zone drawn on a wall's window face (helper "glazing"). Today:
"skylight zones are drawn on ceilings and roofs (surfaces facing down into the room),
on a planar rectangle that is not a zone yet; there is none under the cursor"."""

DATA = Path(__file__).resolve().parents[1] / "data"
OBJ = DATA / "obj" / "classroom-window.obj"
IES = DATA / "photometry" / "rab-square-1.ies"
SHOTS = Path("/tmp/firstday")


def wait_for_light(win, timeout_s: float = 120) -> None:
    """Wait until the status bar names the operator's rank and no progress shows."""
    assert QTest.qWaitFor(
        lambda: "rank k" in win.status_rank.text() and not win.progress.isVisible(),
        int(timeout_s * 1000),
    ), win.status_rank.text()


def named(name: str):
    """An answer to the zone dialog: type the zone's name, click OK."""

    def respond(dialog):
        u.type_text(u.field(dialog, "Name"), name)
        u.ok(dialog)

    return respond


def test_first_day_on_an_obj_classroom(qtbot, window):
    win, vp = window, window.viewport
    shot = SHOTS / "obj"

    # File > Import model..., the file typed in the file dialog, 0.5 m patches, OK.
    def half_metre(dialog):
        u.type_text(u.field(dialog, "Patch size"), "0.5")
        u.ok(dialog)

    seen = u.answer(lambda: u.menu(win, "File", "Import model..."), u.file_name(OBJ), half_metre)
    assert seen == ["Import model", "Import classroom-window.obj"]
    wait_for_light(win)
    assert set(u.tree_texts(win.tree, "Surfaces")) == {"floor", "ceiling", "walls", "window"}
    u.screenshot(win, shot, "01-imported")

    # A skylight rectangle and a luminaire polygon on the same ceiling, from above.
    u.click(u.toolbar_button(win, "Top view"))
    u.choose(win.zone_kind_box, "skylight zone")
    u.click(u.toolbar_button(win, "Draw zone"))
    u.answer(lambda: u.view_drag(vp, (1.0, 2.0, 3.0), (2.5, 4.0, 3.0)), named("roof light"))
    wait_for_light(win)
    u.choose(win.zone_kind_box, "luminaire zone")
    u.click(u.toolbar_button(win, "Draw polygon"))
    corners = [(3.5, 1.0, 3.0), (5.5, 1.0, 3.0), (5.5, 4.0, 3.0), (4.5, 4.5, 3.0), (3.5, 4.0, 3.0)]

    def polygon():
        for c in corners:
            u.view_click(vp, c)
            QTest.qWait(50)
        u.view_key(vp, QtCore.Qt.Key_Return)

    u.answer(polygon, named("lights"))
    wait_for_light(win)
    zones = u.tree_texts(win.tree, "Emitter zones")
    assert zones["roof light"].startswith("skylight, 1.5") and zones["lights"].startswith(
        "luminaire, 2.00 x 3.5"
    ), zones
    u.screenshot(win, shot, "02-zones")

    # The wall's window made glazing: a skylight zone drawn over it from the front.
    if WALL_GLAZING_READY:
        u.click(u.toolbar_button(win, "Front view"))
        u.choose(win.zone_kind_box, "skylight zone")
        u.click(u.toolbar_button(win, "Draw zone"))
        u.answer(lambda: u.view_drag(vp, (1.5, 0.0, 1.0), (4.5, 0.0, 2.2)), named("window"))
        wait_for_light(win)
        assert u.tree_texts(win.tree, "Emitter zones")["window"].startswith("skylight, 3.00")

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
    assert arrays["A1"].startswith("2 x 2 Panel 600") and "rab-square-1.ies" in arrays["A2"]
    assert set(u.tree_texts(win.tree, "Work planes")) == {"wp"}
    assert u.tree_texts(win.tree, "Lighting intentions")["classroom"].startswith(
        "work plane wp: average 300"
    )
    u.screenshot(win, shot, "03-luminaires")
