"""Luminaire schedules as CSV: one placed photometric luminaire per row.

Columns (a header row names them; order free, extra columns ignored):

``name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z`` and optionally ``dimming`` and
``control``

- x, y, z: the photometric centre in metres, in the scene's coordinates;
- ies: the photometric file (IES LM-63 or EULUMDAT .ldt), relative to the CSV;
- aim: direction of gamma = 0 (0,0,-1 for a downlight); c0: direction of the C = 0
  plane (along a linear luminaire); see ``transport.luminaires``;
- dimming: 0 to 1 (default 1), scaling the file's intensities;
- control: the daylight-linked control group the luminaire belongs to (default: one
  group for all; ``study.control_groups``).

Each photometric file is read once however many rows use it. Every problem is a
``PhotometryError`` naming the file and line.
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path

from lightinv_core.errors import LightInvError, PhotometryError
from lightinv_core.luminaires.formats import read_photometry
from lightinv_core.luminaires.photometry import Photometry
from lightinv_core.transport.luminaires import PlacedLuminaire

REQUIRED = ("name", "x", "y", "z", "ies", "aim_x", "aim_y", "aim_z", "c0_x", "c0_y", "c0_z")
MAX_ROWS = 100_000
MAX_BYTES = 50 * 2**20


def read_luminaire_csv(path: str | os.PathLike) -> list[PlacedLuminaire]:
    """The luminaires of a schedule CSV (see the module)."""
    path = Path(path)
    where = path.name
    try:
        if path.stat().st_size > MAX_BYTES:
            raise PhotometryError(
                f"{where}: {path.stat().st_size / 2**20:.0f} MB is too big for a luminaire "
                f"schedule (at most {MAX_BYTES // 2**20} MB)"
            )
        text = path.read_bytes().decode("utf-8-sig", errors="replace")
    except FileNotFoundError:
        raise PhotometryError(
            f"luminaire schedule '{path}' does not exist; check the path"
        ) from None
    except IsADirectoryError:
        raise PhotometryError(
            f"luminaire schedule '{path}' is a folder; give the CSV file"
        ) from None
    except OSError as exc:
        raise PhotometryError(f"cannot read luminaire schedule '{path}': {exc.strerror}") from None
    rows = list(csv.reader(text.splitlines()))
    if not rows:
        raise PhotometryError(f"{where}: empty; the first row must name the columns")
    header = [h.strip().lower() for h in rows[0]]
    missing = [c for c in REQUIRED if c not in header]
    if missing:
        raise PhotometryError(
            f"{where} line 1: missing column(s) {', '.join(missing)}; the header must name "
            f"{','.join(REQUIRED)} (and optionally dimming, control)"
        )
    col = {name: header.index(name) for name in (*REQUIRED, "dimming", "control") if name in header}
    files: dict[Path, Photometry] = {}
    out: list[PlacedLuminaire] = []
    names: set[str] = set()
    for line, row in enumerate(rows[1:], 2):
        if not any(cell.strip() for cell in row):
            continue
        if len(out) >= MAX_ROWS:
            raise PhotometryError(f"{where} line {line}: more than {MAX_ROWS:,} luminaires")
        at = f"{where} line {line}"

        def cell(name: str, row=row, at=at) -> str:
            k = col[name]
            if k >= len(row):
                raise PhotometryError(f"{at}: no value for {name!r}; fill in every column")
            return row[k].strip()

        def number(name: str, cell=cell, at=at) -> float:
            text = cell(name)
            try:
                x = float(text)
            except ValueError:
                raise PhotometryError(f"{at}: {name} {text!r} is not a number") from None
            if not math.isfinite(x) or abs(x) > 1e7:
                raise PhotometryError(f"{at}: {name} {text!r} is not a usable number")
            return x

        name = cell("name") or f"L{len(out) + 1}"
        if name in names:
            raise PhotometryError(f"{at}: luminaire name {name!r} is used twice")
        names.add(name)
        file = cell("ies")
        if not file:
            raise PhotometryError(f"{at}: no photometric file in column 'ies'")
        ies = (path.parent / file).resolve()
        if ies not in files:
            try:
                files[ies] = read_photometry(ies)
            except PhotometryError as exc:
                raise PhotometryError(f"{at}: {exc}") from None
        dimming = number("dimming") if "dimming" in col and cell("dimming") else 1.0
        try:
            out.append(
                PlacedLuminaire(
                    name,
                    [number("x"), number("y"), number("z")],
                    files[ies],
                    aim=[number("aim_x"), number("aim_y"), number("aim_z")],
                    c0=[number("c0_x"), number("c0_y"), number("c0_z")],
                    dimming=dimming,
                    control=(cell("control") if "control" in col else "") or "",
                )
            )
        except LightInvError as exc:
            if isinstance(exc, PhotometryError):
                raise
            raise PhotometryError(f"{at}: {exc}") from None
    if not out:
        raise PhotometryError(f"{where}: no luminaires (only a header)")
    return out
