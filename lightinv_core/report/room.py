"""The room's data for the report: dimensions, floor area, volume, surfaces and their
reflectances, the calculation settings and the maintenance factor.

The volume is the enclosed one (divergence theorem over the inward-facing patches,
so desks and columns are taken out) when the room is closed, else the bounding box's.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from lightinv_core.design.model import Design, LuminaireArray
from lightinv_core.project import Project
from lightinv_core.report.tables import Table, alike_groups
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.types import source_type

DEFAULT_MF = next(
    f.default for f in dataclasses.fields(LuminaireArray) if f.name == "maintenance_factor"
)
"""The maintenance factor a luminaire array gets unless set (the design model's
default, 0.8): CIE 97:2005's value for a clean room with a 3-year cleaning cycle and
LED luminaires (EN 12464-1 asks for the factor to be stated with the design)."""


def floor_area(patches: Patches) -> float:
    """Area (m²) of the upward-facing patches at the lowest level of the scene."""
    up = patches.normal[:, 2] > 0.9
    if not up.any():
        return 0.0
    z0 = patches.centroid[up, 2].min()
    low = up & (patches.centroid[:, 2] < z0 + 0.05)
    return float(patches.area[low].sum())


def room_volume(patches: Patches) -> tuple[float, bool]:
    """(volume m³, enclosed): the volume the inward-facing patches enclose when that is
    plausible (a closed room), else the bounding box's volume and False."""
    lo, hi = patches.centroid.min(axis=0), patches.centroid.max(axis=0)
    box = float(np.prod(np.maximum(hi - lo, 0.0)))
    v = -float((patches.area * np.einsum("ij,ij->i", patches.centroid, patches.normal)).sum()) / 3
    if 0 < v <= box * 1.02 + 1e-9:
        return v, True
    return box, False


def room_table(project: Project, prepared) -> Table:
    """The room: its size, floor area, volume, surface area and the calculation's mesh
    and operator."""
    p, op, spec = prepared.patches, prepared.operator, project.scene
    corners = np.concatenate([p.origin, p.origin + p.edge1 + p.edge2])
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    size = hi - lo
    vol, closed = room_volume(p)
    where = f"built-in scene '{spec.builtin}'" if spec.builtin else f"model {Path(spec.obj).name}"
    err = op.info.get("estimated_rel_error") if isinstance(op.info, dict) else None
    acc = (
        f"{100 * err:.2f}% estimated mean error of the reflected light"
        if isinstance(err, int | float) and math.isfinite(err)
        else "error estimate not recorded"
    )
    res = f"{spec.resolution:g} m" if spec.resolution else "the scene's default"
    rows = [
        ("model", where),
        ("extent (x × y × z)", f"{size[0]:.2f} × {size[1]:.2f} × {size[2]:.2f} m"),
        ("floor area", f"{floor_area(p):,.1f} m²"),
        ("volume", f"{vol:,.1f} m³" + ("" if closed else " (bounding box: the room is open)")),
        ("surface area", f"{p.area.sum():,.1f} m² in {len(p.group_names)} surface groups"),
        ("emitter zones", ", ".join(p.zone_names) or "none"),
        ("calculation mesh", f"{p.n:,} patches of about {res}"),
        (
            "inter-reflections",
            f"radiosity, operator of rank {op.k:,} ({op.info.get('rays', '?')} rays per patch), "
            + acc,
        ),
    ]
    return Table("Dimensions and calculation", ("item", "value"), tuple(rows))


def _reflectance_source(project: Project, group: str) -> str:
    spec = project.scene
    if any(g == group for g, _ in spec.reflectances or ()):
        return "set in the materials panel"
    if spec.builtin:
        return "built-in scene"
    if spec.materials:
        return f"materials file {Path(str(spec.materials)).name}"
    return "the model's material colours (or 0.5 when it has none)"


def surfaces_table(project: Project, prepared) -> Table:
    """Each surface group: its area, reflectance (area-weighted mean and range), its
    surfaces (the model's names) and where the reflectance comes from; alike groups of
    one class share a row (``tables.alike_groups``)."""
    p = prepared.patches
    rows = []
    for title, gids in alike_groups(p, lambda name: _reflectance_source(project, name)):
        idx = np.flatnonzero(np.isin(p.group_id, gids))
        rows.append(_surface_row(project, p, p.group_names[gids[0]], idx, title))
    return Table(
        "Surfaces and materials",
        ("surface group", "area m²", "reflectance ρ", "surfaces", "reflectance from"),
        tuple(rows),
        note="Surfaces are diffuse (Lambertian): ρ is the share of the light they reflect.",
    )


def _surface_row(project: Project, p: Patches, group: str, idx: np.ndarray, title: str) -> tuple:
    area, rho = p.area[idx], p.rho[idx]
    mean = float(rho @ area / area.sum())
    spread = f" ({rho.min():.2f}–{rho.max():.2f})" if np.ptp(rho) > 0.005 else ""
    # A drawn zone cuts a surface into pieces ("ceiling~2"): name the surface once.
    names = sorted({p.surface_names[s].split("~")[0] for s in np.unique(p.surface_id[idx])})
    shown = ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
    return (
        title,
        f"{area.sum():,.1f}",
        f"{mean:.2f}{spread}",
        shown,
        _reflectance_source(project, group),
    )


def maintenance_text(design: Design, arrays: Sequence[LuminaireArray]) -> str:
    """What the maintenance factor is and where it comes from, for the report."""
    factors = sorted({a.maintenance_factor for a in arrays})
    electric = [s for s in design.sources if source_type(s.kind).electric]
    parts = []
    if factors:
        values = ", ".join(f"{f:g}" for f in factors)
        default = all(f == DEFAULT_MF for f in factors)
        parts.append(
            f"Maintenance factor MF = {values} for the luminaire arrays"
            + (
                f" (the project's default, {DEFAULT_MF:g}: CIE 97:2005's value for a clean "
                "room, luminaires cleaned every 3 years, LED lamps)"
                if default
                else " (set per array in the project)"
            )
            + ". Illuminances on work planes and surfaces are maintained values: the new "
            "luminaires' light times MF (EN 12464-1 Em)."
        )
    if electric:
        parts.append(
            "Area luminaires (rectangles of given flux) are calculated as new (MF = 1): "
            f"the maintained values would be their light times the MF chosen for them "
            f"(e.g. {DEFAULT_MF:g}, CIE 97:2005, clean room)."
        )
    if not parts:
        parts.append("No luminaires: no maintenance factor applies.")
    return " ".join(parts)
