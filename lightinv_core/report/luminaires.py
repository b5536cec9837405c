"""The report's pages on luminaire arrays and work planes, in EN 12464-1's terms.

- the luminaire schedule: per array its product, count, spacing, rotation, dimming,
  flux and power, and the totals; the products' photometry warnings in its note;
- per work plane: its grid and the maintained values Em, Emin, Emax and U0 against the
  intentions on it, with an iso-lux plan.

Grid values come with the luminaires placed exactly (not the optimiser's lattice).
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence

import numpy as np

from lightinv_core.design.model import Design, LuminaireArray
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import UPPER_BOUNDS, Bound, Scenario, bound_sign
from lightinv_core.light.arrays import Product, resolve_product
from lightinv_core.light.daylight import LayoutDaylight
from lightinv_core.light.grids import DesignGrids
from lightinv_core.luminaires.photometry import light_warnings
from lightinv_core.quantities import quantity_spec
from lightinv_core.report.figures import new_figure
from lightinv_core.report.tables import EN_LABELS, FAIL, PASS, Table, product_title
from lightinv_core.transport.workplane import grid_statistics
from lightinv_core.value_text import BOUND_LABELS, fmt, u0_text

ISO_LEVELS = 8  # iso-lux lines per plan


def luminaire_table(arrays: Sequence[LuminaireArray], warnings: Sequence[str] = ()) -> Table | None:
    """The luminaire schedule (None without arrays); ``warnings`` about the luminaires
    (``light.arrays.array_escape_warnings``) join the products' in its note."""
    if not arrays:
        return None
    rows = []
    products = []
    count = watts = lumens = 0.0
    for a in arrays:
        p = resolve_product(a.product, a.watts)
        products.append(p)
        su, sv = a.spacing
        w = a.count * p.watts * a.dimming
        lm = a.count * p.lumens * a.dimming
        count, watts, lumens = count + a.count, watts + w, lumens + lm
        rows.append(
            (
                a.name,
                product_title(p),
                f"{a.rows} x {a.columns} = {a.count}",
                f"{su:.2f} x {sv:.2f}",
                f"{a.rotation}°",
                f"{100 * a.dimming:.0f}%",
                f"{p.lumens:,.0f}",
                f"{p.watts:g}",
                f"{lm:,.0f}",
                f"{w:,.1f}",
            )
        )
    rows.append(
        ("total", "", f"{count:.0f}", "", "", "", "", "", f"{lumens:,.0f}", f"{watts:,.1f}")
    )
    return Table(
        "Luminaire schedule",
        (
            "array",
            "product",
            "rows x columns",
            "spacing m",
            "C0",
            "dimming",
            "lm each",
            "W each",
            "lm",
            "W",
        ),
        tuple(rows),
        note="Spacing along the zone's u and v axes; C0 at 0° runs along u. Output and power "
        "scale with dimming."
        + _warnings_note(products)
        + "".join(f" Warning: {w}" for w in warnings),
    )


def _warnings_note(products: Sequence[Product]) -> str:
    """The products' photometry warnings (what changes their light), for the schedule's
    note: the same lines the command line and the window show."""
    warnings = light_warnings(p.photometry for p in products)
    return "".join(f" Warning: {w}." for w in warnings)


def grid_table(
    design: Design, grids: DesignGrids, lux: np.ndarray, daylight: LayoutDaylight | None = None
) -> Table | None:
    """EN 12464-1 values of each work plane (``lux``: the design scenario) with its
    intentions' verdicts. With ``daylight`` (the layout's ``LayoutDaylight``) each
    intention is judged in its own scenario and quantity (``LayoutDaylight.checks``);
    without, on ``lux``."""
    if not grids.spans:
        return None
    rows, flags = [], []
    other = False
    for name, span in grids.spans.items():
        st = grid_statistics(lux[span])
        g = grids.grids[name]
        asks = [it for it in design.intentions if it.grid == name]
        values = {
            Bound.AVERAGE: st["Em"],
            Bound.MIN: st["Emin"],
            Bound.MAX: st["Emax"],
            Bound.UNIFORMITY: st["U0"],
            Bound.MAX_AVERAGE: st["Em"],
        }
        required = []
        ok, unknown = True, False
        for it in asks:
            q = quantity_spec(it.quantity)
            checks, broken = None, False
            if daylight is not None:
                try:
                    checks = {c.bound: c for c in daylight.checks(it)}
                except LightInvError:  # not measurable (an unreadable weather file)
                    broken = True
            for bound in Bound:
                limit = getattr(it, bound)
                if limit is None:
                    continue
                sign = bound_sign(bound)
                if q.metric is None:  # light on the grid: EN 12464-1's Em, Emin, U0
                    text = f"{EN_LABELS[bound]} {sign} {fmt(limit)}"
                    if it.scenario != Scenario.DESIGN:
                        text += f" ({it.scenario})"
                        other = True
                else:
                    units = q.unit if bound != Bound.UNIFORMITY else ""
                    label = BOUND_LABELS.get(bound, str(bound))
                    text = f"{q.metric} {label} {sign} {fmt(limit)}"
                    text += f" {units}" if units else ""
                    other = True
                required.append(text)
                if broken:
                    unknown = True
                    continue
                if checks is not None:
                    chk = checks.get(bound)  # none for a bound of 0: it bounds nothing
                    met = chk is None or bool(chk.met[0])
                else:
                    v = values[bound]
                    met = v <= limit * 1.001 if bound in UPPER_BOUNDS else v >= limit * 0.999
                ok = ok and met
        verdict = PASS if ok and not unknown else FAIL if not ok else "—"
        rows.append(
            (
                name,
                f"{st['points']} ({g.spacing[0]:.2f} x {g.spacing[1]:.2f} m)",
                fmt(st["Em"]),
                fmt(st["Emin"]),
                fmt(st["Emax"]),
                u0_text(st["U0"]),
                ", ".join(required) or "—",
                verdict if asks else "—",
            )
        )
        flags.append({PASS: "pass", FAIL: "fail"}.get(verdict, "") if asks else "")
    note = (
        "Maintained values (maintenance factor applied) with the luminaires placed "
        "exactly; grid spacing by p = 0.2 x 5^log10(d). A bound met to within 0.1% passes."
    )
    if other:
        note += (
            " Em to U0 are in the design scenario; a requirement in another scenario "
            "(bracketed) or on a daylight metric is judged in its own: its value is in "
            "the lighting intentions table."
        )
    return Table(
        "Work planes (EN 12464-1)",
        (
            "work plane",
            "points (spacing)",
            "Em lux",
            "Emin lux",
            "Emax lux",
            "U0",
            "required",
            "result",
        ),
        tuple(rows),
        tuple(flags),
        note=note,
    )


def plan_figure(
    pts: np.ndarray,
    val: np.ndarray,
    spacing: tuple[float, float],
    title: str,
    label: str,
    *,
    cmap: str = "inferno",
    level_format: str = "%.0f",
    vmax: float | None = None,
    outlines: list | None = None,
    fig=None,
):
    """A plan of one work plane's grid points ``pts`` (q, 3) coloured by ``val`` (q,)
    from 0, with iso-lines labelled by ``level_format``, a colour bar labelled ``label``
    and, optionally, 3-D ``outlines`` (``views.Outline``) drawn in plan; into ``fig`` (a
    subfigure of a report page) when given."""
    fig = new_figure() if fig is None else fig
    ax = fig.add_axes([0.08, 0.1, 0.78, 0.8])
    # A long title (the DF plan's) wraps rather than running off a portrait page.
    ax.set_title("\n".join(textwrap.wrap(title, 95)) if "\n" not in title else title, fontsize=11)
    sc = ax.scatter(pts[:, 0], pts[:, 1], c=val, cmap=cmap, s=30, vmin=0.0, vmax=vmax)
    if len(pts) >= 4 and np.ptp(val) > 0:
        levels = np.linspace(val.min(), val.max(), ISO_LEVELS + 2)[1:-1]
        cs = ax.tricontour(pts[:, 0], pts[:, 1], val, levels=levels, colors="0.2", linewidths=0.8)
        ax.clabel(cs, fmt=level_format, fontsize=7)
    pad = 0.5 * max(spacing)
    lo = pts[:, :2].min(axis=0) - pad
    hi = pts[:, :2].max(axis=0) + pad
    for o in outlines or ():
        if o.kind == "zone":
            continue
        xy = np.asarray(o.points, float)[:, :2]
        closed = np.vstack([xy, xy[:1]])
        ax.plot(closed[:, 0], closed[:, 1], color="#00a5c0", lw=1.2, ls="--", zorder=3)
        if o.kind != "luminaire":  # one label per source; luminaires are many: unlabelled
            ax.annotate(
                o.label, xy.mean(axis=0), color="#00a5c0", fontsize=8, ha="center", va="center"
            )
        lo, hi = np.minimum(lo, xy.min(axis=0) - pad), np.maximum(hi, xy.max(axis=0) + pad)
    ax.set_aspect("equal")
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    cb = fig.colorbar(sc, cax=fig.add_axes([0.88, 0.1, 0.02, 0.8]))
    cb.set_label(label)
    return fig


def isolux_plan(grids: DesignGrids, lux: np.ndarray, name: str, fig=None, outlines=None):
    """The plan of work plane ``name`` coloured by ``lux`` with iso-lux lines (into
    ``fig`` when given; ``outlines`` drawn in plan)."""
    span = grids.spans[name]
    pts, val = grids.points[span], lux[span]
    st = grid_statistics(val)
    title = (
        f"Work plane {name} at z = {pts[0, 2]:.2f} m: Em {st['Em']:.0f} lux, "
        f"Emin {st['Emin']:.0f}, Emax {st['Emax']:.0f}, U0 {u0_text(st['U0'])}"
    )
    spacing = grids.grids[name].spacing
    return plan_figure(pts, val, spacing, title, "illuminance (lux)", fig=fig, outlines=outlines)
