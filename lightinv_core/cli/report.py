"""``report``: write a PDF report of a project's solution."""

from __future__ import annotations

from pathlib import Path

from lightinv_core.atomic import check_writable
from lightinv_core.cli.output import out, progress_printer, warn


def cmd_report(args) -> int:
    """Write a PDF report of a project's solution."""
    from lightinv_core.project import load_project
    from lightinv_core.report import write_report
    from lightinv_core.study import prepare

    check_writable(args.output)
    if args.png_dir:
        check_writable(Path(args.png_dir) / "page-1.png")
    project = load_project(args.project)
    prepared = prepare(project, progress=progress_printer("precompute"), warn=warn)
    info = write_report(
        project, prepared, args.output, png_dir=args.png_dir, progress=progress_printer("report")
    )
    result = {
        "project": project.name,
        "report": str(info.path),
        "pages": list(info.pages),
        "sections": list(info.sections),
        "optimiser": info.optimiser,
        "png_files": [str(p) for p in info.png_files],
        "solution": info.solution,
        "feasible": info.feasible,
        "seconds": info.seconds,
        "operator_from_cache": prepared.from_cache,
    }
    state = "feasible" if info.feasible else "infeasible"
    found = f", found by {info.optimiser}" if info.optimiser else ""
    text = (
        f"{info.path}: {len(info.pages)} pages ({info.solution}, {state}{found}) "
        f"in {info.seconds:.1f} s"
    )
    if info.png_files:
        text += f"\n{len(info.png_files)} PNG pages in {args.png_dir}"
    out(args, result, text)
    return 0
