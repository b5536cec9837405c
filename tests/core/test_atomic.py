"""Atomic writes: all or nothing, and ordinary file permissions."""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import threading
import time

import pytest

from lightinv_core.atomic import TEMP_MARK, atomic_writer, remove_stale_temporaries


def test_new_files_get_ordinary_permissions_and_existing_ones_keep_theirs(tmp_path):
    new = tmp_path / "a.json"
    with atomic_writer(new) as fh:
        fh.write("{}")
    assert new.stat().st_mode & 0o777 == 0o644
    new.chmod(0o600)
    with atomic_writer(new) as fh:
        fh.write("[]")
    assert new.read_text() == "[]" and new.stat().st_mode & 0o777 == 0o600


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    path = tmp_path / "b.txt"
    path.write_text("old")
    with pytest.raises(RuntimeError), atomic_writer(path) as fh:
        fh.write("half")
        raise RuntimeError("disk full")
    assert path.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["b.txt"]


def test_a_symbolic_link_stays_a_link_and_its_target_gets_the_content(tmp_path):
    target = tmp_path / "real" / "out.json"
    target.parent.mkdir()
    target.write_text("old")
    link = tmp_path / "link.json"
    link.symlink_to(target)
    with atomic_writer(link) as fh:
        fh.write("new")
    assert link.is_symlink() and target.read_text() == "new"
    dangling = tmp_path / "dangling.json"
    dangling.symlink_to(tmp_path / "real" / "made.json")
    with atomic_writer(dangling) as fh:
        fh.write("made")
    assert dangling.is_symlink() and (tmp_path / "real" / "made.json").read_text() == "made"
    assert not [p for p in tmp_path.rglob(".*") if TEMP_MARK in p.name]


def test_pipes_and_devices_are_written_through(tmp_path):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    got: list[str] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_text()))
    reader.start()
    with atomic_writer(fifo) as fh:
        fh.write("through the pipe")
    reader.join(timeout=10)
    assert got == ["through the pipe"] and stat.S_ISFIFO(os.stat(fifo).st_mode)
    with atomic_writer(os.devnull) as fh:
        fh.write("gone")
    assert stat.S_ISCHR(os.stat(os.devnull).st_mode)  # still the device, not a file
    assert [p.name for p in tmp_path.iterdir()] == ["fifo"]


def test_the_cli_writes_a_csv_to_standard_output_through_dev_stdout(tmp_path):
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "lightinv_core.cli",
            "simulate",
            "cornell",
            "--resolution",
            "0.5",
            "--emit",
            "light=1000",
            "--patches-csv",
            "/dev/stdout",
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
        env={**os.environ, "LIGHTINV_CACHE_DIR": str(tmp_path / "cache")},
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("id,group,") and out.stdout.count("\n") > 50
    assert "Traceback" not in out.stderr


WRITER = """
import sys, time
from lightinv_core.atomic import atomic_writer
with atomic_writer(sys.argv[1]) as fh:
    fh.write("half")
    fh.flush()
    print("writing", flush=True)
    time.sleep(60)
"""


def _writer(path):
    proc = subprocess.Popen(
        [sys.executable, "-c", WRITER, str(path)], stdout=subprocess.PIPE, text=True
    )
    assert proc.stdout.readline().strip() == "writing"
    return proc


def _temporaries(folder):
    return [p for p in folder.iterdir() if TEMP_MARK in p.name]


def test_a_killed_writer_leaves_the_old_file_and_its_leftover_goes_next_time(tmp_path):
    path = tmp_path / "result.json"
    path.write_text("old")
    live = _writer(path)
    killed = _writer(path)
    killed.send_signal(signal.SIGKILL)
    killed.wait()
    assert path.read_text() == "old" and len(_temporaries(tmp_path)) == 2
    old = time.time() - 60
    for p in _temporaries(tmp_path):
        os.utime(p, (old, old))
    # The killed writer's temporary goes; the live writer's (locked) stays.
    assert len(remove_stale_temporaries(tmp_path)) == 1
    assert len(_temporaries(tmp_path)) == 1
    live.send_signal(signal.SIGKILL)
    live.wait()
    for p in _temporaries(tmp_path):
        os.utime(p, (old, old))
    with atomic_writer(path) as fh:  # the next write sweeps the folder
        fh.write("new")
    assert path.read_text() == "new" and _temporaries(tmp_path) == []
