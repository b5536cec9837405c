"""The colour rendering index Ra a product states, for EN 12464-1's Ra criterion.

Ra is a property of the lamps, not of the layout: LightInv does not compute it, it
reads what the product's data states and compares it with the activity's least Ra.

- EULUMDAT (.ldt): line 31, the first lamp set's "colour rendering index" field
  (after the number of lamps, lamp type, flux and colour temperature, lines 27-30).
  Makers write a number ("90"), a bound ("> 80", "Ra>=80", "CRI 90") or a CIE 13.3
  group ("1B"); a group reads as its lower bound (1A: 90, 1B: 80, 2A: 70, 2B: 60,
  3: 40, 4: 20), the least Ra the product guarantees. Empty: not stated.
- IES LM-63: no standard keyword holds it; a ``[_CRI]``/``[CRI]``/``[_RA]`` line
  (user keywords some makers add) is read, else the keywords' text is searched for
  "CRI" or "Ra" followed by a number.
- GLDF (``FILE.gldf`` or ``FILE.gldf#VARIANT``): the variant's light source
  ``ColorRenderingIndex`` (``luminaires.gldf``).
- A catalogue product: its file's.
"""

from __future__ import annotations

import re
from pathlib import Path

from lightinv_core.errors import LightInvError
from lightinv_core.luminaires.catalogue import builtin_catalogue
from lightinv_core.luminaires.formats import split_reference
from lightinv_core.textcodec import decode_text

CIE_GROUPS = {"1A": 90.0, "1B": 80.0, "2A": 70.0, "2B": 60.0, "3": 40.0, "4": 20.0}
"""CIE 13.3 colour rendering groups and the least Ra of each."""
LDT_RA_LINE = 31
"""The 1-based line of the first lamp set's colour rendering index in a EULUMDAT file."""
_NUMBER = re.compile(r"(\d{2,3}(?:[.,]\d+)?)")
_IES_RA = re.compile(r"\b(?:CRI|Ra)\b\s*(?:[:=]|>=|≥|>)?\s*(\d{2,3})", re.IGNORECASE)


def ra_from_text(text: str) -> float | None:
    """The Ra a field states ("90", "Ra>=80", "1B"), None when it states none."""
    t = text.strip().upper().replace(" ", "")
    if not t:
        return None
    if t in CIE_GROUPS:
        return CIE_GROUPS[t]
    m = _NUMBER.search(t)
    if m is None:
        return None
    ra = float(m.group(1).replace(",", "."))
    return ra if 0 < ra <= 100 else None


def stated_ra(path: str | Path) -> float | None:
    """The Ra the photometric file at ``path`` states, None when it states none or
    cannot be read (the photometry reader says why elsewhere)."""
    try:
        text, _ = decode_text(Path(path).read_bytes())
    except (OSError, LightInvError):
        return None
    lines = text.splitlines()
    if Path(path).suffix.lower() == ".ldt":
        return ra_from_text(lines[LDT_RA_LINE - 1]) if len(lines) >= LDT_RA_LINE else None
    head = []
    for line in lines:
        if line.upper().startswith("TILT"):
            break
        key = line.strip().upper()
        if key.startswith(("[_CRI]", "[CRI]", "[_RA]")):
            return ra_from_text(line.split("]", 1)[1])
        head.append(line)
    m = _IES_RA.search("\n".join(head))
    return float(m.group(1)) if m else None


def _gldf_ra(path: Path, variant: str | None) -> float | None:
    """The Ra a GLDF variant's light source states (None: not stated or unreadable)."""
    from lightinv_core.luminaires.gldf import read_gldf

    try:
        return read_gldf(path).variant(variant).cri_ra
    except (OSError, LightInvError):
        return None


def product_ra(product: str) -> float | None:
    """The Ra product ``product`` states: a catalogue name's file, the .ies/.ldt file
    at that path or a GLDF variant (``FILE.gldf#VARIANT``); None when not stated."""
    for entry in builtin_catalogue():
        if entry.name == product:
            return stated_ra(entry.path)
    ref = split_reference(product)
    if ref is not None and ref[0].suffix.lower() == ".gldf":
        return _gldf_ra(ref[0], ref[1]) if ref[0].is_file() else None
    path = Path(product)
    return stated_ra(path) if path.is_file() else None
