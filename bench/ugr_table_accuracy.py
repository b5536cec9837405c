"""Benchmark: the CIE 190 UGR tables of the real photometric files in tests/data/photometry
against eulumdat-ugr 1.0.2 (MIT, the dev extra), every cell (19 rooms x 5 reflectance
sets x 2 orientations), with the position index from CIE 117's Table 4.1 (what
``ugr_table`` uses) and, for comparison, from Guth's formula (``ugr.guth_index``: what it
used before). Per file: the largest |ours - theirs| and its cell, the mean difference,
the 4H 8H 70/50/20 values; for the DN150 downlight, the ratio of our background
luminance and glare sum to eulumdat-ugr's in the 2H 2H and 4H 8H rooms; the built-in
catalogue's 4H 8H values (crosswise, endwise) with either index.

Prints one JSON object; ``--out`` also writes it.

python bench/ugr_table_accuracy.py [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import math
import tempfile
import time
from dataclasses import replace
from pathlib import Path
from unittest import mock

import numpy as np
from eulumdat_luminance import LuminanceCalculator
from eulumdat_ugr import UgrCalculator
from eulumdat_ugr.background import BackgroundLuminance
from eulumdat_ugr.geometry import UgrGrid
from eulumdat_ugr.guth import GuthTable
from eulumdat_ugr.photometry import UgrPhotometry
from pyldt import LdtReader

from lightinv_core.luminaires import builtin_catalogue, read_photometry
from lightinv_core.luminaires import ugr_table as ut
from lightinv_core.luminaires.ldt import format_ldt
from lightinv_core.luminaires.ugr import position_index

DATA = Path(__file__).resolve().parents[1] / "tests" / "data" / "photometry"
FILES = (
    "ledvance-panel-600.ldt",
    "ledvance-downlight-dn150.ldt",
    "rab-square-1.ies",
    "rab-round-4.ies",
)


def _reference(name: str, folder: Path) -> np.ndarray:
    """eulumdat-ugr's table (19, 10): crosswise sets then endwise sets. IES files go as
    EULUMDAT of one lamp set of the table's flux (its lamp-count reading: SOURCES.md)."""
    ph = read_photometry(DATA / name)
    path = DATA / name
    if not name.endswith(".ldt"):
        path = folder / (Path(name).stem + ".ldt")
        path.write_text(format_ldt(replace(ph, lamp_lumens=ph.flux(), n_lamps=1)), "latin-1")
    return UgrCalculator.compute(LdtReader.read(str(path))).values


def _ours(name: str) -> np.ndarray:
    t = ut.ugr_table(read_photometry(DATA / name))
    return np.concatenate([t.values[:, :, 0], t.values[:, :, 1]], axis=1)


def _compare(ours: np.ndarray, ref: np.ndarray) -> dict:
    d = ours - ref
    k = np.unravel_index(int(np.abs(d).argmax()), d.shape)
    sets = [f"{int(c * 100)}/{int(w * 100)}/{int(f * 100)}" for c, w, f in ut.REFLECTANCES]
    room = ut.ROOMS[k[0]]
    return {
        "max_abs_diff": round(float(np.abs(d).max()), 3),
        "at": f"{room[0]}H {room[1]}H, {sets[k[1] % 5]}, {ut.ORIENTATIONS[k[1] // 5]}",
        "mean_diff": round(float(d.mean()), 3),
        "mean_abs_diff": round(float(np.abs(d).mean()), 3),
        "cells_over_0.5": int((np.abs(d) > 0.5).sum()),
        "4H8H_ours": [round(float(ours[10, 0]), 2), round(float(ours[10, 5]), 2)],
        "4H8H_eulumdat_ugr": [round(float(ref[10, 0]), 2), round(float(ref[10, 5]), 2)],
    }


def _dn150_parts() -> dict:
    """Our background and glare sum over eulumdat-ugr's, crosswise at 70/50/20."""
    path = DATA / "ledvance-downlight-dn150.ldt"
    ph, ldt = read_photometry(path), LdtReader.read(str(path))
    theirs = LuminanceCalculator.compute(ldt, full=True)
    out = {}
    for i in (0, 10):
        xh, yh = ut.ROOMS[i]
        grid = UgrGrid(xh, yh)
        lb_ref = BackgroundLuminance.compute(ldt, grid.n_total, 8.0 * (xh + yh), i)["70/50/20"]
        r, t, c, g, dist = grid.angles("crosswise")
        lum, omega = UgrPhotometry.compute(theirs, c, g, dist)
        p = GuthTable.p_vec(ut.H / r, t / r)
        ok = ~np.isnan(p)
        sum_ref = float(np.sum(lum[ok] ** 2 * omega[ok] / p[ok] ** 2))
        n, down, total = grid.n_total, ph.flux(90.0), ph.flux()
        floor = n * down * ut.floor_share(ph, xh, yh)
        flux = (floor, n * down - floor, n * (total - down))
        lb = ut.wall_indirect_lux(xh * ut.H, yh * ut.H, ut.H, flux, ut.REFLECTANCES[0]) / math.pi
        ratio_lb = lb / lb_ref
        out[f"{xh}H {yh}H"] = {
            "background_ratio": round(ratio_lb, 4),
            "glare_sum_ratio": round(ut.glare_sum(ph, xh, yh, "crosswise") / sum_ref, 5),
            "ugr_from_background": round(-8.0 * math.log10(ratio_lb), 3),
        }
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path)
    args = ap.parse_args()
    t0 = time.process_time()
    result: dict = {"files": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for name in FILES:
            ref = _reference(name, Path(tmp))
            table = _compare(_ours(name), ref)
            # Guth's smooth formula in place of Table 4.1 (and its field limits only).
            with mock.patch.object(ut, "table_position_index", position_index):
                guth = _compare(_ours(name), ref)
            result["files"][name] = {"table_4_1": table, "guth_formula": guth}
    result["dn150_parts"] = _dn150_parts()
    cat = {}
    for e in builtin_catalogue():
        table = [round(v, 2) for v in ut.catalogue_ugr(e.photometry())]
        with mock.patch.object(ut, "table_position_index", position_index):
            guth = [round(v, 2) for v in ut.catalogue_ugr(e.photometry())]
        cat[e.name] = {"table_4_1": table, "guth_formula": guth}
    result["catalogue_4H8H"] = cat
    result["cpu_s"] = round(time.process_time() - t0, 1)
    text = json.dumps(result, indent=1)
    print(text)
    if args.out:
        args.out.write_text(text + "\n")


if __name__ == "__main__":
    main()
