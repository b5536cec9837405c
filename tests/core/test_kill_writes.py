"""``kill -9`` at random moments while the program writes each kind of file: the file
is always the old version or a new one, whole, never a corrupt one, and the next start
leaves no temporary behind.

Kinds: a project file (``save_project``; ``lightinv-cli solve -o`` saves results the
same way), an autosave, the operator cache, the patch CSV and the PDF report.

The writer rewrites the file without a pause and says when its first write is whole.
The first process is killed at a random moment from its start (often before any
file exists); each later one at a random moment after its first whole write, within
as long again as that write took, so the kill lands in a later write at any point of
it however slow the machine is. (A fixed delay from the start did not: on a loaded
machine the first report, with its imports, took longer than the 3 s allowed, and
six kills in a row left no file at all.)
"""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from lightinv_core.atomic import TEMP_MARK, remove_stale_temporaries
from lightinv_core.operator import cache as oc
from lightinv_core.project import load_project

WRITER = r"""
import os, sys
from pathlib import Path
kind, path = sys.argv[1], Path(sys.argv[2])
from dataclasses import replace
from lightinv_core.design.model import Design, Goal, Source
from lightinv_core.project import Project, SceneSpec
lamp = Source("L", "light", "luminaire", (0.1, 0.1, 0.4, 0.4), flux=1000.0)
design = Design((lamp,), (Goal("min_electric_power"),))
project = Project("v0", SceneSpec(builtin="cornell", resolution=0.5), design)
if kind == "cache":
    from lightinv_core.operator.build import build_operator
    from lightinv_core.operator.cache import save_operator
    from lightinv_core.operator.settings import OperatorSettings
    from lightinv_core.scene.builtin import builtin_scene
    from lightinv_core.scene.patches import mesh_patches
    op = build_operator(mesh_patches(builtin_scene("cornell", 0.3)), OperatorSettings(rays=64))
if kind == "csv":
    import numpy as np
    from lightinv_core.scene.builtin import builtin_scene
    from lightinv_core.scene.patches import mesh_patches
    from lightinv_core.transport.photometry import write_patch_csv
    patches = mesh_patches(builtin_scene("cornell", 0.1))
if kind == "report":
    from lightinv_core.design.model import CORNERS
    from lightinv_core.optimize.settings import OptimizerSettings
    from lightinv_core.report import write_report
    from lightinv_core.study import prepare, solve
    free = replace(lamp, free=CORNERS)
    project = replace(
        project,
        design=replace(design, sources=(free,)),
        optimizer=OptimizerSettings(method="vns", max_evals=100),
    )
    prepared = prepare(project)
    project = replace(project, solutions=(solve(project, prepared).best,))
print("ready", flush=True)
i = 0
while True:
    i += 1
    if kind == "project":
        from lightinv_core.project import save_project
        save_project(replace(project, name=f"v{i}"), path)
    elif kind == "autosave":
        sys.path.insert(0, os.getcwd())
        from app.autosave import write_autosave
        write_autosave(path, replace(project, name=f"v{i}"), None, note=f"v{i}")
    elif kind == "cache":
        save_operator(op, path, f"key{i % 2}")
    elif kind == "report":
        write_report(replace(project, name=f"v{i}"), prepared, path)
    else:
        E = np.full(patches.n, float(i))
        write_patch_csv(path, patches, E, E, E)
    if i == 1:
        print("wrote", flush=True)
"""


def _check_project(path: Path) -> None:
    assert load_project(path).name.startswith("v")


def _check_autosave(path: Path) -> None:
    data = json.loads(path.read_text(encoding="utf-8"))
    assert data["note"] == data["project"]["name"]


def _check_cache(path: Path) -> None:
    loaded = []
    for key in ("key0", "key1"):  # the two versions written in turn
        try:
            loaded.append(oc.load_operator(path, key))
        except oc.CacheError as exc:
            assert "other settings or version" in str(exc)  # the other version's key
    assert len(loaded) == 1 and loaded[0].k > 0  # exactly one whole version


def _check_csv(path: Path) -> None:
    rows = list(csv.DictReader(path.open()))
    assert len(rows) > 100 and len({r["E"] for r in rows}) == 1  # one whole version


def _check_report(path: Path) -> None:
    data = path.read_bytes()
    assert data.startswith(b"%PDF") and data.rstrip().endswith(b"%%EOF")


CHECKS = {
    "project": ("p.json", _check_project),
    "autosave": ("autosave-1.json", _check_autosave),
    "cache": ("op.lrr", _check_cache),
    "csv": ("patches.csv", _check_csv),
    "report": ("report.pdf", _check_report),
}
FIRST_DELAY_S = {"report": 3.0}  # a report takes about a second to write (quiet machine)


@pytest.mark.slow
@pytest.mark.parametrize("kind", list(CHECKS))
def test_a_kill_at_any_moment_leaves_a_whole_file_and_no_leftover(tmp_path, kind):
    name, check = CHECKS[kind]
    target = tmp_path / name
    rng = np.random.default_rng(7)
    root = Path(__file__).resolve().parents[2]
    for run in range(6):
        proc = subprocess.Popen(
            [sys.executable, "-c", WRITER, kind, str(target)],
            stdout=subprocess.PIPE,
            text=True,
            cwd=root,
            env={**os.environ, "LIGHTINV_CACHE_DIR": str(tmp_path / "cache")},
        )
        assert proc.stdout.readline().strip() == "ready"
        if run == 0:  # any moment from the start: before, during or after the first write
            time.sleep(float(rng.uniform(0.0, FIRST_DELAY_S.get(kind, 0.25))))
        else:  # any moment of the writes after a whole one
            start = time.perf_counter()
            assert proc.stdout.readline().strip() == "wrote"
            time.sleep(float(rng.uniform(0.0, time.perf_counter() - start)))
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        if target.exists():
            check(target)
    leftovers = [p for p in tmp_path.iterdir() if TEMP_MARK in p.name]
    old = time.time() - 60
    for p in leftovers:
        os.utime(p, (old, old))
    # The next start sweeps the folder (as each write, the cache and autosave do).
    remove_stale_temporaries(tmp_path)
    assert [p for p in tmp_path.iterdir() if TEMP_MARK in p.name] == []
    assert target.exists()
    check(target)
