"""Luminaires for the client: the energy figures of the layout and a data sheet per
product (its photometric data, polar curve and how many the design uses).

- ``energy_table``: luminaire count, installed power, power as dimmed, W/m² and
  W/m²/100 lx (the power density per 100 lux of the work plane's maintained Em with the
  luminaires alone, the usual figure of merit);
- ``product_sheets``: for each product of the luminaire arrays, a block with its data
  (manufacturer, name, flux, power, efficacy, opening, lamp) and its polar curve.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from matplotlib.figure import SubFigure
from matplotlib.lines import Line2D

from lightinv_core.design.model import LuminaireArray, Source
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Scenario
from lightinv_core.light.arrays import Product, resolve_product
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.luminaires.catalogue import builtin_catalogue
from lightinv_core.report.tables import Table, product_title
from lightinv_core.sources.emission import source_electric_power
from lightinv_core.sources.types import source_type
from lightinv_core.value_text import fmt

SHEET_HEIGHT = 3.0  # inches: one product's data sheet


@dataclass(frozen=True)
class Energy:
    """The layout's luminaires: ``count``, ``installed_w`` (all at full output),
    ``dimmed_w`` (as dimmed), ``floor_m2`` and the work plane's night Em (lux; None
    without a work plane)."""

    count: int
    installed_w: float
    dimmed_w: float
    floor_m2: float
    em_lux: float | None
    plane: str | None


def layout_energy(
    sources: Sequence[Source],
    arrays: Sequence[LuminaireArray],
    floor_m2: float,
    daylight: LayoutDaylight | None,
) -> Energy:
    """The luminaires' count and power, and the first work plane's Em at night."""
    count, full, dimmed = 0, 0.0, 0.0
    for a in arrays:
        p = resolve_product(a.product, a.watts)
        count += a.count
        full += a.count * p.watts
        dimmed += a.count * p.watts * a.dimming
    for s in sources:
        if source_type(s.kind).electric:
            w = source_electric_power(s)
            count, full, dimmed = count + 1, full + w, dimmed + w
    em, plane = None, None
    grids = daylight.grids if daylight is not None else None
    if daylight is not None and daylight.points is not None and grids is not None and grids.spans:
        plane, span = next(iter(grids.spans.items()))
        em = float(np.mean(daylight.points.lux(Scenario.NIGHT, span)))
    return Energy(count, full, dimmed, floor_m2, em, plane)


def energy_table(e: Energy) -> Table:
    """Count, installed power, W/m² and W/m²/100 lx of the layout."""
    per_m2 = e.installed_w / e.floor_m2 if e.floor_m2 > 0 else float("nan")
    rows = [
        ("luminaires", f"{e.count}"),
        ("installed power (full output)", f"{fmt(e.installed_w)} W"),
    ]
    if abs(e.dimmed_w - e.installed_w) > 1e-6 * max(e.installed_w, 1.0):
        rows.append(("power as dimmed in this layout", f"{fmt(e.dimmed_w)} W"))
    rows.append(("floor area", f"{e.floor_m2:,.1f} m²"))
    rows.append(("power density", f"{fmt(per_m2, 3)} W/m²"))
    note = "Installed power is every luminaire at full output."
    if e.em_lux is not None and e.em_lux > 0:
        dimmed_m2 = e.dimmed_w / e.floor_m2 if e.floor_m2 > 0 else float("nan")
        rows.append((f"Em on work plane {e.plane} (luminaires only)", f"{fmt(e.em_lux)} lux"))
        rows.append(
            ("power density per 100 lux", f"{fmt(100 * dimmed_m2 / e.em_lux, 3)} W/m²/100 lx")
        )
        note += (
            " The power density per 100 lux divides the power as dimmed per m² by the "
            "work plane's maintained Em with the luminaires alone, over 100 lux."
        )
    return Table("Installed power", ("item", "value"), tuple(rows), note=note)


def _entry(p: Product):
    return next((e for e in builtin_catalogue() if e.name == p.name), None)


def product_rows(p: Product, arrays: Sequence[LuminaireArray]) -> list[tuple[str, str]]:
    """(item, value) lines of one product's data sheet."""
    ph = p.photometry
    entry = _entry(p)
    where = "LightInv catalogue" if entry is not None else Path(ph.source).name or "file"
    mine = [a for a in arrays if resolve_product(a.product, a.watts).name == p.name]
    count = sum(a.count for a in mine)
    w, length = p.opening
    rows = [
        ("manufacturer", ph.manufacturer or "not given in the data"),
        ("product", product_title(p)),
        ("photometric data", where),
        ("luminous flux", f"{p.lumens:,.0f} lm"),
        ("input power", f"{p.watts:g} W"),
        ("luminous efficacy", f"{p.lumens / p.watts:,.1f} lm/W" if p.watts > 0 else "—"),
        ("luminous opening", f"{w:.2f} × {length:.2f} m"),
    ]
    if ph.lamp:
        rows.append(("lamp", ph.lamp))
    if entry is not None and entry.description:
        rows.append(("description", entry.description))
    elif p.name != product_title(p):
        rows.append(("description", p.name))
    if ph.catalogue_number and ph.catalogue_number not in product_title(p):
        rows.append(("catalogue number", ph.catalogue_number))
    rows.append(("in this design", f"{count} in {', '.join(a.name for a in mine)}"))
    rows.append(("installed power", f"{count * p.watts:,.1f} W"))
    return rows


def polar_axes(sf: SubFigure, p: Product, rect) -> None:
    """The product's polar curve (cd/klm, C0-C180 solid, C90-C270 dashed) in ``rect``."""
    ax = sf.add_axes(rect, projection="polar")
    ax.set_theta_zero_location("S")
    gam = np.linspace(0.0, 180.0, 181)
    per_klm = 1000.0 / max(p.lumens, 1e-9)
    for c, style in ((0.0, "-"), (90.0, "--")):
        right = p.photometry.intensity(np.full_like(gam, c), gam) * per_klm
        left = p.photometry.intensity(np.full_like(gam, c + 180.0), gam) * per_klm
        theta = np.concatenate([np.radians(gam), -np.radians(gam[::-1])])
        ax.plot(theta, np.concatenate([right, left[::-1]]), style, lw=1.4)
        ax.plot([], [], style, color=ax.lines[-1].get_color(), label=f"C{c:.0f}-C{c + 180:.0f}")
    ax.tick_params(labelsize=6.5)
    ax.set_title("cd/klm", fontsize=8, pad=2)
    ax.legend(fontsize=6.5, loc="lower left", bbox_to_anchor=(-0.15, -0.12), frameon=False)


def product_sheets(arrays: Sequence[LuminaireArray]) -> list[tuple[Product, list]]:
    """(product, rows) of each distinct product of the arrays, in order of use."""
    seen: dict[str, Product] = {}
    for a in arrays:
        try:
            p = resolve_product(a.product, a.watts)
        except LightInvError:
            continue
        seen.setdefault(p.name, p)
    return [(p, product_rows(p, arrays)) for p in seen.values()]


def draw_sheet(sf: SubFigure, p: Product, rows: list[tuple[str, str]]) -> None:
    """One data sheet: the title, the polar curve on the left and the data on the right."""
    sf.text(0.0, 0.97, f"Data sheet: {product_title(p)}", fontsize=11, fontweight="bold", va="top")
    sf.add_artist(Line2D([0, 1], [0.9, 0.9], color="0.6", lw=0.6, transform=sf.transSubfigure))
    polar_axes(sf, p, (0.03, 0.08, 0.3, 0.72))
    y = 0.84
    for item, value in rows:
        sf.text(0.4, y, item, fontsize=8.5, va="top", color="0.3")
        for line in textwrap.wrap(value, 42)[:3]:
            sf.text(0.62, y, line, fontsize=8.5, va="top")
            y -= 0.062
