"""Cancelling long core work: each task runs in a background thread, is cancelled once
well under way, and must end with CancelledError having done at most LATENCY seconds
of work after the cancel, leave no partial output and no thread behind.

The work after the cancel is the CPU time the process spends from the cancel to the
task's end (all its threads: the ray-casting and product pools too), which does not
grow when other programs share the cores; the wall time gets a margin that holds with
the two cores shared 3 to 1 (``stress-ng --cpu 4`` beside the tests), and still fails
a task that waits on something instead of stopping. A cancel not heard, or heard
only after a slow step, still fails: the report has about 1.5 s of CPU left after its
title page. Measured on the 2-core machine (largest interval between cancel polls
over a whole run): form factors of office 0.1 s; operator build of office 0.14 s, of
patio 0.75 s (6.3 s before the bounces, the Jacobi reference and the final CSR
assembly polled or shortened); PDF report 0.1 to 0.35 s of CPU per page (0.6 to
0.8 s of wall time on a quiet machine, 1.85 s and more loaded).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import replace

import pytest

from lightinv_core.design.model import CORNERS, Design, Goal, Intention, Source
from lightinv_core.errors import CancelledError
from lightinv_core.operator.cache import get_operator
from lightinv_core.project import OperatorSettings, OptimizerSettings, Project, SceneSpec
from lightinv_core.report import write_report
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import prepare, solve
from lightinv_core.transport.formfactors import form_factor_matrix

pytestmark = pytest.mark.slow  # operator builds and runs cancelled at points

LATENCY = 1.0  # s of CPU time (the process's) from setting the cancel flag to the task's end
WALL_MARGIN = 10.0  # s of wall time for the same, on a loaded machine

Task = Callable[[Callable[[float], None], Callable[[], bool]], object]


def assert_prompt(latency: tuple[float, float]) -> None:
    """The (wall, CPU) seconds from a cancel to the task's end are within bounds."""
    wall, cpu = latency
    assert cpu < LATENCY, f"{cpu:.2f} s of CPU after the cancel ({wall:.2f} s wall)"
    assert wall < WALL_MARGIN, f"{wall:.2f} s after the cancel ({cpu:.2f} s of CPU)"


def cancel_when(task: Task, started_at: float) -> tuple[float, float]:
    """Run ``task(progress, cancel)`` in a thread, set the cancel flag once its progress
    reaches ``started_at``, and return the (wall, process CPU) seconds from the flag to
    the task's end. Asserts the task ended with CancelledError and left no thread
    running."""
    before = set(threading.enumerate())
    flag, started = threading.Event(), threading.Event()
    outcome: dict = {}

    def progress(fraction: float) -> None:
        if fraction >= started_at:
            started.set()

    def run() -> None:
        try:
            task(progress, flag.is_set)
            outcome["error"] = None
        except BaseException as exc:
            outcome["error"] = exc
        outcome["end"] = time.perf_counter(), time.process_time()

    thread = threading.Thread(target=run, name="cancel-latency-task")
    thread.start()
    assert started.wait(timeout=60), "the task never reported progress"
    t_cancel = time.perf_counter(), time.process_time()
    flag.set()
    thread.join(timeout=30)
    assert not thread.is_alive()
    assert isinstance(outcome["error"], CancelledError), outcome["error"]
    # Worker pools (ray casting, sparse products) are shut down, not left running.
    assert set(threading.enumerate()) == before
    return outcome["end"][0] - t_cancel[0], outcome["end"][1] - t_cancel[1]


@pytest.fixture(scope="module")
def office():
    return mesh_patches(builtin_scene("office"))


def test_form_factors(office):
    latency = cancel_when(
        lambda progress, cancel: form_factor_matrix(office, 1024, progress=progress, cancel=cancel),
        started_at=0.3,
    )
    assert_prompt(latency)


# Progress of a build: 0-0.7 form factors, 0.7-0.75 reference solutions, 0.75-0.85
# exact bounces, 0.85-1 clustering and measuring the error at growing k.
@pytest.mark.parametrize("started_at", [0.3, 0.7, 0.75, 0.85])
def test_operator_build(office, tmp_path, monkeypatch, started_at):
    cache = tmp_path / "cache"
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(cache))
    latency = cancel_when(
        lambda progress, cancel: get_operator(office, progress=progress, cancel=cancel),
        started_at=started_at,
    )
    assert_prompt(latency)
    assert not cache.exists() or not any(cache.iterdir())


@pytest.fixture(scope="module")
def solved_office():
    """A small office project with a solution (and its convergence history)."""
    lum = Source(
        "L1",
        "lum_west",
        "luminaire",
        (0.5, 1.5, 1.5, 4.5),
        free=(*CORNERS, "flux"),
        flux=8000.0,
        flux_range=(0.0, 30000.0),
    )
    design = Design(
        (lum,),
        (Goal("min_electric_power"),),
        intentions=(Intention("desks", group="desks", average=300.0),),
    )
    project = Project(
        "Cancel test office",
        SceneSpec(builtin="office", resolution=0.6),
        design,
        OperatorSettings(rank=120, rays=256),
        OptimizerSettings(),
    )
    prepared = prepare(project)
    best = solve(project, prepared, max_evals=300).best
    return replace(project, solutions=(best,)), prepared


def test_report(solved_office, tmp_path):
    project, prepared = solved_office
    out = tmp_path / "out"
    latency = cancel_when(
        lambda progress, cancel: write_report(
            project,
            prepared,
            out / "report.pdf",
            png_dir=out / "pages",
            progress=progress,
            cancel=cancel,
        ),
        started_at=0.1,  # the title page is done
    )
    assert_prompt(latency)
    assert not out.exists() or not [p for p in out.rglob("*") if p.is_file()]


@pytest.mark.parametrize(
    "method", ["vns", "multilevel", "cmaes", "auto", "epsilon", "two_step", "nsga2"]
)
def test_optimisation_ends_within_a_second_and_keeps_its_best(solved_office, method):
    project, prepared = solved_office
    sky = Source("S1", "skylight", "skylight", (1.0, 1.0, 2.0, 2.0), free=CORNERS)
    design = replace(
        project.design,
        sources=(*project.design.sources, sky),
        goals=(Goal("min_electric_power"), Goal("max_light_power")),
    )
    endless = replace(
        project,
        design=design,
        optimizer=OptimizerSettings(method=method, max_evals=None, divisors=(4, 1)),
    )
    flag, snaps = threading.Event(), []
    out: dict = {}

    def run() -> None:
        out["result"] = solve(endless, prepared, progress=snaps.append, cancel=flag.is_set)
        out["end"] = time.perf_counter(), time.process_time()

    thread = threading.Thread(target=run)
    thread.start()
    deadline = time.perf_counter() + 30
    while len(snaps) < 20 and time.perf_counter() < deadline:
        time.sleep(0.01)
    t_cancel = time.perf_counter(), time.process_time()
    flag.set()
    thread.join(timeout=30)
    assert not thread.is_alive()
    assert_prompt((out["end"][0] - t_cancel[0], out["end"][1] - t_cancel[1]))
    result = out["result"]
    assert result.status == "cancelled"
    if method in ("vns", "multilevel", "cmaes"):
        assert result.best is not None and result.best.info.status == "cancelled"
        assert result.best.info.evaluations >= snaps[19].evaluations
