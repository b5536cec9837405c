"""A two-storey model: the upper storey's floor hides the ground floor's ceiling from
every view, so no zone could be drawn on it (found walking through KIT's FZK-Haus,
docs/walkthrough-first-day.md). *Materials and view > Model: cut above* hides what is
above a height, in the view and for picking and drawing: the zone goes on the ceiling
under the cut. Done by clicks (tests/app/user.py) on an OBJ the test writes."""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from tests.app import user as u
from tests.app.test_first_day import named, wait_for_light


def box(lines: list[str], name: str, z0: float, z1: float, first: int) -> int:
    """A 4 x 3 m room from z0 to z1, faces into it, groups NAME_floor, NAME_ceiling,
    NAME_walls; returns the next vertex number."""
    corners = [(0, 0), (4, 0), (4, 3), (0, 3)]
    lines += [f"v {x} {y} {z0}" for x, y in corners] + [f"v {x} {y} {z1}" for x, y in corners]
    a, b, c, d, e, f, g, h = range(first, first + 8)
    lines += [f"g {name}_floor", f"f {a} {b} {c} {d}", f"g {name}_ceiling", f"f {e} {h} {g} {f}"]
    lines += [f"g {name}_walls", f"f {a} {e} {f} {b}", f"f {b} {f} {g} {c}"]
    lines += [f"f {c} {g} {h} {d}", f"f {d} {h} {e} {a}"]
    return first + 8


def two_storeys(path: Path) -> Path:
    """Ground floor 0..3 m, upper storey 3.3..6 m (a 0.3 m slab between)."""
    lines: list[str] = ["# two storeys, written by tests/app/test_storey_cut.py"]
    box(lines, "upper", 3.3, 6.0, box(lines, "ground", 0.0, 3.0, 1))
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_a_zone_on_the_ground_floor_ceiling_under_a_cut(window, tmp_path):
    win, vp = window, window.viewport
    model = two_storeys(tmp_path / "house.obj")

    def half_metre(dialog):
        u.type_text(u.field(dialog, "Patch size"), "0.5")
        u.ok(dialog)

    u.answer(lambda: u.menu(win, "File", "Import model..."), u.file_name(model), half_metre)
    wait_for_light(win)
    u.click(u.toolbar_button(win, "Top view"))
    u.choose(win.zone_kind_box, "luminaire zone")
    u.click(u.toolbar_button(win, "Draw zone"))
    # Without a cut the rectangle goes on the upper storey's ceiling.
    u.answer(lambda: u.view_drag(vp, (1.0, 1.0, 3.0), (3.0, 2.0, 3.0)), named("upstairs"))
    wait_for_light(win)

    u.tab(win, "Properties")
    u.tab(win, "Materials and view")
    props = win.findChild(QtWidgets.QDockWidget, "properties")
    u.click(u.button(props, "cut above"))
    height = u.field(props, "Model").parentWidget().findChildren(QtWidgets.QDoubleSpinBox)
    (spin,) = [s for s in height if u.shown(s) and s.suffix() == " m"]
    u.type_text(spin, "3.15")
    u.press(spin, QtCore.Qt.Key_Return)
    QTest.qWait(300)
    u.screenshot(win, Path("/tmp/cut"), "cut")
    u.answer(lambda: u.view_drag(vp, (1.0, 1.0, 3.0), (3.0, 2.0, 3.0)), named("downstairs"))
    wait_for_light(win)

    u.tab(win, "Drawn zones")
    zone = u.field(props, "Zone")
    on = {zone.itemText(i).split(" on ")[0]: zone.itemText(i) for i in range(zone.count())}
    assert on["upstairs"].endswith("on upper_ceiling"), on
    assert on["downstairs"].endswith("on ground_ceiling"), on
