"""EULUMDAT (.ldt) photometric files: reading and writing.

The layout is fixed by line: 1-12 identification, Ityp, Isym, Mc, Dc, Ng, Dg; 13-21
sizes (mm); 22-25 DFF, LORL, conversion factor, tilt; 26 the number n of lamp sets,
then six lines per set (number of lamps, type, total flux, colour, colour rendering,
watts); then, as numbers in any layout, the 10 direct ratios, Mc C angles, Ng gamma
angles and the stored planes' intensities in cd/klm: Isym 0 all Mc planes, 1 one plane,
2 C0..C180, 3 C270..C360..C90, 4 C0..C90.

Intensities in candela (what ``Photometry.candela`` holds) are

    I [cd] = value [cd/klm] x F / 1000 x conversion factor,

where F is the total luminous flux of the FIRST lamp set (line 26c): the flux the
table is relative to. LORL is not applied: cd/klm in EULUMDAT already include the
luminaire's losses (its light output ratio). Further lamp sets are alternatives:
not added, and a warning. A negative number of lamps marks absolute photometry (the
DIAL/Lighting Analysts convention of 2009: F is then the luminaire's flux); it gives
``lamp_lumens = None`` and the same candela formula.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from lightinv_core.atomic import atomic_writer
from lightinv_core.luminaires.photometry import (
    ANGLE_TOL,
    AXIAL,
    BILATERAL_C0,
    BILATERAL_C90,
    MIRRORS,
    NONE,
    QUADRANT,
    Photometry,
    expand_c,
    fail,
    with_output_ratio_warning,
)
from lightinv_core.luminaires.textfile import (
    MAX_ANGLES,
    MAX_LUMENS,
    MAX_VALUES,
    Tokens,
    check_angles,
    check_candela,
    check_intensities,
    decode_lines,
    fmt_number,
    one_line,
    parse_number,
    read_bytes,
)

MAX_LAMP_SETS = 100
TEXT_WIDTH = 78  # characters of a text line, per the format


def read_ldt(path: str | os.PathLike) -> Photometry:
    """Read a EULUMDAT file; every problem with it is a one-line PhotometryError."""
    return parse_ldt(read_bytes(path), str(path))


class _Fixed:
    """The fixed-position lines of the header, read by 1-based line number."""

    def __init__(self, lines: list[str], source: str) -> None:
        self.lines = lines
        self.source = source

    def text(self, k: int, what: str) -> str:
        if k > len(self.lines):
            raise fail(
                self.source,
                len(self.lines),
                f"the file ends before line {k} ({what})",
                "the file is truncated or not EULUMDAT: export it again",
            )
        return self.lines[k - 1].strip()

    def number(self, k: int, what: str) -> float:
        text = self.text(k, what)
        value = parse_number(text.replace(",", "."))  # some writers use a decimal comma
        if value is None:
            shown = "an empty line" if not text else f"'{text[:24]}'"
            raise fail(
                self.source,
                k,
                f"expected {what} (one number), found {shown}",
                "check the line layout of the EULUMDAT file",
            )
        return value

    def integer(self, k: int, what: str, lo: int, hi: int) -> int:
        value = self.number(k, what)
        if value != int(value) or not lo <= value <= hi:
            raise fail(
                self.source,
                k,
                f"{what} is {value:g}",
                f"it must be a whole number from {lo} to {hi}",
            )
        return int(value)

    def positive(self, k: int, what: str, allow_zero: bool = False) -> float:
        value = self.number(k, what)
        if value < 0 or (value == 0 and not allow_zero):
            raise fail(
                self.source,
                k,
                f"{what} is {value:g}",
                f"it must be {'>=' if allow_zero else '>'} 0",
            )
        return value


def _stored_count(isym: int, mc: int, source: str) -> int:
    """How many C planes a file with this Isym stores."""
    need = {2: 2, 3: 4, 4: 4}.get(isym, 1)
    if mc % need:
        raise fail(
            source,
            4,
            f"Mc = {mc} C planes with Isym = {isym}",
            f"Isym {isym} needs Mc divisible by {need}",
        )
    return {0: mc, 1: 1, 2: mc // 2 + 1, 3: mc // 2 + 1, 4: mc // 4 + 1}[isym]


def _stored_angles(isym: int, c: np.ndarray, c_lines: list[int], source: str) -> np.ndarray:
    """The C angles of the stored planes, in file order; checks the planes Isym needs."""
    mc = c.size

    def at(k: int, angle: float) -> None:
        if abs(c[k] - angle) > ANGLE_TOL:
            raise fail(
                source,
                c_lines[k],
                f"C angle {k + 1} is {c[k]:g}, Isym = {isym} needs {angle:g} there",
                "check Isym and the C angles",
            )

    if isym == 2:
        at(0, 0.0)
        at(mc // 2, 180.0)
        return c[: mc // 2 + 1]
    if isym == 3:
        at(mc // 4, 90.0)
        at(3 * mc // 4, 270.0)
        return np.concatenate([c[3 * mc // 4 :], c[: mc // 4 + 1]])
    if isym == 4:
        at(0, 0.0)
        at(mc // 4, 90.0)
        return c[: mc // 4 + 1]
    return c


def parse_ldt(data: bytes | str, source: str = "<ldt>") -> Photometry:
    """Parse the text (or bytes) of a EULUMDAT file; ``source`` names it in messages."""
    lines = decode_lines(data, source)
    f = _Fixed(lines, source)
    company = f.text(1, "company")
    f.integer(2, "type indicator Ityp", 0, 3)
    isym = f.integer(3, "symmetry indicator Isym", 0, 4)
    mc = f.integer(4, "number of C planes Mc", 1, MAX_ANGLES)
    f.number(5, "C plane step Dc")
    ng = f.integer(6, "number of gamma angles Ng", 2, MAX_ANGLES)
    f.number(7, "gamma step Dg")
    name, number = f.text(9, "luminaire name"), f.text(10, "luminaire number")
    f.text(12, "date/user")
    sizes = [f.number(k, what) for k, what in enumerate(_SIZES, start=13)]
    f.number(22, "downward flux fraction DFF (%)")
    f.number(23, "light output ratio LORL (%)")
    conversion = f.positive(24, "conversion factor for intensities")
    f.number(25, "tilt during measurement")
    n_sets = f.integer(26, "number of lamp sets", 1, MAX_LAMP_SETS)
    lamps = f.integer(27, "number of lamps", -10_000, 10_000)
    if lamps == 0:
        raise fail(source, 27, "number of lamps is 0", "give the lamp count (negative: absolute)")
    lamp_type = f.text(28, "lamp type")
    lamp_flux = f.positive(29, "total luminous flux of the lamps (lm)")
    if lamp_flux > MAX_LUMENS:
        raise fail(source, 29, f"lamp flux {lamp_flux:g} lm is absurd", "check the value")
    watts = f.positive(32, "wattage including ballast (W)", allow_zero=True)
    for s in range(1, n_sets):  # the alternatives: checked, not used
        f.integer(27 + 6 * s, "number of lamps", -10_000, 10_000)
        f.positive(29 + 6 * s, "total luminous flux of the lamps (lm)")
        f.positive(32 + 6 * s, "wattage including ballast (W)", allow_zero=True)

    stored = _stored_count(isym, mc, source)
    if stored * ng > MAX_VALUES:
        raise fail(
            source,
            6,
            f"{stored} x {ng} intensities is too many",
            f"this reader takes at most {MAX_VALUES:,}",
        )
    tokens = Tokens(lines, 26 + 6 * n_sets, source, separators=r"[\s\x1a]+", decimal_comma=True)
    tokens.numbers(10, "direct ratios")
    c, c_lines = tokens.numbers(mc, "C angles")
    check_angles(source, c, c_lines, "C angle", 0.0, 360.0)
    g, g_lines = tokens.numbers(ng, "gamma angles")
    check_angles(source, g, g_lines, "gamma angle", 0.0, 180.0)
    values, value_lines = tokens.numbers(stored * ng, "intensities (cd/klm)")
    check_intensities(source, values, value_lines)
    tokens.expect_end(f"the {stored * ng} intensities")

    scale = lamp_flux / 1000.0 * conversion
    check_candela(source, values, scale, value_lines)
    rows = values.reshape(stored, ng) * scale
    if isym == 1:
        c_full, candela = np.array([0.0]), rows
    else:
        mirrors = MIRRORS[{0: NONE, 2: BILATERAL_C0, 3: BILATERAL_C90, 4: QUADRANT}[isym]]
        c_full, candela = expand_c(_stored_angles(isym, c, c_lines, source), rows, mirrors)
    warnings = []
    if n_sets > 1:
        warnings.append(
            f"{n_sets} lamp sets: the intensities are scaled by the first ({lamp_flux:g} lm); "
            "the other sets are not used"
        )
    ph = Photometry(
        kind="C",
        c_angles=c_full,
        gamma_angles=g,
        candela=candela,
        lamp_lumens=None if lamps < 0 else lamp_flux,
        input_watts=watts if watts > 0 else None,
        opening=_opening(sizes),
        name=name,
        manufacturer=company,
        catalogue_number=number,
        source=source,
        n_lamps=abs(lamps),
        lamp=lamp_type,
        warnings=tuple(warnings),
    )
    return with_output_ratio_warning(ph)


def _opening(sizes: list[float]) -> tuple[float, float, float]:
    """(width, length, height) of the luminous area, m, from lines 13-21 (mm). A width
    of 0 with a length marks a circle of that diameter: it becomes LM-63's code for one
    (width and length both minus the diameter), so one convention holds everywhere."""
    length, width = sizes[3] / 1000.0, sizes[4] / 1000.0
    height = float(np.mean(sizes[5:9])) / 1000.0
    if width == 0.0 and length > 0.0:
        return (-length, -length, height)
    return (width, length, height)


_SIZES = (
    "luminaire length (mm)",
    "luminaire width (mm)",
    "luminaire height (mm)",
    "luminous area length (mm)",
    "luminous area width (mm)",
    "luminous area height at C0 (mm)",
    "luminous area height at C90 (mm)",
    "luminous area height at C180 (mm)",
    "luminous area height at C270 (mm)",
)


def _step(angles: np.ndarray, span: float | None) -> float:
    """The common step of equidistant angles (Dc, Dg), else 0 as the format says."""
    if angles.size < 2:
        return 0.0
    d = np.diff(angles)
    if not np.allclose(d, d[0], atol=ANGLE_TOL):
        return 0.0
    if span is not None and abs(angles[-1] + d[0] - angles[0] - span) > ANGLE_TOL:
        return 0.0
    return float(d[0])


def _layout(ph: Photometry) -> tuple[int, np.ndarray, np.ndarray]:
    """(Isym, the Mc C angles listed, the stored rows) for ``ph``: the most compact
    symmetry whose planes the C grid has at the positions the format fixes."""
    symmetry = ph.symmetry()
    if symmetry == AXIAL:
        return 1, np.arange(24) * 15.0, ph.candela[:1]
    c, cd = ph.c_angles, ph.candela
    mc = c.size

    def has(k: int, angle: float) -> bool:
        return abs(c[k % mc] - angle) <= ANGLE_TOL

    if symmetry == QUADRANT and mc % 4 == 0 and has(0, 0) and has(mc // 4, 90):
        return 4, c, cd[: mc // 4 + 1]
    if symmetry in (QUADRANT, BILATERAL_C0) and mc % 2 == 0 and has(0, 0) and has(mc // 2, 180):
        return 2, c, cd[: mc // 2 + 1]
    if (
        symmetry in (QUADRANT, BILATERAL_C90)
        and mc % 4 == 0
        and has(mc // 4, 90)
        and has(3 * mc // 4, 270)
    ):
        return 3, c, np.vstack([cd[3 * mc // 4 :], cd[: mc // 4 + 1]])
    return 0, c, cd


def format_ldt(ph: Photometry, file_name: str = "") -> str:
    """The EULUMDAT text of a type C ``ph`` (what write_ldt writes). Direct ratios are
    written as 0 (not computed); sizes come from the luminous opening."""
    if ph.kind != "C":
        raise fail(
            ph.source or "photometry",
            None,
            f"EULUMDAT holds type C photometry only, this table is type {ph.kind}",
            "write it as IES (.ies) instead",
        )
    isym, c_list, rows = _layout(ph)
    flux = ph.flux()
    if ph.lamp_lumens is None:  # absolute: the table relative to its own flux
        ref, lamps = (flux if flux > 0 else 1000.0), -ph.n_lamps
    else:
        ref, lamps = ph.lamp_lumens, ph.n_lamps
    w_mm, l_mm, h_mm = (1000.0 * abs(x) for x in ph.opening)
    circle = ph.opening[0] < 0 and ph.opening[1] < 0 and w_mm == l_mm  # IES's circle code
    linear = ph.symmetry() != AXIAL and l_mm >= 2 * w_mm > 0
    ityp = 1 if isym == 1 else 2 if linear else 3
    out = [
        one_line(ph.manufacturer, TEXT_WIDTH),
        str(ityp),
        str(isym),
        str(c_list.size),
        fmt_number(_step(c_list, 360.0)),
        str(ph.gamma_angles.size),
        fmt_number(_step(ph.gamma_angles, None)),
        "",  # measurement report number
        one_line(ph.name, TEXT_WIDTH),
        one_line(ph.catalogue_number, TEXT_WIDTH),
        one_line(file_name, TEXT_WIDTH),
        "LightInv",  # date/user: no date, so the output is reproducible
    ]
    area_w = 0.0 if circle else w_mm  # EULUMDAT: a luminous width of 0 marks a circle
    out += [fmt_number(x) for x in (l_mm, w_mm, h_mm, l_mm, area_w, h_mm, h_mm, h_mm, h_mm)]
    dff = 100.0 * ph.flux(90.0) / flux if flux > 0 else 100.0
    out += [fmt_number(dff), fmt_number(100.0 * flux / ref), "1", "0", "1"]
    out += [str(lamps), one_line(ph.lamp, TEXT_WIDTH), fmt_number(ref, 10), "", ""]
    out.append(fmt_number(ph.input_watts or 0.0, 10))
    out += ["0"] * 10  # direct ratios
    out += [fmt_number(a, 10) for a in c_list]
    out += [fmt_number(a, 10) for a in ph.gamma_angles]
    out += [fmt_number(v) for v in (rows * (1000.0 / ref)).ravel()]
    return "\n".join(out) + "\n"


def write_ldt(ph: Photometry, path: str | os.PathLike) -> None:
    """Write a type C ``ph`` as a EULUMDAT file (Latin-1), all or nothing (atomic)."""
    text = format_ldt(ph, Path(path).name)
    with atomic_writer(path, "w", encoding="latin-1", errors="replace", newline="\n") as fh:
        fh.write(text)
