"""Photometric read-outs of a radiosity solution, per patch group."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from lightinv_core.atomic import atomic_writer
from lightinv_core.scene.patches import Patches


def group_illuminance(patches: Patches, H: np.ndarray) -> list[dict]:
    """Per group: patch count, area (m²) and min / area-weighted average / max illuminance (lux)."""
    out = []
    for gid, name in enumerate(patches.group_names):
        idx = np.flatnonzero(patches.group_id == gid)
        if len(idx) == 0:
            continue
        a = patches.area[idx]
        h = H[idx]
        out.append(
            {
                "group": name,
                "patches": len(idx),
                "area_m2": float(a.sum()),
                "min_lux": float(h.min()),
                "avg_lux": float(np.dot(h, a) / a.sum()),
                "max_lux": float(h.max()),
            }
        )
    return out


CSV_COLUMNS = ("id", "group", "cx", "cy", "cz", "nx", "ny", "nz", "area", "rho", "E", "B", "lux")


def write_patch_csv(
    path: str | Path,
    patches: Patches,
    E: np.ndarray,
    B: np.ndarray,
    H: np.ndarray,
    df: np.ndarray | None = None,
) -> None:
    """One row per patch (columns ``CSV_COLUMNS``; E and B in lm/m², lux = illuminance),
    and a last column ``df`` (daylight factor, %) when given."""
    with atomic_writer(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(CSV_COLUMNS + (("df",) if df is not None else ()))
        names = patches.group_names
        for i in range(patches.n):
            c, nrm = patches.centroid[i], patches.normal[i]
            w.writerow(
                [
                    i,
                    names[patches.group_id[i]],
                    *(f"{x:.6g}" for x in c),
                    *(f"{x:.6g}" for x in nrm),
                    f"{patches.area[i]:.6g}",
                    f"{patches.rho[i]:.6g}",
                    f"{E[i]:.6g}",
                    f"{B[i]:.6g}",
                    f"{H[i]:.6g}",
                    *((f"{df[i]:.6g}",) if df is not None else ()),
                ]
            )
