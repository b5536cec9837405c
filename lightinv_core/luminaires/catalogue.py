"""The luminaire catalogue: a JSON list of products, each with its photometric file.

``resources/luminaires/catalogue.json``::

    {"format": "lightinv-luminaires", "version": 1,
     "luminaires": [{"name": "...", "file": "x.ldt", "lumens": 2000, "watts": 20,
                     "size_m": [0.15, 0.15, 0.0], "description": "..."}]}

``file`` is relative to the catalogue's folder (one variant of a GLDF file is
``x.gldf#VARIANT``); ``size_m`` is the luminous opening
(width across C90-C270, length along C0-C180, height), metres. The shipped files are
made by ``generate_builtin`` from analytic distributions; regenerate them with

    python -m lightinv_core.luminaires.catalogue --write resources/luminaires
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from dataclasses import dataclass
from pathlib import Path

from lightinv_core.atomic import atomic_writer
from lightinv_core.errors import LightInvError
from lightinv_core.luminaires.analytic import (
    batwing_linear,
    direct_indirect_linear,
    downlight,
    lambertian_panel,
)
from lightinv_core.luminaires.formats import (
    file_facts,
    file_products,
    read_photometry,
    split_reference,
    write_photometry,
)
from lightinv_core.luminaires.photometry import Photometry, fail
from lightinv_core.luminaires.textfile import read_bytes

FORMAT = "lightinv-luminaires"
VERSION = 1
# Found like every other resource: the repository's (or the bundle's) resources/ folder
# two levels above this package (packaging/lightinv.spec ships resources/ whole).
BUILTIN_FOLDER = Path(__file__).resolve().parents[2] / "resources" / "luminaires"
CATALOGUE_NAME = "catalogue.json"


@dataclass(frozen=True)
class CatalogueEntry:
    """One product: its photometric file, rated flux (lm), electric power (W) and
    luminous opening ``size`` (width, length, height), metres."""

    name: str
    path: Path
    lumens: float
    watts: float
    size: tuple[float, float, float]
    description: str = ""
    variant: str = ""

    @property
    def reference(self) -> str:
        """How a project names it: the file, or ``FILE#VARIANT`` for a GLDF variant."""
        return f"{self.path}#{self.variant}" if self.variant else str(self.path)

    @property
    def efficacy(self) -> float:
        """Luminous efficacy, lm/W."""
        return self.lumens / self.watts

    def photometry(self) -> Photometry:
        """The entry's photometric table, read from its file."""
        return read_photometry(self.reference)


def _line_of(text: str, needle: str, start: int) -> tuple[int | None, int]:
    """(1-based line of ``needle`` at or after ``start``, where to look next)."""
    pos = text.find(needle, start)
    if pos < 0:
        return None, start
    return text.count("\n", 0, pos) + 1, pos + len(needle)


def _number(value: object) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    return float(value) if math.isfinite(value) else None


def read_catalogue(path: str | os.PathLike) -> list[CatalogueEntry]:
    """Read and check a catalogue file; each problem is a one-line PhotometryError
    naming the entry. Photometric files must exist (they are not parsed here)."""
    source = str(path)
    data = read_bytes(path)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise fail(source, line, "not UTF-8 text", "save the catalogue as UTF-8 JSON") from None
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise fail(source, exc.lineno, f"not valid JSON: {exc.msg}", "fix the JSON") from None
    if not isinstance(doc, dict) or not isinstance(doc.get("luminaires"), list):
        raise fail(source, 1, 'no "luminaires" list', f"write a {FORMAT} catalogue")
    if doc.get("version", VERSION) != VERSION:
        raise fail(
            source, 1, f"catalogue version {doc.get('version')!r}", f"this LightInv reads {VERSION}"
        )
    folder = Path(path).parent
    entries: list[CatalogueEntry] = []
    seen: set[str] = set()
    look = 0
    for k, item in enumerate(doc["luminaires"], start=1):
        if not isinstance(item, dict):
            raise fail(source, None, f"luminaire {k} is not an object", 'write {"name": ...}')
        name = item.get("name")
        if not isinstance(name, str) or not name.strip():
            raise fail(source, None, f"luminaire {k} has no name", "give each luminaire a name")
        line, look = _line_of(text, json.dumps(name), look)
        label = f"luminaire {name!r}"
        if name in seen:
            raise fail(source, line, f"{label} appears twice", "give each luminaire its own name")
        seen.add(name)
        file = item.get("file")
        if not isinstance(file, str) or not file.strip():
            raise fail(source, line, f'{label} has no "file"', "name its .ies or .ldt file")
        values = {}
        for key in ("lumens", "watts"):
            v = _number(item.get(key))
            if v is None or v <= 0:
                raise fail(
                    source, line, f"{label}: {key} = {item.get(key)!r}", "give a positive number"
                )
            values[key] = v
        size = item.get("size_m", [0.0, 0.0, 0.0])
        sizes = [_number(x) for x in size] if isinstance(size, list) else []
        if len(sizes) != 3 or any(x is None or x < 0 for x in sizes):
            raise fail(
                source,
                line,
                f"{label}: size_m = {size!r}",
                "give [width, length, height] in metres, each >= 0",
            )
        description = item.get("description", "")
        if not isinstance(description, str):
            raise fail(source, line, f"{label}: description is not text", "write a string")
        target, variant = split_reference(folder / file) or (folder / file, None)
        if not target.is_file():
            raise fail(
                source,
                line,
                f"{label}: photometric file {file!r} not found in {folder}",
                "check the file name, or regenerate the catalogue",
            )
        entries.append(
            CatalogueEntry(
                name=name,
                path=target,
                lumens=values["lumens"],
                watts=values["watts"],
                size=(sizes[0], sizes[1], sizes[2]),  # type: ignore[arg-type]
                description=description,
                variant=variant or "",
            )
        )
    return entries


def file_entries(path: str | os.PathLike) -> list[CatalogueEntry]:
    """Catalogue entries of the products in a photometric file: one for an IES or
    EULUMDAT file, one per variant for a GLDF (named product + variant), each with the
    flux its table gives, the watts it states (0 where it states none) and, as its
    description, what the file states beyond the table (a GLDF's ratings, CCT, Ra,
    size and maintenance)."""
    entries = []
    for ref, ph in file_products(path):
        file, variant = split_reference(ref) or (Path(ref), None)
        _, stated = file_facts(ref)
        entries.append(
            CatalogueEntry(
                name=ph.name or file.stem,
                path=file,
                lumens=ph.flux(),
                watts=ph.input_watts or 0.0,
                size=ph.opening,  # type: ignore[arg-type]
                description="\n".join(stated),
                variant=variant or "",
            )
        )
    return entries


def builtin_catalogue() -> list[CatalogueEntry]:
    """The catalogue shipped in resources/luminaires."""
    return read_catalogue(BUILTIN_FOLDER / CATALOGUE_NAME)


def _builtin_products() -> list[tuple[str, Photometry, tuple[str, ...], str]]:
    """(file stem, photometry, formats written, description) of each shipped product."""
    return [
        (
            "downlight-2000lm",
            downlight(
                2000.0,
                4.0,
                watts=20.0,
                size_m=(0.15, 0.15, 0.0),
                name="Downlight 2000 lm 20 W",
                catalogue_number="LI-DL-2000",
            ),
            ("ldt", "ies"),
            "LED downlight 0.15 x 0.15 m, I = I0 cos^4(gamma), half intensity at 33 deg",
        ),
        (
            "batwing-linear-4000lm",
            batwing_linear(
                4000.0,
                watts=32.0,
                size_m=(0.15, 1.2, 0.0),
                peak_deg=35.0,
                name="Linear batwing 4000 lm 32 W",
                catalogue_number="LI-BW-4000",
            ),
            ("ies",),
            "Linear 1.2 x 0.15 m, wide batwing across (C90, peak at 35 deg), cos^2 along",
        ),
        (
            "panel-600-3600lm",
            lambertian_panel(
                3600.0,
                watts=30.0,
                size_m=(0.6, 0.6, 0.0),
                name="Panel 600 x 600 3600 lm 30 W",
                catalogue_number="LI-PN-3600",
            ),
            ("ldt",),
            "Lambertian LED panel 0.6 x 0.6 m, I = I0 cos(gamma)",
        ),
        *_office_products(),
    ]


def _office_products() -> list[tuple[str, Photometry, tuple[str, ...], str]]:
    """The flagship office's products (issue #34): generated from analytic distributions,
    not measured (no manufacturer file with a licence to redistribute was found); sizes,
    fluxes and powers are those of common LED products of each type, their UGR (CIE
    190, 4H x 8H, 70/50/20) below EN 12464-1's 19 for offices."""
    return [
        (
            "panel-600-recessed-3400lm",
            downlight(
                3400.0,
                1.8,
                watts=27.0,
                size_m=(0.6, 0.6, 0.0),
                name="Recessed panel 600 x 600 3400 lm 27 W",
                catalogue_number="LI-RP-3400",
            ),
            ("ldt", "ies"),
            "Recessed LED panel 0.6 x 0.6 m with a micro-prismatic diffuser, "
            "I = I0 cos^1.8(gamma) (analytic, not measured); UGR 4H8H 18.0",
        ),
        (
            "linear-direct-indirect-4800lm",
            direct_indirect_linear(
                4800.0,
                0.3,
                watts=36.0,
                size_m=(0.2, 1.5, 0.0),
                peak_deg=20.0,
                name="Linear direct/indirect 1500 mm 4800 lm 36 W",
                catalogue_number="LI-DI-4800",
            ),
            ("ldt", "ies"),
            "Suspended linear 1.5 x 0.2 m, 70% down (batwing across, peak 20 deg, cos^2 "
            "along), 30% up (Lambertian) (analytic, not measured); UGR 4H8H 15.0 / 18.2",
        ),
        (
            "downlight-150-reflector-1800lm",
            downlight(
                1800.0,
                6.0,
                watts=16.0,
                size_m=(0.15, 0.15, 0.0),
                name="Downlight 150 mm reflector 1800 lm 16 W",
                catalogue_number="LI-DR-1800",
            ),
            ("ldt", "ies"),
            "LED downlight 0.15 x 0.15 m with a reflector, I = I0 cos^6(gamma), half "
            "intensity at 27 deg (analytic, not measured); UGR 4H8H 17.0",
        ),
    ]


STATED_LAMPS = {
    "panel-600-recessed-3400lm": ("4000", "80"),
    "linear-direct-indirect-4800lm": ("4000", "80"),
    "downlight-150-reflector-1800lm": ("3000", "90"),
}
"""(colour temperature K, Ra) the office products' EULUMDAT files state (the lamp set's
lines 30-31), as LED products of each type commonly do; EN 12464-1's Ra criterion reads
the Ra (``luminaires/rendering.py``)."""


def _state_lamp(path: Path, cct: str, ra: str) -> None:
    """Write the colour temperature and Ra into the first lamp set of a EULUMDAT file
    that ``write_ldt`` wrote (it leaves both empty)."""
    lines = path.read_text(encoding="latin-1").split("\n")
    # 1-based lines 30 and 31 (rendering.LDT_RA_LINE, which imports this module).
    lines[29], lines[30] = cct, ra
    with atomic_writer(path, "w", encoding="latin-1", newline="\n") as fh:
        fh.write("\n".join(lines))


def format_catalogue(entries: list[dict]) -> str:
    """The catalogue file's text (stable: the same entries give the same bytes)."""
    doc = {"format": FORMAT, "version": VERSION, "luminaires": entries}
    return json.dumps(doc, indent=2, ensure_ascii=False) + "\n"


def generate_builtin(folder: str | os.PathLike) -> list[Path]:
    """Write the shipped photometric files and catalogue.json into ``folder``;
    deterministic (the same bytes every time). Returns the paths written."""
    out = Path(folder)
    written: list[Path] = []
    entries: list[dict] = []
    for stem, ph, formats, description in _builtin_products():
        for fmt in formats:
            target = out / f"{stem}.{fmt}"
            write_photometry(ph, target)
            if fmt == "ldt" and stem in STATED_LAMPS:
                _state_lamp(target, *STATED_LAMPS[stem])
            written.append(target)
        entries.append(
            {
                "name": ph.name,
                "file": f"{stem}.{formats[0]}",
                "lumens": ph.lamp_lumens,
                "watts": ph.input_watts,
                "size_m": list(ph.opening),
                "description": description,
            }
        )
    target = out / CATALOGUE_NAME
    with atomic_writer(target, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(format_catalogue(entries))
    written.append(target)
    return written


def main(argv: list[str] | None = None) -> int:
    """``python -m lightinv_core.luminaires.catalogue --write FOLDER``."""
    ap = argparse.ArgumentParser(
        prog="python -m lightinv_core.luminaires.catalogue",
        description="Regenerate the shipped luminaire files and catalogue.json.",
    )
    ap.add_argument("--write", required=True, metavar="FOLDER", help="e.g. resources/luminaires")
    args = ap.parse_args(argv)
    try:
        for path in generate_builtin(args.write):
            print(path)
    except (LightInvError, OSError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
