"""Benchmark: time from a source edit to the re-rendered viewport, in the real window.

Needs an X server (run under ``xvfb-run -a``). Prints one JSON object.

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python bench/gui_latency.py --json
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import tempfile
import time
from pathlib import Path

from PySide6 import QtCore, QtWidgets

from app.window.main_window import MainWindow

DEMO = Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-demo.json"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default=str(DEMO))
    ap.add_argument("--edits", type=int, default=200)
    ap.add_argument("--json", action="store_true", help="(default) print JSON")
    args = ap.parse_args()
    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication([])
    # A private settings file: QSettings saves by renaming a new file over its path, so
    # os.devnull here replaced the machine's /dev/null with a regular file.
    ini = Path(tempfile.mkdtemp()) / "settings.ini"
    settings = QtCore.QSettings(str(ini), QtCore.QSettings.IniFormat)
    win = MainWindow(settings)
    win.ask_before_discard = False
    win.show()
    win.open_path(args.project)
    t0 = time.perf_counter()
    while win.worker is not None or win.doc.operator is None:
        app.processEvents()
        time.sleep(0.01)
    precompute = time.perf_counter() - t0
    name = win.doc.design.sources[0].name
    times, evals, renders = [], [], []
    for q in range(args.edits):
        step = 0.05 if (q // 20) % 2 == 0 else -0.05
        t = time.perf_counter()
        win.doc.move_source(name, step, 0.0)  # relight + recolour + render, synchronously
        times.append(1e3 * (time.perf_counter() - t))
        evals.append(win.doc.last_eval_ms)
        renders.append(win.colouring.last_render_ms)
    times.sort()
    print(
        json.dumps(
            {
                "project": Path(args.project).name,
                "patches": win.doc.patches.n,
                "k": win.doc.operator.k,
                "cores": os.cpu_count(),
                "edits": args.edits,
                "precompute_or_cache_seconds": precompute,
                "edit_to_render_ms_median": statistics.median(times),
                "edit_to_render_ms_p95": times[int(0.95 * len(times)) - 1],
                "lighting_ms_median": statistics.median(evals),
                "view_update_ms_median": statistics.median(renders),
            },
            indent=2,
        )
    )
    win.close()


if __name__ == "__main__":
    main()
