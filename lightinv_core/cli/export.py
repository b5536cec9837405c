"""``export``: write a solved project's design as IFC, a Radiance scene or a lit glTF
(one option per registered exporter, ``export.registry``; docs/export.md)."""

from __future__ import annotations

import argparse
from pathlib import Path

from lightinv_core.atomic import check_writable
from lightinv_core.cli.output import out, progress_printer, warn
from lightinv_core.errors import LightInvError
from lightinv_core.export.radiance_scene import SKIES
from lightinv_core.export.registry import exporters


def add_export_args(p: argparse.ArgumentParser) -> None:
    """The ``export`` arguments: the result file, one ``--<format> OUT`` per exporter."""
    p.add_argument("result", help="project file holding results (lightinv-cli solve ... -o)")
    group = p.add_mutually_exclusive_group(required=True)
    for e in exporters():
        group.add_argument(
            f"--{e.name}",
            metavar="OUT",
            help=f"write the design as {e.label} ({', '.join(e.suffixes)})",
        )
    p.add_argument(
        "--solution",
        type=int,
        metavar="N",
        help="the Nth saved solution or Pareto front point (1-based; default: the first, "
        "as the report)",
    )
    p.add_argument(
        "--sky",
        choices=SKIES,
        default="auto",
        help="Radiance: the CIE overcast sky at the design's exterior lux, none, or auto "
        "(overcast when the design has glazing)",
    )


def _chosen(project, n: int | None):
    """The solution numbered ``n`` (1-based) of the saved ones, else of the front."""
    if n is None:
        return None
    sols = project.solutions or (project.pareto.solutions if project.pareto else ())
    if not 1 <= n <= len(sols):
        raise LightInvError(f"--solution {n}: the project holds {len(sols)} solution(s)")
    return sols[n - 1]


def cmd_export(args) -> int:
    """Export the design of a solved project in one format."""
    from lightinv_core.export import export_design
    from lightinv_core.project import load_project
    from lightinv_core.study import prepare

    e = next(e for e in exporters() if getattr(args, e.name, None))
    target = Path(getattr(args, e.name))
    if target.suffix.lower() not in e.suffixes:
        raise LightInvError(
            f"--{e.name} {target}: the file name must end with {' or '.join(e.suffixes)}"
        )
    check_writable(target)
    project = load_project(args.result)
    if not (project.solutions or project.pareto or project.runs):
        name = Path(args.result).name
        raise LightInvError(
            f"project {project.name!r} holds no solution to export; run 'lightinv-cli solve "
            f"{name} -o RESULT.json' first and export RESULT.json"
        )
    prepared = prepare(project, progress=progress_printer("precompute"), warn=warn)
    ex = export_design(project, prepared, _chosen(project, args.solution))
    options = {"sky": args.sky} if e.name == "radiance" else {}
    written = e.write(ex, target, **options)
    result = {
        "project": project.name,
        "format": e.name,
        "solution": ex.label,
        "path": str(written.path),
        "files": [str(f) for f in written.files],
        "counts": written.counts,
        "notes": list(written.notes),
    }
    held = ", ".join(f"{v} {k}" for k, v in written.counts.items())
    text = f"{written.path}: {e.label}, {held} ({ex.label})"
    if len(written.files) > 1:
        text += f"\n{len(written.files) - 1} more files beside it"
    text += "".join(f"\nnote: {n}" for n in written.notes)
    out(args, result, text)
    return 0
