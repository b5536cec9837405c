"""Emitter zones of any polygon: the outline geometry against shapely, zones drawn as
polygons, sources and arrays kept inside them by the rules, the editor and the optimiser."""

from __future__ import annotations

import copy
import json
from itertools import combinations

import numpy as np
import pytest
import shapely
from shapely.geometry import Polygon, box

from lightinv_core import study
from lightinv_core.design.arrays import array_violations
from lightinv_core.design.geometry import rule_violations
from lightinv_core.design.variables import array_layout
from lightinv_core.editing import rules
from lightinv_core.errors import SceneError
from lightinv_core.project import project_from_dict
from lightinv_core.project.write import project_dict
from lightinv_core.scene.builtin import office
from lightinv_core.scene.edits import ZoneEdit, apply_zone_edits
from lightinv_core.scene.model import EmitterZone, Scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.scene.zone_outline import (
    check_outline,
    inner_square,
    inside_area,
    is_inside,
    kept_inside,
    outside_area,
    points_inside,
)

# An L on the office ceiling (u = x, v = 8 - y), between the skylight and the wall.
L_OUTLINE = ((3.5, 0.5), (8.5, 0.5), (8.5, 1.5), (5.0, 1.5), (5.0, 2.5), (3.5, 2.5))
L_LOCAL = np.array(L_OUTLINE) - (3.5, 0.5)  # in the zone's own metres


def _random_polygons(rng, count):
    """Random simple polygons (shapely-valid), some clockwise, some not convex."""
    out = []
    while len(out) < count:
        pts = rng.uniform(-2, 2, (rng.integers(3, 10), 2))
        if Polygon(pts).is_valid and Polygon(pts).area > 1e-3:
            out.append(pts)
    return out


def test_inside_area_is_exact_against_shapely():
    rng = np.random.default_rng(7)
    worst = 0.0
    for poly in [*_random_polygons(rng, 60), L_LOCAL]:
        outline = check_outline(poly, "test")
        rects = rng.uniform(-2.5, 2.5, (40, 4))
        got = inside_area(outline, rects)
        shape = Polygon(outline)
        want = [
            shape.intersection(box(*np.minimum(r[:2], r[2:]), *np.maximum(r[:2], r[2:]))).area
            for r in rects
        ]
        worst = max(worst, float(np.abs(got - want).max()))
        full = np.abs(rects[:, 2] - rects[:, 0]) * np.abs(rects[:, 3] - rects[:, 1])
        assert outside_area(outline, rects) == pytest.approx(full - got, abs=1e-12)
        pts = rng.uniform(-2, 2, (200, 2))
        assert np.array_equal(points_inside(outline, pts), shapely.contains_xy(shape, *pts.T))
    assert worst < 1e-12
    # Rectangles that touch the outline's edges from inside are wholly inside.
    assert outside_area(check_outline(L_LOCAL, "L"), np.array([[0, 0, 1.5, 2], [0, 0, 5, 1]])) == (
        pytest.approx([0.0, 0.0], abs=1e-12)
    )
    assert outside_area(None, np.array([[0, 0, 9, 9]])) == [0.0]


EDGY = [
    [(0, 0), (3, 0), (3, 2), (2, 2), (2, 1), (1, 1), (1, 2), (0, 2)],  # U
    [(1, 1), (2, 1), (2, 2), (1, 2)],  # a square off the origin
    [(0, 0), (4, 0), (4, 1), (1, 1), (1, 3), (4, 3), (4, 4), (0, 4)],  # C
    [(0, 0), (2, 0), (2, 1), (3, 1), (3, 2), (1, 2), (1, 3), (0, 3)],  # stairs
    [(0, 0), (1, 0), (2, 0), (2, 2), (0, 2)],  # collinear corners
]


@pytest.mark.parametrize("poly", EDGY, ids=["U", "square", "C", "stairs", "collinear"])
def test_rectangles_with_sides_on_the_outline_edges(poly):
    """Sides lying exactly on the polygon's edges (a source flush against a notch's wall)
    were counted twice on the rectangle's left side: a legal source came out wholly
    outside and one in the notch wholly inside."""
    outline = check_outline(poly, "edgy")
    shape = Polygon(outline)
    xs = sorted({p[0] for p in poly} | {0.5, 1.5, 2.5})
    ys = sorted({p[1] for p in poly} | {0.5, 1.5})
    rects = np.array(
        [(a, b, c, d) for a, c in combinations(xs, 2) for b, d in combinations(ys, 2)], float
    )
    want = [shape.intersection(box(*r)).area for r in rects]
    np.testing.assert_allclose(inside_area(outline, rects), want, atol=1e-12)
    assert is_inside(outline, inner_square(outline, 1.0))


def test_check_outline_orients_and_rejects():
    clockwise = L_LOCAL[::-1]
    got = check_outline(np.vstack([clockwise, clockwise[:1]]), "Z")  # closed: last dropped
    assert len(got) == 6 and Polygon(got).exterior.is_ccw
    cases = [
        ([[0, 0], [1, 0]], "at least 3 distinct corners"),
        ([[0, 0], [1, 0], [1, 0.0001]], "at least 3 distinct corners"),
        ([[0, 0], [1, 1], [1, 0], [0, 1]], r"crosses itself \(edges 1 and 3\)"),
        ([[0, 0], [1, 0], [2, 0]], "encloses no area"),
        ([[0, 0], [1, np.nan], [0, 1]], r"list of \[u, v\] corners"),
        ("abc", r"list of \[u, v\] corners"),
    ]
    for value, message in cases:
        with pytest.raises(SceneError, match=message):
            check_outline(value, "Z")


def test_a_polygon_zone_on_the_office_ceiling():
    edit = ZoneEdit("ZL", "skylight", "ceiling", outline=L_OUTLINE)
    assert edit.rect == (3.5, 0.5, 8.5, 2.5)
    assert ZoneEdit("ZL", "skylight", "ceiling", (8.5, 2.5, 3.5, 0.5), L_OUTLINE) == edit
    with pytest.raises(SceneError, match=r"rect \(3.5, 0.5, 8.5, 3\) is not the bounding"):
        ZoneEdit("ZL", "skylight", "ceiling", (3.5, 0.5, 8.5, 3), L_OUTLINE)
    base = office(0.5)
    scene = apply_zone_edits(base, [edit])
    zone = scene.zone("ZL")
    assert np.allclose(zone.outline, L_LOCAL)
    assert scene.zone_rect("ZL").size == pytest.approx((5.0, 2.0))
    assert scene.area == pytest.approx(base.area)  # the bounding rectangle is cut, as ever
    patches = mesh_patches(scene)
    assert np.allclose(patches.zone_outline("ZL"), L_LOCAL)
    assert patches.zone_outline("skylight") is None
    # An outline running off its rectangle is refused by the scene.
    with pytest.raises(SceneError, match="its outline runs outside its surface 'ZL'"):
        Scene(
            scene.name,
            scene.surfaces,
            (*scene.zones[:-1], EmitterZone("ZL", "skylight", "ZL", L_LOCAL + 0.5)),
            scene.resolution,
        )


def _l_project(**optimizer) -> dict:
    with open("resources/projects/office-demo.json", encoding="utf-8") as f:
        d = json.load(f)
    d["scene"]["zones"] = [
        {"name": "ZL", "kind": "skylight", "surface": "ceiling", "outline": L_OUTLINE}
    ]
    d["sources"].append(
        {
            "name": "S2",
            "zone": "ZL",
            "kind": "skylight",
            "rect": [0.2, 0.2, 1, 0.8],
            "free": ["u0", "v0", "u1", "v1"],
            "filter": 0.5,
        }
    )
    d["optimizer"].update(optimizer)
    return d


def test_polygon_zones_in_project_files_round_trip():
    d = _l_project()
    project = project_from_dict(copy.deepcopy(d))
    written = project_dict(project, None)["scene"]["zones"][0]
    assert written["outline"] == [list(p) for p in L_OUTLINE]
    assert written["rect"] == [3.5, 0.5, 8.5, 2.5]
    assert project_from_dict(json.loads(json.dumps(project_dict(project, None)))) == project
    # A rectangle zone writes no outline (older files stay as they were).
    d["scene"]["zones"][0] = {"name": "ZL", "kind": "skylight", "surface": "ceiling"}
    d["scene"]["zones"][0]["rect"] = [3.5, 0.5, 8.5, 2.5]
    assert "outline" not in project_dict(project_from_dict(d), None)["scene"]["zones"][0]


def test_rules_reject_sources_outside_the_outline():
    d = _l_project()
    project = project_from_dict(d)
    prepared = study.prepare(project)
    problem = study.DesignProblem(project.design, prepared.light)
    design = project.design
    names = [s.name for s in design.sources]
    i = names.index("S2")
    rect = np.array([[s.rect for s in design.sources]] * 3, dtype=float)
    rect[0, i] = (0.0, 0.0, 5.0, 1.0)  # the L's long arm: inside
    rect[1, i] = (0.0, 0.0, 1.5, 2.0)  # the short arm: inside
    rect[2, i] = (1.0, 0.5, 2.5, 1.5)  # 1.5 m², of which 1.0 x 0.5 m in the notch
    geo = rule_violations(design, rect, problem.zone_size, outlines=problem.outlines)
    assert geo[0, 0] == 0 and geo[1, 0] == 0
    assert geo[2, 0] == pytest.approx(0.5 / 1.5, abs=1e-8)  # the share outside
    # Without the outline the same rectangle is fine: the check is the outline's.
    assert rule_violations(design, rect, problem.zone_size)[2, 0] == 0


def test_the_optimiser_keeps_sources_inside_an_l_shaped_zone():
    project = project_from_dict(_l_project(max_evals=2500, stall=1500))
    prepared = study.prepare(project)
    shape = Polygon(L_LOCAL)
    for seed in (0, 1):
        r = study.solve(project, prepared, seed=seed)
        assert r.status == "feasible"
        u0, v0, u1, v1 = next(s for s in r.best.sources if s.name == "S2").rect
        b = box(min(u0, u1), min(v0, v1), max(u0, u1), max(v0, v1))
        assert b.area - shape.intersection(b).area <= 1e-9 * b.area
        assert not r.best.violations


def test_editing_places_and_drags_sources_inside_the_outline():
    outline = check_outline(L_LOCAL, "L")
    square = inner_square(outline, 1.0)
    assert is_inside(outline, square) and square[2] - square[0] == pytest.approx(1.0)
    thin = check_outline([(0, 0), (4, 0), (4, 0.3), (0, 0.3)], "thin")
    small = inner_square(thin, 1.0)
    assert is_inside(thin, small) and 0.15 < small[2] - small[0] <= 0.3
    # A drag towards the notch stops at its edge; back out, it moves freely.
    start = (0.2, 0.2, 1.2, 1.2)
    stopped = kept_inside(outline, start, (3.2, 0.7, 4.2, 1.7))
    assert is_inside(outline, stopped)
    assert stopped[3] == pytest.approx(1.5, abs=1e-9) or stopped[2] == pytest.approx(1.5)
    assert kept_inside(outline, start, (0.4, 0.4, 1.4, 1.4)) == (0.4, 0.4, 1.4, 1.4)
    outside = (2.0, 1.2, 3.0, 1.8)
    assert kept_inside(outline, outside, (2.5, 1.2, 3.5, 1.8)) == (2.5, 1.2, 3.5, 1.8)
    project = project_from_dict(_l_project())
    src = rules.new_source(project.design, "ZL", "skylight", (5.0, 2.0), outline=outline)
    assert is_inside(outline, src.rect)
    moved = rules.moved_rect(src, 10.0, 10.0, (5.0, 2.0), outline)
    assert is_inside(outline, moved)


def test_array_luminaires_must_fit_the_outline():
    d = _l_project()
    d["scene"]["zones"][0]["kind"] = "luminaire"
    d["sources"] = d["sources"][:2]
    d["rules"] = [r for r in d["rules"] if r["kind"] == "mirror"]
    d["arrays"] = [
        {
            "name": "A1",
            "zone": "ZL",
            "product": "Downlight 2000 lm 20 W",
            "rect": [0, 0, 5, 1],
            "rows": 1,
            "columns": 4,
        }
    ]
    project = project_from_dict(d)
    prepared = study.prepare(project)
    problem = study.DesignProblem(project.design, prepared.light)
    shapes = problem.array_shapes
    assert shapes.outline[0] is not None
    good = array_layout(project.design.arrays)
    assert array_violations(project.design, good, shapes)[0, 0] == 0
    # Two rows over the whole rectangle: the second row's right luminaires are in the notch.
    a = project.design.arrays[0]
    bad = array_layout((type(a)(**{**a.__dict__, "rect": (0, 0, 5, 2), "rows": 2}),))
    assert array_violations(project.design, bad, shapes)[0, 0] > 1.0


def test_a_source_that_cannot_fit_the_polygon_says_why():
    from lightinv_core.errors import DesignError
    from lightinv_core.optimize.search import random_start

    d = _l_project()
    # Centred on the bounding rectangle's centre (2.5, 1), on the notch's edge: any
    # rectangle there reaches into the notch.
    d["rules"].append({"kind": "centred", "sources": ["S2"]})
    project = project_from_dict(d)
    problem = study.DesignProblem(project.design, study.prepare(project).light)
    with pytest.raises(DesignError, match="inside their zone's polygon outline"):
        random_start(problem, np.random.default_rng(0))
