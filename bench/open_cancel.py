"""Benchmark: what opening a project costs the window's GUI thread, and how long a Cancel
waits in the clear trace's reflections and in ``layout_daylight`` (issue #30). Prints JSON.

    python bench/open_cancel.py [--project resources/projects/office-flagship.json]
    python bench/open_cancel.py --open-without-clear   # the open alone, arrays only

``open``: CPU seconds on the GUI thread when the operator arrives, as before (the
document lights the design itself: the work planes' grids and the arrays placed
exactly, ``DocumentModel.set_operator(op)``) and now (``set_operator(op, shown,
daylight)`` with the light laid out by the worker's ``lay_out``, whose CPU is given
too); medians of ``--repeats`` runs, the grids' per-operator memo emptied before each.

``cancel``: the CPU seconds of the working thread between a cancel request and the
moment the work stops (its progress callback raises), for requests at 10%, 30%, 50%,
70% and 90% of the step's CPU: the clear build's reflections step (before: one block,
checked at its end, ``reflect_columns`` = every column; now: blocks of
``REFLECT_WORK``) and ``layout_daylight`` on the design with its clear light built
(before: checked only when it returns, as the window's worker did; now: its own
progress calls). The request is made by another thread watching the worker's CPU clock
(``time.pthread_getcpuclockid``), as Compute > Cancel comes from the GUI thread. Also
the longest CPU gap between two progress calls of a whole clear build (the worst wait
anywhere in the trace) before and now. One BLAS thread, as the window's workers.
"""

from __future__ import annotations

import argparse
import contextlib
import itertools
import json
import statistics
import tempfile
import threading
import time
from pathlib import Path

from threadpoolctl import threadpool_limits

import lightinv_core.light.arrays as arrays
import lightinv_core.light.clear_build as clear_build
import lightinv_core.light.grids as grids
from app.window.workers import lay_out
from lightinv_core.editing import DocumentModel
from lightinv_core.errors import CancelledError
from lightinv_core.light.clear_build import clear_light
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.project import load_project
from lightinv_core.study import prepare

PROJECT = Path(__file__).resolve().parent.parent / "resources" / "projects" / "office-flagship.json"
AT = (0.1, 0.3, 0.5, 0.7, 0.9)


def open_cost(path: Path, operator, repeats: int) -> dict:
    """The GUI thread's CPU when the operator arrives, before and now: lighting the
    design, and (as the Achieved tab does next) its light in every scenario unless its
    clear glazing waits for its trace."""
    before, after, worker = [], [], []
    for _ in range(repeats):
        doc = DocumentModel()
        doc.clear_elsewhere = True  # as the window
        doc.open(path)
        grids._GRIDS.clear()
        arrays._FIELDS.clear()  # the arrays' responses traced, as on a first open
        c0 = time.process_time()
        doc.set_operator(operator)
        if doc.design.intentions and not doc.clear_pending():
            doc.layout_daylight()
        before.append(time.process_time() - c0)
        doc = DocumentModel()
        doc.clear_elsewhere = True
        doc.open(path)
        grids._GRIDS.clear()
        arrays._FIELDS.clear()  # the arrays' responses traced, as on a first open
        c0 = time.process_time()
        shown, daylight = lay_out(doc.scene, doc.patches, operator, doc.design, lambda f: None)
        worker.append(time.process_time() - c0)
        c0 = time.process_time()
        doc.set_operator(operator, shown=shown, daylight=daylight)
        if doc.design.intentions and not doc.clear_pending():
            doc.layout_daylight()  # found made
        after.append(time.process_time() - c0)
    med = statistics.median
    return {
        "gui_thread_cpu_s_before": round(med(before), 3),
        "gui_thread_cpu_s_now": round(med(after), 3),
        "worker_cpu_s_now": round(med(worker), 3),
        "runs": repeats,
    }


class Cancelled:
    """Run ``work(progress)`` in a thread; request a cancel once the thread's CPU clock
    passes ``start() + at``; give the thread CPU between the request and the stop."""

    def __init__(self, work, start_fraction: float | None):
        self.work, self.start_fraction = work, start_fraction
        self.stop = threading.Event()
        self.start_cpu: float | None = None if start_fraction is not None else 0.0
        self.stopped_cpu: float | None = None
        self.clock: int | None = None

    def progress(self, f: float) -> None:
        # The working thread's clock even when a pool thread asks (a sparse product's
        # cancel check runs in its workers).
        now = time.thread_time() if self.clock is None else time.clock_gettime(self.clock)
        if self.start_cpu is None and f >= self.start_fraction:
            self.start_cpu = now
        if self.stop.is_set():
            self.stopped_cpu = now
            raise CancelledError("bench")

    def run(self, at_cpu: float) -> float | None:
        """CPU seconds from the request to the stop (None: it ended first)."""

        def target():
            with threadpool_limits(limits=1, user_api="blas"):
                if self.start_fraction is None:
                    self.start_cpu = time.thread_time()
                with contextlib.suppress(CancelledError):
                    self.work(self.progress)

        t = threading.Thread(target=target)
        t.start()
        while t.ident is None:
            time.sleep(0.001)
        clock = self.clock = time.pthread_getcpuclockid(t.ident)
        requested = None
        while t.is_alive():
            cpu = time.clock_gettime(clock)
            if requested is None and self.start_cpu is not None and cpu >= self.start_cpu + at_cpu:
                self.stop.set()
                requested = cpu
            time.sleep(0.002)
        t.join()
        if requested is None or self.stopped_cpu is None:
            return None
        return self.stopped_cpu - requested


def latencies(make_work, start_fraction, step_cpu: float) -> dict:
    got = []
    for u in AT:
        lat = Cancelled(make_work(), start_fraction).run(u * step_cpu)
        got.append(None if lat is None else round(lat, 3))
    done = [x for x in got if x is not None]
    return {
        "at_share_of_step": list(AT),
        "latency_cpu_s": got,
        "median_cpu_s": round(statistics.median(done), 3) if done else None,
        "max_cpu_s": round(max(done), 3) if done else None,
    }


def gaps(light, design) -> float:
    """Longest CPU between two progress calls (and the ends) of a whole clear build."""
    clear_build._CACHE.pop(light.op, None)
    marks = [time.thread_time()]
    clear_light(light, design, lambda f: marks.append(time.thread_time()))
    marks.append(time.thread_time())
    return round(max(b - a for a, b in itertools.pairwise(marks)), 3)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--project", default=str(PROJECT))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument(
        "--open-without-clear",
        action="store_true",
        help="only the open's cost, on a copy of the project without its clear glazing "
        "(its arrays and intentions: the light in every scenario is made on opening)",
    )
    args = ap.parse_args()
    path = Path(args.project)
    if args.open_without_clear:
        data = json.loads(path.read_text(encoding="utf-8"))
        data["sources"] = [s for s in data.get("sources", []) if s.get("glazing") != "clear"]
        path = Path(tempfile.mkdtemp()) / f"{path.stem}-without-clear.json"
        path.write_text(json.dumps(data), encoding="utf-8")
    project = load_project(path)
    prepared = prepare(project)
    light, design = prepared.light, project.design
    out = {"project": path.name, "patches": prepared.patches.n}
    with threadpool_limits(limits=1, user_api="blas"):
        out["open"] = open_cost(path, prepared.operator, args.repeats)
    if args.open_without_clear:
        print(json.dumps(out, indent=1))
        return
    with threadpool_limits(limits=1, user_api="blas"):
        # The reflections' CPU in one go, then cancels inside it.
        reflected = clear_build._reflected
        spent: list[float] = []

        def timed(*a):
            c0 = time.thread_time()
            r = reflected(*a)
            spent.append(time.thread_time() - c0)
            return r

        clear_build._reflected = timed
        out["clear_build_longest_gap_cpu_s_now"] = gaps(light, design)
        blocks = clear_build.reflect_columns(light)
        every = clear_build.reflect_columns
        clear_build.reflect_columns = lambda _light: 10**9
        spent.clear()
        out["clear_build_longest_gap_cpu_s_before"] = gaps(light, design)
        step = sum(spent)
        clear_build._reflected = reflected

        def build():
            clear_build._CACHE.pop(light.op, None)
            return lambda progress: clear_light(light, design, progress)

        before = latencies(build, 0.22, step)
        clear_build.reflect_columns = every
        now = latencies(build, 0.22, step)
    out["reflections"] = {
        "step_cpu_s": round(step, 3),
        "columns_per_block_now": blocks,
        "before": before,
        "now": now,
    }
    # layout_daylight with the clear light built (what the window's worker runs next).
    with threadpool_limits(limits=1, user_api="blas"):
        clear_light(light, design)
        c0 = time.thread_time()
        layout_daylight(light, design)
        warm = time.thread_time() - c0  # the arrays' responses kept (a Climate-tab edit)
        arrays._FIELDS.clear()
        c0 = time.thread_time()
        layout_daylight(light, design)
        step = time.thread_time() - c0  # traced afresh (the arrays moved): the worst case

        def old():  # checked only once it returns
            arrays._FIELDS.clear()
            return lambda progress: (layout_daylight(light, design), progress(1.0))

        def new():
            arrays._FIELDS.clear()
            return lambda progress: layout_daylight(light, design, progress=progress)

        out["layout_daylight"] = {
            "step_cpu_s": round(step, 3),
            "step_cpu_s_arrays_kept": round(warm, 3),
            "before": latencies(old, None, step),
            "now": latencies(new, None, step),
        }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
