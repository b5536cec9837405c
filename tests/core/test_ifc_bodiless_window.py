"""IFC windows with no body (issue #29, item 8): one that fills an opening in its wall
becomes a glazing zone from its placement and OverallWidth x OverallHeight; one that
fills no opening is skipped with the reason in the import report and a warning."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.scene.importers.ifc import load_ifc
from lightinv_core.scene.importers.report import report_of
from tests.core.test_ifc_import import W, ifc_room

ifcopenshell = pytest.importorskip("ifcopenshell")

NORTH = (2.0, 3.2, 1.0, 2.2)  # north wall opening: x from, x to, z from, z to


def bodiless(folder, unit: str):
    """The test room with two windows that have no body: N1 in an opening of the north
    wall (its placement in the middle of the wall, width along x), N2 filling nothing."""
    import ifcopenshell.api.feature
    import ifcopenshell.api.geometry
    import ifcopenshell.api.root

    api = ifcopenshell.api

    def extra(box, f):
        north = next(w for w in f.by_type("IfcWall") if w.Name == "North")
        x0, x1, z0, z1 = NORTH
        hole = box("IfcOpeningElement", "N1 opening", x0, W - 0.1, z0, x1 - x0, 0.4, z1 - z0)
        api.feature.add_feature(f, feature=hole, element=north)
        scale = 1000.0 if unit == "mm" else 1.0
        for name in ("N1", "N2"):
            win = api.root.create_entity(f, ifc_class="IfcWindow", name=name)
            m = np.eye(4)
            m[:3, 3] = (x0, W + 0.1, z0)
            api.geometry.edit_object_placement(f, product=win, matrix=m)
            win.OverallWidth, win.OverallHeight = (x1 - x0) * scale, (z1 - z0) * scale
            if name == "N1":
                api.feature.add_filling(f, opening=hole, element=win)

    return ifc_room(folder / f"bodiless-{unit}.ifc", unit=unit, extra=extra)


@pytest.mark.parametrize("unit", ["mm", "m"])
def test_a_window_without_a_body_in_an_opening_becomes_a_glazing_zone(tmp_path, unit):
    scene = load_ifc(bodiless(tmp_path, unit), resolution=0.5)
    assert scene.info["ifc"]["zones"]["IfcWindow:N1"] == "wall window"
    zone = next(z for z in scene.zones if z.name == "IfcWindow:N1")
    assert zone.kind == "window"  # a wall window: a window (glazing) zone
    rect = scene.zone_rect("IfcWindow:N1")
    x0, x1, z0, z1 = NORTH
    assert sorted(rect.size) == pytest.approx(sorted([x1 - x0, z1 - z0]), abs=1e-6)
    # In the wall, facing into the room (-y), where the opening is.
    assert rect.normal == pytest.approx((0.0, -1.0, 0.0), abs=1e-9)
    centre = rect.origin + 0.5 * (rect.u + rect.v)
    assert centre[[0, 2]] == pytest.approx([(x0 + x1) / 2, (z0 + z1) / 2], abs=1e-6)
    assert W <= centre[1] <= W + 0.2
    report = report_of(scene)
    by_name = {it.name.split(" #")[0]: it for it in report.items}
    assert by_name["N1"].outcome == "zone"
    n2 = by_name["N2"]
    assert n2.outcome == "dropped" and "fills no opening" in n2.reason
    warning = next(w for w in scene.info["warnings"] if "without a body" in w)
    assert "IfcWindow:N2" in warning and "IfcWindow:N1" not in warning
