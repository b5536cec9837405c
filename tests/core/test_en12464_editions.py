"""EN 12464-1 editions: the 2011 and 2021 presets, each edition's grid rule, and the
edition a work plane names through project files."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from lightinv_core.design.en12464 import (
    EDITION_2011,
    EDITION_2021,
    EDITIONS,
    preset_intention,
    ra_check,
    requirement,
    requirements,
)
from lightinv_core.design.model import DesignError, Workplane
from lightinv_core.light.grids import edition_grid, grid_counts_2021
from lightinv_core.scene.builders import room_faces
from lightinv_core.scene.model import Scene, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.workplane import grid_counts


def test_the_2021_presets_are_the_published_rows():
    office = requirement("office", EDITION_2021)
    assert (office.em, office.em_mod, office.u0, office.ugr_l, office.ra) == (
        500,
        1000,
        0.60,
        19,
        80,
    )
    assert office.activity == "Writing, typing, reading, data processing"
    filing = requirement("filing", EDITION_2021)  # Performance in Lighting's table row
    assert (filing.em, filing.em_mod, filing.u0, filing.ra) == (300, 500, 0.40, 80)
    drawing = requirement("drawing", EDITION_2021)
    assert (drawing.em, drawing.u0, drawing.ugr_l) == (750, 0.70, 16)
    for key in ("cad", "meeting", "reception", "archive", "classroom", "corridor"):
        r = requirement(key, EDITION_2021)
        assert r.edition == EDITION_2021 and r.em_mod > r.em
    # Every 2011 task has its 2021 row, and the 2011 values stay as they were.
    assert [r.key for r in requirements(EDITION_2011)] == [
        r.key for r in requirements(EDITION_2021)
    ]
    assert requirement("classroom").em == 300 and requirement("classroom").edition == EDITION_2011
    assert "EN 12464-1:2021 ref. 34.2" in office.label
    assert office.values == "Em 500 lux (modified 1000), U0 0.60, UGR_L 19, Ra 80"


def test_a_preset_makes_the_intention_of_its_edition():
    it = preset_intention("classroom", "desks", edition=EDITION_2021)
    assert (it.average, it.uniformity, it.scenario) == (500, 0.6, "night")
    assert preset_intention("classroom", "desks").average == 300  # 2011 by default
    assert preset_intention("office", "wp", edition=EDITION_2021, modified=True).average == 1000
    with pytest.raises(DesignError, match="editions: EN 12464-1:2011, EN 12464-1:2021"):
        requirements("EN 12464-1:2002")
    with pytest.raises(DesignError, match="no EN 12464-1:2021 preset 'gym'"):
        requirement("gym", EDITION_2021)


def test_the_products_ra_against_the_preset():
    assert ra_check(80, [90.0, 82.0]) == ("Ra 82", True)
    assert ra_check(80, [70.0]) == ("Ra 70", False)
    assert ra_check(80, [None]) == ("not stated", None)
    assert ra_check(80, [None, 60.0]) == ("Ra 60 (one product not stated)", False)
    assert ra_check(80, []) == ("no luminaires", None)


def _p(d: float) -> float:
    return 0.2 * 5 ** math.log10(d)


def test_the_grid_rules_on_the_issue_room_and_two_by_hand():
    # The issue's room: 8 x 6 m less a 0.5 m border is 7 x 5 m; p(7) = 0.7796 m;
    # 7 / p = 8.98, 5 / p = 6.41: 2011 rounds up (9 x 7), 2021 rounds (9 x 6).
    assert grid_counts(7.0, 5.0)[:2] == (9, 7)
    nx, ny, p = grid_counts_2021(7.0, 5.0)
    assert (nx, ny) == (9, 6) and p == pytest.approx(0.7793, abs=1e-4)
    # 12 x 3 m: p(12) = 0.2 x e^(1.07918 x 1.60944) = 1.1359 m; 12 / p = 10.56 -> 11,
    # 3 / p = 2.64 -> 3 (2011 takes the shorter side as the longer is 4 times it:
    # p(3) = 0.4310, 27.8 -> 28 and 6.96 -> 7).
    assert grid_counts_2021(12.0, 3.0) == (11, 3, pytest.approx(1.1359, abs=1e-4))
    assert grid_counts(12.0, 3.0)[:2] == (28, 7)
    # 6 x 4.5 m: p(6) = 0.6997 m; 8.58 -> 9 both ways, 6.43 -> 6 (2011: 7).
    assert grid_counts_2021(6.0, 4.5) == (9, 6, pytest.approx(_p(6.0)))
    assert _p(6.0) == pytest.approx(0.6997, abs=1e-4)
    assert grid_counts(6.0, 4.5)[:2] == (9, 7)
    # A sliver keeps one point: p(0.1) = 0.04 m, 0.01 / p = 0.25 rounds to 0.
    assert grid_counts_2021(0.1, 0.01)[1] == 1


@pytest.fixture(scope="module")
def room():
    faces = room_faces(0, 0, 0, 8, 6, 3)
    p = mesh_patches(
        Scene("r", [Surface(k, k, 0.5, rect=r) for k, r in faces.items()], resolution=0.5)
    )
    return p, RayCaster(p)


def test_the_work_plane_grid_follows_its_edition(room):
    p, caster = room
    old = edition_grid(p, caster, Workplane("wp", 0.8, 0.5))
    new = edition_grid(p, caster, Workplane("wp", 0.8, 0.5, edition=EDITION_2021))
    assert old.counts == (9, 7) and len(old.points) == 63
    assert new.counts == (9, 6) and len(new.points) == 54
    # Cell centres over the same 7 x 5 m area, 0.8 m up.
    np.testing.assert_allclose(new.spacing, (7 / 9, 5 / 6))
    assert new.points[:, 0].min() == pytest.approx(0.5 + 7 / 18)
    assert new.points[:, 1].max() == pytest.approx(5.5 - 5 / 12)
    assert np.all(new.points[:, 2] == pytest.approx(0.8))


def test_the_edition_is_saved_and_old_files_read_as_2011(tmp_path):
    from lightinv_core.project import load_project, save_project

    base = Path(__file__).resolve().parents[2] / "resources" / "projects" / "office-arrays.json"
    data = json.loads(base.read_text())
    planes = data.get("workplanes") or []
    assert planes and all("edition" not in wp for wp in planes)
    proj = load_project(base)
    assert all(wp.edition == EDITION_2011 for wp in proj.design.workplanes)
    # Saved again unchanged, an old file stays as it was: no edition written.
    same = tmp_path / "same.json"
    save_project(proj, same)
    assert "edition" not in json.loads(same.read_text())["workplanes"][0]
    wp = dataclasses.replace(proj.design.workplanes[0], edition=EDITION_2021)
    design = dataclasses.replace(proj.design, workplanes=(wp, *proj.design.workplanes[1:]))
    out = tmp_path / "p.json"
    save_project(dataclasses.replace(proj, design=design), out)
    saved = json.loads(out.read_text())["workplanes"][0]
    assert saved["edition"] == "EN 12464-1:2021"
    assert load_project(out).design.workplanes[0].edition == EDITION_2021
    assert set(EDITIONS) == {EDITION_2011, EDITION_2021}
