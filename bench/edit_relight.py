"""Benchmark: what a Climate-tab edit of a control group costs the window on the
flagship office: the group's mode set by ``update_control_group`` and the design's light
in every scenario made again (``layout_daylight``: the energy box and the Achieved tab
read it), with the arrays' exact responses traced afresh (``cold``: as before they were
kept per operator) and kept (``warm``: ``light.arrays.arrays_field``'s memo). Prints
JSON: medians of ``--repeat`` edits, wall and CPU seconds.

    python bench/edit_relight.py [--resolution 1.0] [--repeat 5] [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import dgp_view  # bench/, beside this script

import lightinv_core.light.arrays as arrays_mod
from lightinv_core.editing import DocumentModel

FLAGSHIP = dgp_view.FLAGSHIP


def flagship(resolution: float) -> DocumentModel:
    """The flagship office as ``bench/dgp_view.py`` opens it (meshed at ``resolution``
    m, operator rank 120), its design's light in every scenario made once."""
    doc = dgp_view.flagship(resolution)
    doc.layout_daylight()
    return doc


def edits(doc: DocumentModel, repeat: int, cold: bool) -> dict:
    """Median wall and CPU seconds of ``repeat`` mode edits of the first group, each
    followed by the layout's light made again."""
    name = doc.design.control_groups[0].name
    walls, cpus = [], []
    for i in range(repeat):
        if cold:
            arrays_mod._FIELDS.clear()
        mode = "switching" if i % 2 == 0 else "dimming"
        t0, c0 = time.perf_counter(), time.process_time()
        doc.update_control_group(name, mode=mode)
        doc.layout_daylight()
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    return {
        "wall_s": round(statistics.median(walls), 3),
        "cpu_s": round(statistics.median(cpus), 3),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--resolution", type=float, default=1.0)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--out")
    args = ap.parse_args()
    doc = flagship(args.resolution)
    cold = edits(doc, args.repeat, True)
    warm = edits(doc, args.repeat, False)
    out = {
        "bench": "edit_relight",
        "project": FLAGSHIP.name,
        "resolution_m": args.resolution,
        "patches": int(doc.patches.n),
        "repeat": args.repeat,
        "cold": cold,
        "warm": warm,
        "cpu_ratio_cold_over_warm": round(cold["cpu_s"] / max(warm["cpu_s"], 1e-9), 2),
    }
    text = json.dumps(out, indent=2)
    print(text)
    if args.out:
        Path(args.out).write_text(text + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
