"""``photometry FILE``: what a photometric file says, where its flux goes and its CIE 190
UGR table (docs/photometry.md, "Glare: UGR"). A file of several products (a GLDF with
variants) is described product by product; ``FILE.gldf#VARIANT`` picks one."""

from __future__ import annotations

import argparse

import numpy as np

from lightinv_core.cli.output import out
from lightinv_core.luminaires.formats import (
    file_facts,
    file_products,
    read_photometry,
    split_reference,
)
from lightinv_core.luminaires.ugr import NoLuminousArea, luminous_area
from lightinv_core.luminaires.ugr_table import (
    ORIENTATIONS,
    REFLECTANCES,
    ROOMS,
    flux_fractions,
    ugr_table,
)


def add_photometry_args(p: argparse.ArgumentParser) -> None:
    """The file and ``--table``."""
    p.add_argument(
        "file", help="photometric file (.ies, .ldt, .gldf; FILE.gldf#VARIANT for one variant)"
    )
    p.add_argument(
        "--table", action="store_true", help="print the whole UGR table (19 rooms x 5 x 2)"
    )


def _pct(x: float) -> str:
    return f"{100.0 * x:.1f}%"


def _table_text(values: np.ndarray) -> list[str]:
    labels = " ".join(f"{round(100 * c):>2d}/{round(100 * w):>2d}" for c, w, _ in REFLECTANCES)
    width = len(labels)
    lines = [
        "UGR table (CIE 190; luminaires 2 m above the eye, spacing 0.25 H; reference plane 20%)",
        f"{'':<10}{'crosswise':<{width}} | endwise   (ceiling/walls)",
        f"{'room X Y':<10}{labels} | {labels}",
    ]
    for (x, y), row in zip(ROOMS, values, strict=True):
        cells = [" ".join(f"{v:5.1f}" for v in row[:, k]) for k in range(len(ORIENTATIONS))]
        lines.append(f"{f'{x}H {y}H':<10}{cells[0]} | {cells[1]}")
    return lines


def cmd_photometry(args) -> int:
    """Print a photometric file's data, flux fractions and UGR (4H 8H, or the table),
    for each product it holds (every variant of a GLDF)."""
    ref = split_reference(args.file)
    if ref is not None and ref[1] is None:
        products = file_products(args.file)  # all of them: one, or a GLDF's variants
    else:
        products = [(args.file, read_photometry(args.file))]
    described = [_describe(name, ph, args.table) for name, ph in products]
    if len(described) == 1:
        out(args, described[0][0], described[0][1])
    else:
        payload = {"file": str(args.file), "products": [d[0] for d in described]}
        text = f"{args.file}: {len(described)} products\n\n" + "\n\n".join(d[1] for d in described)
        out(args, payload, text)
    return 0


def _describe(name: str, ph, full_table: bool) -> tuple[dict, str]:
    """(JSON data, text) of one product's table."""
    flux = ph.flux()
    w, length, height = ph.opening
    area = luminous_area(ph.opening)
    ff = flux_fractions(ph)
    facts, fact_lines = file_facts(name)
    result: dict = {
        "file": str(name),
        "manufacturer": ph.manufacturer,
        "catalogue_number": ph.catalogue_number,
        "name": ph.name,
        "lumens": flux,
        "watts": ph.input_watts,
        "luminous_area": {
            "width_m": abs(w),
            "length_m": abs(length),
            "height_m": abs(height),
            "round": w < 0 and length < 0,
            "area_m2": area,
        },
        "flux_fractions": {
            "down": ff.down,
            "up": ff.up,
            "direct_4h8h": {"reference_plane": ff.floor, "walls": ff.walls, "ceiling": ff.ceiling},
        },
        "warnings": list(ph.warnings),
    }
    watts = f", {ph.input_watts:g} W ({flux / ph.input_watts:.0f} lm/W)" if ph.input_watts else ""
    shape = "round, diameter" if w < 0 and length < 0 else "rectangle"
    size = (
        f"{abs(length):.3f} m"
        if shape.startswith("round")
        else f"{abs(w):.3f} x {abs(length):.3f} m"
    )
    lines = [
        f"{name}: {ph.manufacturer or '?'} {ph.catalogue_number or ''}".rstrip(),
        f"  {ph.name}" if ph.name else "",
        f"flux {flux:,.0f} lm{watts}",
        f"luminous area: {shape} {size}, {area:.4f} m², height {abs(height):.3f} m"
        if area > 0
        else "luminous area: none given",
        f"flux fractions: down {_pct(ff.down)}, up {_pct(ff.up)}; direct in the 4H x 8H room: "
        f"reference plane {_pct(ff.floor)}, walls {_pct(ff.walls)}, ceiling {_pct(ff.ceiling)}",
    ]
    try:
        table = ugr_table(ph)
    except NoLuminousArea as exc:
        result["ugr"], result["ugr_error"] = None, str(exc)
        lines.append(f"UGR: not computed: {exc}")
    else:
        cross, end = (
            table.at((4, 8), orientation="crosswise"),
            table.at((4, 8), orientation="endwise"),
        )
        result["ugr"] = {"room": "4H 8H", "reflectances": [0.7, 0.5, 0.2]}
        result["ugr"].update(crosswise=round(cross, 2), endwise=round(end, 2))
        result["ugr_table"] = {
            "rooms": [f"{x}H {y}H" for x, y in ROOMS],
            "reflectances": [list(r) for r in REFLECTANCES],
            "orientations": list(ORIENTATIONS),
            "values": np.round(table.values, 2).tolist(),
        }
        lines.append(f"UGR (CIE 190, 4H 8H, 70/50/20): crosswise {cross:.1f}, endwise {end:.1f}")
        if full_table:
            lines += _table_text(table.values)
    if facts:
        result["stated"] = facts
        lines[2:2] = fact_lines  # after the name: the maker's ratings, then the table's
    lines += [f"warning: {w}" for w in ph.warnings]
    return result, "\n".join(line for line in lines if line)
