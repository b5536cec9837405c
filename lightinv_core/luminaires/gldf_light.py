"""A GLDF variant's light as one photometric table.

Each light emitter's EULUMDAT or IES file inside the zip is read by the readers of
``ldt.py`` and ``ies.py``, so every check and message of those formats holds. Then:

- **GLDF over photometry** (gldf.io, "Conventions: GLDF over Photometry"): where the
  GLDF states a rated flux for an emitter and its file another, the GLDF wins. A
  relative table (cd per the file's lamp lumens) is scaled by rated / lamp lumens; an
  absolute one by rated / its integrated flux when they differ by more than 1% (the
  integration rule and printed digits alone differ by 0.01-0.1%). Equal ratings leave
  the table's numbers untouched. Either scaling is a warning the user sees.
- **Several emitters on together** (a direct and an indirect part): their tables are
  summed on the union of their C and gamma angles. Bilinear interpolation on a finer
  grid reproduces each table's own interpolation exactly; where a table stops short of
  0 or 180 degrees (a direct part ending at 90) its step to 0 is kept by a grid angle
  ``EDGE_STEP`` beyond its last one, so the sum's flux is the parts' to 1e-5.
  The luminous opening is the first emitter's.
- The table's name is the product's and the variant's, its maker the GLDF's
  manufacturer, its input watts the GLDF's rated power (the files' where the GLDF
  states none), its ``source`` the reference ``FILE.gldf#VARIANT``.
"""

from __future__ import annotations

import os
from dataclasses import replace
from pathlib import Path

import numpy as np

from lightinv_core.luminaires.gldf import (
    GldfEmitter,
    GldfProduct,
    GldfVariant,
    read_gldf,
    read_member,
)
from lightinv_core.luminaires.ies import parse_ies
from lightinv_core.luminaires.ldt import parse_ldt
from lightinv_core.luminaires.photometry import Photometry, fail

FLUX_TOLERANCE = 0.01
"""An absolute table within 1% of the GLDF's rated flux is used as it is."""
EDGE_STEP = 1e-3
"""Degrees: a table ending at gamma G (a direct part at 90) is 0 from G + this on."""
_PARSERS = {"ldt": parse_ldt, "ies": parse_ies}


def reference(path: str | os.PathLike, variant_id: str) -> str:
    """How a project names one variant of a GLDF file: ``PATH#VARIANT``."""
    return f"{path}#{variant_id}"


def emitter_photometry(path: str | os.PathLike, emitter: GldfEmitter) -> Photometry:
    """One emitter's table from its file in the zip, scaled to the GLDF's rated flux
    (see the module)."""
    source = f"{path}:{emitter.member}"
    ph = _PARSERS[emitter.kind](read_member(path, emitter.member), source)
    if emitter.rotated:
        raise fail(
            source,
            None,
            f"emitter {emitter.emitter_id!r} is rotated ({emitter.rotated})",
            "LightInv reads emitters in their measured position only",
        )
    rated = emitter.lumens
    if not rated or ph.kind != "C":
        return ph
    if ph.lamp_lumens is not None:
        ratio, said = rated / ph.lamp_lumens, f"lamp flux {ph.lamp_lumens:,.0f} lm"
        if ratio == 1.0:
            return ph
    else:
        flux = ph.flux()
        ratio, said = rated / flux, f"table integrates to {flux:,.0f} lm"
        if abs(ratio - 1.0) <= FLUX_TOLERANCE:
            return ph
    warning = (
        f"the GLDF rates emitter {emitter.emitter_id} at {rated:,.0f} lm, its file's "
        f"{said}: intensities scaled by {ratio:.4g} (the GLDF's values win)"
    )
    return replace(
        ph,
        candela=ph.candela * ratio,
        lamp_lumens=None if ph.lamp_lumens is None else rated,
        warnings=(*ph.warnings, warning),
    )


def _summed(tables: list[Photometry]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(C angles, gamma angles, candela) of the tables' sum on the union grid."""
    c = np.unique(np.concatenate([t.c_angles for t in tables]))
    edges = []  # where a table ends short of 0 or 180 deg its light stops: a step, kept
    for t in tables:
        lo, hi = t.gamma_angles[0], t.gamma_angles[-1]
        edges += [lo - EDGE_STEP] if lo > EDGE_STEP else []
        edges += [hi + EDGE_STEP] if hi < 180.0 - EDGE_STEP else []
    g = np.unique(np.concatenate([t.gamma_angles for t in tables] + [np.array(edges)]))
    cc, gg = np.meshgrid(c, g, indexing="ij")
    return c, g, sum(t.intensity(cc, gg) for t in tables)


def variant_photometry(
    path: str | os.PathLike, variant_id: str | None = None, product: GldfProduct | None = None
) -> Photometry:
    """The photometry of variant ``variant_id`` (None: the first) of the GLDF at
    ``path``; ``product`` is its ``read_gldf`` when already read."""
    product = product or read_gldf(path)
    v = product.variant(variant_id)
    tables = [emitter_photometry(path, e) for e in v.emitters]
    first = tables[0]
    notes = [*v.notes, f"GLDF {product.format_version}, variant {v.variant_id}"]
    if len(tables) > 1:
        notes.append(f"{len(tables)} emitters on together, their tables summed")
        c, g, cd = _summed(tables)
        kinds = {t.kind for t in tables}
        if kinds != {"C"}:
            raise fail(str(path), None, "emitters of photometry types other than C", "")
    else:
        c, g, cd = first.c_angles, first.gamma_angles, first.candela
    lamps = [t.lamp_lumens for t in tables]
    file_watts = [t.input_watts for t in tables]
    watts = v.watts
    if watts is None and None not in file_watts:
        watts = float(sum(file_watts))  # type: ignore[arg-type]
    return Photometry(
        kind=first.kind,
        c_angles=c,
        gamma_angles=g,
        candela=cd,
        lamp_lumens=None if None in lamps else float(sum(lamps)),  # type: ignore[arg-type]
        input_watts=watts or None,
        opening=first.opening,
        name=v.name,
        manufacturer=product.manufacturer or first.manufacturer,
        catalogue_number=v.number or first.catalogue_number,
        source=reference(Path(path), v.variant_id),
        n_lamps=sum(t.n_lamps for t in tables),
        lamp=" + ".join(e.lamp or t.lamp for e, t in zip(v.emitters, tables, strict=True)),
        notes=(*notes, *(n for t in tables for n in t.notes)),
        warnings=tuple(w for t in tables for w in t.warnings),
    )


def _maintenance_lines(v: GldfVariant) -> list[str]:
    m = v.maintenance
    lines = [f"LLMF {llmf:g}, LSF {lsf:g} at {hours:,.0f} h" for hours, llmf, lsf in m.lamp]
    lines += [
        f"LMF {lmf:g} after {years:g} years ({room or '?'})" for years, room, lmf in m.luminaire
    ]
    if m.lifetime_h:
        lines.append(f"light source life {m.lifetime_h:,.0f} h")
    return lines + list(m.useful_life)


def variant_facts(path: str | os.PathLike, variant_id: str | None) -> tuple[dict, list[str]]:
    """What the GLDF states of a variant beyond its table, as (JSON data, text lines):
    rated flux and power, CCT, CRI (Ra), product size, maintenance, the reader's notes."""
    v = read_gldf(path).variant(variant_id)
    data = {
        "variant": v.variant_id,
        "variant_name": v.variant_name,
        "rated_lumens": v.lumens,
        "rated_watts": v.watts,
        "cct_k": v.cct_k,
        "cri_ra": v.cri_ra,
        "size_m": list(v.size_m) if v.size_m else None,
        "maintenance": _maintenance_lines(v),
        "notes": list(v.notes),
    }
    rated = [
        f"{v.lumens:,.0f} lm" if v.lumens is not None else "",
        f"{v.watts:g} W" if v.watts is not None else "",
        f"CCT {v.cct_k:g} K" if v.cct_k else "",
        f"Ra {v.cri_ra:g}" if v.cri_ra else "",
        "size {:g} x {:g} x {:g} m (L x W x H)".format(*v.size_m) if v.size_m else "",
    ]
    lines = [f"GLDF variant {v.variant_id}: " + (", ".join(t for t in rated if t) or "-")]
    if data["maintenance"]:
        lines.append("maintenance: " + "; ".join(data["maintenance"]))
    return data, lines
