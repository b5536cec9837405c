"""Benchmark: what the window's live run display costs the optimizer.

Runs the same project and seed (a fixed evaluation budget, no stall stop) three ways
in one process: the core ``solve`` alone, the window's run with the viewport showing
the best so far, and the window's run with plots only. Prints one JSON object with
evaluations per second, the ratios to the core alone, and the plot redraw rate.
Needs an X server (run under ``xvfb-run -a``).

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python bench/gui_run.py --evals 60000
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
from lightinv_core.study import solve

DEMO = Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-demo.json"


def gui_run(win, preview: bool) -> dict:
    win.run_panel.show_best.setChecked(preview)
    loop = QtCore.QEventLoop()  # waits in Qt's C++ loop, as app.exec() does: no GIL held
    win.runs.finished.connect(loop.quit)
    redraws = win.run_panel.plot.redraws
    t0 = time.perf_counter()
    assert win.runs.start()
    loop.exec()
    wall = time.perf_counter() - t0
    win.runs.finished.disconnect(loop.quit)
    sol = win.doc.project.runs[-1].solutions[-1]
    return {
        "evaluations": sol.info.evaluations,
        "seconds": sol.info.seconds,
        "wall": wall,
        "redraws_per_s": (win.run_panel.plot.redraws - redraws) / wall,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default=str(DEMO))
    ap.add_argument(
        "--method",
        default="vns",
        help="optimisation method (default vns: the figure in docs/app.md is VNS's rate)",
    )
    ap.add_argument("--evals", type=int, default=60_000)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    os.environ.setdefault("LIGHTINV_AUTOSAVE_DIR", tempfile.mkdtemp())
    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication([])
    settings = QtCore.QSettings(str(Path(tempfile.mkdtemp()) / "s.ini"), QtCore.QSettings.IniFormat)
    win = MainWindow(settings, autosave_seconds=3600)
    win.ask_before_discard = False
    win.resize(1400, 900)
    win.show()
    assert win.open_path(args.project)
    while win.worker is not None:
        app.processEvents(QtCore.QEventLoop.AllEvents, 20)
    win.doc.set_optimizer(
        method=args.method, max_evals=args.evals, stall=None, target=None, time_limit=None
    )
    d = win.doc
    prepared = d.prepared()
    rows: dict[str, list[dict]] = {"core": [], "gui_preview": [], "gui_plots_only": []}
    for _ in range(args.repeat):
        r = solve(d.project, prepared)
        rows["core"].append({"evaluations": r.evaluations, "seconds": r.seconds})
        rows["gui_preview"].append(gui_run(win, True))
        rows["gui_plots_only"].append(gui_run(win, False))
    rate = {
        k: statistics.median(x["evaluations"] / x["seconds"] for x in v) for k, v in rows.items()
    }
    out = {
        "benchmark": "gui_run",
        "project": Path(args.project).name,
        "method": args.method,
        "patches": d.patches.n,
        "cores": os.cpu_count(),
        "evaluations": args.evals,
        "repeat": args.repeat,
        "evals_per_s_median": {k: round(v) for k, v in rate.items()},
        "ratio_to_core": {k: round(v / rate["core"], 3) for k, v in rate.items()},
        "plot_redraws_per_s_median": {
            k: round(statistics.median(x["redraws_per_s"] for x in v), 1)
            for k, v in rows.items()
            if k != "core"
        },
    }
    win.close()
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
