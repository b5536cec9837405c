"""Finer skies and switching with a dead band, by clicks at 1366 x 768 (issue #30,
docs/daylight.md "Finer skies in projects; switching with a dead band"): the built-in
office with its roof light clear and two control groups (``office_project``) opened by
File > Open project...; Climate > Sky patches "577 (Reinhart MF:2)" traces the clear
glazing again on the finer sky, and Edit > Undo takes it back; Climate > Control
groups > Edit... on the west group: Control "switching (on/off)", Dead band 20
typed, OK; the list and the energy box say so, and Edit > Undo takes it back. The
figures are checked in tests/core/test_sky_subdivision.py and test_dead_band.py.

Screenshots go to /tmp/shots-skyband/."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from PySide6 import QtWidgets

from lightinv_core.light.clear_build import clear_light
from tests.app import user as u
from tests.app.conftest import open_by_menu
from tests.app.test_group_modes_gui import _select

PROJECT = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-integrated.json"
SHOTS = Path("/tmp/shots-skyband")


def office_project(path: Path) -> None:
    """The built-in office (0.5 m patches) with its roof light clear and fixed, its west
    luminaire in control group "west" (the west half's sensor), the east one in the
    default group."""
    data = json.loads(PROJECT.read_text(encoding="utf-8"))
    data["scene"]["resolution"] = 0.5
    data["operator"] = {"rays": 256}
    for src in data["sources"]:
        if src["name"] == "S1":
            src.update(glazing="clear", free=[])
        if src["name"] == "L1":
            src["control_group"] = "west"
    data["rules"] = [r for r in data["rules"] if "S1" not in r["sources"]]
    data["control_groups"] = [{"name": "west", "sensor": [0.0, 0.0, 6.0, 8.0]}]
    path.write_text(json.dumps(data), encoding="utf-8")


def _settled(qtbot, window) -> None:
    """Wait until the clear glazing's trace (a worker) has ended."""
    qtbot.waitUntil(
        lambda: window.worker is None and not window.doc.clear_pending(), timeout=120_000
    )
    QtWidgets.QApplication.processEvents()


def _columns(window) -> int:
    return clear_light(window.doc.light, window.doc.design).patches.columns.count


def _switching_with_a_band(dialog: QtWidgets.QWidget) -> None:
    band = u.field(dialog, "Dead band")
    assert not band.isEnabled()  # dimming takes none
    u.choose(u.field(dialog, "Control"), "switching (on/off)")
    assert band.isEnabled()
    u.type_number(band, "20")
    u.screenshot(dialog, SHOTS, "group-dialog-dead-band")
    u.ok(dialog)


@pytest.mark.slow
def test_sky_patches_and_a_dead_band_by_clicks(qtbot, window, tmp_path):
    path = tmp_path / "office.json"
    office_project(path)
    open_by_menu(qtbot, window, path)  # the operator, then the clear glazing's trace
    window.activateWindow()
    _settled(qtbot, window)
    d = window.doc
    G = 1  # one clear rooflight: a block of columns and its closed blinds' glow
    before = _columns(window)

    u.tab(window, "Climate")
    u.reveal(window.climate_panel.sky)  # scrolled into sight, as a user does
    sky = u.field(window.climate_panel, "Sky patches")
    assert sky.currentText() == "145 (Tregenza)"
    u.choose(sky, "577 (Reinhart MF:2)")
    assert d.design.daylight.sky_subdivision == 2
    _settled(qtbot, window)
    # Traced again on the finer sky: 577 - 145 more sky columns per window, the sun's alike.
    assert _columns(window) - before == G * (577 - 145)
    u.screenshot(window, SHOTS, "climate-sky-patches")
    u.menu(window, "Edit", "Undo climate: sky_subdivision")
    assert d.design.daylight.sky_subdivision == 1 and sky.currentText() == "145 (Tregenza)"
    _settled(qtbot, window)
    assert _columns(window) == before

    box = u.reveal(window.climate_panel.groups)
    _select(box, "west")
    u.answer(lambda: u.click(u.button(box, "Edit...")), _switching_with_a_band)
    group = d.design.control_groups[0]
    assert (group.name, group.mode, group.dead_band) == ("west", "switching", 0.2)
    assert "; switching; dead band 20%;" in box.list.item(0).text()
    energy = u.reveal(window.climate_panel.energy.text)
    qtbot.waitUntil(
        lambda: "group west (switching to 500 lux, off from 600 lux)" in energy.text(),
        timeout=60_000,
    )
    u.screenshot(window, SHOTS, "climate-dead-band")
    u.menu(window, "Edit", "Undo edit control group west")
    QtWidgets.QApplication.processEvents()
    group = d.design.control_groups[0]
    assert (group.mode, group.dead_band) == ("dimming", 0.0)
    assert "dead band" not in box.list.item(0).text()
