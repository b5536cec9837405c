"""Photometric file formats, in one registry: IES LM-63, EULUMDAT, GLDF.

Each format is a ``PhotometryFormat`` (name, suffixes, how a file becomes a
``Photometry``, and for formats that hold several products, how their variants are
listed). Everything that takes a photometric file (the catalogue, the arrays' products,
the luminaire CSV, ``lightinv-cli photometry``, the window's file choosers) goes
through ``read_photometry`` and the lookups here, so a registered format is read
everywhere. A file with variants (GLDF) is named ``FILE#VARIANT`` for one of them;
``FILE`` alone is its first variant.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from lightinv_core.luminaires.gldf import read_gldf
from lightinv_core.luminaires.gldf_light import reference, variant_facts, variant_photometry
from lightinv_core.luminaires.ies import parse_ies, write_ies
from lightinv_core.luminaires.ldt import parse_ldt, write_ldt
from lightinv_core.luminaires.photometry import Photometry, fail
from lightinv_core.luminaires.textfile import decode_lines, read_bytes

_IES_MARK = re.compile(r"\s*(IESNA|IES\s*:|TILT\s*=)", re.IGNORECASE)
_SMALL_INT = re.compile(r"\s*[0-4]\s*")
_ZIP_MAGIC = b"PK\x03\x04"


@dataclass(frozen=True)
class PhotometryFormat:
    """A photometric file format: ``read(file, variant)`` gives the table (``variant``
    None for the file's only or first product); ``variants(file)`` lists the ids of the
    products a file holds, None for formats of one product per file; ``facts(file,
    variant)`` says what the file states beyond the table, as (JSON data, text lines)."""

    name: str
    suffixes: tuple[str, ...]
    read: Callable[[Path, str | None], Photometry]
    variants: Callable[[Path], list[str]] | None = None
    facts: Callable[[Path, str | None], tuple[dict, list[str]]] | None = None


def _text_reader(parse: Callable[[bytes, str], Photometry]) -> Callable:
    return lambda path, variant: parse(read_bytes(path), str(path))


BUILTIN: tuple[PhotometryFormat, ...] = (
    PhotometryFormat("IES LM-63", (".ies",), _text_reader(parse_ies)),
    PhotometryFormat("EULUMDAT", (".ldt",), _text_reader(parse_ldt)),
    PhotometryFormat(
        "GLDF",
        (".gldf",),
        lambda path, variant: variant_photometry(path, variant),
        lambda path: [v.variant_id for v in read_gldf(path).variants],
        variant_facts,
    ),
)
_FORMATS: list[PhotometryFormat] = list(BUILTIN)


def register_format(fmt: PhotometryFormat) -> None:
    """Add (or replace, by name) a photometric format."""
    unregister_format(fmt.name)
    _FORMATS.append(fmt)


def unregister_format(name: str) -> None:
    """Remove a registered format (the built-in ones stay)."""
    if name not in {f.name for f in BUILTIN}:
        _FORMATS[:] = [f for f in _FORMATS if f.name != name]


def formats() -> tuple[PhotometryFormat, ...]:
    """The registered formats, built-in first."""
    return tuple(_FORMATS)


def format_of(path: str | os.PathLike) -> PhotometryFormat | None:
    """The format a file's extension (any case) names, or None."""
    suffix = Path(path).suffix.lower()
    return next((f for f in _FORMATS if suffix in f.suffixes), None)


def split_reference(name: str | os.PathLike) -> tuple[Path, str | None] | None:
    """(file, variant or None) of a photometric file reference (``FILE`` or
    ``FILE#VARIANT`` for a format with variants), or None if ``name`` names none."""
    text = str(name)
    file, sep, variant = text.rpartition("#")
    if sep:
        fmt = format_of(file)
        if fmt is not None and fmt.variants is not None:
            return Path(file), variant or None
    return (Path(text), None) if format_of(text) is not None else None


def is_photometry_reference(name: str | os.PathLike) -> bool:
    """Whether ``name`` names a photometric file (or one product in one), not a
    catalogue entry."""
    return split_reference(name) is not None


def file_filter() -> str:
    """The file chooser's filter: every registered suffix."""
    patterns = " ".join(f"*{s}" for f in _FORMATS for s in f.suffixes)
    return f"Photometric files ({patterns})"


def file_products(path: str | os.PathLike) -> list[tuple[str, Photometry]]:
    """(reference, table) of each product a photometric file holds: one for IES and
    EULUMDAT, one per variant for GLDF."""
    file = Path(path)
    fmt = format_of(file)
    if fmt is None:
        return [(str(path), read_photometry(path))]
    if fmt.variants is None:
        return [(str(path), fmt.read(file, None))]
    return [(reference(file, v), fmt.read(file, v)) for v in fmt.variants(file)]


def file_facts(reference_: str | os.PathLike) -> tuple[dict, list[str]]:
    """What a photometric file states of one product beyond its table (its format's
    ``facts``), or nothing."""
    ref = split_reference(reference_)
    fmt = format_of(ref[0]) if ref else None
    if ref is None or fmt is None or fmt.facts is None:
        return {}, []
    return fmt.facts(ref[0], ref[1])


def sniff(lines: list[str]) -> str | None:
    """'ies' or 'ldt' from the first lines of a file, or None if it looks like neither.

    IES: a version line or a TILT= line near the top. EULUMDAT: lines 2 and 3 are
    Ityp and Isym, single digits."""
    head = lines[:200]
    if any(_IES_MARK.match(line) for line in head):
        return "ies"
    if len(lines) > 26 and all(_SMALL_INT.fullmatch(line) for line in lines[1:3]):
        return "ldt"
    return None


def read_photometry(path: str | os.PathLike) -> Photometry:
    """Read a photometric file of a registered format (IES .ies, EULUMDAT .ldt, GLDF
    .gldf or ``FILE.gldf#VARIANT``), the extension in any case; another extension is
    read by its content. Files over 20 MB are refused unread."""
    ref = split_reference(path)
    if ref is not None:
        file, variant = ref
        return format_of(file).read(file, variant)  # type: ignore[union-attr]
    source = str(path)
    data = read_bytes(path)
    if data.startswith(_ZIP_MAGIC):  # a zip: GLDF is the one zipped format
        return variant_photometry(path)
    kind = sniff(decode_lines(data, source))
    if kind == "ies":
        return parse_ies(data, source)
    if kind == "ldt":
        return parse_ldt(data, source)
    raise fail(
        source,
        None,
        "neither an IES LM-63 nor a EULUMDAT file (nor a GLDF zip)",
        "give a photometric file with the extension .ies, .ldt or .gldf",
    )


def write_photometry(ph: Photometry, path: str | os.PathLike) -> None:
    """Write ``ph`` as EULUMDAT for a .ldt path, else as IES LM-63-2002."""
    if Path(path).suffix.lower() == ".ldt":
        write_ldt(ph, path)
    else:
        write_ies(ph, path)
