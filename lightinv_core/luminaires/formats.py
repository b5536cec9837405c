"""One entry point for photometric files: by extension, else by content."""

from __future__ import annotations

import os
import re
from pathlib import Path

from lightinv_core.luminaires.ies import parse_ies, write_ies
from lightinv_core.luminaires.ldt import parse_ldt, write_ldt
from lightinv_core.luminaires.photometry import Photometry, fail
from lightinv_core.luminaires.textfile import decode_lines, read_bytes

_IES_MARK = re.compile(r"\s*(IESNA|IES\s*:|TILT\s*=)", re.IGNORECASE)
_SMALL_INT = re.compile(r"\s*[0-4]\s*")


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
    """Read an IES (.ies) or EULUMDAT (.ldt) file, the extension in any case; another
    extension is read by its content. Files over 20 MB are refused unread."""
    source = str(path)
    data = read_bytes(path)
    suffix = Path(path).suffix.lower()
    if suffix == ".ies":
        return parse_ies(data, source)
    if suffix == ".ldt":
        return parse_ldt(data, source)
    kind = sniff(decode_lines(data, source))
    if kind == "ies":
        return parse_ies(data, source)
    if kind == "ldt":
        return parse_ldt(data, source)
    raise fail(
        source,
        None,
        "neither an IES LM-63 nor a EULUMDAT file",
        "give a photometric file with the extension .ies or .ldt",
    )


def write_photometry(ph: Photometry, path: str | os.PathLike) -> None:
    """Write ``ph`` as EULUMDAT for a .ldt path, else as IES LM-63-2002."""
    if Path(path).suffix.lower() == ".ldt":
        write_ldt(ph, path)
    else:
        write_ies(ph, path)
