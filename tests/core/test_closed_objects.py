"""Checks on an imported room that must not cry wolf (issue #29): closed desk boxes
standing on the floor are no opening (the floor under them and their bottoms get no
light, so the rays those faces lose are no light lost), while a desk turned inside out
and a room without its ceiling still are; an operator built before any zone keeps its
first rank; an OBJ without materials says which reflectance it assumed."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightinv_core.scene.importers.obj import load_obj
from lightinv_core.scene.importers.report import report_of
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.formfactors import escape_warning, form_factor_matrix, lost_fraction

CORNERS = [(i, j, k) for i in (0, 1) for j in (0, 1) for k in (0, 1)]
OUTWARD = [  # each face counter-clockwise seen from outside the box
    [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)],
    [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
    [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],
    [(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)],
    [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)],
    [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)],
]


def box(lines: list[str], count: list[int], group: str, lo, hi, inward: bool) -> None:
    """OBJ lines of a box from ``lo`` to ``hi`` (m): faces looking out of it (a desk)
    or into it (a room)."""
    lines.append(f"g {group}")
    base = count[0]
    for c in CORNERS:
        xyz = [lo[a] if c[a] == 0 else hi[a] for a in range(3)]
        lines.append("v {} {} {}".format(*xyz))
    count[0] += len(CORNERS)
    for face in OUTWARD:
        ids = [base + CORNERS.index(c) + 1 for c in face]
        lines.append("f " + " ".join(str(i) for i in (ids[::-1] if inward else ids)))


def classroom(folder: Path, desks_inside_out: int = 0, ceiling: bool = True) -> Path:
    """A 10 x 7 x 3 m room with six closed desks (1.6 x 0.8 x 0.75 m) on its floor;
    the first ``desks_inside_out`` with their faces turned into them."""
    lines, count = [], [0]
    box(lines, count, "room", (0, 0, 0), (10, 7, 3), inward=True)
    if not ceiling:
        lines.pop(-5)  # the room's top face (the second of OUTWARD)
    k = 0
    for x in (1.5, 4.5, 7.5):
        for y in (1.5, 4.5):
            box(lines, count, f"desk{k}", (x, y, 0), (x + 1.6, y + 0.8, 0.75), k < desks_inside_out)
            k += 1
    path = folder / "classroom.obj"
    path.write_text("\n".join(lines) + "\n")
    return path


def lost(path: Path) -> tuple[float, float]:
    """(lost fraction, the share of rays lost over all the surfaces' area): the check's
    answer and the plain measure it replaced."""
    p = mesh_patches(load_obj(path, resolution=0.4))
    F = form_factor_matrix(p, 256, seed=3)
    plain = float(np.dot(p.area, 1 - np.asarray(F.sum(axis=1)).ravel()) / p.area.sum())
    return lost_fraction(F, p), plain


def test_closed_desks_on_the_floor_are_no_opening(tmp_path):
    got, plain = lost(classroom(tmp_path))
    # The plain measure counted the floor under the desks and their bottoms (about 6 %
    # of the area) as open.
    assert plain > 0.01 and escape_warning(plain) is not None
    # What is left is the floor patches the desks' edges cross (0.4 m patches): their
    # hidden part does lose the light the patch's uniform exitance sends from it.
    assert got < plain / 5 and escape_warning(got) is None


def test_a_desk_turned_inside_out_or_a_missing_ceiling_still_warns(tmp_path):
    got, _ = lost(classroom(tmp_path, desks_inside_out=6))
    # Light from the room meets the backs of the desks' faces: lost.
    assert got > 0.02 and "escapes the model" in escape_warning(got)
    got, _ = lost(classroom(tmp_path, ceiling=False))
    assert got > 0.2


def test_an_operator_before_any_zone_keeps_its_first_rank(tmp_path):
    from lightinv_core.operator.build import build_operator
    from lightinv_core.operator.cache import accuracy_warning
    from lightinv_core.operator.settings import OperatorSettings

    p = mesh_patches(load_obj(classroom(tmp_path), resolution=0.5))
    settings = OperatorSettings(rays=64, tol=0.01)
    op = build_operator(p, settings)
    info = op.info
    assert info["nz"] == 0 and len(info["tries"]) == 1
    # Scattered single patches are far from any zone's light: the error would have
    # asked for doubling after doubling, for no source at all.
    assert info["estimated_rel_error"] > settings.tol
    assert info["tol_met"] and accuracy_warning(op) is None


def test_an_obj_without_mtl_says_which_reflectance_it_assumed(tmp_path):
    scene = load_obj(classroom(tmp_path), resolution=0.5)
    report = report_of(scene)
    assert report.needs_attention
    (note,) = report.notes
    assert "no MTL Kd for group(s) 'desk0', 'desk1'" in note and "(every surface)" in note
    assert "built-in default reflectance 0.5" in note
    assert set(np.unique([s.reflectance for s in scene.surfaces])) == {0.5}
    # Given a mapping for some groups, the rest are named with the mapping's default.
    scene = load_obj(
        classroom(tmp_path), resolution=0.5, materials={"default": 0.4, "groups": {"room": 0.7}}
    )
    (note,) = report_of(scene).notes
    assert "'room'" not in note and "(every surface)" not in note
    assert "the materials mapping's default reflectance 0.4" in note
    # Every group named: nothing assumed.
    groups = {"room": 0.7} | {f"desk{k}": 0.3 for k in range(6)}
    scene = load_obj(classroom(tmp_path), resolution=0.5, materials={"groups": groups})
    assert report_of(scene).notes == () and not report_of(scene).needs_attention
