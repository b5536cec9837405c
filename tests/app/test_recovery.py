"""Autosave and crash recovery: a LightInv process killed mid-run leaves its work behind,
and the next session recovers the project with the run's best layout."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from PySide6 import QtCore

from app.autosave import orphaned_autosaves, read_autosave
from app.window.main_window import MainWindow
from lightinv_core.design.model import CORNERS, Design, Goal, Intention, Source
from lightinv_core.project import OptimizerSettings, Project, SceneSpec, save_project
from tests.app.conftest import wait_for_operator

ROOT = Path(__file__).resolve().parents[2]


def endless_project(path: Path) -> Path:
    """Cornell box, one luminaire to place, no evaluation limit: runs until stopped."""
    lum = Source("L", "light", "luminaire", (0.1, 0.1, 0.3, 0.3), free=(*CORNERS, "flux"), flux=3e3)
    project = Project(
        name="kill test",
        scene=SceneSpec(builtin="cornell", resolution=0.25),
        design=Design(
            (lum,), (Goal("min_electric_power"),), (), (Intention("floor", "floor", min=20.0),)
        ),
        optimizer=OptimizerSettings(max_evals=None),
    )
    save_project(project, path)
    return path


@pytest.fixture
def make_window(qtbot, tmp_path):
    made = []

    def make(folder: Path, seconds: float = 3600.0) -> MainWindow:
        settings = QtCore.QSettings(str(tmp_path / "s.ini"), QtCore.QSettings.IniFormat)
        win = MainWindow(settings, autosave_seconds=seconds, autosave_folder=folder)
        win.ask_before_discard = False
        win.show()
        made.append(win)
        return win

    yield make
    for win in made:
        win.close()


def test_autosave_holds_the_running_best_and_a_clean_exit_removes_it(qtbot, make_window, tmp_path):
    folder = tmp_path / "autosave"
    win = make_window(folder)
    assert win.open_path(endless_project(tmp_path / "p.json"))
    wait_for_operator(qtbot, win)
    assert not win.autosaver.save_now() and not win.autosaver.path.exists()  # nothing unsaved
    assert win.runs.start()
    qtbot.waitUntil(lambda: len(win.runs.best_so_far()) == 1, timeout=30_000)
    assert win.autosaver.save_now()
    rec = read_autosave(win.autosaver.path)
    (best,) = rec.project.solutions
    assert best.info.status == "running" and rec.note == "optimisation running"
    assert orphaned_autosaves(folder) == []  # this process is alive: not offered
    with qtbot.waitSignal(win.runs.finished, timeout=30_000):
        win.runs.cancel()
    assert win.doc.dirty and win.autosaver.save_now()  # the result is not saved yet
    assert win.save_to(tmp_path / "p.json")
    assert not win.autosaver.path.exists()  # saved: nothing to recover
    win.doc.add_intention(Intention("more", "floor", min=10.0))
    assert win.autosaver.save_now()
    win.close()
    assert not win.autosaver.path.exists()  # a clean exit leaves nothing behind


def test_kill_mid_run_then_recover(qtbot, make_window, tmp_path):
    folder = tmp_path / "autosave"
    path = endless_project(tmp_path / "endless.json")
    original = path.read_bytes()
    env = dict(
        os.environ,
        LIGHTINV_AUTOSAVE_DIR=str(folder),
        LIGHTINV_AUTOSAVE_SECONDS="0.5",
        XDG_CONFIG_HOME=str(tmp_path / "config"),
    )
    proc = subprocess.Popen(
        [sys.executable, "-m", "app", str(path), "--run", "--no-recovery"],
        cwd=ROOT,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    autosave = None
    try:
        deadline = time.monotonic() + 90
        while True:
            assert proc.poll() is None, proc.stderr.read().decode()
            assert time.monotonic() < deadline, "no autosave of the running optimisation"
            found = list(folder.glob(f"autosave-{proc.pid}-*.json"))
            if found:
                autosave = found[0]
                data = json.loads(autosave.read_text())
                sols = data["project"].get("results", {}).get("solutions", [])
                if sols and sols[-1]["info"]["evaluations"] >= 500:
                    break
            time.sleep(0.2)
    finally:
        proc.send_signal(signal.SIGKILL)  # a crash: no clean-up runs
        proc.wait(timeout=30)
    assert path.read_bytes() == original  # the user's file was never touched
    win = make_window(folder)
    offered = []
    assert win.offer_recovery(ask=lambda rec: offered.append(rec) or "recover")
    (rec,) = offered
    assert rec.original == path.resolve() and rec.path == autosave
    wait_for_operator(qtbot, win)
    (best,) = [s for s in win.doc.project.solutions if s.info.status == "running"]
    assert best.info.evaluations >= 500
    assert win.doc.design.sources[0].rect == best.sources[0].rect  # loaded into the design
    assert win.doc.dirty and win.doc.path == path.resolve()
    assert not autosave.exists()  # taken over by this session's own autosave
    assert win.autosaver.path.exists()
    # Saving writes the recovered work to the original file.
    assert win.save_to(win.doc.path)
    assert json.loads(path.read_text())["results"]["solutions"][0]["info"]["status"] == "running"


def _crashed_session(folder: Path, name: str, tmp_path: Path) -> Path:
    """An autosave left by a session that died: the file, and its lock file unheld."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    project = endless_project(tmp_path / f"{name}.project.json")
    from app.autosave import write_autosave
    from lightinv_core.project import load_project

    write_autosave(path, load_project(project), project, "unsaved changes")
    return path


def test_a_new_session_with_the_crashed_ones_process_id_offers_its_work(
    qtbot, make_window, tmp_path
):
    """In a container every window gets the same process id: the crashed session's
    autosave must be offered, never taken for this session's and deleted."""
    folder = tmp_path / "autosave"
    pid = os.getpid()
    locked = _crashed_session(folder, f"autosave-{pid}-0badc0de.json", tmp_path)
    locked.with_suffix(".lock").touch()  # its lock died with it
    legacy = _crashed_session(folder, f"autosave-{pid}.json", tmp_path)  # before lock files
    win = make_window(folder)
    assert win.autosaver.path not in (locked, legacy)
    assert not win.autosaver.save_now()  # nothing unsaved: removes only its own file
    assert locked.exists() and legacy.exists()
    offered = {rec.path for rec in orphaned_autosaves(folder)}
    assert offered == {locked, legacy}
    # This live session's own autosave is never offered, to it or to another window.
    assert win.open_path(endless_project(tmp_path / "p.json"))
    wait_for_operator(qtbot, win)
    win.doc.add_intention(Intention("more", "floor", min=10.0))
    assert win.autosaver.save_now()
    assert win.autosaver.path not in {rec.path for rec in orphaned_autosaves(folder)}
    win.close()
    assert not win.autosaver.path.exists() and not win.autosaver.lock_path.exists()
