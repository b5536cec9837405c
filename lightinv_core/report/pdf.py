"""``write_report``: a project's solution as a PDF (and optionally PNG pages).

The content is ``sections.report_blocks``: the title page with the design's status per
criterion and how the layout was found, the room, the luminaires (schedule, installed
power, data sheets, maintenance factor), the work planes' EN 12464-1 criteria and
iso-lux plans, the views, the sources and rules, the lighting intentions, the daylight
and energy section, convergence and the Pareto front. ``layout.compose`` pours it onto
A4 portrait pages (flow layout: a new page only when the next block does not fit).

The PDF is written atomically: a failed or cancelled report leaves neither a PDF nor
any of its PNG pages behind, and an older file at ``path`` is kept untouched.
"""

from __future__ import annotations

import contextlib
import dataclasses
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from matplotlib.backends.backend_pdf import PdfPages

from lightinv_core.atomic import atomic_writer
from lightinv_core.errors import CancelledError
from lightinv_core.project import Project
from lightinv_core.report.chosen import choose_solution
from lightinv_core.report.layout import compose, draw_page, page_names
from lightinv_core.report.provenance import provenance
from lightinv_core.report.sections import Context, report_blocks
from lightinv_core.study import solution_light

PDF_DPI = 150  # resolution of the rasterised views inside the PDF
PNG_DPI = 100


@dataclass(frozen=True)
class ReportInfo:
    """What ``write_report`` wrote: the PDF, its page names in order (each page is
    named by the first section on it: "title", "room", "luminaires", "workplanes",
    "views", "sources", "intentions", "daylight", "convergence", "pareto"; a section
    continued on the next page adds "-2"), the sections in the report (``sections``),
    the PNG files (empty without ``png_dir``), which solution it shows, the optimiser
    that found it (``optimiser``: its registry name, "" for a layout given by hand) and
    how long it took."""

    path: Path
    pages: tuple[str, ...]
    png_files: tuple[Path, ...]
    solution: str
    feasible: bool
    seconds: float
    sections: tuple[str, ...] = ()
    optimiser: str = ""


def stop_if(cancel: Callable[[], bool] | None) -> None:
    """Raise ``CancelledError`` if ``cancel()`` says so (the report's Cancel)."""
    if cancel is not None and cancel():
        raise CancelledError("the report was cancelled; no file was written")


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
    found = provenance(project, sol)
    ctx = Context(project, prepared, chosen, solution_light(prepared, project.design, sol), found)
    laid = compose(report_blocks(ctx))
    names = page_names(laid)
    sections = tuple(dict.fromkeys(b.section for page in laid for b in page))
    footer = f"{project.name}  ·  lighting design report  ·  LightInv"
    metadata = {
        "Title": f"LightInv report: {project.name}",
        "Creator": "LightInv",
        "Subject": f"{chosen.label}, {'feasible' if sol.feasible else 'infeasible'}",
    }
    pngs: list[Path] = []
    png_root = Path(png_dir) if png_dir is not None else None
    try:
        with atomic_writer(path, "wb") as fh, PdfPages(fh, metadata=metadata) as pdf:
            for k, items in enumerate(laid):
                stop_if(cancel)
                fig = draw_page(items, k + 1, len(laid), footer).figure
                stop_if(cancel)  # a page's drawing and each of its saves take ~0.3 s
                pdf.savefig(fig, dpi=PDF_DPI)
                if png_root is not None:
                    stop_if(cancel)
                    png = png_root / f"{k + 1:02d}-{names[k]}.png"
                    with atomic_writer(png, "wb") as out:
                        fig.savefig(out, format="png", dpi=PNG_DPI)
                    pngs.append(png)
                if progress is not None:
                    progress((k + 1) / len(laid))
    except BaseException:
        for png in pngs:
            with contextlib.suppress(OSError):
                png.unlink()
        raise
    return ReportInfo(
        path,
        tuple(names),
        tuple(pngs),
        chosen.label,
        sol.feasible,
        time.perf_counter() - t0,
        sections,
        found.method if found is not None else "",
    )
