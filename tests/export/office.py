"""A small solved project for the export tests: the built-in office meshed at 1 m,
an array of a real product, a rectangular luminaire, a skylight and a work plane,
with the design itself saved as its solution (no optimisation: the exporters read a
solution, whichever found it)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from lightinv_core.design.model import Design, Goal, Intention, LuminaireArray, Source, Workplane
from lightinv_core.design.solution import Solution
from lightinv_core.export import export_design
from lightinv_core.project import OperatorSettings, OptimizerSettings, Project, SceneSpec
from lightinv_core.study import prepare

DATA = Path(__file__).resolve().parents[1] / "data"
IES = DATA / "photometry" / "rab-round-4.ies"  # a real downlight (tests/data/SOURCES.md)
COARSE = OperatorSettings(rank=60, rays=128)
BATWING = "Linear batwing 4000 lm 32 W"  # asymmetric C planes, a 1.2 m opening


def office_project(
    *,
    arrays: bool = True,
    panel: bool = True,
    skylight: bool = True,
    product: str | None = None,
    fine: bool = False,
) -> Project:
    """The office design (see the module), its parts chosen; ``fine``: meshed at 0.5 m
    (the skylight's and panel's edges on patch edges) with the default operator
    tolerance and 512 rays per patch instead of 1 m, rank 60 and 128 rays."""
    arr = (
        LuminaireArray(
            "west", "lum_west", product or str(IES), (0.0, 0.0, 2.0, 6.0), rows=3, columns=1,
            rotation=90, dimming=0.8, watts=None if product else 20.0, maintenance_factor=0.8,
        ),
    ) if arrays else ()  # fmt: skip
    sources = []
    if skylight:
        sources.append(Source("S1", "skylight", "skylight", (1.0, 0.5, 3.0, 1.5), filter=0.5))
    if panel:
        sources.append(Source("L2", "lum_east", "luminaire", (0.5, 1.5, 1.5, 4.5), flux=3000.0))
    design = Design(
        tuple(sources), (Goal("min_electric_power"),), (),
        (Intention("wp300", grid="wp", quantity="lux", average=300.0, uniformity=0.4),),
        arrays=arr, workplanes=(Workplane("wp", 0.8, 0.5),),
    )  # fmt: skip
    project = Project(
        "Export test office", SceneSpec(builtin="office", resolution=0.5 if fine else 1.0),
        design, OperatorSettings(rank=None, rays=512) if fine else COARSE,
        OptimizerSettings(),
    )  # fmt: skip
    solution = Solution(design.sources, {}, 0.0, arrays=design.arrays)
    return replace(project, solutions=(solution,))


def exported(project: Project | None = None):
    """The export of ``project`` (default: the whole office design)."""
    project = project or office_project()
    return export_design(project, prepare(project))
