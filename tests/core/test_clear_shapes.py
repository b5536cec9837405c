"""Clear glazing whose shape the optimiser chooses (issue #30, docs/daylight.md "Clear
shapes in the optimiser"): the light traced per zone cell and summed per candidate
(``light.clear_cells``, ``light.clear_batch``) against fresh fixed builds of the same
rectangle (``light.clear_build``, the forward way), a batch against its candidates one
by one, every daylight figure of a moving candidate against the layout's own, an
optimisation choosing a clear rooflight's size for sDA and ASE checked by the forward
study of the chosen room, and ``lightinv-cli solve`` on such a project."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.design.model import (
    Daylight,
    Design,
    DesignError,
    Goal,
    Intention,
    Observer,
    Rule,
    Source,
    Workplane,
)
from lightinv_core.light.clear_cells import clear_cells
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.method import RunContext
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.registry import get_method
from lightinv_core.optimize.termination import StopRule
from lightinv_core.quantities import quantity_spec
from lightinv_core.scene.builders import Insert, room_faces, split_rect
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import SimulationSpec, simulate
from lightinv_core.study.clear_metrics import work_plane_metrics
from lightinv_core.transport.workplane import WorkPlane

TAU = 0.7
ZONE = (2.5, 2.5, 5.5, 5.5)  # the rooflight zone in the ceiling, 3 x 3 m


def roof_room(rooflight=ZONE) -> Scene:
    """A room 8 x 8 x 3 m with a rooflight zone ``rooflight`` (ceiling u, v: x and 8 - y)
    and a luminaire strip along its south side."""
    faces = room_faces(0, 0, 0, 8, 8, 3)
    ceiling = [
        Insert("roof", *rooflight, group="roof", zone_kind="skylight"),
        Insert("lum", 0.5, 0.5, 7.5, 1.5, group="lum", zone_kind="luminaire"),
    ]
    parts = {"floor": ("floor", 0.3, []), "ceiling": ("ceiling", 0.8, ceiling)}
    parts |= {k: ("walls", 0.6, []) for k in ("south", "north", "west", "east")}
    surfaces, zones = [], []
    for key, (group, rho, inserts) in parts.items():
        s, z = split_rect(key, group, rho, faces[key], inserts)
        surfaces += s
        zones += z
    return Scene("roomlit", tuple(surfaces), tuple(zones), 0.5, "a room with a rooflight zone")


@pytest.fixture(scope="module")
def room():
    scene = roof_room()
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=512, seed=0)))


def design(light: LightModel, rect=None, free=("u0", "v0"), **kw) -> Design:
    """A centred clear rooflight (free size) and a fixed luminaire strip; least annual
    energy; sDA300/50% at least 50% and ASE1000,250 at most 10% (LEED v4)."""
    w, h = light.zone_size("roof")
    s1 = Source("S1", "roof", "skylight", rect or (0.0, 0.0, w, h), glazing="clear", free=free)
    lum = Source("L1", "lum", "luminaire", (0, 0, *light.zone_size("lum")), flux=6000.0)
    rules = (Rule("centred", ("S1",)),) if free == ("u0", "v0") else ()
    base = Design(
        sources=(s1, lum),
        rules=rules,
        goals=(Goal("min_annual_energy"),),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        daylight=Daylight(transmittance=TAU, target_lux=300.0),
        intentions=(
            Intention("sDA", grid="wp", quantity="sda", average=0.5),
            Intention("ASE", grid="wp", quantity="ase", max_average=0.1),
        ),
    )
    return replace(base, **kw)


def candidate(problem: DesignProblem, x):
    """The light of candidate x at the full level, and the offset of its grid points."""
    level = problem.level(1)
    lit = problem.lighting.of(*problem.vars.decode(np.atleast_2d(x)), level, None)
    return lit.parts, slice(len(level.rows), None)


FIGURES = ("da", "udi", "sda", "ase")


def figures(parts, idx) -> dict:
    """DA, UDI, sDA, ASE, cDA (grid means), the EN 17037 score and the share of the
    plane with 300 lux in half of EN 17037's daylight hours, of one layout."""
    out = {q: float(parts.band(quantity_spec(q).hours, idx)[:, 0].mean()) for q in FIGURES}
    out["cda"] = float(parts.cda(idx)[:, 0].mean())
    out["en17037"] = float(parts.en17037_score(idx)[0, 0])
    # EN 17037's 300 lux in half the daylight hours, every blind open: the score's input
    # (the score itself jumps by up to 1 where a level is just met or just missed).
    out["en300"] = float((parts.en17037_reach(idx, 300.0)[:, 0] >= 0.5).mean())
    return out


@pytest.mark.parametrize("mf", [1, 2])
def test_the_whole_zone_from_its_cells_is_the_fixed_build(room, mf):
    """Every cell glazed: the same panes, rays and seeds as a fixed build of the whole
    zone, so the same light to float rounding, and the same figures; on Tregenza's sky
    and on Reinhart's MF:2 (``daylight.sky_subdivision``: the cells read it too)."""
    sky = Daylight(transmittance=TAU, target_lux=300.0, sky_subdivision=mf)
    p = DesignProblem(design(room, free=("u0", "v0", "u1", "v1"), daylight=sky), room)
    w, h = room.zone_size("roof")
    parts, idx = candidate(p, [0.0, 0.0, w, h])
    fixed = layout_daylight(room, design(room, free=(), daylight=sky))
    span = fixed.grids.span("wp")
    got, want = parts.clear_hours(idx)[:, 0], fixed.points.clear_hours(span)
    assert np.abs(got - want).max() <= 1e-5 * want.max()
    assert np.allclose(
        parts.overcast_daylight(idx)[:, 0], fixed.points.overcast_daylight(span)[:, 0]
    )
    assert figures(parts, idx) == pytest.approx(figures(fixed.points, span), abs=1e-6)
    assert p.clear_cells.count == 36 and p.clear_cells.nbytes < 64e6


@pytest.mark.parametrize("rect", [(0.0, 0.0, 3.0, 1.5), (0.5, 0.5, 2.5, 2.5), (0.3, 0.7, 2.2, 2.6)])
def test_a_part_of_the_zone_against_a_fresh_fixed_build(room, rect):
    """Half the zone (whole cells), a centred square of whole cells and a rectangle
    cutting cells: the cells' sum against a fixed build traced at that rectangle (other
    glass samples; its uncovered zone reflects, the cells' is black; a cut cell is glass
    of share x T there, its share of full glass here): per point annual mean within 3%
    on average and 8% at any point, DA/UDI/sDA/ASE/cDA and EN 17037's
    300 lux share within 4 points."""
    p = DesignProblem(design(room, free=("u0", "v0", "u1", "v1")), room)
    parts, idx = candidate(p, rect)
    fixed = layout_daylight(room, design(room, rect=rect, free=()))
    span = fixed.grids.span("wp")
    a = parts.clear_hours(idx)[:, 0].mean(axis=1)
    b = fixed.points.clear_hours(span).mean(axis=1)
    rel = np.abs(a / b - 1)
    assert rel.mean() < 0.03 and rel.max() < 0.08, (rel.mean(), rel.max())
    got, want = figures(parts, idx), figures(fixed.points, span)
    for q in (*FIGURES, "cda", "en300"):
        assert got[q] == pytest.approx(want[q], abs=0.04), q


def test_a_batch_is_its_candidates_one_by_one(room):
    """The batch's constraints and energy equal each candidate's alone (its own blinds,
    its own year), and the sizes order them: ASE grows with the rooflight."""
    p = DesignProblem(design(room), room)
    X = np.array([[0.0, 0.0], [0.5, 0.5], [0.55, 0.6], [1.0, 1.0]])
    ev = p.evaluate(X)
    for j, x in enumerate(X):
        one = p.evaluate(x[None])
        assert np.allclose(one.G[0], ev.G[j]) and np.isclose(
            one.goals["min_annual_energy"][0], ev.goals["min_annual_energy"][j]
        )
    ase = ev.G[:, -1]  # (mean - 0.1) / 0.1 - tol
    assert ase[0] > ase[1] >= ase[3]
    assert ev.goals["min_annual_energy"][0] < ev.goals["min_annual_energy"][3]


def test_a_moving_candidates_year_is_its_layouts(room):
    """One candidate's energy, DA, UDI, sDA, ASE, cDA and EN 17037 figures from the
    batch path (``ClearBatch``: candidates' blinds vectorised) against
    ``layout_daylight`` of the same layout (what ``lightinv-cli solve`` and the report
    read: the cells' sum laid out as a fixed glazing's columns, ``light.clear_layout``,
    read by the fixed glazing's code with its own LM-83 blinds): equal."""
    d = design(room, intentions=(Intention("EN", grid="wp", quantity="en17037", min=1),))
    p = DesignProblem(d, room)
    x = np.array([0.6, 0.55])
    parts, idx = candidate(p, x)
    kwh = p.evaluate(x[None]).goals["min_annual_energy"][0]
    lay = layout_daylight(room, d, p.sources_at(x))
    span = lay.grids.span("wp")
    assert lay.design.sources[0].rect == d.sources[0].rect  # the design as written
    assert figures(parts, idx) == pytest.approx(figures(lay.points, span), abs=1e-6)
    assert np.allclose(parts.clear_hours(idx)[:, 0], lay.points.clear_hours(span), atol=1e-2)
    assert kwh == pytest.approx(lay.energy().energy_kwh, rel=1e-6)
    assert 0.05 < figures(parts, idx)["ase"] < 0.5  # the blinds have work to do


def test_what_a_moving_clear_glazing_refuses(room):
    """Sunlight exposure at observers counts the glazing as drawn: refused with a free
    clear shape; a free filter or flux on clear glazing is refused by the source."""
    d = design(room, observers=(Observer("eye", (4.0, 4.0), azimuth=90.0),))
    d = replace(d, intentions=(Intention("sun", observers=("eye",), quantity="sunlight", min=1.5),))
    with pytest.raises(DesignError, match="sunlight exposure is counted through clear glazing"):
        DesignProblem(d, room)
    with pytest.raises(DesignError, match="frees only its rectangle"):
        design(room, free=("u0", "filter"))
    assert clear_cells(room, design(room, free=()), np.zeros(0, int)) is None  # fixed: as before


def test_an_optimisation_chooses_the_rooflights_size(room):
    """Least energy with sDA300/50% >= 50% and ASE1000,250 <= 10%: the whole rooflight
    gives too much sun, a small one too little daylight; CMA-ES finds a size between
    that meets both, and the forward study (``study.simulate``) of a room whose
    rooflight is the chosen one agrees with what the optimiser reported."""
    d = design(room)
    p = DesignProblem(d, room)
    ctx = RunContext(stop=StopRule(max_evals=150, stall=None), seed=1, x0=np.array([0.9, 0.9]))
    best = get_method("cmaes").run(p, ctx).best
    x = np.asarray(best.x)
    ev = p.evaluate(x[None])
    assert ev.feasible[0], ev.G
    parts, idx = candidate(p, x)
    sda = float(parts.band(quantity_spec("sda").hours, idx)[:, 0].mean())
    ase = float(parts.band(quantity_spec("ase").hours, idx)[:, 0].mean())
    assert sda >= 0.5 and ase <= 0.1
    u0, v0, u1, v1 = p.sources_at(x)[0].rect
    assert 1.0 < (u1 - u0) * (v1 - v0) < 9.0  # neither the whole zone nor nothing
    # The forward study: the chosen rooflight as the room's glazing, meshed anew.
    x0, y0 = ZONE[0], ZONE[1]
    scene = roof_room((x0 + u0, y0 + v0, x0 + u1, y0 + v1))
    spec = SimulationSpec(
        scene=scene,
        glazing={"roof": TAU},
        glazing_kinds={"roof": "clear"},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=Daylight(transmittance=TAU),
    )
    want, _ = work_plane_metrics(simulate(spec).clear_year)
    assert want["sda300_50"] == pytest.approx(sda, abs=0.06)
    assert want["ase1000_250"] == pytest.approx(ase, abs=0.06)


def test_solve_a_project_with_a_free_clear_rooflight(tmp_path, capsys):
    """``lightinv-cli solve`` on the built-in toplit room, its rooflight clear and free
    (centred), least glazing area with sDA300/50% at least 50%."""
    project = {
        "schema": 1,
        "name": "clear rooflight",
        "scene": {"builtin": "toplit", "resolution": 0.5},
        "sources": [
            {
                "name": "S1",
                "zone": "rooflight",
                "kind": "skylight",
                "rect": [0, 0, 2, 2],
                "glazing": "clear",
                "free": ["u0", "v0"],
            },
        ],
        "rules": [{"kind": "centred", "sources": ["S1"]}],
        "intentions": [{"name": "sDA", "grid": "wp", "quantity": "sda", "average": 0.5}],
        "goals": [{"kind": "min_glazing_area"}],
        "workplanes": [{"name": "wp", "height": 0.8, "border": 0.5}],
        "daylight": {"transmittance": TAU},
        "optimizer": {"method": "cmaes", "seed": 0, "max_evals": 120, "divisors": [1]},
        "operator": {"rays": 256},
    }
    path = tmp_path / "clear-shape.json"
    path.write_text(json.dumps(project))
    assert cli.main(["solve", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "feasible"
    assert out["daylight"]["sda300_50"] >= 0.5  # the work plane as the optimiser judged it
    assert out["sources"][0]["area_m2"] < 4.0  # smaller than the whole rooflight
    assert "min_glazing_area" in json.dumps(out)


def test_blocks_of_patches_and_a_fixed_clear_source_beside_a_free_one(monkeypatch):
    """A zone of more patches than ``MAX_CELLS`` is traced in blocks; a fixed clear
    source beside a free one is one cell at its own transmittance (its blinds its own):
    with the free one over its whole zone the cells' sum is a fixed build of both."""
    import lightinv_core.light.clear_cells as cc

    monkeypatch.setattr(cc, "MAX_CELLS", 4)
    faces = room_faces(0, 0, 0, 6, 6, 3)
    ceiling = [Insert("roof", 1, 2, 3, 4, group="roof", zone_kind="skylight")]
    south = [Insert("win", 0.9, 1, 2.1, 5, group="win", zone_kind="window")]
    parts = {"floor": ("floor", 0.3, []), "ceiling": ("ceiling", 0.8, ceiling)}
    parts |= {k: ("walls", 0.6, []) for k in ("north", "west", "east")}
    parts["south"] = ("walls", 0.6, south)
    surfaces, zones = [], []
    for key, (group, rho, inserts) in parts.items():
        s, z = split_rect(key, group, rho, faces[key], inserts)
        surfaces += s
        zones += z
    scene = Scene("two", tuple(surfaces), tuple(zones), 0.5, "two clear openings")
    patches = mesh_patches(scene)
    light = LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=256)))
    w, h = light.zone_size("roof")
    roof = Source("S1", "roof", "skylight", (0, 0, w, h), glazing="clear", free=("u1",))
    win = Source("W1", "win", "window", (0, 0.5, 1.2, 3.5), glazing="clear", filter=0.8)
    d = Design(
        sources=(roof, win),
        goals=(Goal("min_glazing_area"),),
        workplanes=(Workplane("wp", 0.8, 1.0),),
        daylight=Daylight(transmittance=TAU),
        intentions=(Intention("DA", grid="wp", quantity="da", average=0.1),),
    )
    p = DesignProblem(d, light)
    cells = p.clear_cells
    assert light.emission.grid("roof").patch.size == 16 and cells.count == 4 + 1
    parts_, idx = candidate(p, [w])
    fixed = layout_daylight(light, replace(d, sources=(replace(roof, free=()), win)))
    span = fixed.grids.span("wp")
    got, want = parts_.clear_hours(idx)[:, 0], fixed.points.clear_hours(span)
    assert np.abs(got - want).max() <= 1e-5 * want.max()
    assert figures(parts_, idx) == pytest.approx(figures(fixed.points, span), abs=1e-6)
    # Half the rooflight: two of its four blocks, and less light than the whole.
    half, _ = candidate(p, [w / 2])
    assert half.clear_hours(idx)[:, 0].mean() < got.mean()
    # Two sources' blinds (the fewest closed, per hour) for a batch as one by one.
    X = np.array([[w], [w / 2], [0.3 * w], [0.0]])
    batch = p.lighting.of(*p.vars.decode(X), p.level(1), None).parts.clear.closed
    for j, x in enumerate(X):
        assert np.array_equal(candidate(p, x)[0].clear.closed[0], batch[j])
    assert batch.any() and not np.array_equal(batch[0], batch[3])


def test_patch_receivers_read_the_cells_too(room):
    """Intentions on the floor's patches (annual) and the walls' (night): the cells keep
    the year's columns at the floor, the overcast factor at both; over the whole zone
    the floor's DA and ASE and the walls' overcast light are a fixed build's (last in
    this file: other rows rebuild the cells)."""
    floor = (
        Intention("floor DA", group="floor", quantity="da", average=0.1),
        Intention("floor ASE", group="floor", quantity="ase", max_average=0.9),
        Intention("walls at night", group="walls", quantity="lux", min=0.0, scenario="night"),
    )
    d = design(room, free=("u0", "v0", "u1", "v1"), intentions=floor)
    p = DesignProblem(d, room)
    w, h = room.zone_size("roof")
    level = p.level(1)
    parts, _ = candidate(p, [0.0, 0.0, w, h])
    fixed = layout_daylight(room, design(room, free=(), intentions=floor))
    rows = np.flatnonzero(np.isin(level.rows, p.clear_cells.year_rows))
    for q in ("da", "ase"):
        band = quantity_spec(q).hours
        got = parts.band(band, rows)[:, 0]
        want = fixed.patches.band(band, level.rows[rows])[:, 0]
        assert np.allclose(got, want, atol=1e-9), q
    # The year's columns at the floor only; the walls (a night intention) read none.
    cells = p.clear_cells
    assert len(cells.rows) == len(level.rows) > len(cells.year_rows) > 100
    assert np.array_equal(cells.year_rows, np.sort(room.patches.group_index("floor")))
    walls = np.flatnonzero(~np.isin(level.rows, cells.year_rows))
    over = fixed.patches.overcast_daylight(level.rows[walls])[:, 0]
    assert np.allclose(parts.overcast_daylight(walls)[:, 0], over)  # the walls' overcast


def test_two_control_groups_dim_to_each_candidates_clear_light(room):
    """Two control groups (the strip under the rooflight's sensor, a second luminaire
    near the wall on its own): the batch's annual energy is each candidate's alone and,
    for one layout, ``layout_daylight``'s groups' energy (each dimmed to its own sensor's
    share of that candidate's clear light)."""
    from lightinv_core.design.model import ControlGroup

    base = design(room)
    strip, lum = base.sources[1], replace(base.sources[1], name="L2", rect=(0, 0, 3.0, 1.0))
    groups = (ControlGroup("middle", sensor=(2.0, 2.0, 6.0, 6.0)), ControlGroup("edge"))
    d = replace(
        base,
        sources=(
            base.sources[0],
            replace(strip, control_group="middle"),
            replace(lum, control_group="edge"),
        ),
        control_groups=groups,
    )
    p = DesignProblem(d, room)
    X = np.array([[0.0, 0.0], [0.6, 0.55], [1.2, 1.2]])
    kwh = p.evaluate(X).goals["min_annual_energy"]
    for j, x in enumerate(X):
        assert p.evaluate(x[None]).goals["min_annual_energy"][0] == pytest.approx(kwh[j], rel=1e-6)
        lay = layout_daylight(room, d, p.sources_at(x))
        assert len(lay.energy().groups) == 2
        assert lay.energy().energy_kwh == pytest.approx(kwh[j], rel=1e-6)
    assert kwh[0] < kwh[2]  # more daylight, less energy


def test_float32_counts_are_the_float64_definitions():
    """The batch counts its bands on float32 light (``clear_batch.hour_counts``): the
    float32 bounds it picks give exactly ``HourBand.of_hours``'s float64 answer, on
    values at and beside each bound (thresholds a float32 holds and ones it does not)."""
    from lightinv_core.light.clear_batch import band_of_counts, hour_counts
    from lightinv_core.quantities import HourBand

    rng = np.random.default_rng(3)
    bounds = [100.0, 300.0, 1000.0, 3000.0, 0.1, 250.3, 2999.9999]
    near = np.array(bounds, np.float32)
    edge = np.concatenate(
        [near, np.nextafter(near, np.float32(0)), np.nextafter(near, np.float32(1e9))]
    )
    lux = rng.choice(np.concatenate([edge, rng.uniform(0, 4000, 200).astype(np.float32)]),
                     (30, 500)).astype(np.float32)  # fmt: skip
    bands = [quantity_spec(q).hours for q in ("da", "sda", "udi", "ase")]
    bands += [HourBand(lo, hi, above=a) for lo in bounds for hi in (np.inf, 2999.9999) for a in
              (False, True)]  # fmt: skip
    bands += [HourBand(250.3, point_share=0.5), HourBand(0.1, point_hours=120, above=True)]
    for band in bands:
        counts = hour_counts(lux, band.lo, band.hi, band.above)
        want = band.of_hours(lux.astype(float))
        assert np.array_equal(band_of_counts(band, counts, lux.shape[1]), want), band
    assert hour_counts(lux, 300.0, np.inf, False).sum() > 0


def test_the_sun_read_on_its_support_is_the_dense_sun(room):
    """ASE and the one-source blinds read the candidates' direct sun only where some
    cell has any (``clear_batch.SunSupport``): the same marks and blinds as the dense
    sun of each candidate through ``HourBand.of_hours`` and ``blinds_closed``."""
    from lightinv_core.climate.sun_metrics import blinds_closed

    p = DesignProblem(design(room), room)
    level = p.level(1)
    X = np.array([[0.0, 0.0], [0.4, 0.7], [0.9, 0.2], [1.3, 1.3]])
    clear = p.lighting.of(*p.vars.decode(X), level, None).parts.clear
    idx = slice(len(level.rows), None)
    ase = quantity_spec("ase").hours
    got = clear.band(ase, idx, clear.occupied)  # (R, m)
    sun = clear.hours(idx, clear.occupied, sun_only=True)  # (R, m, T) dense
    on = clear.control  # the control plane's span of the grid points
    for j in range(len(X)):
        assert np.array_equal(got[:, j], ase.of_hours(sun[:, j].astype(float)))
        want = blinds_closed(sun[on, j].astype(float))
        assert np.array_equal(clear.closed[j, 0, clear.occupied], want)
    assert 0 < got.mean() < 1 and clear.closed.any() and not clear.closed.all()
