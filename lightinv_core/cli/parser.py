"""The argument parser of ``lightinv-cli``: one sub-parser per subcommand, each bound to
its ``cmd_*`` function."""

from __future__ import annotations

import argparse

from lightinv_core.cli import args as types
from lightinv_core.cli.export import add_export_args, cmd_export
from lightinv_core.cli.photometry import add_photometry_args, cmd_photometry
from lightinv_core.cli.precompute import cmd_precompute
from lightinv_core.cli.report import cmd_report
from lightinv_core.cli.scenes import add_scene_args, cmd_scene_info, cmd_scenes
from lightinv_core.cli.simulate import cmd_simulate
from lightinv_core.cli.solve import cmd_solve
from lightinv_core.optimize.registry import method_names
from lightinv_core.study.simulation import AUTO_LRR_PATCHES
from lightinv_core.transport.formfactors import DEFAULT_RAYS, MAX_RAYS
from lightinv_core.transport.workplane import DEFAULT_BORDER, DEFAULT_HEIGHT

DESCRIPTION = "``lightinv-cli``: the headless command line."


class _Parser(argparse.ArgumentParser):
    """Usage errors as one line on stderr and exit status 2, like every other user error."""

    def error(self, message: str):
        self.exit(2, f"lightinv-cli: error: {self.prog}: {message} (see --help)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``lightinv-cli``."""
    ap = _Parser(prog="lightinv-cli", description=DESCRIPTION)
    sub = ap.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def add(name: str, fn, help_text: str) -> argparse.ArgumentParser:
        p = sub.add_parser(name, help=help_text, description=help_text)
        p.add_argument("--json", action="store_true", help="print one JSON object")
        p.set_defaults(func=fn)
        return p

    add("scenes", cmd_scenes, "list the built-in scenes")

    add_scene_args(add("scene-info", cmd_scene_info, "patches, groups and zones of a scene"))
    sim = add("simulate", cmd_simulate, "forward radiosity simulation")
    add_scene_args(sim)
    sim.add_argument(
        "--emit",
        type=types.group_lumens,
        action="append",
        default=[],
        metavar="GROUP=LUMENS",
        help="a group emitting this luminous flux (lm), uniformly over its area",
    )
    sim.add_argument(
        "--luminaires",
        metavar="CSV",
        help="photometric luminaires, one per row: name,x,y,z,ies,aim_x,aim_y,aim_z,"
        "c0_x,c0_y,c0_z[,dimming] (IES/LDT paths relative to the CSV; docs/photometry.md)",
    )
    sim.add_argument(
        "--workplane",
        type=types.length,
        nargs="?",
        const=DEFAULT_HEIGHT,
        metavar="HEIGHT",
        help=f"an EN 12464-1 grid this high above the floor (m; {DEFAULT_HEIGHT} if no value)",
    )
    sim.add_argument(
        "--border",
        type=types.length,
        help=f"work plane: band left out along the walls (m, default {DEFAULT_BORDER})",
    )
    sim.add_argument(
        "--workplane-group", default="floor", help="work plane: the floor group it lies over"
    )
    sim.add_argument("--grid-csv", metavar="FILE", help="work plane: write x,y,z,lux per point")
    sim.add_argument(
        "--edition",
        choices=("2011", "2021"),
        default="2021",
        help="work plane: the EN 12464-1 edition whose grid rule lays the points (default 2021)",
    )
    sim.add_argument(
        "--points",
        metavar="CSV",
        help="illuminance at free points: rows x,y,z[,nx,ny,nz] (m; facing up without a "
        "normal; a header line allowed)",
    )
    sim.add_argument(
        "--sky",
        choices=("cie-overcast", "cie-clear"),
        help="light the glazing groups with this sky (docs/daylight.md); cie-overcast adds "
        "df (%%) outputs, cie-clear needs --sun",
    )
    sim.add_argument(
        "--sun",
        type=types.sun_position,
        metavar="ALTITUDE,AZIMUTH",
        help="the CIE clear sky's sun: altitude and compass azimuth (deg, clockwise from north)",
    )
    sim.add_argument(
        "--sun-lux",
        type=types.lux,
        default=80000.0,
        help="the CIE clear sky's sun: direct normal illuminance (lux, default 80000)",
    )
    sim.add_argument(
        "--hour",
        type=types.hour_of_year,
        help="light the glazing with one hour of the --weather file (0: the hour ending "
        "01:00 on 1 January): its Perez sky and sun",
    )
    sim.add_argument(
        "--exterior-lux",
        type=types.lux,
        default=10000.0,
        help="unobstructed horizontal illuminance outside (lux, default 10000)",
    )
    sim.add_argument(
        "--glazing",
        type=types.group_transmittance,
        action="append",
        default=[],
        metavar="GROUP=TRANSMITTANCE[:clear]",
        help="a glazing group, its visible transmittance (0 to 1) and kind: diffusing (the "
        "default) or clear (the sky and sun seen through it, sun patches)",
    )
    sim.add_argument(
        "--weather",
        metavar="FILE",
        help="EPW or TMY3 weather file ('builtin': Greensboro NC) for annual daylight on the "
        "work plane through the glazing (DA300, sDA, UDI; dimming energy with luminaires)",
    )
    sim.add_argument(
        "--north",
        type=types.angle,
        default=0.0,
        help="compass bearing of the scene's +y axis (deg; 0: +y is north, 90: +y is east)",
    )
    sim.add_argument(
        "--occupancy",
        type=types.hours,
        default=(8.0, 18.0),
        metavar="START-END",
        help="occupied hours on weekdays, local time (default 8-18)",
    )
    sim.add_argument(
        "--sky-subdivision",
        type=int,
        choices=(1, 2, 4),
        default=1,
        metavar="MF",
        help="clear glazing over a year: the sky in Reinhart MF patches (1: Tregenza's 145, "
        "the default; 2: 577; 4: 2,305)",
    )
    sim.add_argument(
        "--all-days",
        action="store_true",
        help="occupied on every day of the week, not only Monday to Friday",
    )
    sim.add_argument(
        "--sensor",
        type=types.group_rect,
        action="append",
        default=[],
        metavar="GROUP=X0,Y0,X1,Y1",
        help="dimming: the sensor region (a plan rectangle on the work plane, m) of a "
        "control group of the luminaire schedule's control column; repeat per group",
    )
    sim.add_argument(
        "--group-control",
        type=types.group_control,
        action="append",
        default=[],
        metavar="GROUP=MODE[:LUX[:BAND]]",
        help="a control group's control: dimming (the default) or switching (off while "
        "the daylight on its sensor alone meets the target), its own target in lux "
        "(default --target-lux) and for switching a dead band BAND, a fraction of the "
        "target (off from LUX x (1 + BAND), on again below LUX; default 0); repeat per group",
    )
    sim.add_argument(
        "--view",
        type=types.vector6,
        action="append",
        default=[],
        metavar="X,Y,Z,DX,DY,DZ",
        help="a view point and direction for glare (simplified DGP from the vertical eye "
        "illuminance, sun included) over the year; repeat for several",
    )
    sim.add_argument(
        "--sunlight-point",
        type=types.point3,
        metavar="X,Y,Z",
        help="EN 17037 sunlight exposure: the reference point (m) inside the window",
    )
    sim.add_argument(
        "--sunlight-date",
        type=types.month_day,
        default=(3, 21),
        metavar="MM-DD",
        help="EN 17037 sunlight exposure: the day, 1 February to 21 March (default 03-21)",
    )
    sim.add_argument(
        "--sunlight-min-altitude",
        type=types.altitude,
        metavar="DEG",
        help="EN 17037 sunlight exposure: the sun counts above this altitude (deg; the "
        "standard's value for the site, required with --sunlight-point)",
    )
    sim.add_argument(
        "--target-lux",
        type=types.lux,
        default=500.0,
        help="dimming: the grid's mean illuminance to keep (lux, default 500)",
    )
    sim.add_argument(
        "--min-dimming",
        type=types.fraction,
        default=0.1,
        help="dimming: lowest level of the luminaires (default 0.1)",
    )
    sim.add_argument(
        "--standby-w",
        type=types.length,
        default=0.0,
        help="dimming: standby power of the controls, drawn all year (W, default 0)",
    )
    sim.add_argument(
        "--ground-reflectance",
        type=types.fraction,
        default=0.2,
        help="reflectance of the ground outside (default 0.2)",
    )
    sim.add_argument("--patches-csv", metavar="FILE", help="write one CSV row per patch")
    sim.add_argument(
        "--method",
        choices=("auto", "reference", "lrr"),
        default="auto",
        help=f"solver: reference (exact, sparse F) or lrr (the low-rank operator); "
        f"auto uses lrr above {AUTO_LRR_PATCHES} patches",
    )
    sol = add("solve", cmd_solve, "optimise a project file (inverse design)")
    sol.add_argument("project", help="project file (JSON, schema 1)")
    sol.add_argument("--seed", type=types.seed, help="random seed (default: the project's)")
    sol.add_argument(
        "--method",
        choices=method_names(),
        help="optimisation method (default: the project's; docs/design.md compares them)",
    )
    sol.add_argument("--max-evals", type=types.count, help="radiosity evaluations at most")
    sol.add_argument("--time-limit", type=types.positive, help="seconds of optimisation at most")
    sol.add_argument(
        "--resolution", type=types.positive, help="override the scene's patch size (m)"
    )
    sol.add_argument("-o", "--output", help="save the project with its results to this file")
    _scheduler_arg(sol)
    rep = add("report", cmd_report, "write a PDF report of a project's solution")
    rep.add_argument("project", help="project file holding results (lightinv-cli solve ... -o)")
    rep.add_argument("-o", "--output", required=True, help="PDF file to write")
    rep.add_argument("--png-dir", help="also save every page as a PNG in this folder")
    add_export_args(
        add("export", cmd_export, "write a solved design as IFC, a Radiance scene or glTF")
    )
    add_photometry_args(
        add("photometry", cmd_photometry, "a photometric file: its data, flux and UGR table")
    )
    pre = add("precompute", cmd_precompute, "build or load the radiosity operator of a scene")
    add_scene_args(pre)
    for p in (sim, pre):
        p.add_argument(
            "--rays",
            type=types.rays,
            default=DEFAULT_RAYS,
            help=f"rays per patch (1 to {MAX_RAYS:,})",
        )
        p.add_argument("--seed", type=types.seed, default=0, help="random seed of the form factors")
        group = p.add_mutually_exclusive_group()
        group.add_argument("--rank", type=int, help="fix the low-rank operator's rank k")
        group.add_argument(
            "--tol",
            type=float,
            default=0.01,
            help="target relative error of C that chooses k (default 0.01)",
        )
        p.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
        _scheduler_arg(p)
    return ap


def _scheduler_arg(p: argparse.ArgumentParser) -> None:
    """--scheduler: build the operator on a Dask cluster (docs/cluster.md)."""
    p.add_argument(
        "--scheduler",
        type=types.scheduler,
        metavar="tcp://HOST:PORT",
        help="build the radiosity operator on this Dask cluster (the cluster extra; "
        "docs/cluster.md): the same operator as a local build",
    )
