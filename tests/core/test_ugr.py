"""UGR (CIE 117 at an observer, CIE 190 tables): against hand computations, CIE 117's
position-index table, CIE 190's transfer factors and an independent implementation
(eulumdat-ugr, MIT, a test-only extra) on real manufacturer files."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from lightinv_core.luminaires import lambertian_panel, read_photometry
from lightinv_core.luminaires.ldt import format_ldt
from lightinv_core.luminaires.ugr import (
    NoLuminousArea,
    background_luminance,
    glare_terms,
    in_field,
    position_index,
    projected_area,
    ugr,
)
from lightinv_core.luminaires.ugr_table import (
    ORIENTATIONS,
    REFLECTANCES,
    ROOMS,
    flux_fractions,
    parallel_view_factor,
    ugr_table,
    wall_indirect_lux,
)
from lightinv_core.transport.luminaires import PlacedLuminaire

DATA = Path(__file__).resolve().parents[1] / "data" / "photometry"
# Largest |ours - eulumdat-ugr| over the 190 cells, measured, and the bound tested (issue
# #31: 0.5 on every cell). With CIE 117's Table 4.1 for the position index (as CIE 190
# and eulumdat-ugr take it) the glare sums agree to 0.05%; what is left is the background:
# our exact direct flux on the floor against CIE 190's zonal multipliers (up to 8% more
# background in 2H x 2H: 0.27 UGR lower for the DN150 downlight).
REAL_FILES = {
    "ledvance-panel-600.ldt": 0.15,  # measured 0.13
    "ledvance-downlight-dn150.ldt": 0.3,  # measured 0.27 (was 0.52 with Guth's formula)
    "rab-square-1.ies": 0.05,  # measured 0.02
    "rab-round-4.ies": 0.3,  # measured 0.28
}

# CIE 117:1995 Table 4.1, a few cells (T/R, H/R) -> p, as published (and as eulumdat-ugr
# transcribes them).
TABLE_4_1 = {
    (0.0, 0.0): 1.00,
    (0.0, 0.5): 2.86,
    (0.0, 1.0): 7.00,
    (0.0, 1.5): 13.15,
    (0.5, 0.5): 2.91,
    (1.0, 0.5): 3.91,
    (1.0, 1.0): 7.00,
    (2.0, 1.0): 8.90,
    (3.0, 0.5): 6.60,
    (3.0, 1.9): 16.00,
}


def test_guth_formula_matches_table_4_1_at_published_cells():
    for (t_r, h_r), p_table in TABLE_4_1.items():
        p = float(position_index(h_r, t_r))
        # Guth's formula smooths the table: 7% low at T/R = 2, H/R = 1 (8.30 for 8.90).
        assert p == pytest.approx(p_table, rel=0.07), (t_r, h_r, p)


def test_guth_formula_against_the_whole_transcribed_table():
    guth = pytest.importorskip("eulumdat_ugr.guth").GuthTable
    tr, hr = np.meshgrid(guth._TR_AXIS, guth._HR_AXIS, indexing="ij")
    table = guth._TABLE
    ok = ~np.isnan(table)
    rel = np.abs(position_index(hr, tr)[ok] / table[ok] - 1.0)
    # Measured: median 4.5%, 90th percentile 7.2%, largest 10.6% (T/R = 3, H/R = 0). In
    # UGR terms 16 log10(1 + rel): at most 0.7 for a luminaire alone, the table's sums of
    # hundreds move far less (the cross-check below).
    assert np.median(rel) < 0.05
    assert rel.max() < 0.11
    # The field limits are the table's defined cells.
    defined = in_field(hr, tr)
    assert np.array_equal(defined[ok], np.ones(ok.sum(), bool))


def test_table_4_1_cells_and_interpolation():
    from lightinv_core.luminaires.position_table import TABLE, table_position_index

    for (t_r, h_r), p_table in TABLE_4_1.items():  # published cells, exactly
        assert float(table_position_index(h_r, t_r)) == pytest.approx(p_table, abs=1e-12)
    # Bilinear between cells: the middle of T/R 1-1.1, H/R 0.5-0.6 is the four's mean.
    want = (3.91 + 4.20 + 4.40 + 4.70) / 4
    assert float(table_position_index(0.55, 1.05)) == pytest.approx(want, abs=1e-12)
    # Undefined above the table's top cells and beyond its edges; symmetric in T and H.
    assert np.isnan(table_position_index([1.8, 1.75, 2.0, 0.5], [0.2, 0.35, 1.0, 3.2])).all()
    assert table_position_index(-0.5, -1.0) == table_position_index(0.5, 1.0)
    assert np.isfinite(TABLE).sum() == 31 * 20 - 2 * 4 - 5  # 4 rows miss 2, 5 miss 1
    guth = pytest.importorskip("eulumdat_ugr.guth").GuthTable
    # eulumdat-ugr's own transcription and interpolation (scipy's), at random points.
    rng = np.random.default_rng(1)
    h, t = rng.uniform(0, 2.0, 5000), rng.uniform(0, 3.1, 5000)
    ours, theirs = table_position_index(h, t), guth.p_vec(h, t)
    assert np.array_equal(np.isnan(ours), np.isnan(theirs))
    assert np.nanmax(np.abs(ours - theirs)) < 1e-12


def test_background_luminance_is_e_over_pi():
    assert background_luminance(100.0) == pytest.approx(100.0 / math.pi)


def test_transfer_factors_reproduce_cie_190_table():
    background = pytest.importorskip("eulumdat_ugr.background")
    h, worst = 2.0, 0.0
    for key in background.REFLECTANCES:
        rho = tuple(int(v) / 100 for v in key.split("/"))
        for i, (xh, yh) in enumerate(ROOMS):
            x, y = xh * h, yh * h
            aw = 2 * h * (x + y)
            got = [
                wall_indirect_lux(x, y, h, flux, rho)
                for flux in ((aw, 0, 0), (0, aw, 0), (0, 0, aw))
            ]
            worst = max(worst, np.max(np.abs(np.array(got) - background._FT[key][i])))
    assert worst < 0.0015  # the table prints three decimals


def test_parallel_view_factor_unit_cube():
    # Opposite faces of a cube: 0.19982 (Howell's catalogue, C-11).
    assert parallel_view_factor(1.0, 1.0, 1.0) == pytest.approx(0.19982, abs=1e-5)


def _panel(lumens: float = 3000.0, size=(0.6, 0.6, 0.0)):
    return lambertian_panel(lumens, size_m=size)


def _hand_ugr(i0: float, area: float, r: float, t: float, h: float, p: float, lb: float):
    """One Lambertian flat opening: L = I0 cos g / (A cos g) = I0 / A, omega = A cos g / d²."""
    d = math.sqrt(r * r + t * t + h * h)
    cos_g = h / d
    lum = i0 * cos_g / (area * cos_g)
    omega = area * cos_g / d**2
    return 8 * math.log10(0.25 / lb * lum**2 * omega / p**2)


@pytest.mark.parametrize(("r", "t", "h", "p_table"), [(3.0, 0.0, 1.5, 2.86), (2.0, 2.0, 2.0, 7.00)])
def test_one_lambertian_panel_by_hand(r, t, h, p_table):
    ph = _panel()
    eye = np.array([1.0, 2.0, 1.2])
    lum = PlacedLuminaire("p", eye + np.array([r, -t, h]), ph)  # T is to the right of +x
    lb = background_luminance(120.0)
    got = ugr(eye, (1.0, 0.0, 0.0), [lum], lb)
    i0 = 3000.0 / math.pi
    hand = _hand_ugr(i0, 0.36, r, t, h, p_table, lb)  # p from CIE 117's table
    assert got == pytest.approx(hand, abs=0.1)
    # Dimmed to half: L halves, UGR drops by 8 log10(4).
    half = ugr(eye, (1.0, 0.0, 0.0), [replace(lum, dimming=0.5)], lb)
    assert got - half == pytest.approx(8 * math.log10(4.0), abs=1e-9)


def test_out_of_view_luminaires_do_not_count():
    ph = _panel()
    eye = np.zeros(3)
    behind = PlacedLuminaire("b", (-2.0, 0.0, 1.5), ph)
    aside = PlacedLuminaire("a", (1.0, 3.5, 1.5), ph)  # T/R = 3.5
    overhead = PlacedLuminaire("o", (0.5, 0.0, 2.0), ph)  # H/R = 4
    terms = glare_terms(eye, (1, 0, 0), [behind, aside, overhead])
    assert not terms.counts.any()
    assert ugr(eye, (1, 0, 0), [behind, aside, overhead], 10.0) == -math.inf
    ahead = PlacedLuminaire("f", (3.0, 0.0, 1.5), ph)
    both = ugr(eye, (1, 0, 0), [behind, ahead], 10.0)
    assert both == pytest.approx(ugr(eye, (1, 0, 0), [ahead], 10.0))


def test_projected_area_of_a_box_and_a_disc():
    box = (0.2, 1.2, 0.05)  # width along C90, length along C0, luminous height
    assert projected_area(box, 0.0, 0.0) == pytest.approx(0.24)
    # Seen horizontally along C0: the end face, width x height.
    assert projected_area(box, 0.0, 90.0) == pytest.approx(0.2 * 0.05, abs=1e-12)
    assert projected_area(box, 90.0, 90.0) == pytest.approx(1.2 * 0.05, abs=1e-12)
    disc = (-0.4, -0.4, 0.0)
    assert projected_area(disc, 30.0, 60.0) == pytest.approx(math.pi * 0.04 * 0.5)


def test_no_luminous_area_is_an_error():
    ph = _panel(size=(0.0, 0.0, 0.0))
    with pytest.raises(NoLuminousArea, match="no luminous opening"):
        ugr_table(ph)


def test_flux_fractions_of_a_downlight():
    ff = flux_fractions(_panel())
    assert ff.down == pytest.approx(1.0) and ff.up == pytest.approx(0.0, abs=1e-12)
    assert ff.floor + ff.walls == pytest.approx(ff.down)
    assert 0.5 < ff.floor < 0.95


def _as_relative_ldt(ph, tmp_path: Path) -> Path:
    """The table as EULUMDAT for eulumdat-ugr: one lamp set of the table's own flux.
    (eulumdat-ugr multiplies the flux of the set by its number of lamps, where
    EULUMDAT's line 29 is already the set's total: a 192-LED file would come out
    8 log10(192) = 18.3 too high, so the count is written as 1.)"""
    path = tmp_path / (Path(ph.source).stem + ".ldt")
    rel = replace(ph, lamp_lumens=ph.flux(), n_lamps=1)
    path.write_text(format_ldt(rel), encoding="latin-1")
    return path


@pytest.mark.parametrize(("name", "bound"), REAL_FILES.items())
def test_table_against_eulumdat_ugr(name, bound, tmp_path):
    pytest.importorskip("eulumdat_ugr")
    from eulumdat_ugr import UgrCalculator
    from pyldt import LdtReader

    ph = read_photometry(DATA / name)
    path = DATA / name if name.endswith(".ldt") else _as_relative_ldt(ph, tmp_path)
    ref = UgrCalculator.compute(LdtReader.read(str(path))).values  # (19, 10)
    table = ugr_table(ph)
    ours = np.concatenate([table.values[:, :, 0], table.values[:, :, 1]], axis=1)
    assert not np.isnan(ours).any() and not np.isnan(ref).any()
    diff = np.abs(ours - ref)
    assert diff.max() < bound, (name, diff.max())
    assert np.mean(diff) < 0.1
    # The catalogue's value (4H 8H, 70/50/20) is within 0.15 for every file (DN150: 0.11).
    for k, col in ((0, 0), (1, 5)):
        assert table.at((4, 8), REFLECTANCES[0], ORIENTATIONS[k]) == pytest.approx(
            ref[10, col], abs=0.15
        )


def test_the_panel_table_is_plausible():
    table = ugr_table(read_photometry(DATA / "ledvance-panel-600.ldt"))
    # Darker rooms glare more; the 4H x 8H value of a 4,400 lm 0.6 m panel is in the teens.
    assert np.all(np.diff(table.values[:, [0, 2, 4], :], axis=1) > 0)
    assert 15.0 < table.at() < 22.0
    assert len(ROOMS) == 19


def test_cli_photometry_json_and_table(capsys):
    from lightinv_core import cli

    panel = DATA / "ledvance-panel-600.ldt"
    assert cli.main(["photometry", str(panel), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    table = ugr_table(read_photometry(panel))
    assert got["manufacturer"] == "LEDVANCE GmbH" and got["catalogue_number"] == "4058075724549"
    assert got["lumens"] == pytest.approx(4400.0, rel=1e-3) and got["watts"] == 40.0
    assert got["luminous_area"]["area_m2"] == pytest.approx(0.553**2)
    assert got["ugr"]["crosswise"] == pytest.approx(table.at(), abs=0.005)
    assert got["ugr"]["endwise"] == pytest.approx(table.at(orientation="endwise"), abs=0.005)
    assert np.array(got["ugr_table"]["values"]).shape == (19, 5, 2)
    assert cli.main(["photometry", str(panel), "--table"]) == 0
    text = capsys.readouterr().out
    row = next(line for line in text.splitlines() if line.startswith("4H 8H"))
    assert f"{table.at():5.1f}" in row and "crosswise" in text and "endwise" in text


def test_cli_photometry_errors(capsys, tmp_path):
    from lightinv_core import cli
    from lightinv_core.luminaires import write_photometry

    bad = tmp_path / "bad.ies"
    bad.write_text("IESNA:LM-63-2002\nTILT=NONE\n1 2 3\n")
    assert cli.main(["photometry", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("lightinv-cli: error:") and err.count("\n") == 1
    point = tmp_path / "point.ies"
    write_photometry(_panel(size=(0.0, 0.0, 0.0)), point)
    assert cli.main(["photometry", str(point)]) == 0
    assert "UGR: not computed" in capsys.readouterr().out


def test_where_the_dn150_differs_from_eulumdat_ugr():
    """Where the DN150's table differs from eulumdat-ugr (docs/photometry.md): the glare
    sums agree (the same luminance, solid angles and Table 4.1 position index); the
    background differs by our exact floor flux against CIE 190's zonal multipliers."""
    pytest.importorskip("eulumdat_ugr")
    from eulumdat_luminance import LuminanceCalculator
    from eulumdat_ugr.background import BackgroundLuminance
    from eulumdat_ugr.geometry import UgrGrid
    from eulumdat_ugr.guth import GuthTable
    from eulumdat_ugr.photometry import UgrPhotometry
    from pyldt import LdtReader

    from lightinv_core.luminaires import ugr as u
    from lightinv_core.luminaires import ugr_table as ut

    path = DATA / "ledvance-downlight-dn150.ldt"
    ph, ldt = read_photometry(path), LdtReader.read(str(path))
    theirs = LuminanceCalculator.compute(ldt, full=True)
    c, g = np.array([0.0, 20.0, 45.0, 90.0]), np.array([30.0, 55.0, 65.0, 75.0])
    # Luminance and projected area: the same model, the same numbers.
    assert np.allclose(u.luminance(ph, c, g), theirs.at(c_deg=c, g_deg=g), rtol=1e-9)
    assert np.allclose(u.projected_area(ph.opening, c, g), theirs.projected_area(c, g))
    for i, lb_ratio, sum_ratio in (
        (0, (1.07, 1.09), (0.999, 1.001)),
        (10, (1.02, 1.04), (0.999, 1.001)),
    ):
        xh, yh = ut.ROOMS[i]
        grid = UgrGrid(xh, yh)
        lb_ref = BackgroundLuminance.compute(ldt, grid.n_total, 8.0 * (xh + yh), i)["70/50/20"]
        r, t, cc, gg, dist = grid.angles("crosswise")
        lum, omega = UgrPhotometry.compute(theirs, cc, gg, dist)
        p = GuthTable.p_vec(ut.H / r, t / r)
        ok = ~np.isnan(p)
        sum_ref = np.sum(lum[ok] ** 2 * omega[ok] / p[ok] ** 2)
        n = grid.n_total
        down, total = ph.flux(90.0), ph.flux()
        floor = n * down * ut.floor_share(ph, xh, yh)
        flux = (floor, n * down - floor, n * (total - down))
        lb = ut.wall_indirect_lux(xh * ut.H, yh * ut.H, ut.H, flux, REFLECTANCES[0]) / math.pi
        assert lb_ratio[0] < lb / lb_ref < lb_ratio[1]
        assert sum_ratio[0] < ut.glare_sum(ph, xh, yh, "crosswise") / sum_ref < sum_ratio[1]


def test_catalogue_ugr_is_the_tables_4h8h_cell():
    from lightinv_core.luminaires.ugr_table import catalogue_ugr

    ph = read_photometry(DATA / "rab-round-4.ies")
    table = ugr_table(ph)
    assert catalogue_ugr(ph) == (table.at(), table.at(orientation="endwise"))
