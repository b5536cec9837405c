"""Design model, geometric rules, emission, penalty and goals of the inverse problem."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.design.geometry import rule_names, rule_violations
from lightinv_core.design.model import (
    CORNERS,
    Daylight,
    Design,
    DesignError,
    Goal,
    Intention,
    Rule,
    Source,
)
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.problem import FEASIBILITY_TOL, DesignProblem
from lightinv_core.project.source_kinds import check_source_kinds
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches


@pytest.fixture(scope="module")
def office():
    scene = builtin_scene("office", 0.5)
    patches = mesh_patches(scene)
    return scene, patches, build_operator(patches, OperatorSettings(rank=150, rays=256))


def sky(name="s", rect=(0.5, 0.5, 2.0, 1.5), free=CORNERS, **kw):
    return Source(name, "skylight", "skylight", rect, free=free, **kw)


def lum(name="L", zone="lum_west", rect=(0.5, 1.0, 1.5, 3.0), free=CORNERS, **kw):
    kw.setdefault("flux", 3000.0)
    return Source(name, zone, "luminaire", rect, free=free, **kw)


def problem(office, sources, rules=(), intentions=(), goals=None, **kw):
    scene, patches, op = office
    goals = goals or (Goal("max_light_power"),)
    design = Design(tuple(sources), goals, tuple(rules), tuple(intentions), **kw)
    return DesignProblem(design, LightModel(scene, patches, op))


def _emission(p, rect, flux, filt, **kw):
    return p.light.zone_emission(p.design.sources, rect, flux, filt, p.design.daylight, **kw)


def _viol(design, rects, zone_size):
    return rule_violations(design, np.asarray(rects, float)[None], np.asarray(zone_size, float))[0]


def test_area_and_aspect_rules():
    d = Design(
        (sky(),),
        (Goal("max_light_power"),),
        (Rule("area", ("s",), min=1.0, max=2.0), Rule("aspect", ("s",), max=2.0)),
    )
    zone = [[4.0, 2.0]]
    assert np.all(_viol(d, [[0, 0, 1.2, 1.2]], zone) == 0)  # 1.44 m², aspect 1
    v = _viol(d, [[0, 0, 0.5, 0.5]], zone)  # 0.25 m² < 1
    assert v[1] == pytest.approx(0.75) and v[2] == 0
    v = _viol(d, [[0, 0, 3.0, 1.0]], zone)  # 3 m² > 2, aspect 3 > 2
    assert v[1] == pytest.approx(0.5) and v[2] == pytest.approx(0.5)
    assert rule_names(d) == ["inside zone and non-degenerate", "area s", "aspect s"]


def test_inside_zone_and_degenerate_sources_are_rejected():
    d = Design((sky(),), (Goal("max_light_power"),))
    zone = [[4.0, 2.0]]
    assert _viol(d, [[3.0, 0.0, 4.5, 1.0]], zone)[0] > 0  # sticks out along u
    assert _viol(d, [[1.0, 1.0, 1.0, 1.5]], zone)[0] > 0  # zero width
    assert _viol(d, [[3.9, 1.9, 0.1, 0.1]], zone)[0] == 0  # corners in any order


def test_spacing_and_alignment_rules():
    a, b = sky("a"), sky("b")
    d = Design(
        (a, b),
        (Goal("max_light_power"),),
        (Rule("spacing", ("a", "b"), min=1.0), Rule("align", ("a", "b"), axis="u")),
    )
    zone = [[12.0, 4.0], [12.0, 4.0]]
    ok = _viol(d, [[0, 1, 1, 2], [3, 1, 4, 2]], zone)  # gap 2 m along u, same v centre
    assert np.all(ok == 0)
    close = _viol(d, [[0, 1, 1, 2], [1.5, 1, 2.5, 2]], zone)  # gap 0.5 m
    assert close[1] == pytest.approx(0.5) and close[2] == 0
    diagonal = _viol(d, [[0, 0, 1, 1], [1.6, 1.8, 2, 2]], zone)  # gap hypot(0.6, 0.8) = 1
    assert diagonal[1] == pytest.approx(0.0, abs=1e-12)
    misaligned = _viol(d, [[0, 1, 1, 2], [3, 1.5, 4, 2.5]], zone)
    assert misaligned[2] > 0


def test_mirror_and_centred_rules_tie_the_variables(office):
    rules = (Rule("mirror", ("east", "west"), axis="u"), Rule("centred", ("mid",)))
    sources = (
        lum("west", "lum_west", (0.2, 1.0, 1.0, 3.0)),
        lum("east", "lum_east", (0.0, 0.0, 1.0, 1.0)),
        sky("mid", (0.5, 0.5, 1.0, 1.0), free=("u0", "v0")),
    )
    p = problem(office, sources, rules)
    names = [(p.design.sources[v.source].name, v.name) for v in p.vars.vars]
    assert ("east", "u0") not in names and ("mid", "u1") not in names
    assert [v.hi for v in p.vars.vars if v.source == 2] == [2.0, 1.0]  # half the 4 x 2 zone
    rect, _, _ = p.vars.decode(p.vars.initial()[None])
    np.testing.assert_allclose(rect[0, 1], [2.0 - 0.2, 1.0, 2.0 - 1.0, 3.0])  # flipped in u
    np.testing.assert_allclose(rect[0, 2], [0.5, 0.5, 3.5, 1.5])  # centred in 4 x 2


def test_emission_conserves_flux_and_daylight(office):
    _scene, patches, op = office
    p = problem(office, (lum(), sky(filter=0.5)))
    rect, flux, filt = p.vars.decode(p.vars.initial()[None])
    V, by_kind = _emission(p, rect, flux, filt, split_kinds=True)
    area = patches.area[op.zone_patches]
    assert float(area @ by_kind["luminaire"][:, 0]) == pytest.approx(3000.0, rel=1e-5)
    expected_sky = 0.5 * 0.6 * 10000 * 1.5 * 1.0  # f * tau * exterior * area
    assert float(area @ by_kind["skylight"][:, 0]) == pytest.approx(expected_sky, rel=1e-5)
    np.testing.assert_allclose(V, by_kind["luminaire"] + by_kind["skylight"])


def test_goals_match_direct_computation(office):
    _scene, patches, op = office
    p = problem(
        office,
        (lum(efficacy=120.0), sky()),
        goals=(Goal("max_light_power"), Goal("min_electric_power")),
    )
    x = p.vars.initial()
    ev = p.evaluate(x[None])
    rect, flux, filt = p.vars.decode(x[None])
    V = _emission(p, rect, flux, filt)
    C = patches.rho * (op.Phi @ V[:, 0])
    assert ev.goals["max_light_power"][0] == pytest.approx(float(C @ patches.area), rel=1e-4)
    assert ev.goals["min_electric_power"][0] == pytest.approx(3000.0 / 120.0)
    assert ev.penalty[0] == 0.0
    assert ev.value[0] == pytest.approx(-ev.goals["max_light_power"][0] / p.scales[p.primary])


def test_penalty_follows_equation_3(office):
    _scene, patches, op = office
    desks = patches.group_index("desks")
    it = Intention("desks", group="desks", min=5000.0, average=6000.0, uniformity=0.9, weight=7.0)
    p = problem(office, (lum(),), intentions=(it,))
    x = p.vars.initial()
    rect, flux, filt = p.vars.decode(x[None])
    H = (op.Phi @ _emission(p, rect, flux, filt)[:, 0])[desks]
    a = patches.area[desks]
    avg = float(H @ a / a.sum())
    cs = [(5000 - H.min()) / 5000, (6000 - avg) / 6000, (0.9 - H.min() / avg) / 0.9]
    expected = sum(7.0 * max(0.0, c - FEASIBILITY_TOL) ** 2 for c in cs)
    ev = p.evaluate(x[None])
    assert ev.penalty[0] == pytest.approx(expected, rel=1e-4)
    sol = p.solution(x)
    assert not sol.feasible
    assert {(v.name, v.constraint) for v in sol.violations} == {
        ("desks", "min"),
        ("desks", "average"),
        ("desks", "uniformity"),
    }
    viol = {v.constraint: v for v in sol.violations}
    assert viol["average"].value == pytest.approx(avg, rel=1e-4)
    assert viol["min"].units == "lux" and viol["uniformity"].units == ""


def test_upper_bound_on_reflected_exitance(office):
    _scene, _patches, _op = office
    it = Intention("walls", group="walls", quantity="C", max=1.0)
    p = problem(office, (lum(),), intentions=(it,))
    sol = p.solution(p.vars.initial())
    (v,) = sol.violations
    assert v.constraint == "max" and v.units == "lm/m²" and v.value > 1.0
    assert v.amount == pytest.approx(v.value - 1.0, rel=1e-6)


def test_geometric_violations_skip_the_radiosity(office):
    p = problem(office, (sky(),), rules=(Rule("area", ("s",), max=1.0),))
    X = np.array([[0.5, 0.5, 1.0, 1.0], [0.0, 0.0, 3.0, 2.0]])  # 0.25 m² ok, 6 m² too big
    ev = p.evaluate(X)
    assert ev.ok.tolist() == [True, False] and ev.evaluated == 1
    assert np.isinf(ev.value[1])
    sol = p.solution(X[1])
    assert sol.violations[0].constraint == "geometry" and sol.violations[0].name == "area s"


def test_invalid_designs_are_refused_clearly(office):
    with pytest.raises(DesignError, match=r"min 3\.0 is larger than max 1\.0"):
        Rule("area", ("s",), min=3, max=1)
    with pytest.raises(DesignError, match=r"min 600\.0 is above max 500\.0"):
        Intention("x", group="desks", min=600, max=500)
    with pytest.raises(DesignError, match="unknown sources"):
        Design((sky(),), (Goal("max_light_power"),), (Rule("aspect", ("nope",), max=2),))
    with pytest.raises(DesignError, match="target_sources"):
        Design((sky(),), (Goal("match"),))
    with pytest.raises(DesignError, match="luminaire needs either flux or exitance"):
        kinds_of(Source("L", "lum_west", "luminaire", (0, 0, 1, 1)))
    with pytest.raises(DesignError, match="filter"):
        sky(filter=1.5)
    with pytest.raises(DesignError, match="takes skylights"):
        problem(office, (Source("L", "skylight", "luminaire", (0, 0, 1, 1), flux=10.0),))
    with pytest.raises(DesignError, match="no emitter zone 'roof'"):
        problem(office, (Source("s", "roof", "skylight", (0, 0, 1, 1)),))
    with pytest.raises(DesignError, match="intention 't': no group 'tables'"):
        problem(office, (sky(),), intentions=(Intention("t", group="tables", min=1),))


def kinds_of(source: Source) -> None:
    """Check ``source`` against its kind (the source type's own fields)."""
    check_source_kinds(Design((source,), (Goal("max_light_power"),)))


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (
            lambda: Intention("x", patches=[1.5], min=1),
            r"intention 'x': patches\[0\] must be an integer >= 0, got number 1\.5",
        ),
        (lambda: Intention("x", patches=["3"], min=1), "must be an integer >= 0, got string"),
        (lambda: Intention("x", patches=[True], min=1), "must be an integer >= 0, got true"),
        (
            lambda: Rule("area", "S1", max=1),
            "rule 'area': sources must be a list of source names, got string 'S1'",
        ),
        (lambda: Rule("spacing", ("a", "a"), min=1), r"sources\[1\]: 'a' is listed twice"),
        (
            lambda: Goal("max_light_power", ("skylights",)),
            r"kinds\[0\] must be one of 'luminaire', 'skylight', 'window', got string 'skylights'",
        ),
        (lambda: Goal("match", ("skylight",)), "only a max_light_power goal takes source kinds"),
        (lambda: Rule("mirror", ("a", "b"), axis="u", min=1.0), "mirror rules do not take 'min'"),
        (lambda: Daylight(exterior_lux=-1.0), "exterior_lux"),
        (lambda: Daylight(transmittance=1.5), "transmittance"),
        (lambda: lum(exitance=10.0), "not both"),
        (lambda: kinds_of(sky(exitance=10.0)), "exitance: only luminaires have this"),
        (lambda: kinds_of(lum(free=("filter",))), "a luminaire has no filter variable"),
        (lambda: lum(flux=float("nan")), "finite"),
        (lambda: lum(flux_range=(0, 1, 2)), "flux_range must be 2 numbers, got 3"),
        (
            lambda: Design((sky(), sky("t")), (Goal("max_light_power"), Goal("max_light_power"))),
            "goal names must be unique",
        ),
    ],
)
def test_model_values_are_validated(build, message):
    with pytest.raises(DesignError, match=message):
        build()


def test_reported_corners_run_low_to_high():
    """An optimiser (or a mirror) may swap a rectangle's corners; solutions report them
    low to high, the same rectangle."""
    from lightinv_core.design.model import CORNERS, Design, Goal, Source
    from lightinv_core.design.variables import Variables

    src = Source("L", "z", "luminaire", (0.5, 0.5, 1.0, 1.0), free=CORNERS, flux=1000.0)
    design = Design((src,), (Goal("min_electric_power"),))
    v = Variables(design, {"z": (4.0, 3.0)})
    (s,) = v.sources_at(np.array([2.0, 1.5, 0.5, 0.25]))
    assert s.rect == (0.5, 0.25, 2.0, 1.5) and s.flux == 1000.0
