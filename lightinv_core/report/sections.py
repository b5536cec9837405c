"""The report's content as flow blocks, section by section (``layout.Block``).

``report_blocks(ctx)`` gives every block in order: the title and the design's status,
how the layout was found, the room, the luminaires (schedule, installed power, a data
sheet per product, the maintenance factor), the work planes (EN 12464-1 criteria and
iso-lux plans), the views with their legend, the sources and rules, the lighting
intentions, the daylight and energy section, convergence and the Pareto front.
Each block draws lazily: the views are rendered only when their page is made.
"""

from __future__ import annotations

import datetime
import textwrap
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lightinv_core.design.solution import Solution
from lightinv_core.errors import LightInvError
from lightinv_core.light.arrays import array_escape_warnings, resolve_product
from lightinv_core.optimize.mop import front_pair
from lightinv_core.optimize.quality import front_quality, front_scales
from lightinv_core.project import Project
from lightinv_core.report import daylight as dl
from lightinv_core.report.calc_objects import calc_table
from lightinv_core.report.chosen import Chosen
from lightinv_core.report.criteria import status_table, workplane_criteria
from lightinv_core.report.datasheet import (
    SHEET_HEIGHT,
    draw_sheet,
    energy_table,
    layout_energy,
    product_sheets,
)
from lightinv_core.report.en17037 import en17037_table
from lightinv_core.report.figures import convergence_figure, pareto_figure
from lightinv_core.report.layout import (
    TEXT_WIDTH,
    Block,
    drawing,
    heading,
    paragraph,
    table_block,
)
from lightinv_core.report.luminaires import grid_table, isolux_plan, luminaire_table
from lightinv_core.report.provenance import Provenance, settings_rows
from lightinv_core.report.room import floor_area, maintenance_text, room_table, surfaces_table
from lightinv_core.report.tables import (
    Table,
    group_table,
    intention_table,
    product_title,
    rules_table,
    source_table,
)
from lightinv_core.report.views import (
    CAMERAS,
    luminaire_outlines,
    marker_legend,
    render_view,
    source_outlines,
    view_extent,
)
from lightinv_core.sources.types import daylit
from lightinv_core.study.solution_light import SolutionLight
from lightinv_core.value_text import objective_text


@dataclass
class Context:
    """What the sections read: the project, its prepared scene, the reported solution
    (``chosen``), its light, and the run that found it (``found``, None: by hand)."""

    project: Project
    prepared: object
    chosen: Chosen
    light: SolutionLight
    found: Provenance | None

    @property
    def sol(self) -> Solution:
        return self.chosen.solution


def _plot_height(aspect: float, lo: float = 2.3, hi: float = 6.2) -> float:
    """Inches a plot of height/width ``aspect`` needs at the text width (colour bar,
    title and axis labels included)."""
    return float(np.clip((TEXT_WIDTH - 1.5) * aspect + 0.9, lo, hi))


def title_blocks(ctx: Context) -> list[Block]:
    """The title, the design's status per criterion and how the layout was found."""
    project, sol = ctx.project, ctx.sol
    date = datetime.date.today().isoformat()
    source = project.path.name if project.path is not None else "(unsaved project)"
    desc = textwrap.wrap(project.description, 105)[:3]

    # A long name wraps (up to two lines) rather than running off the page.
    name = textwrap.wrap(project.name, 44)[:2] or [""]
    extra = 0.36 * (len(name) - 1)

    def title(sf) -> None:
        h = 1.15 + extra + 0.17 * len(desc)
        sf.text(0, 1 - 0.12 / h, "Lighting design report", fontsize=10, color="0.35", va="top")
        for k, line in enumerate(name):
            sf.text(0, 1 - (0.32 + 0.36 * k) / h, line, fontsize=20, fontweight="bold", va="top")
        y = 0.78 + extra
        for line in desc:
            sf.text(0, 1 - y / h, line, fontsize=9.5, color="0.25", va="top")
            y += 0.17
        meta = f"Date {date}   ·   project file {source}   ·   layout: {ctx.chosen.label}"
        sf.text(0, 1 - (y + 0.08) / h, meta, fontsize=9, va="top")

    blocks = [drawing(1.15 + extra + 0.17 * len(desc), title, "title", shrink=1.0)]
    rules = rules_table(sol, project.design, ctx.prepared.patches)
    blocks.append(
        table_block(status_table(project.design, sol, ctx.light.daylight, rules), "title")
    )
    goals = [
        (objective_text(k, v).split(":")[0], objective_text(k, v).split(": ", 1)[-1])
        for k, v in sol.objectives.items()
    ]
    primary = project.design.goals[0].kind
    goals = [
        (name + (" (optimised goal)" if k == primary else ""), value)
        for (name, value), k in zip(goals, sol.objectives, strict=True)
    ]
    if ctx.found is not None:
        rows = settings_rows(ctx.found) + goals
        blocks.append(
            table_block(Table("How this layout was found", ("item", "value"), tuple(rows)), "title")
        )
    else:
        blocks.append(
            table_block(
                Table(
                    "How this layout was found",
                    ("item", "value"),
                    (
                        ("optimiser", "none: the layout as designed, not from an optimisation run"),
                        *goals,
                    ),
                ),
                "title",
            )
        )
    return blocks


def room_blocks(ctx: Context) -> list[Block]:
    """The room's data and its surfaces."""
    return [
        heading("Room", "room"),
        table_block(room_table(ctx.project, ctx.prepared), "room"),
        table_block(surfaces_table(ctx.project, ctx.prepared), "room"),
    ]


def luminaire_blocks(ctx: Context) -> list[Block]:
    """The luminaire schedule, the installed power, a data sheet per product and the
    maintenance factor; none without luminaires."""
    sol, design, p = ctx.sol, ctx.project.design, ctx.prepared.patches
    lay = ctx.light.daylight
    floor = lay.floor_m2 if lay is not None and lay.floor_m2 > 0 else floor_area(p)
    energy = layout_energy(sol.sources, sol.arrays, floor, lay)
    if energy.count == 0:
        return []
    blocks = [heading("Luminaires", "luminaires")]
    if sol.arrays:
        lost = array_escape_warnings(p, sol.arrays)
        blocks.append(table_block(luminaire_table(sol.arrays, lost), "luminaires"))
    blocks.append(table_block(energy_table(energy), "luminaires"))
    blocks.append(paragraph(maintenance_text(design, sol.arrays), "luminaires"))
    for product, rows in product_sheets(sol.arrays):
        blocks.append(
            drawing(
                SHEET_HEIGHT,
                lambda sf, product=product, rows=rows: draw_sheet(sf, product, rows),
                "luminaires",
            )
        )
    return blocks


def workplane_blocks(ctx: Context) -> list[Block]:
    """Each work plane's EN 12464-1 criteria, its statistics and its iso-lux plan."""
    light, design = ctx.light, ctx.project.design
    grids, lux = light.grids, light.grid_lux
    if grids is None:
        return []
    title = "Work planes" if design.workplanes else "Calculation objects"
    blocks = [heading(title, "workplanes")]
    crit = workplane_criteria(design, ctx.sol, light.daylight)
    if crit is not None:
        blocks.append(table_block(crit, "workplanes"))
    stats = grid_table(design, grids, lux, light.daylight)
    if stats is not None:
        blocks.append(table_block(stats, "workplanes"))
    calc = calc_table(design, grids, lux, light.daylight)
    if calc is not None:
        blocks.append(table_block(calc, "workplanes"))
    outlines = _outlines(ctx)
    for name, span in grids.spans.items():
        pts = grids.points[span]
        w, h = np.ptp(pts[:, 0]) + 1.0, np.ptp(pts[:, 1]) + 1.0
        blocks.append(
            drawing(
                _plot_height(h / w),
                lambda sf, name=name: isolux_plan(grids, lux, name, fig=sf, outlines=outlines),
                "workplanes",
            )
        )
    return blocks


def _outlines(ctx: Context) -> list:
    p = ctx.prepared.patches
    return source_outlines(p, ctx.sol.sources) + luminaire_outlines(p, ctx.sol.arrays)


def view_blocks(ctx: Context) -> list[Block]:
    """The false-colour views (plan, elevation, isometric) with numbered markers and
    their legend."""
    p, H = ctx.prepared.patches, ctx.light.field.illuminance
    outlines = _outlines(ctx)
    blocks = [
        heading("Light on the room's surfaces", "views"),
        paragraph(
            "Illuminance (lux) of every surface with the layout's sources, false colour "
            "(each view has its own scale, 0 to its 99th percentile). Sources and "
            "luminaires are outlined in cyan and numbered; the legend below the views "
            "names them.",
            "views",
            keep_with_next=True,
        ),
    ]
    for name in ("top", "front", "iso"):
        w, h = view_extent(p, name)

        def draw(sf, name=name) -> None:
            render_view(p, H, CAMERAS[name], outlines=outlines, vmin=0.0, fig=sf, numbered=True)

        high = 4.6 if name == "iso" else 5.5  # the isometric view shows least: smaller
        blocks.append(drawing(_plot_height(h / w, hi=high), draw, "views"))
    if any(o.kind != "zone" for o in outlines):
        describe = {s.name: f"{s.kind} in {s.zone}" for s in ctx.sol.sources}
        for a in ctx.sol.arrays:
            try:
                product = product_title(resolve_product(a.product, a.watts))
            except LightInvError:
                product = Path(a.product).name
            describe[a.name] = f"array of {product} in {a.zone}"
        blocks.append(table_block(marker_legend(outlines, describe), "views"))
    return blocks


def source_blocks(ctx: Context) -> list[Block]:
    """The sources (and arrays) with their settings, and the geometric rules."""
    sol, design = ctx.sol, ctx.project.design
    blocks = [table_block(source_table(sol, design), "sources")]
    rules = rules_table(sol, design, ctx.prepared.patches)
    if rules is not None:
        blocks.append(table_block(rules, "sources"))
    return blocks


def intention_blocks(ctx: Context) -> list[Block]:
    """Every lighting intention's bounds, and the illuminance per surface group."""
    field, lay = ctx.light.field, ctx.light.daylight
    blocks = []
    table = intention_table(ctx.sol, ctx.project.design, field, lay)
    if table is not None:
        blocks.append(table_block(table, "intentions"))
    blocks.append(table_block(group_table(field), "intentions"))
    return blocks


def daylight_blocks(ctx: Context) -> list[Block]:
    """The daylight and energy section (skylights and work planes)."""
    sol, lay = ctx.sol, ctx.light.daylight
    if not dl.has_daylight(ctx.project.design, sol.sources) or lay.points is None:
        return []
    section = dl.daylight_section(lay, list(daylit(sol.sources)))
    outlines = _outlines(ctx)
    blocks = [
        heading("Daylight and energy", "daylight"),
        table_block(dl.climate_table(section), "daylight"),
        table_block(dl.daylight_table(section), "daylight"),
    ]
    en17037 = None if section.problem else en17037_table(lay)
    if en17037 is not None:
        blocks.append(table_block(en17037, "daylight"))
    if section.energy is not None:
        blocks.append(table_block(dl.energy_table(section), "energy"))
        groups = dl.control_groups_table(section)
        if groups is not None:
            blocks.append(table_block(groups, "energy"))
        blocks.append(drawing(3.2, lambda sf: dl.monthly_chart(section, sf), "energy"))
    plans = [(p, dl.df_plan, "df-plan") for p in section.planes]
    plans += [(p, dl.da_plan, "da-plan") for p in section.planes if p.da is not None]
    for plane, plan, kind in plans:
        aspect = (np.ptp(plane.points[:, 1]) + 1) / (np.ptp(plane.points[:, 0]) + 1)
        blocks.append(
            drawing(
                _plot_height(aspect),
                lambda sf, plane=plane, plan=plan: plan(section, plane, outlines, fig=sf),
                kind,
            )
        )
    return blocks


def run_blocks(ctx: Context) -> list[Block]:
    """Convergence of the search (when recorded) and the Pareto front."""
    project, sol = ctx.project, ctx.sol
    blocks = []
    history_of = ctx.found.solution if ctx.found is not None else sol
    if history_of.info.history:
        primary = project.design.goals[0].kind
        blocks.append(
            drawing(5.0, lambda sf: convergence_figure(history_of, primary, fig=sf), "convergence")
        )
    if project.pareto is not None and project.pareto.solutions:
        quality = None
        # Measured (hypervolume, spacing) when the front is of the design's own pair.
        pair = front_pair(project.design)
        if set(project.pareto.objectives) == set(map(str, pair)):
            # The pair given: a front of another pair (energy against installed power,
            # the flagship's) has no default to fall back on.
            scales = front_scales(project.design, ctx.prepared.light, pair)
            quality = front_quality(project.pareto.solutions, scales, pair)
        blocks.append(
            drawing(5.5, lambda sf: pareto_figure(project.pareto, sol, quality, fig=sf), "pareto")
        )
    return blocks


def report_blocks(ctx: Context) -> list[Block]:
    """Every block of the report, in order."""
    return [
        *title_blocks(ctx),
        *room_blocks(ctx),
        *luminaire_blocks(ctx),
        *workplane_blocks(ctx),
        *view_blocks(ctx),
        *source_blocks(ctx),
        *intention_blocks(ctx),
        *daylight_blocks(ctx),
        *run_blocks(ctx),
    ]
