"""IES LM-63 photometric files (1986/1991, 1995, 2002, 2019): reading and writing.

Read: the version line (absent in 1986 files), ``[KEYWORD] value`` lines with
``[MORE]`` continuations, ``TILT=NONE`` or ``TILT=INCLUDE`` (its table is read, not
applied, and a warning; ``TILT=<file>`` is refused), then numbers separated by spaces,
commas or line breaks in any layout: the ten-number line, ballast factor / second
factor / input watts, vertical angles, horizontal angles, candela. Type C horizontal symmetry (one
angle, 0-90, 0-180, 90-270, 0-360) is expanded to the full circle. Written: LM-63-2002,
``TILT=NONE``, metres, the fewest C planes the table's symmetry allows.
"""

from __future__ import annotations

import os
import re
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
    quote,
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
    read_bytes,
)

FEET = 0.3048  # m per foot
_VERSION = re.compile(r"\s*(?:IESNA|IES)\s*:?\s*(?:LM-63-)?(\d{2,4})\b", re.IGNORECASE)
_KEYWORD = re.compile(r"\s*\[([A-Za-z0-9_ -]{1,40})\]\s*(.*)")
_TILT = re.compile(r"\s*TILT\s*=\s*(.*?)\s*$", re.IGNORECASE)
TYPES = {1: "C", 2: "B", 3: "A"}


def read_ies(path: str | os.PathLike) -> Photometry:
    """Read an IES LM-63 file; every problem with it is a one-line PhotometryError."""
    return parse_ies(read_bytes(path), str(path))


def _version(first: str) -> tuple[int, int]:
    """(year of the LM-63 revision, index of the first header line); 1986 files have
    no version line."""
    m = _VERSION.match(first)
    if not m:
        return 1986, 0
    year = int(m.group(1))
    return (year + 1900 if year < 100 else year), 1


def _header(
    lines: list[str], start: int, source: str
) -> tuple[dict[str, str], list[str], int, str]:
    """Keywords (upper-case name -> value, [MORE] appended), other header lines, the
    index of the TILT= line and its value."""
    keywords: dict[str, str] = {}
    free: list[str] = []
    last = None
    for k in range(start, len(lines)):
        text = lines[k]
        tilt = _TILT.match(text)
        if tilt:
            return keywords, free, k, tilt.group(1)
        m = _KEYWORD.match(text)
        if m:
            key, value = m.group(1).strip().upper(), m.group(2).strip()
            if key == "MORE" and last is not None:
                keywords[last] = f"{keywords[last]} {value}".strip()
            else:
                keywords[key] = f"{keywords[key]} {value}".strip() if key in keywords else value
                last = key
        elif text.strip():
            free.append(text.strip())
    raise fail(
        source,
        1,
        "no TILT= line: this is not an IES LM-63 photometric file",
        "export the luminaire's photometry as IES LM-63 (.ies) or EULUMDAT (.ldt)",
    )


def _skip_tilt(tokens: Tokens) -> str:
    """Read past an included lamp-tilt table; returns the warning that it is not applied
    (with its angles and the range of its factors, so the user sees how much it could
    matter)."""
    tokens.integer("lamp-to-luminaire geometry of the tilt table", 1, 3)
    n, _ = tokens.integer("number of tilt angles", 1, MAX_ANGLES)
    angles, lines = tokens.numbers(n, "tilt angles")
    check_angles(tokens.source, angles, lines, "tilt angle", 0.0, 180.0)
    factors, _ = tokens.numbers(n, "tilt multiplying factors")
    return (
        f"TILT=INCLUDE: the lamp-tilt factors ({n} angle{'s' * (n != 1)}, "
        f"{factors.min():g} to {factors.max():g}) are not applied; the light is computed "
        "with the lamp as photometered"
    )


def _positive(tokens: Tokens, what: str, allow_zero: bool = False) -> float:
    value, line = tokens.number(what)
    if value < 0 or (value == 0 and not allow_zero):
        need = ">= 0" if allow_zero else "> 0"
        raise fail(tokens.source, line, f"{what} is {value:g}", f"it must be {need}")
    return value


def _c_symmetry(source: str, h: np.ndarray, line: int) -> str:
    """The symmetry LM-63 type C states by its first and last horizontal angles."""

    def near(a: float, b: float) -> bool:
        return abs(a - b) <= ANGLE_TOL

    first, last = h[0], h[-1]
    if h.size == 1:
        return AXIAL
    if near(first, 0) and near(last, 90):
        return QUADRANT
    if near(first, 0) and near(last, 180):
        return BILATERAL_C0
    if near(first, 90) and near(last, 270):
        return BILATERAL_C90
    if near(first, 0) and last > 180:
        return NONE
    raise fail(
        source,
        line,
        f"type C horizontal angles run from {first:g} to {last:g}",
        "LM-63 allows a single 0, 0..90, 0..180, 90..270 or 0..360 (or 0 to more than 180)",
    )


def parse_ies(data: bytes | str, source: str = "<ies>") -> Photometry:
    """Parse the text (or bytes) of an IES file; ``source`` names it in messages."""
    lines = decode_lines(data, source)
    year, start = _version(lines[0])
    keywords, free, tilt_at, tilt = _header(lines, start, source)
    tokens = Tokens(lines, tilt_at + 1, source)
    notes: list[str] = []
    warnings: list[str] = []
    if tilt.upper() == "INCLUDE":
        warnings.append(_skip_tilt(tokens))
    elif tilt.upper() != "NONE":
        raise fail(
            source,
            tilt_at + 1,
            f"TILT={quote(tilt)}: external tilt files are not supported",
            "include the tilt table in the file (TILT=INCLUDE) or use TILT=NONE",
        )

    n_lamps, _ = tokens.integer("number of lamps", 1, 10_000)
    lumens, lumens_line = tokens.number("lumens per lamp")
    if lumens != -1 and not 0 < lumens * n_lamps <= MAX_LUMENS:
        raise fail(
            source,
            lumens_line,
            f"lumens per lamp is {lumens:g}",
            f"give a positive number (at most {MAX_LUMENS:g} lm in all), or -1",
        )
    multiplier = _positive(tokens, "candela multiplier")
    n_v, _ = tokens.integer("number of vertical angles", 2, MAX_ANGLES)
    n_h, h_line = tokens.integer("number of horizontal angles", 1, MAX_ANGLES)
    if n_v * n_h > MAX_VALUES:
        raise fail(
            source,
            h_line,
            f"{n_v} x {n_h} = {n_v * n_h:,} candela values is too many",
            f"this reader takes at most {MAX_VALUES:,}",
        )
    ptype, _ = tokens.integer("photometric type", 1, 3)
    units, _ = tokens.integer("units type", 1, 2)
    dims, dim_lines = tokens.numbers(3, "luminous opening (width, length, height)")
    scale = FEET if units == 1 else 1.0
    for k, d in enumerate(dims):
        if abs(d * scale) > 1000:
            raise fail(source, dim_lines[k], f"opening size {d:g} is absurd", "check the units")
    ballast = _positive(tokens, "ballast factor")
    # 1986-1995: the ballast-lamp photometric factor, a multiplier; 2002: "future use";
    # 2019: the file generation type. Only the old meaning scales the candela.
    second = _positive(tokens, "ballast-lamp photometric factor") if year < 2002 else None
    if second is None:
        tokens.number("future use / file generation type")
    watts = _positive(tokens, "input watts", allow_zero=True)

    kind = TYPES[ptype]
    v, v_lines = tokens.numbers(n_v, "vertical angles")
    h, h_lines = tokens.numbers(n_h, "horizontal angles")
    if kind == "C":
        check_angles(source, v, v_lines, "vertical angle", 0.0, 180.0)
        check_angles(source, h, h_lines, "horizontal angle", 0.0, 360.0)
    else:
        check_angles(source, v, v_lines, "vertical angle", -180.0, 180.0)
        check_angles(source, h, h_lines, "horizontal angle", -180.0, 180.0)
    values, value_lines = tokens.numbers(n_v * n_h, "candela values")
    check_intensities(source, values, value_lines, "candela value")
    tokens.expect_end(f"the {n_v * n_h} candela values")

    factor = multiplier * ballast * (second if second is not None else 1.0)
    check_candela(source, values, factor, value_lines)
    candela = values.reshape(n_h, n_v) * factor
    if kind == "C":
        symmetry = _c_symmetry(source, h, h_lines[-1])
        if symmetry == AXIAL:
            c, candela = np.array([0.0]), candela[:1]
        else:
            c, candela = expand_c(h, candela, MIRRORS[symmetry])
    else:
        c = h
        notes.append(f"type {kind} photometry: stored, not usable for lighting calculations")
    if year < 2002 and start == 0:
        notes.append("no version line: read as LM-63-1986/1991")

    name = keywords.get("LUMINAIRE") or (free[0] if free and not keywords else "")
    ph = Photometry(
        kind=kind,
        c_angles=c,
        gamma_angles=v,
        candela=candela,
        lamp_lumens=None if lumens == -1 else lumens * n_lamps,
        input_watts=watts if watts > 0 else None,
        opening=(float(dims[0]) * scale, float(dims[1]) * scale, float(dims[2]) * scale),
        name=name,
        manufacturer=keywords.get("MANUFAC", ""),
        catalogue_number=keywords.get("LUMCAT", ""),
        source=source,
        n_lamps=n_lamps,
        lamp=keywords.get("LAMP", ""),
        notes=tuple(notes),
        warnings=tuple(warnings),
    )
    return with_output_ratio_warning(ph)


def _wrap(values, digits: int = 7, per_line: int = 10) -> list[str]:
    """Values ``per_line`` to a line (LM-63 lines stay under 132 characters)."""
    words = [fmt_number(v, digits) for v in values]
    return [" ".join(words[k : k + per_line]) for k in range(0, len(words), per_line)]


def format_ies(ph: Photometry, file_name: str = "") -> str:
    """The LM-63-2002 text of ``ph`` (what write_ies writes)."""
    c, rows = ph.c_angles, ph.candela
    if ph.kind == "C":
        symmetry = ph.symmetry()
        idx = ph.stored_planes(symmetry)
        if idx.size == 0:
            symmetry, idx = NONE, np.arange(c.size)
        c, rows = c[idx], rows[idx]
        if symmetry == AXIAL:
            c = np.array([0.0])
        elif symmetry == NONE:
            # LM-63 type C starts at 0 and, to say "no symmetry", ends at 360.
            if c[0] > ANGLE_TOL:
                c = np.append(0.0, c)
                rows = np.vstack([ph.intensity(0.0, ph.gamma_angles), rows])
            c = np.append(c, 360.0)
            rows = np.vstack([rows, rows[:1]])
    ptype = {v: k for k, v in TYPES.items()}[ph.kind]
    per_lamp = -1.0 if ph.lamp_lumens is None else ph.lamp_lumens / ph.n_lamps
    out = ["IESNA:LM-63-2002"]
    out.append(f"[TEST] {one_line(file_name or ph.source or 'LightInv')}")
    out.append(f"[MANUFAC] {one_line(ph.manufacturer)}".rstrip())
    for key, value in (("LUMCAT", ph.catalogue_number), ("LUMINAIRE", ph.name), ("LAMP", ph.lamp)):
        if one_line(value):
            out.append(f"[{key}] {one_line(value)}")
    for note in (*ph.notes, *ph.warnings):
        out.append(f"[OTHER] {one_line(note)}")
    out.append("TILT=NONE")
    w, length, height = ph.opening
    out.append(
        f"{ph.n_lamps} {fmt_number(per_lamp, 10)} 1 {ph.gamma_angles.size} {c.size} {ptype} 2 "
        f"{fmt_number(w)} {fmt_number(length)} {fmt_number(height)}"
    )
    out.append(f"1 1 {fmt_number(ph.input_watts or 0.0, 10)}")
    out += _wrap(ph.gamma_angles, 10)
    out += _wrap(c, 10)
    for row in rows:
        out += _wrap(row)
    return "\n".join(out) + "\n"


def write_ies(ph: Photometry, path: str | os.PathLike) -> None:
    """Write ``ph`` as an LM-63-2002 file, all or nothing (atomic)."""
    text = format_ies(ph, Path(path).name)
    with atomic_writer(path, "w", encoding="latin-1", errors="replace", newline="\n") as fh:
        fh.write(text)
