"""UGR as a design limit: observers in the design, the glare rating of many candidate
layouts at once (``light/glare.py``), the optimiser meeting a UGR bound.

Checked against: ``luminaires/ugr.py`` (CIE 117 per luminaire, the luminaires placed
one by one) for the batched glare sums; a hand-computed Lambertian panel and zone
luminaire (L = I0 / A, omega = A cos / d², p from CIE 117's Table 4.1); the reference
radiosity solver (dense solve, the luminaires placed exactly, the eye's own form factors
traced with 8 times the rays and another seed) for the background.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from lightinv_core.cli.solve_text import solve_text
from lightinv_core.design.model import (
    Design,
    DesignError,
    Goal,
    Intention,
    LuminaireArray,
    Observer,
    Rule,
    Source,
    Workplane,
)
from lightinv_core.design.variables import ArrayLayout
from lightinv_core.light.arrays import (
    array_luminaires,
    caster_for,
    form_factors,
    resolve_product,
    zone_frame,
)
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.glare import (
    array_glare_sums,
    layout_glare,
    observer_eyes,
)
from lightinv_core.light.model import LightModel
from lightinv_core.luminaires.ugr import glare_terms, ugr
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.method import RunContext
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.registry import get_method
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.optimize.termination import StopRule
from lightinv_core.project import project_from_dict, project_to_dict
from lightinv_core.quantities import quantity_spec
from lightinv_core.report.criteria import status_table
from lightinv_core.report.tables import PASS
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.receivers import receiver_factors
from lightinv_core.transport.scene_light import light_scene

ROOT = Path(__file__).resolve().parents[2]
BATWING = "Linear batwing 4000 lm 32 W"
PANEL = "Panel 600 x 600 3600 lm 30 W"
OBSERVERS = (Observer("south", (6.0, 0.6), azimuth=90), Observer("west", (0.6, 4.0), azimuth=0))


@pytest.fixture(scope="module")
def office():
    scene = builtin_scene("office", 1.0)
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=256)))


def _design(limit: float = 40.0) -> Design:
    """Batwing strips in the two ceiling zones (rows, columns and dimming free), EN
    12464-1 filing on the work plane, UGR <= ``limit`` at two observers."""
    kw = dict(free=("rows", "columns", "dimming"), rows_range=(1, 6), columns_range=(1, 3))
    arrays = tuple(
        LuminaireArray(n, z, BATWING, (0, 0, 2, 6), rows=3, columns=1, rotation=90, **kw)
        for n, z in (("west", "lum_west"), ("east", "lum_east"))
    )
    return Design(
        sources=(),
        goals=(Goal("min_electric_power"),),
        arrays=arrays,
        workplanes=(Workplane("wp", 0.8, 0.5),),
        rules=(
            Rule("shr", ("west", "east"), max=1.5),
            Rule("clearance", ("west", "east"), min=0.1),
        ),
        intentions=(
            Intention("filing", grid="wp", average=300.0, uniformity=0.4),
            Intention("glare", observers=("south", "west"), quantity="ugr", max=limit),
        ),
        observers=OBSERVERS,
    )


@pytest.fixture(scope="module")
def problem(office):
    return DesignProblem(_design(), office)


# -- observers in the design and the project file ---------------------------------------------


def test_observers_and_ugr_intentions_are_checked_with_clear_errors():
    with pytest.raises(DesignError, match="azimuth or a direction"):
        Observer("a", (1, 1))
    with pytest.raises(DesignError, match=r"\[0, 0, 0\] has no direction"):
        Observer("a", (1, 1), direction=(0, 0, 0))
    with pytest.raises(DesignError, match="vertical"):
        Observer("a", (1, 1), direction=(0, 0, -1))
    assert np.allclose(Observer("a", (1, 1), azimuth=90).view, (0, 1, 0), atol=1e-12)
    assert Observer("a", (1, 1), azimuth=0).height == 1.2  # seated
    with pytest.raises(DesignError, match="give max only"):
        Intention("g", observers=("a",), quantity="ugr", average=19)
    with pytest.raises(DesignError, match="measured at observers"):
        Intention("g", group="floor", quantity="ugr", max=19)
    with pytest.raises(DesignError, match="observers take quantity 'ugr'"):
        Intention("g", observers=("a",), quantity="lux", max=19)
    with pytest.raises(DesignError, match="no observer 'north'"):
        replace(
            _design(), intentions=(Intention("g", observers=("north",), quantity="ugr", max=19),)
        )
    with pytest.raises(DesignError, match="observer names must be unique"):
        replace(_design(), observers=OBSERVERS + OBSERVERS[:1])


def test_an_observer_outside_the_room_is_refused(office):
    patches = office.patches
    with pytest.raises(DesignError, match=r"\(20, 4\) is outside the room"):
        observer_eyes(patches, (Observer("out", (20, 4), azimuth=0),))
    with pytest.raises(DesignError, match="above the room"):
        observer_eyes(patches, (Observer("high", (6, 4), height=5, azimuth=0),))
    with pytest.raises(DesignError, match="outside the room"):
        DesignProblem(
            replace(_design(), observers=(OBSERVERS[0], replace(OBSERVERS[1], position=(-1, 4)))),
            office,
        )
    eyes = observer_eyes(patches, OBSERVERS)
    assert np.allclose(eyes.points, [(6.0, 0.6, 1.2), (0.6, 4.0, 1.2)])


def test_projects_round_trip_observers_and_ugr_intentions():
    data = json.loads((ROOT / "resources/projects/office-arrays.json").read_text())
    data["observers"] = [
        {"name": "desk", "position": [6, 0.6], "azimuth": 90},
        {"name": "door", "position": [0.6, 4], "height": 1.7, "direction": [1, 0.2, 0]},
    ]
    data["intentions"].append(
        {"name": "glare", "observers": ["desk", "door"], "quantity": "ugr", "max": 19}
    )
    p = project_from_dict(data)
    assert [o.name for o in p.design.observers] == ["desk", "door"]
    assert p.design.observers[1].height == 1.7
    again = project_to_dict(p)
    assert again["observers"][0] == {
        "name": "desk",
        "position": [6.0, 0.6],
        "height": 1.2,
        "azimuth": 90.0,
        "group": "floor",
    }
    assert project_from_dict(again).design == p.design
    data["observers"][0]["position"] = [6]
    with pytest.raises(Exception, match=r"observers\[0\]\.position"):
        project_from_dict(data)


# -- the batched glare sums against CIE 117 luminaire by luminaire -----------------------------


def _placed(problem, x):
    return [p for _, _, ps in array_luminaires(problem.patches, problem.arrays_at(x)) for p in ps]


def test_in_loop_ugr_equals_the_cie117_function_luminaire_by_luminaire(problem):
    rng = np.random.default_rng(3)
    lo, hi = problem.vars.lo, problem.vars.hi
    X = lo + rng.random((8, len(lo))) * (hi - lo)
    lay = problem.layout_of(X)
    total, lb = problem.glare.sums(problem.arrays, lay)
    eyes = problem.glare.eyes
    spec = quantity_spec("ugr")
    checked = 0
    for c, x in enumerate(X):
        placed = _placed(problem, x)
        for i in range(2):
            ref = glare_terms(eyes.points[i], eyes.views[i], placed).total
            assert total[i, c] == pytest.approx(ref, rel=1e-9, abs=1e-12)
            if ref > 0:
                want = ugr(eyes.points[i], eyes.views[i], placed, lb[i, c])
                assert abs(float(spec.from_glare(total[i, c], lb[i, c])) - want) < 1e-6
                checked += 1
    assert checked >= 8
    # The background from the search's own (maintained) lattice weights, rescaled per
    # node to the light as new, equals the one from unmaintained weights.
    _, lb2 = problem.glare.sums(problem.arrays, lay, problem.arrays.weights(lay))
    assert np.allclose(lb2, lb, rtol=1e-6)
    # Rotated a quarter turn (C0 along the zone's u axis): the same agreement.
    turned = replace(lay, rotation=np.zeros_like(lay.rotation))
    t2 = array_glare_sums(problem.arrays, turned, eyes)
    arr = [replace(a, rotation=0) for a in problem.arrays_at(X[0])]
    placed = [p for _, _, ps in array_luminaires(problem.patches, arr) for p in ps]
    for i in range(2):
        ref = glare_terms(eyes.points[i], eyes.views[i], placed).total
        assert t2[i, 0] == pytest.approx(ref, rel=1e-9)
    assert not np.allclose(t2[:, 0], total[:, 0])


def test_a_hand_computed_panel_and_zone_luminaire(office):
    patches = office.patches
    # The west zone's centre is (2, 4, 3); the panel's photometric centre 2 cm below.
    # An eye 1.78 m below it and 3.56 m before it: H/R = 0.5, T/R = 0 (Table 4.1: 2.86).
    ob = Observer("eye", (2.0, 4.0 - 3.56), azimuth=90)
    eyes = observer_eyes(patches, (ob,))
    prod = resolve_product(PANEL)
    lum = SimpleNamespace(products=[prod], frames=[zone_frame(patches, "lum_west")])
    lay = ArrayLayout(
        np.array([[[0.0, 0.0, 2.0, 6.0]]]),
        np.array([[1]]),
        np.array([[1]]),
        np.array([[0]]),
        np.array([[1.0]]),
    )
    got = array_glare_sums(lum, lay, eyes)[0, 0]
    H, R = 1.78, 3.56
    d = math.hypot(H, R)
    area = 0.6 * 0.6
    L = (3600.0 / math.pi) / area  # Lambertian: I0 = flux / pi, L = I0 / A at every angle
    omega = area * (H / d) / d**2
    hand = L**2 * omega / 2.86**2
    assert got == pytest.approx(hand, rel=0.005)
    assert 8 * math.log10(0.25 / 20 * got) == pytest.approx(
        8 * math.log10(0.25 / 20 * hand), abs=0.02
    )
    # Zone luminaires (no photometry) are refused, not rated from their patches.
    src = Source("z", "lum_west", "luminaire", rect=(0.75, 2.75, 1.25, 3.25), flux=2000.0)
    with pytest.raises(DesignError, match=r"zone luminaires \['z'\] have no photometry"):
        DesignProblem(replace(_design(), sources=(src,)), office)


def test_background_matches_the_reference_solver_at_the_eye(problem, office):
    patches = office.patches
    x = problem.vars.initial()
    lay = problem.layout_of(x[None])
    _, lb = problem.glare.sums(problem.arrays, lay)
    # Reference: dense radiosity, luminaires placed exactly as new (no maintenance
    # factor), its reflected exitance seen from the eye through 8x the rays, another seed.
    caster = caster_for(patches)
    lums = _placed(problem, x)
    sl = light_scene(patches, form_factors(patches, office.op), caster, np.zeros(patches.n), lums)
    eyes = problem.glare.eyes
    R = receiver_factors(eyes.points, eyes.views, caster, patches.n, 8192, seed=123)
    ref = R @ sl.B
    assert np.all(ref > 20)
    assert np.allclose(lb[:, 0] * math.pi, ref, rtol=0.03), (lb[:, 0] * math.pi, ref)
    # The one-layout path (report, window): luminaires placed exactly, same agreement.
    exact = layout_glare(office, problem.design, (), problem.arrays_at(x))
    for i, name in enumerate(eyes.names):
        want = 8 * math.log10(
            0.25 * glare_terms(eyes.points[i], eyes.views[i], lums).total / (ref[i] / math.pi)
        )
        assert exact[name] == pytest.approx(want, abs=0.15)


# -- the optimiser meets the bound ------------------------------------------------------------


@pytest.mark.slow
def test_the_optimiser_meets_a_ugr_bound_the_unbounded_optimum_breaks(problem, office):
    def run(pb):
        ctx = RunContext(OptimizerSettings(seed=0), StopRule(3000), seed=0)
        return get_method("auto").run(pb, ctx).best

    free = run(problem)  # UGR <= 40: never binding
    assert free.feasible, free.violations
    free_ugr = layout_glare(office, problem.design, (), free.arrays)
    assert max(free_ugr.values()) > 19.0, free_ugr
    bounded_pb = DesignProblem(_design(19.0), office)
    bounded = run(bounded_pb)
    assert bounded.feasible, bounded.violations
    got = layout_glare(office, bounded_pb.design, (), bounded.arrays)
    assert max(got.values()) <= 19.0 * 1.001, got
    # The report's criteria: one row per observer, each with the bound and pass.
    light = layout_daylight(office, bounded_pb.design, (), bounded.arrays)
    values, _ = light.quantity(bounded_pb.design.intentions[1])
    assert np.allclose(values, [got["south"], got["west"]])
    assert bounded.objectives["min_electric_power"] >= free.objectives["min_electric_power"] - 1.0
    table = status_table(bounded_pb.design, bounded, light, None)
    rows = {r[0]: r for r in table.rows if r[1] == "UGR (CIE 117)"}
    assert set(rows) == {"observer south (glare)", "observer west (glare)"}
    for name in ("south", "west"):
        row = rows[f"observer {name} (glare)"]
        assert row[2:] == ("≤ 19", f"{got[name]:.1f}", PASS)


def test_the_cli_text_prints_ugr_at_each_observer():
    out = {
        "project": "p",
        "status": "feasible",
        "method": "auto",
        "evaluations": 10,
        "seconds": 1.0,
        "precompute_seconds": 0.1,
        "ugr": {"desk": 18.94, "door": 12.0},
    }
    assert "  glare: UGR 18.9 at desk, 12.0 at door (CIE 117;" in solve_text(out)


def test_a_ugr_violation_is_named_with_its_value(problem, office):
    d = _design(10.0)
    pb = DesignProblem(d, office)
    sol = pb.solution(pb.vars.initial())
    v = [v for v in sol.violations if v.name == "glare"]
    assert len(v) == 1 and v[0].constraint == "max" and v[0].bound == 10.0
    exact = layout_glare(office, d, (), pb.arrays_at(pb.vars.initial()))
    # Judged with the luminaires placed exactly; the background from the lattice blend.
    assert v[0].value == pytest.approx(max(exact.values()), abs=0.02)


def test_the_editing_model_adds_and_removes_observers_with_their_limit():
    from lightinv_core.editing.document import DocumentModel

    doc = DocumentModel()
    doc.set_project(
        project_from_dict(json.loads((ROOT / "resources/projects/office-arrays.json").read_text()))
    )
    limit = Intention("glare desk", observers=("desk",), quantity="ugr", max=19.0)
    doc.add_observer(Observer("desk", (6.0, 0.6), azimuth=90), limit)
    doc.add_observer(Observer("door", (0.6, 4.0), azimuth=0))
    doc.replace_intention("glare desk", replace(limit, observers=("desk", "door")))
    assert [o.name for o in doc.design.observers] == ["desk", "door"]
    with pytest.raises(DesignError, match="observer names must be unique"):
        doc.add_observer(Observer("desk", (1.0, 1.0), azimuth=0))
    doc.remove_observer("desk")  # the limit keeps the other eye
    assert doc.design.intentions[-1].observers == ("door",)
    doc.remove_observer("door")  # and goes with the last
    assert not doc.design.observers and all(i.observers is None for i in doc.design.intentions)
