"""Photometric files (IES LM-63, EULUMDAT), analytic distributions and the catalogue.

Closed forms for flux and interpolation; write -> read round trips for every symmetry;
hand-written LM-63 headers of each revision; an independent MIT reader (eulumdat-py)
and converter (eulumdat-ies) cross-check our EULUMDAT files; every bad file gives one
line with its line number (``BAD_PHOTOMETRY_CASES``, also a fuzz of mutations).
"""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from eulumdat_ies import ldt_to_ies
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pyldt import LdtReader, LdtWriter

from lightinv_core.errors import PhotometryError
from lightinv_core.luminaires import (
    Photometry,
    batwing_linear,
    builtin_catalogue,
    downlight,
    generate_builtin,
    lambertian_panel,
    parse_ies,
    parse_ldt,
    read_catalogue,
    read_ies,
    read_ldt,
    read_photometry,
    write_ies,
    write_ldt,
)
from lightinv_core.luminaires.analytic import batwing_coefficient, tabulate
from lightinv_core.luminaires.catalogue import BUILTIN_FOLDER
from lightinv_core.luminaires.photometry import (
    AXIAL,
    BILATERAL_C0,
    BILATERAL_C90,
    NONE,
    QUADRANT,
)
from lightinv_core.luminaires.textfile import MAX_FILE_BYTES

ROOT = Path(__file__).resolve().parents[2]


def _sub(text: str, old: str, new: str) -> str:
    """``text`` with its one ``old`` replaced (the sample must contain it)."""
    assert text.count(old) == 1, old
    return text.replace(old, new)


# A small valid IES file: quadrant symmetric (horizontal 0..90), 3 x 3 candela.
IES_OK = """IESNA:LM-63-2002
[TEST] sample
[MANUFAC] Acme
[LUMINAIRE] Sample downlight
TILT=NONE
1 1000 1 3 3 1 2 0.1 0.1 0
1 1 10
0 45 90
0 45 90
100 80 0
90 70 0
80 60 0
"""

# A small valid EULUMDAT file: Isym 4 (planes C0 and C90 stored), Mc 4, Ng 3.
LDT_OK = (
    "\n".join(
        [
            "Acme",
            "3",
            "4",
            "4",
            "90",
            "3",
            "45",
            "report",
            "Sample LDT",
            "L-1",
            "sample.ldt",
            "date",
        ]
        + ["100", "100", "50", "100", "100", "0", "0", "0", "0"]  # 13-21 sizes, mm
        + ["100", "80", "1", "0"]  # 22-25 DFF, LORL, conversion factor, tilt
        + ["1", "1", "LED", "1000", "3000K", "80", "10"]  # 26 one lamp set, 27-32
        + ["0.5"] * 10  # 33-42 direct ratios
        + ["0", "90", "180", "270"]  # 43-46 C angles
        + ["0", "45", "90"]  # 47-49 gamma angles
        + ["300", "200", "0", "280", "150", "0"]  # 50-55 C0 and C90 planes, cd/klm
    )
    + "\n"
)


# ---------------------------------------------------------------------------------------
# Closed forms: flux and interpolation


def test_isotropic_flux_is_4_pi_i_and_the_lower_half_2_pi_i():
    iso = Photometry("C", [0.0], [0.0, 90.0, 180.0], [[100.0, 100.0, 100.0]])
    assert iso.flux() == pytest.approx(4 * math.pi * 100.0, rel=1e-12)
    assert iso.flux(90.0) == pytest.approx(2 * math.pi * 100.0, rel=1e-12)
    coarse = Photometry("C", [0.0, 120.0, 240.0], [0.0, 180.0], np.full((3, 2), 7.0))
    assert coarse.flux() == pytest.approx(4 * math.pi * 7.0, rel=1e-12)


@pytest.mark.parametrize("step", [1.0, 2.5, 5.0])
def test_lambertian_flux_is_pi_i0(step):
    g = np.arange(0.0, 90.0 + step / 2, step)
    ph = Photometry("C", [0.0], g, [200.0 * np.cos(np.radians(g))])
    # The table is piecewise linear in gamma: its error is O(step^2).
    assert ph.flux() == pytest.approx(math.pi * 200.0, rel=2e-4 * (step / 2.5) ** 2)


def test_flux_is_exact_for_the_interpolated_table():
    """flux() integrates what intensity() returns: compare with a fine quadrature."""
    ph = batwing_linear(4000.0)
    c = np.linspace(0.0, 360.0, 1441)[:-1] + 0.125
    g = np.linspace(0.0, 90.0, 3601)
    gm = 0.5 * (g[1:] + g[:-1])
    ring = (np.cos(np.radians(g[:-1])) - np.cos(np.radians(g[1:]))) * (2 * math.pi / c.size)
    total = float(np.sum(ph.intensity(c[:, None], gm[None, :]) * ring[None, :]))
    assert total == pytest.approx(ph.flux(), rel=1e-5)


@pytest.mark.parametrize(
    "make, lumens",
    [
        (lambda: downlight(2000.0, 4.0), 2000.0),
        (lambda: downlight(1500.0, 0.0), 1500.0),
        (lambda: downlight(800.0, 30.0, gamma_step_deg=1.0), 800.0),
        (lambda: lambertian_panel(3600.0), 3600.0),
        (lambda: batwing_linear(4000.0), 4000.0),
        (lambda: batwing_linear(5000.0, peak_deg=20.0, c_step_deg=10.0), 5000.0),
    ],
)
def test_analytic_distributions_have_the_requested_flux(make, lumens):
    assert make().flux() == pytest.approx(lumens, rel=0.005)


def test_analytic_peaks_and_planes():
    dl = downlight(2000.0, 4.0)
    assert dl.max_intensity() == pytest.approx(5 * 2000.0 / (2 * math.pi))
    half = math.degrees(math.acos(0.5**0.25))  # cos^4 = 1/2
    assert dl.intensity(0.0, half) == pytest.approx(dl.max_intensity() / 2, rel=2e-3)
    assert dl.intensity(0.0, 95.0) == 0.0

    bw = batwing_linear(4000.0, peak_deg=35.0)
    across = bw.intensity(90.0, np.arange(0.0, 90.1, 2.5))
    along = bw.intensity(0.0, np.arange(0.0, 90.1, 2.5))
    assert np.argmax(across) * 2.5 == 35.0  # the batwing, across the luminaire
    assert np.argmax(along) == 0  # cos^2 along it: narrower
    assert across[0] == pytest.approx(along[0])
    a = batwing_coefficient(35.0)
    assert across[14] / across[0] == pytest.approx(
        math.cos(math.radians(35)) ** 2 * (1 + a * math.sin(math.radians(35)) ** 2)
    )
    assert bw.symmetry() == QUADRANT and dl.symmetry() == AXIAL


def test_interpolation_at_table_points_between_them_and_outside():
    c = [0.0, 90.0, 180.0, 270.0]
    g = [0.0, 45.0, 90.0]
    cd = [[100.0, 80.0, 0.0], [60.0, 40.0, 0.0], [20.0, 10.0, 0.0], [60.0, 40.0, 0.0]]
    ph = Photometry("C", c, g, cd)
    cc, gg = np.meshgrid(c, g, indexing="ij")
    np.testing.assert_allclose(ph.intensity(cc, gg), cd)
    assert ph.intensity(45.0, 0.0) == pytest.approx(80.0)  # halfway in C
    assert ph.intensity(0.0, 22.5) == pytest.approx(90.0)  # halfway in gamma
    assert ph.intensity(45.0, 22.5) == pytest.approx((100 + 80 + 60 + 40) / 4)  # bilinear
    assert ph.intensity(315.0, 0.0) == pytest.approx(80.0)  # the wrap 270 -> 360
    assert ph.intensity(-45.0, 0.0) == pytest.approx(80.0)  # periodic
    assert ph.intensity(720.0, 45.0) == pytest.approx(80.0)
    assert ph.intensity(0.0, 120.0) == 0.0 and ph.intensity(0.0, -1.0) == 0.0  # outside
    # Broadcasting: a column of C against a row of gamma.
    out = ph.intensity(np.array([[0.0], [90.0], [45.0]]), np.array([0.0, 45.0, 90.0, 100.0]))
    assert out.shape == (3, 4)
    np.testing.assert_allclose(out[1], [60.0, 40.0, 0.0, 0.0])


def test_one_c_plane_is_the_same_in_every_direction():
    ph = downlight(1000.0, 2.0)
    np.testing.assert_allclose(ph.intensity([0, 33.3, 181, 359.9], 30.0), ph.intensity(0, 30.0))


def test_photometry_is_frozen_and_checked():
    ph = lambertian_panel(1000.0)
    with pytest.raises(ValueError):
        ph.candela[0, 0] = 5.0
    with pytest.raises(PhotometryError, match="shape"):
        Photometry("C", [0.0, 90.0], [0.0, 90.0], [[1.0, 2.0]])
    with pytest.raises(PhotometryError, match="do not increase"):
        Photometry("C", [0.0], [0.0, 90.0, 45.0], [[1.0, 2.0, 3.0]])
    with pytest.raises(PhotometryError, match=">= 0"):
        Photometry("C", [0.0], [0.0, 90.0], [[1.0, -2.0]])
    with pytest.raises(PhotometryError, match=r"\[0, 360\)"):
        Photometry("C", [0.0, 360.0], [0.0, 90.0], [[1.0, 2.0], [1.0, 2.0]])


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: downlight(-5.0), "lumens"),
        (lambda: downlight(1000.0, n=-1.0), "n = -1.0"),
        (lambda: downlight(1000.0, watts=0.0), "watts"),
        (lambda: downlight(1000.0, gamma_step_deg=7.0), "does not divide"),
        (lambda: batwing_linear(1000.0, peak_deg=60.0), "peak_deg"),
        (lambda: lambertian_panel(float("nan")), "lumens"),
        (lambda: tabulate(lambda c, g: 0 * g, [0.0], [0.0, 90.0], lumens=5.0), "no light"),
    ],
)
def test_analytic_arguments_are_checked(call, fragment):
    with pytest.raises(PhotometryError, match=re.escape(fragment)):
        call()


# ---------------------------------------------------------------------------------------
# Round trips for every symmetry


def _sample(symmetry: str, *, absolute: bool = False) -> Photometry:
    """A 24 x 37 full-sphere table with exactly the given mirror symmetry."""

    def shape(c, g):
        cr, gr = np.radians(c), np.radians(g)
        base = 100.0 + 50.0 * np.cos(gr)
        s = np.sin(gr)
        return (
            base
            * {
                AXIAL: 1.0 + 0.0 * cr,
                QUADRANT: 1.0 + 0.3 * np.cos(2 * cr) * s,
                BILATERAL_C0: 1.0 + 0.3 * np.cos(cr) * s,
                BILATERAL_C90: 1.0 + 0.3 * np.sin(cr) * s,
                NONE: 1.0 + 0.3 * np.cos(cr) * s + 0.2 * np.sin(2 * cr) * s,
            }[symmetry]
        )

    ph = tabulate(
        shape,
        np.arange(24) * 15.0,
        np.linspace(0.0, 180.0, 37),
        lumens=None if absolute else 5000.0,
        watts=40.0,
        size_m=(0.3, 1.2, 0.05),
        name=f"Sample {symmetry}",
        catalogue_number=f"S-{symmetry}",
    )
    assert ph.symmetry() == symmetry
    return ph


SYMMETRIES = [AXIAL, QUADRANT, BILATERAL_C0, BILATERAL_C90, NONE]
IES_PLANES = {AXIAL: 1, QUADRANT: 7, BILATERAL_C0: 13, BILATERAL_C90: 13, NONE: 25}
LDT_ISYM = {AXIAL: 1, QUADRANT: 4, BILATERAL_C0: 2, BILATERAL_C90: 3, NONE: 0}


def _same(a: Photometry, b: Photometry, atol: float = 1e-9) -> None:
    """The same table (an axial one may come back as one plane) and the same header."""
    if b.c_angles.size == a.c_angles.size:
        np.testing.assert_allclose(b.c_angles, a.c_angles, atol=1e-9)
        np.testing.assert_allclose(b.candela, a.candela, rtol=1e-6, atol=atol)
    else:
        assert b.symmetry() == a.symmetry() == AXIAL
    np.testing.assert_allclose(b.gamma_angles, a.gamma_angles, atol=1e-9)
    c = np.arange(0.0, 360.0, 7.5)[:, None]
    g = np.linspace(0.0, 180.0, 97)[None, :]
    np.testing.assert_allclose(b.intensity(c, g), a.intensity(c, g), rtol=1e-6, atol=atol)
    assert (b.lamp_lumens is None) == (a.lamp_lumens is None)
    if a.lamp_lumens is not None:
        assert b.lamp_lumens == pytest.approx(a.lamp_lumens, rel=1e-9)
    assert b.input_watts == pytest.approx(a.input_watts)
    np.testing.assert_allclose(b.opening, a.opening, atol=1e-9)
    assert (b.name, b.manufacturer, b.catalogue_number) == (
        a.name,
        a.manufacturer,
        a.catalogue_number,
    )
    assert b.flux() == pytest.approx(a.flux(), rel=1e-6)


@pytest.mark.parametrize("symmetry", SYMMETRIES)
def test_ies_round_trip_stores_the_fewest_planes(tmp_path, symmetry):
    ph = _sample(symmetry)
    path = tmp_path / "x.ies"
    write_ies(ph, path)
    lines = path.read_text().splitlines()
    numbers = lines[lines.index("TILT=NONE") + 1].split()
    assert int(numbers[4]) == IES_PLANES[symmetry]
    _same(ph, read_ies(path))


@pytest.mark.parametrize("symmetry", SYMMETRIES)
def test_ldt_round_trip_stores_the_fewest_planes(tmp_path, symmetry):
    ph = _sample(symmetry)
    path = tmp_path / "x.ldt"
    write_ldt(ph, path)
    assert int(path.read_text().splitlines()[2]) == LDT_ISYM[symmetry]
    _same(ph, read_ldt(path))


@pytest.mark.parametrize("writer, reader", [(write_ies, read_ies), (write_ldt, read_ldt)])
def test_absolute_photometry_round_trips(tmp_path, writer, reader):
    ph = _sample(QUADRANT, absolute=True)
    writer(ph, tmp_path / "abs.file")
    back = reader(tmp_path / "abs.file")
    assert back.lamp_lumens is None
    _same(ph, back)


def test_an_uneven_grid_without_symmetry_round_trips(tmp_path):
    ph = Photometry(
        "C",
        [0.0, 10.0, 45.0, 200.0],
        [0.0, 30.0, 90.0, 170.0],
        [[5.0, 4.0, 3.0, 1.0], [6.0, 4.0, 2.0, 0.0], [7.0, 5.0, 1.0, 0.0], [9.0, 1.0, 0.0, 0.0]],
        lamp_lumens=100.0,
        name="uneven",
    )
    for name in ("u.ies", "u.ldt"):
        write_ies(ph, tmp_path / name) if name.endswith("ies") else write_ldt(ph, tmp_path / name)
        _same(ph, read_photometry(tmp_path / name))


# ---------------------------------------------------------------------------------------
# LM-63 headers of each revision, keywords, tilt, layouts


def test_lm63_2002_keywords_and_more():
    text = _sub(IES_OK, "[LUMINAIRE] Sample downlight\n", "[LUMINAIRE] Sample\n[MORE] downlight\n")
    text = _sub(text, "[TEST] sample\n", "[TEST] sample\n[LUMCAT] AC-1\n[LAMP] LED 1000 lm\n")
    ph = parse_ies(text, "s.ies")
    assert (ph.name, ph.manufacturer, ph.catalogue_number) == ("Sample downlight", "Acme", "AC-1")
    assert ph.lamp == "LED 1000 lm" and ph.lamp_lumens == 1000.0 and ph.input_watts == 10.0
    # Quadrant symmetry expanded: eight planes, mirrored.
    np.testing.assert_allclose(ph.c_angles, np.arange(8) * 45.0)
    np.testing.assert_allclose(ph.intensity([135, 180, 225, 270, 315], 0.0), [90, 100, 90, 80, 90])


def test_lm63_1995_applies_the_ballast_lamp_factor():
    text = _sub(IES_OK, "IESNA:LM-63-2002", "IESNA:LM-63-1995")
    text = _sub(text, "1 1000 1 3 3", "2 500 2 3 3")
    text = _sub(text, "\n1 1 10\n", "\n0.9 0.5 10\n")
    ph = parse_ies(text, "s.ies")
    assert ph.candela[0, 0] == pytest.approx(100 * 2 * 0.9 * 0.5)
    assert ph.lamp_lumens == 1000.0 and ph.n_lamps == 2


def test_lm63_2019_ignores_the_file_generation_type_and_reads_absolute():
    text = _sub(IES_OK, "IESNA:LM-63-2002", "IES:LM-63-2019\n[TESTLAB] Lab\n[ISSUEDATE] 2024")
    text = _sub(text, "1 1000 1 3 3", "1 -1 2 3 3")
    text = _sub(text, "\n1 1 10\n", "\n0.5 1.10000 10\n")
    ph = parse_ies(text, "s.ies")
    assert ph.lamp_lumens is None and ph.candela[0, 0] == pytest.approx(100 * 2 * 0.5)


def test_lm63_1986_without_version_line_takes_its_name_from_the_header():
    text = _sub(IES_OK, "IESNA:LM-63-2002\n[TEST] sample\n[MANUFAC] Acme\n[LUMINAIRE] ", "")
    text = "Acme 1986 " + text
    ph = parse_ies(text, "old.ies")
    assert ph.name == "Acme 1986 Sample downlight" and ph.candela.shape == (8, 3)
    assert any("1986" in note for note in ph.notes)
    ph91 = parse_ies("IESNA91\n" + text, "old.ies")
    np.testing.assert_array_equal(ph91.candela, ph.candela)


def test_tilt_include_is_read_ignored_and_a_warning():
    text = _sub(IES_OK, "TILT=NONE\n", "TILT=INCLUDE\n1\n3\n0 45\n90\n1.0 0.95 0.9\n")
    ph = parse_ies(text, "t.ies")
    np.testing.assert_array_equal(ph.candela, parse_ies(IES_OK, "t.ies").candela)
    # It changes the light (the lamp's tilt is not accounted for): a warning, not a note.
    assert ph.warnings == (
        "TILT=INCLUDE: the lamp-tilt factors (3 angles, 0.9 to 1) are not applied; "
        "the light is computed with the lamp as photometered",
    )
    assert not any("TILT" in note for note in ph.notes)
    assert parse_ies(IES_OK, "t.ies").warnings == ()


def test_numbers_in_any_layout_commas_crlf_and_feet():
    body = (
        "1,1000,1\n3 3 1\n1\n3.28084 6.56168 0\r\n1 1 10 0 45\n90 0 45 90 100\n80,0 90 70 0 80 60 0"
    )
    text = IES_OK.split("TILT=NONE\n")[0].replace("\n", "\r\n") + "TILT=NONE\r\n" + body
    ph = parse_ies(text, "layout.ies")
    np.testing.assert_array_equal(ph.candela, parse_ies(IES_OK, "x").candela)
    np.testing.assert_allclose(ph.opening, (1.0, 2.0, 0.0), rtol=1e-6)  # feet -> m


@pytest.mark.parametrize(
    "h_angles, rows, expect_c, probe",
    [
        ("0", "1 2 3", [0.0], {(123.0, 0.0): 1.0}),
        ("0 90 180", "1 2 3 4 5 6 7 8 9", [0, 90, 180, 270], {(270.0, 0.0): 4.0}),
        ("90 180 270", "1 2 3 4 5 6 7 8 9", [0, 90, 180, 270], {(0.0, 0.0): 4.0}),
        ("0 120 240", "1 2 3 4 5 6 7 8 9", [0, 120, 240], {(300.0, 0.0): 4.0}),
        ("0 90 180 270 360", "1 2 3 4 5 6 7 8 9 1 2 3 9 9 9", [0, 90, 180, 270], {}),
    ],
)
def test_horizontal_symmetries_expand_to_the_full_circle(h_angles, rows, expect_c, probe):
    n_h = len(h_angles.split())
    text = f"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 {n_h} 1 2 0 0 0\n1 1 0\n0 45 90\n"
    ph = parse_ies(f"{text}{h_angles}\n{rows}\n", "h.ies")
    np.testing.assert_allclose(ph.c_angles, expect_c)
    for (c, g), value in probe.items():
        assert ph.intensity(c, g) == pytest.approx(value)


def test_vertical_ranges_upper_and_full():
    up = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 0\n90 135 180\n0\n0 50 100\n"
    ph = parse_ies(up, "up.ies")
    assert ph.intensity(0.0, 45.0) == 0.0 and ph.intensity(0.0, 180.0) == 100.0
    assert ph.flux(90.0) == 0.0 and ph.flux() > 0


def test_type_b_is_stored_but_not_used(tmp_path):
    text = _sub(IES_OK, "1 1000 1 3 3 1 2", "1 1000 1 3 3 2 2")
    text = _sub(text, "0 45 90\n0 45 90\n", "-90 0 90\n-90 0 90\n")
    ph = parse_ies(text, "b.ies")
    assert ph.kind == "B" and ph.candela.shape == (3, 3)
    with pytest.raises(PhotometryError, match="type C"):
        ph.intensity(0.0, 0.0)
    with pytest.raises(PhotometryError, match="type C"):
        ph.flux()
    with pytest.raises(PhotometryError, match="EULUMDAT holds type C"):
        write_ldt(ph, tmp_path / "b.ldt")
    write_ies(ph, tmp_path / "b.ies")
    back = read_ies(tmp_path / "b.ies")
    assert back.kind == "B"
    np.testing.assert_allclose(back.candela, ph.candela)


# ---------------------------------------------------------------------------------------
# EULUMDAT: layout, symmetry, conversion to candela, encodings


def test_ldt_sample_symmetry_and_candela():
    ph = parse_ldt(LDT_OK, "s.ldt")
    assert (ph.name, ph.manufacturer, ph.catalogue_number, ph.lamp) == (
        "Sample LDT",
        "Acme",
        "L-1",
        "LED",
    )
    assert ph.lamp_lumens == 1000.0 and ph.input_watts == 10.0
    assert ph.opening == (0.1, 0.1, 0.0)
    np.testing.assert_allclose(ph.c_angles, [0, 90, 180, 270])
    # cd = cd/klm x 1000 lm / 1000 x conversion factor 1; C180 mirrors C0, C270 C90.
    np.testing.assert_allclose(ph.candela[:, 0], [300, 280, 300, 280])


def test_ldt_conversion_factor_lamp_flux_and_absolute():
    text = _sub(LDT_OK, "\n80\n1\n0\n", "\n80\n1.5\n0\n")  # conversion factor 1.5
    text = _sub(text, "\nLED\n1000\n", "\nLED\n2000\n")  # 2000 lm of lamps
    assert parse_ldt(text, "s.ldt").candela[0, 0] == pytest.approx(300 * 2 * 1.5)
    absolute = _sub(LDT_OK, "\n1\n1\nLED\n", "\n1\n-1\nLED\n")
    ph = parse_ldt(absolute, "s.ldt")
    assert ph.lamp_lumens is None and ph.candela[0, 0] == 300.0


def test_ldt_isym_3_stores_c270_to_c90():
    lines = LDT_OK.splitlines()
    lines[2] = "3"  # Isym 3: planes C270, C0, C90 stored (Mc/2 + 1 = 3)
    lines[49:] = ["10", "9", "0", "20", "19", "0", "30", "29", "0"]
    ph = parse_ldt("\n".join(lines), "s.ldt")
    np.testing.assert_allclose(ph.candela[:, 0], [20, 30, 20, 10])  # C0, C90, C180, C270


def test_ldt_isym_2_and_0_and_1():
    lines = LDT_OK.splitlines()
    lines[2] = "2"  # C0, C90, C180 stored
    lines[49:] = ["10", "9", "0", "20", "19", "0", "30", "29", "0"]
    ph = parse_ldt("\n".join(lines), "s.ldt")
    np.testing.assert_allclose(ph.candela[:, 0], [10, 20, 30, 20])
    lines[2] = "0"
    lines[49:] = ["10", "9", "0", "20", "19", "0", "30", "29", "0", "40", "39", "0"]
    np.testing.assert_allclose(parse_ldt("\n".join(lines), "s").candela[:, 0], [10, 20, 30, 40])
    lines[2] = "1"
    lines[49:] = ["10", "9", "0"]
    ph = parse_ldt("\n".join(lines), "s.ldt")
    assert ph.candela.shape == (1, 3) and ph.symmetry() == AXIAL


def test_ldt_encodings_crlf_and_decimal_comma(tmp_path):
    text = _sub(LDT_OK, "Acme\n", "Lichtfabrik Müller\n").replace("\n", "\r\n")
    text = _sub(text, "\r\n80\r\n1\r\n", "\r\n80,5\r\n1,0\r\n")
    for encoding in ("latin-1", "utf-8"):
        path = tmp_path / f"{encoding}.ldt"
        path.write_bytes(text.encode(encoding))
        ph = read_ldt(path)
        assert ph.manufacturer == "Lichtfabrik Müller" and ph.candela[0, 0] == 300.0


# ---------------------------------------------------------------------------------------
# Cross-check with independent MIT code: eulumdat-py (pyldt) and eulumdat-ies


def _ldt_files(tmp_path) -> list[Path]:
    out = sorted(BUILTIN_FOLDER.glob("*.ldt"))
    for symmetry in SYMMETRIES:
        path = tmp_path / f"{symmetry}.ldt"
        write_ldt(_sample(symmetry), path)
        out.append(path)
    return out


def test_eulumdat_py_reads_our_ldt_files_the_same(tmp_path):
    for path in _ldt_files(tmp_path):
        ours, theirs = read_ldt(path), LdtReader.read(path)
        h = theirs.header
        assert (h.company, h.luminaire_name, h.luminaire_number) == (
            ours.manufacturer,
            ours.name,
            ours.catalogue_number,
        )
        assert (h.isym, h.ng, h.n_sets) == (
            int(path.read_text().splitlines()[2]),
            ours.gamma_angles.size,
            1,
        )
        np.testing.assert_allclose(h.g_angles, ours.gamma_angles)
        assert h.num_lamps == [ours.n_lamps] and h.lamp_types == [ours.lamp]
        assert h.lamp_flux == [pytest.approx(ours.lamp_lumens)]
        assert h.lamp_watt == [pytest.approx(ours.input_watts)]
        assert h.conv_factor == 1.0 and h.tilt == 0.0
        assert (h.width_lum_area, h.length_lum_area, h.h_lum_c0) == pytest.approx(
            [1000 * x for x in ours.opening]
        )
        assert h.lorl == pytest.approx(100 * ours.flux() / ours.lamp_lumens, rel=1e-6)
        assert h.dff == pytest.approx(100 * ours.flux(90) / ours.flux(), rel=1e-6)
        # Every intensity: theirs is cd/klm on the full Mc x Ng grid.
        theirs_cd = np.array(theirs.intensities) * ours.lamp_lumens / 1000.0
        assert theirs_cd.shape == (h.mc, h.ng)
        mine = ours.intensity(np.array(h.c_angles)[:, None], ours.gamma_angles[None, :])
        np.testing.assert_allclose(mine, theirs_cd, rtol=1e-12, atol=1e-9)


def test_files_written_by_eulumdat_py_read_back(tmp_path):
    for path in _ldt_files(tmp_path):
        out = tmp_path / "pyldt" / path.name
        out.parent.mkdir(exist_ok=True)
        LdtWriter.write(LdtReader.read(path), out, overwrite=True)
        _same(read_ldt(path), read_ldt(out), atol=1e-5)  # it prints 6 decimals of cd/klm


def test_eulumdat_ies_conversion_reads_as_the_same_intensities(tmp_path):
    for path in _ldt_files(tmp_path):
        ours = read_ldt(path)
        converted = parse_ies(ldt_to_ies(LdtReader.read(path)), f"{path.name} via eulumdat-ies")
        assert converted.lamp_lumens == pytest.approx(ours.lamp_lumens)
        assert converted.input_watts == pytest.approx(ours.input_watts, abs=0.005)
        c = np.arange(0.0, 360.0, 7.5)[:, None]
        g = ours.gamma_angles[None, :]
        # eulumdat-ies prints candela with 3 decimals.
        np.testing.assert_allclose(converted.intensity(c, g), ours.intensity(c, g), atol=6e-4)
        # (It writes the opening's length in LM-63's width slot: not compared.)


# ---------------------------------------------------------------------------------------
# Real files (tests/data/photometry, SOURCES.md there), other encodings, warnings

DATA = ROOT / "tests" / "data" / "photometry"
ROUND = DATA / "rab-round-4.ies"  # a 0.3175 m disc (IES width and length -1.041667 ft)
SQUARE = DATA / "rab-square-1.ies"  # 1.47 x 1.47 ft


def _utf16(text: str, variant: str) -> bytes:
    """``text`` as Windows tools write "Unicode": UTF-16 with a byte-order mark (either
    order), or without one."""
    order = "utf-16-le" if variant.startswith("le") else "utf-16-be"
    bom = {"utf-16-le": b"\xff\xfe", "utf-16-be": b"\xfe\xff"}[order]
    return (bom if variant.endswith("bom") else b"") + text.encode(order)


def test_real_files_integrate_to_the_flux_an_independent_program_gives():
    # Photometric Toolbox's flux of the same files (the source repository's summary).
    assert read_photometry(ROUND).flux() == pytest.approx(5821.76, rel=5e-4)
    assert read_photometry(SQUARE).flux() == pytest.approx(9217.18, rel=5e-4)
    ph = read_photometry(ROUND)
    assert ph.opening[:2] == pytest.approx((-0.3175, -0.3175), abs=1e-4)  # feet -> m, kept
    assert ph.input_watts == 88.7 and ph.lamp_lumens is None and ph.warnings == ()


@pytest.mark.parametrize("variant", ["le-bom", "be-bom", "le", "be"])
def test_utf16_ies_files_read_as_the_same_table(tmp_path, variant):
    original = read_photometry(ROUND)
    text = ROUND.read_bytes().decode("latin-1")  # the manufacturer's encoding
    for name in ("round.ies", "round.txt"):  # by extension, and by content
        path = tmp_path / name
        path.write_bytes(_utf16(text, variant))
        ph = read_photometry(path)
        np.testing.assert_array_equal(ph.candela, original.candela)
        assert ph.catalogue_number == original.catalogue_number  # a Latin-1 byte, kept
        assert (ph.name, ph.opening, ph.input_watts) == (
            original.name,
            original.opening,
            original.input_watts,
        )


@pytest.mark.parametrize("variant", ["le-bom", "be-bom", "le", "be"])
def test_utf16_ldt_files_read_as_the_same_table(tmp_path, variant):
    text = _sub(LDT_OK, "Acme\n", "Lichtfabrik Müller\n").replace("\n", "\r\n")
    for name in ("u.ldt", "u.dat"):
        path = tmp_path / name
        path.write_bytes(_utf16(text, variant))
        ph = read_photometry(path)
        assert ph.manufacturer == "Lichtfabrik Müller"
        np.testing.assert_array_equal(ph.candela, parse_ldt(LDT_OK, "x").candela)


def test_binary_data_is_still_refused_where_it_shows(tmp_path):
    for data in (b"IESNA:LM-63-2002\n\0\x01\x02", bytes(64), b"\xff\xfe" + bytes(63)):
        path = tmp_path / "bin.ies"
        path.write_bytes(data)
        with pytest.raises(PhotometryError, match="binary data"):
            read_photometry(path)


def _relative(lumens_per_lamp: float) -> str:
    """The round real file as relative photometry: ``lumens_per_lamp`` for its table."""
    text = ROUND.read_bytes().decode("latin-1")
    return _sub(text, "1 -1 0.9687 73", f"1 {lumens_per_lamp:g} 0.9687 73")


def test_a_light_output_ratio_above_100_percent_is_a_warning():
    ph = parse_ies(_relative(5000.0), "rel.ies")  # the table holds 5,820 lm
    assert ph.lamp_lumens == 5000.0
    assert ph.warnings == (
        "light output ratio 116.4%: the table integrates to 5,820 lm, more than the "
        "5,000 lm of its lamps; check the lamp lumens and the multipliers (the table is "
        "used as it is)",
    )
    # Within 1% (integration and printed digits) and below 100%: no warning.
    assert parse_ies(_relative(5800.0), "rel.ies").warnings == ()
    assert parse_ies(_relative(8000.0), "rel.ies").warnings == ()
    assert (
        parse_ies(_sub(IES_OK, "1 1000 1 3", "1 1 1 3"), "x.ies")
        .warnings[0]
        .startswith("light output ratio 2")
    )


def test_an_ldt_whose_table_exceeds_its_lamps_is_a_warning(tmp_path):
    bright = downlight(2000.0, watts=20.0)
    path = tmp_path / "bright.ldt"
    write_ldt(bright, path)
    text = _sub(path.read_text(encoding="latin-1"), "\n2000\n", "\n1600\n")  # lamp flux
    ph = parse_ldt(text, "bright.ldt")  # cd/klm x 1.6 klm: 1,601 lm from 1,600 lm lamps
    assert ph.warnings == ()
    text = _sub(text, "\n1\n0\n1\n", "\n1.25\n0\n1\n")  # conversion factor 1.25
    ph = parse_ldt(text, "bright.ldt")
    assert ph.warnings == (
        "light output ratio 125.1%: the table integrates to 2,001 lm, more than the "
        "1,600 lm of its lamps; check the lamp lumens and the multipliers (the table is "
        "used as it is)",
    )


def test_extra_lamp_sets_are_a_warning():
    lines = LDT_OK.splitlines()
    lines[25] = "2"  # line 26: two lamp sets
    lines[32:32] = ["2", "LED", "2000", "4000K", "80", "20"]
    ph = parse_ldt("\n".join(lines), "two.ldt")
    assert ph.warnings == (
        "2 lamp sets: the intensities are scaled by the first (1000 lm); the other sets "
        "are not used",
    )


def test_the_shipped_catalogue_gives_no_warnings():
    for entry in builtin_catalogue():
        assert entry.photometry().warnings == (), entry.name


def test_ldt_round_opening_reads_as_the_ies_circle_and_writes_back(tmp_path):
    lines = LDT_OK.splitlines()
    lines[15], lines[16] = "400", "0"  # luminous area: length 400 mm, width 0 (a circle)
    ph = parse_ldt("\n".join(lines), "round.ldt")
    assert ph.opening[:2] == (-0.4, -0.4)  # LM-63's code for a 0.4 m circle
    write_ldt(ph, tmp_path / "r.ldt")
    written = (tmp_path / "r.ldt").read_text(encoding="latin-1").splitlines()
    assert (written[15], written[16]) == ("400", "0")
    assert read_ldt(tmp_path / "r.ldt").opening[:2] == (-0.4, -0.4)
    write_ies(ph, tmp_path / "r.ies")
    assert read_ies(tmp_path / "r.ies").opening[:2] == pytest.approx((-0.4, -0.4))


# ---------------------------------------------------------------------------------------
# Dispatch, size limit, missing files


def test_read_photometry_by_extension_any_case_and_by_content(tmp_path):
    (tmp_path / "A.IES").write_text(IES_OK)
    (tmp_path / "B.Ldt").write_text(LDT_OK)
    (tmp_path / "c.txt").write_text(IES_OK)
    (tmp_path / "d.dat").write_text(LDT_OK)
    assert read_photometry(tmp_path / "A.IES").name == "Sample downlight"
    assert read_photometry(tmp_path / "B.Ldt").name == "Sample LDT"
    assert read_photometry(tmp_path / "c.txt").name == "Sample downlight"
    assert read_photometry(str(tmp_path / "d.dat")).name == "Sample LDT"
    (tmp_path / "e.txt").write_text("hello\nworld\n")
    with pytest.raises(PhotometryError, match=r"e\.txt: neither an IES LM-63 nor a EULUMDAT"):
        read_photometry(tmp_path / "e.txt")


def test_too_large_missing_and_folder_are_refused_unread(tmp_path):
    big = tmp_path / "big.ies"
    with open(big, "wb") as fh:
        fh.truncate(MAX_FILE_BYTES + 1_000_000)  # sparse: nothing is written, nothing read
    with pytest.raises(PhotometryError, match=r"big\.ies: 21\.0 MB is too large .*limit 20 MB"):
        read_photometry(big)
    with pytest.raises(PhotometryError, match=r"nope\.ldt: no such file; check the path"):
        read_photometry(tmp_path / "nope.ldt")
    with pytest.raises(PhotometryError, match="is a folder"):
        read_ies(tmp_path)


# ---------------------------------------------------------------------------------------
# Bad files: one line each, with the line number


def _ies_case(old: str, new: str) -> str:
    return _sub(IES_OK, old, new)


def _ldt_case(line: int, new: str) -> str:
    lines = LDT_OK.splitlines()
    lines[line - 1] = new
    return "\n".join(lines) + "\n"


BAD_PHOTOMETRY_CASES: list[tuple[str, str, str]] = [
    # (description, file text, fragment of the message). "LDT:" descriptions are
    # EULUMDAT files (read as .ldt), the others IES (read as .ies).
    ("IES: an empty file", "", ":1: the file is empty"),
    ("IES: only blank lines", "\n \n\t\n", ":1: the file is empty"),
    ("IES: binary data", "IESNA:LM-63-2002\n\0\x01\x02", ":2: binary data (NUL bytes)"),
    ("IES: no TILT line", "hello\nworld\n", ":1: no TILT= line"),
    (
        "IES: an external tilt file",
        _ies_case("TILT=NONE", "TILT=lamp.tlt"),
        ":5: TILT='lamp.tlt': external tilt files are not supported",
    ),
    (
        "IES: text where a count belongs",
        _ies_case("1 1000 1 3 3", "1 1000 1 three 3"),
        ":6: number of vertical angles: 'three' is not a number",
    ),
    (
        "IES: no vertical angles",
        _ies_case("1 1000 1 3 3", "1 1000 1 0 3"),
        ":6: number of vertical angles is 0",
    ),
    (
        "IES: an absurd number of horizontal angles",
        _ies_case("1 1000 1 3 3", "1 1000 1 3 20000"),
        ":6: number of horizontal angles is 20000; it must be a whole number from 1 to 10000",
    ),
    (
        "IES: a table too large to hold",
        _ies_case("1 1000 1 3 3", "1 1000 1 9000 9000"),
        ":6: 9000 x 9000 = 81,000,000 candela values is too many",
    ),
    (
        "IES: a fractional count",
        _ies_case("1 1000 1 3 3", "1.5 1000 1 3 3"),
        ":6: number of lamps is 1.5",
    ),
    (
        "IES: photometric type 4",
        _ies_case("1 1000 1 3 3 1 2", "1 1000 1 3 3 4 2"),
        ":6: photometric type is 4",
    ),
    ("IES: units type 3", _ies_case("3 3 1 2", "3 3 1 3"), ":6: units type is 3"),
    ("IES: zero lumens per lamp", _ies_case("1 1000 1", "1 0 1"), ":6: lumens per lamp is 0"),
    (
        "IES: a negative candela multiplier",
        _ies_case("1 1000 1", "1 1000 -2"),
        ":6: candela multiplier is -2; it must be > 0",
    ),
    (
        "IES: a zero ballast factor",
        _ies_case("\n1 1 10\n", "\n0 1 10\n"),
        ":7: ballast factor is 0",
    ),
    (
        "IES: negative input watts",
        _ies_case("\n1 1 10\n", "\n1 1 -10\n"),
        ":7: input watts is -10; it must be >= 0",
    ),
    (
        "IES: vertical angles out of order",
        _ies_case("0 45 90\n0 45 90\n", "0 90 45\n0 45 90\n"),
        ":8: vertical angle 45 does not increase (after 90)",
    ),
    (
        "IES: a vertical angle past 180",
        _ies_case("0 45 90\n0 45 90\n", "0 45 200\n0 45 90\n"),
        ":8: vertical angle 200 is outside 0..180",
    ),
    (
        "IES: horizontal angles ending at 120",
        _ies_case("0 45 90\n0 45 90\n", "0 45 90\n0 60 120\n"),
        ":9: type C horizontal angles run from 0 to 120",
    ),
    (
        "IES: a negative candela value",
        _ies_case("90 70 0", "90 -70 0"),
        ":11: negative candela value -70",
    ),
    (
        "IES: NaN candela",
        _ies_case("90 70 0", "90 nan 0"),
        ":11: candela values: 'nan' is not a number",
    ),
    (
        "IES: a candela value too large with its multiplier",
        _ies_case("1 1000 1 3 3", "1 1000 1e11 3 3"),
        ":10: an intensity of 1e+13 cd (with the file's multipliers) is absurd",
    ),
    ("LDT: an absurd lamp flux", _ldt_case(29, "1e12"), ":29: lamp flux 1e+12 lm is absurd"),
    (
        "IES: infinite candela",
        _ies_case("90 70 0", "90 1e999 0"),
        ":11: candela values: '1e999' is too large",
    ),
    (
        "IES: a truncated table",
        _ies_case("80 60 0\n", "80 60\n"),
        ":12: the file ends after 8 of 9 candela values; the file is truncated",
    ),
    (
        "IES: the file ends after TILT",
        IES_OK.split("TILT=NONE")[0] + "TILT=NONE\n",
        ":5: the file ends before the number of lamps",
    ),
    (
        "IES: too many values",
        _ies_case("80 60 0\n", "80 60 0\n7\n"),
        ":13: unexpected '7' after the 9 candela values; too many values",
    ),
    (
        "IES: a truncated tilt table",
        "TILT=INCLUDE\n1\n3\n0 45 90\n1 1\n",
        ":5: the file ends after 2 of 3 tilt multiplying factors",
    ),
    (
        "LDT: a truncated header",
        "\n".join(LDT_OK.splitlines()[:20]) + "\n",
        ":20: the file ends before line 21",
    ),
    ("LDT: Isym 5", _ldt_case(3, "5"), ":3: symmetry indicator Isym is 5"),
    ("LDT: no C planes", _ldt_case(4, "0"), ":4: number of C planes Mc is 0"),
    ("LDT: Mc not divisible for Isym 4", _ldt_case(4, "6"), ":4: Mc = 6 C planes with Isym = 4"),
    (
        "LDT: text where a size belongs",
        _ldt_case(13, "abc"),
        ":13: expected luminaire length (mm) (one number), found 'abc'",
    ),
    ("LDT: an empty numeric line", _ldt_case(23, ""), ":23: expected light output ratio LORL"),
    ("LDT: no lamps", _ldt_case(27, "0"), ":27: number of lamps is 0"),
    ("LDT: zero lamp flux", _ldt_case(29, "0"), ":29: total luminous flux of the lamps (lm) is 0"),
    (
        "LDT: zero conversion factor",
        _ldt_case(24, "0"),
        ":24: conversion factor for intensities is 0",
    ),
    ("LDT: C angles out of order", _ldt_case(45, "60"), ":45: C angle 60 does not increase"),
    ("LDT: a gamma angle past 180", _ldt_case(49, "190"), ":49: gamma angle 190 is outside 0..180"),
    (
        "LDT: the C90 plane missing for Isym 4",
        _ldt_case(44, "80"),
        ":44: C angle 2 is 80, Isym = 4 needs 90 there",
    ),
    ("LDT: a negative intensity", _ldt_case(52, "-3"), ":52: negative intensity -3"),
    (
        "LDT: truncated intensities",
        "\n".join(LDT_OK.splitlines()[:53]) + "\n",
        ":53: the file ends after 4 of 6 intensities (cd/klm)",
    ),
    (
        "LDT: too many intensities",
        LDT_OK + "5\n",
        ":56: unexpected '5' after the 6 intensities",
    ),
    (
        "LDT: NaN intensity",
        _ldt_case(51, "NaN"),
        ":51: intensities (cd/klm): 'NaN' is not a number",
    ),
]


@pytest.mark.parametrize(
    "description, text, fragment", BAD_PHOTOMETRY_CASES, ids=[c[0] for c in BAD_PHOTOMETRY_CASES]
)
def test_bad_files_give_one_line_with_the_line_number(tmp_path, description, text, fragment):
    path = tmp_path / ("case.ldt" if description.startswith("LDT:") else "case.ies")
    path.write_bytes(text.encode("utf-8"))
    with pytest.raises(PhotometryError) as info:
        read_photometry(path)
    message = str(info.value)
    assert "\n" not in message and "\r" not in message
    assert re.match(re.escape(str(path)) + r":\d+: [^;]+; .+", message), message
    assert fragment in message, message


def _mutate(data: bytes, ops) -> bytes:
    for kind, where, payload in ops:
        pos = int(where * len(data))
        if kind == "truncate":
            data = data[:pos]
        elif kind == "delete":
            data = data[:pos] + data[pos + len(payload) :]
        elif kind == "insert":
            data = data[:pos] + payload + data[pos:]
        else:  # overwrite
            data = data[:pos] + payload + data[pos + len(payload) :]
    return data


NASTY = [b"nan", b"-1", b"1e309", b"0", b"-0", b",", b"\x00", b"360", b"1e-320", b"99999999"]
NASTY += [b"\n", b"\r", b"TILT=INCLUDE\n", b"[MORE]", b"abc", b"\xff\xfe", b" ", b"-", b"."]
OPS = st.lists(
    st.tuples(
        st.sampled_from(["truncate", "delete", "insert", "overwrite"]),
        st.floats(0.0, 1.0),
        st.one_of(st.sampled_from(NASTY), st.binary(min_size=1, max_size=4)),
    ),
    min_size=1,
    max_size=4,
)
BASES = [
    (IES_OK.encode(), parse_ies),
    (LDT_OK.encode(), parse_ldt),
    ((BUILTIN_FOLDER / "batwing-linear-4000lm.ies").read_bytes(), parse_ies),
    ((BUILTIN_FOLDER / "downlight-2000lm.ldt").read_bytes(), parse_ldt),
]


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(base=st.sampled_from(range(len(BASES))), ops=OPS)
def test_fuzzed_files_give_a_photometry_error_or_a_valid_table(base, ops):
    data, parse = BASES[base]
    try:
        ph = parse(_mutate(data, ops), "fuzz")
    except PhotometryError as exc:
        assert "\n" not in str(exc) and str(exc).startswith("fuzz")
    else:
        if ph.kind == "C":
            assert math.isfinite(ph.flux()) and ph.flux() >= 0


# ---------------------------------------------------------------------------------------
# The shipped catalogue


def test_shipped_catalogue_matches_its_files():
    entries = builtin_catalogue()
    assert [e.name for e in entries] == [
        "Downlight 2000 lm 20 W",
        "Linear batwing 4000 lm 32 W",
        "Panel 600 x 600 3600 lm 30 W",
        "Recessed panel 600 x 600 3400 lm 27 W",
        "Linear direct/indirect 1500 mm 4800 lm 36 W",
        "Downlight 150 mm reflector 1800 lm 16 W",
    ]
    for e in entries:
        ph = e.photometry()
        assert ph.flux() == pytest.approx(e.lumens, rel=0.005)
        assert ph.input_watts == e.watts and ph.opening == e.size
        assert e.efficacy == pytest.approx(e.lumens / e.watts)
    assert [e.efficacy for e in entries] == pytest.approx(
        [100.0, 125.0, 120.0, 3400 / 27, 4800 / 36, 1800 / 16]
    )
    twin = read_photometry(BUILTIN_FOLDER / "downlight-2000lm.ies")
    _same(entries[0].photometry(), twin)


def test_shipped_files_are_exactly_what_generate_builtin_writes(tmp_path):
    written = generate_builtin(tmp_path)
    shipped = sorted(p.name for p in BUILTIN_FOLDER.iterdir())
    assert sorted(p.name for p in written) == shipped
    for path in written:
        assert path.read_bytes() == (BUILTIN_FOLDER / path.name).read_bytes(), path.name


def test_the_resources_folder_is_where_the_bundle_ships_it():
    assert BUILTIN_FOLDER == ROOT / "resources" / "luminaires"
    spec = (ROOT / "packaging" / "lightinv.spec").read_text()
    assert '(str(ROOT / "resources"), "resources")' in spec


MODULE = "lightinv_core.luminaires.catalogue"


def test_the_module_command_regenerates_the_files(tmp_path):
    out = subprocess.run(
        [sys.executable, "-W", "error", "-m", MODULE, "--write", str(tmp_path)],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert out.returncode == 0, out.stderr
    assert len(out.stdout.splitlines()) == 11 and (tmp_path / "catalogue.json").is_file()


def _catalogue(tmp_path, entries) -> Path:
    (tmp_path / "a.ies").write_text(IES_OK)
    path = tmp_path / "catalogue.json"
    path.write_text(json.dumps({"version": 1, "luminaires": entries}, indent=2))
    return path


GOOD = {"name": "A", "file": "a.ies", "lumens": 1000, "watts": 10, "size_m": [0.1, 0.1, 0]}


@pytest.mark.parametrize(
    "entries, fragment",
    [
        (
            [{**GOOD, "file": "missing.ldt"}],
            ":5: luminaire 'A': photometric file 'missing.ldt' not",
        ),
        ([{**GOOD, "lumens": "lots"}], ":5: luminaire 'A': lumens = 'lots'; give a positive"),
        ([{**GOOD, "watts": -1}], "luminaire 'A': watts = -1"),
        ([{**GOOD, "watts": True}], "luminaire 'A': watts = True"),
        ([{**GOOD, "size_m": [1, 2]}], "luminaire 'A': size_m = [1, 2]"),
        ([GOOD, GOOD], ":16: luminaire 'A' appears twice"),
        ([{**GOOD, "name": ""}], "luminaire 1 has no name"),
        ([{**GOOD, "file": None}], "luminaire 'A' has no \"file\""),
    ],
)
def test_bad_catalogues_name_the_entry(tmp_path, entries, fragment):
    path = _catalogue(tmp_path, entries)
    with pytest.raises(PhotometryError) as info:
        read_catalogue(path)
    assert fragment in str(info.value) and "\n" not in str(info.value)


def test_catalogue_file_problems(tmp_path):
    good = read_catalogue(_catalogue(tmp_path, [GOOD]))
    assert good[0].efficacy == 100.0 and good[0].photometry().name == "Sample downlight"
    with pytest.raises(PhotometryError, match="no such file"):
        read_catalogue(tmp_path / "none.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{\n  "luminaires": [\n    {"name": "A",,}\n  ]\n}\n')
    with pytest.raises(PhotometryError, match=r"bad\.json:3: not valid JSON"):
        read_catalogue(bad)
    bad.write_text('{"luminaires": {}}')
    with pytest.raises(PhotometryError, match='no "luminaires" list'):
        read_catalogue(bad)


def test_importing_the_package_does_not_import_the_catalogue_module():
    code = (
        "import sys, lightinv_core.luminaires as L\n"
        "assert 'lightinv_core.luminaires.catalogue' not in sys.modules\n"
        "assert L.builtin_catalogue and 'lightinv_core.luminaires.catalogue' in sys.modules\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)
