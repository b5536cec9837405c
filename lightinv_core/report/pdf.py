"""``write_report``: a project's solution as a PDF (and optionally PNG pages).

Pages, in order: title (project, scene, operator, solution status and objectives),
the false-colour views (top, front, iso), the tables (sources and geometric rules,
lighting intentions and illuminance per group), the luminaire schedule and polar curves
(designs with luminaire arrays), the work planes' EN 12464-1 values and iso-lux plans
(designs with work planes), the daylight and energy section (designs with skylights and
work planes: ``report/daylight.py``), convergence (when the solution recorded a history)
and the Pareto front (multi-objective projects).

The PDF is written atomically: a failed or cancelled report leaves neither a PDF nor
any of its PNG pages behind, and an older file at ``path`` is kept untouched.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure

from lightinv_core.atomic import atomic_writer
from lightinv_core.errors import CancelledError
from lightinv_core.light.arrays import array_escape_warnings, resolve_product
from lightinv_core.optimize.mop import front_pair
from lightinv_core.optimize.quality import front_quality, front_scales
from lightinv_core.project import Project
from lightinv_core.report.chosen import Chosen, choose_solution
from lightinv_core.report.daylight import (
    climate_table,
    da_figures,
    daylight_section,
    daylight_table,
    df_figures,
    energy_figure,
    has_daylight,
)
from lightinv_core.report.figures import (
    convergence_figure,
    pareto_figure,
    table_pages,
    text_page,
)
from lightinv_core.report.luminaires import (
    grid_table,
    isolux_figures,
    luminaire_table,
    polar_figure,
)
from lightinv_core.report.tables import (
    Table,
    group_table,
    intention_table,
    rules_table,
    source_table,
)
from lightinv_core.report.views import (
    CAMERAS,
    luminaire_outlines,
    render_view,
    source_outlines,
)
from lightinv_core.sources.types import daylit
from lightinv_core.study import solution_light
from lightinv_core.value_text import fmt, objective_text

PDF_DPI = 150  # resolution of the rasterised views inside the PDF
PNG_DPI = 100


@dataclass(frozen=True)
class ReportInfo:
    """What ``write_report`` wrote: the PDF, its page names in order ("title",
    "view-top", ..., "sources", "intentions", "convergence", "pareto"), the PNG files
    (empty without ``png_dir``), which solution it shows and how long it took."""

    path: Path
    pages: tuple[str, ...]
    png_files: tuple[Path, ...]
    solution: str
    feasible: bool
    seconds: float


def _scene_lines(project: Project, prepared) -> list[str]:
    spec, patches, op = project.scene, prepared.patches, prepared.operator
    where = f"built-in '{spec.builtin}'" if spec.builtin else f"OBJ {Path(spec.obj).name}"
    res = f"{spec.resolution:g} m patches" if spec.resolution else "default patch size"
    err = op.info.get("estimated_rel_error") if isinstance(op.info, dict) else None
    err_text = (
        f"{100 * err:.2f}% mean relative error of C (estimated)"
        if isinstance(err, int | float) and math.isfinite(err)
        else "error estimate not recorded"
    )
    zones = ", ".join(patches.zone_names) or "none"
    return [
        f"Scene: {where}, {res}",
        f"{patches.n:,} patches, {patches.area.sum():,.1f} m² of surface",
        f"Groups: {', '.join(patches.group_names)}",
        f"Emitter zones: {zones}",
        f"Radiosity operator: rank k = {op.k:,}, {op.info.get('rays', '?')} rays per patch",
        f"Operator accuracy: {err_text}",
    ]


def _solution_lines(project: Project, chosen: Chosen) -> list[str]:
    sol = chosen.solution
    status = (
        "FEASIBLE: every rule and intention met"
        if sol.feasible
        else f"INFEASIBLE: {len(sol.violations)} violated rule(s) or intention(s)"
    )
    lines = [f"Reported: {chosen.label}", f"Status: {status}", f"Penalty P = {fmt(sol.penalty)}"]
    primary = project.design.goals[0].kind
    for kind, value in sol.objectives.items():
        tag = "  (optimised goal)" if kind == primary else ""
        lines.append(objective_text(kind, value) + tag)
    info = sol.info
    run = []
    if info.evaluations is not None:
        run.append(f"{info.evaluations:,} evaluations")
    if info.seconds is not None:
        run.append(f"{info.seconds:.1f} s")
    if info.seed is not None:
        run.append(f"seed {info.seed}")
    if info.status:
        run.append(f"stopped by {info.status}")
    if not info.method and not run:  # a layout given by hand, never optimised
        lines.append("Optimiser: none (the layout as given)")
    else:
        lines.append(
            f"Optimiser: {project.optimizer.method}" + (f"; {', '.join(run)}" if run else "")
        )
    return lines


def _bounds_line(intentions: Table | None) -> list[str]:
    if intentions is None:
        return ["Lighting intentions: none"]
    ok = intentions.flags.count("pass")
    failed = [
        f"{r[0]} {r[2].split()[0]}"
        for r, f in zip(intentions.rows, intentions.flags, strict=True)
        if f == "fail"
    ]
    text = f"Lighting intention bounds met: {ok} of {len(intentions.rows)}"
    return [text + (f" (failed: {', '.join(failed)})" if failed else "")]


def _title_page(
    project: Project, prepared, chosen: Chosen, contents: list[str], intentions: Table | None
) -> Figure:
    date = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    source = project.path.name if project.path is not None else "(unsaved project)"
    sections = [
        ("Project", [f"File: {source}", f"Report made {date} by LightInv"]),
        ("Scene and operator", _scene_lines(project, prepared)),
        ("Solution", _solution_lines(project, chosen) + _bounds_line(intentions)),
        ("Pages", [", ".join(contents[i : i + 6]) for i in range(0, len(contents), 6)]),
    ]
    return text_page(project.name, sections, project.description)


def write_report(
    project: Project,
    prepared,
    path: str | Path,
    solution=None,
    png_dir: str | Path | None = None,
    label: str | None = None,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
) -> ReportInfo:
    """Write a PDF report of ``solution`` (default: the project's first saved solution,
    else the first of its Pareto front) to ``path``.

    ``prepared`` is ``lightinv_core.study.prepare(project)`` (scene, patches and
    operator). With ``png_dir`` each page is also saved as ``NN-name.png``. ``progress``
    gets the fraction done after each page; ``label`` names where the solution came
    from on the title page (default: as ``choose_solution`` says); ``cancel`` is polled
    between pages and a True answer raises ``CancelledError`` (nothing is left on disk).
    """
    t0 = time.perf_counter()
    path = Path(path)
    chosen = choose_solution(project, solution)
    if label is not None:  # e.g. "the design on screen" rather than "given solution"
        chosen = dataclasses.replace(chosen, label=label)
    sol = chosen.solution
    patches, design = prepared.patches, project.design
    light = solution_light(prepared, design, sol)
    field = light.field
    H = field.illuminance
    outlines = source_outlines(patches, sol.sources) + luminaire_outlines(patches, sol.arrays)
    # The layout's light in every scenario: intentions are judged in their own.
    lay = light.daylight
    intentions = intention_table(sol, design, field, lay)

    def view(name):
        # Each view has its own colour bar, from 0 to the 99th percentile of what it
        # shows, so a bright wall seen from one side does not darken the floor plan.
        return lambda: render_view(patches, H, CAMERAS[name], outlines=outlines, vmin=0.0)

    def tables_first():
        return table_pages([source_table(sol, design), rules_table(sol, design, patches)])

    def tables_second():
        return table_pages([intentions, group_table(field)])

    grids, grid_lux = light.grids, light.grid_lux

    primary = design.goals[0].kind
    plan: list[tuple[str, Callable[[], Figure | list[Figure] | None]]] = [
        ("view-top", view("top")),
        ("view-front", view("front")),
        ("view-iso", view("iso")),
        ("sources", tables_first),
        ("intentions", tables_second),
    ]
    if sol.arrays:
        lost = array_escape_warnings(patches, sol.arrays)
        plan.append(("luminaires", lambda: table_pages([luminaire_table(sol.arrays, lost)])))
        products = [resolve_product(a.product, a.watts) for a in sol.arrays]
        plan.append(("polar", lambda: polar_figure(products)))
    if grids is not None:
        plan.append(("workplanes", lambda: table_pages([grid_table(design, grids, grid_lux, lay)])))
        plan.append(("isolux", lambda: isolux_figures(grids, grid_lux)))
    if has_daylight(design, sol.sources) and lay.points is not None:
        skylights = list(daylit(sol.sources))
        section = daylight_section(lay, skylights)

        daylight_tables = [climate_table(section), daylight_table(section)]
        plan.append(("daylight", lambda: table_pages(daylight_tables)))
        if section.energy is not None:
            plan.append(("energy", lambda: energy_figure(section)))
        plan.append(("df-plan", lambda: df_figures(section, outlines)))
        if any(p.da is not None for p in section.planes):
            plan.append(("da-plan", lambda: da_figures(section, outlines)))
    history = sol.info.history
    if history:
        plan.append(("convergence", lambda: convergence_figure(sol, primary)))
    if project.pareto is not None and project.pareto.solutions:
        quality = None
        # Measured (hypervolume, spacing) when the front is of the design's own pair
        # (power and light, or the climate pair): the pair its scales normalise.
        if set(project.pareto.objectives) == set(map(str, front_pair(design))):
            scales = front_scales(project.design, prepared.light)
            quality = front_quality(project.pareto.solutions, scales)
        plan.append(("pareto", lambda: pareto_figure(project.pareto, sol, quality)))
    names = ["title", *(n for n, _ in plan)]
    plan.insert(0, ("title", lambda: _title_page(project, prepared, chosen, names, intentions)))

    metadata = {
        "Title": f"LightInv report: {project.name}",
        "Creator": "LightInv",
        "Subject": f"{chosen.label}, {'feasible' if sol.feasible else 'infeasible'}",
    }
    pages: list[str] = []
    pngs: list[Path] = []
    png_root = Path(png_dir) if png_dir is not None else None
    try:
        with atomic_writer(path, "wb") as fh, PdfPages(fh, metadata=metadata) as pdf:
            for k, (name, make) in enumerate(plan):
                if cancel is not None and cancel():
                    raise CancelledError("the report was cancelled; no file was written")
                made = make()
                figs = [] if made is None else made if isinstance(made, list) else [made]
                for j, fig in enumerate(figs):
                    page = name if j == 0 else f"{name}-{j + 1}"
                    pdf.savefig(fig, dpi=PDF_DPI)
                    pages.append(page)
                    if png_root is not None:
                        png = png_root / f"{len(pages):02d}-{page}.png"
                        with atomic_writer(png, "wb") as out:
                            fig.savefig(out, format="png", dpi=PNG_DPI)
                        pngs.append(png)
                if progress is not None:
                    progress((k + 1) / len(plan))
    except BaseException:
        for png in pngs:
            with contextlib.suppress(OSError):
                png.unlink()
        raise
    return ReportInfo(
        path, tuple(pages), tuple(pngs), chosen.label, sol.feasible, time.perf_counter() - t0
    )
