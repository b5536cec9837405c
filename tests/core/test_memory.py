"""The memory guard reads the container's limit (cgroup v1 and v2), not only the
machine's, and OBJ files are sized up by a streaming count before they are parsed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from lightinv_core import memory
from lightinv_core.scene.importers import obj_size
from lightinv_core.scene.importers.obj_size import count_obj_lines

GiB = 2**30


def fake_proc(tmp_path: Path, cgroup: str, available_kib: int = 16 * 2**20) -> Path:
    proc = tmp_path / "proc"
    (proc / "self").mkdir(parents=True)
    (proc / "self" / "cgroup").write_text(cgroup)
    (proc / "meminfo").write_text(f"MemTotal: 1 kB\nMemAvailable: {available_kib} kB\n")
    return proc


def test_cgroup_v2_limit_minus_usage_counts_reclaimable_cache_as_free(tmp_path):
    proc = fake_proc(tmp_path, "0::/user.slice/app\n")
    root = tmp_path / "cg"
    leaf = root / "user.slice" / "app"
    leaf.mkdir(parents=True)
    (leaf / "memory.max").write_text(str(4 * GiB))
    (leaf / "memory.current").write_text(str(3 * GiB))
    (leaf / "memory.stat").write_text(f"anon 1\ninactive_file {GiB}\n")
    assert memory.cgroup_available_bytes(proc, root) == 2 * GiB
    (leaf / "memory.max").write_text("max\n")
    assert memory.cgroup_available_bytes(proc, root) == memory.UNLIMITED


def test_cgroup_v1_limit_and_a_stricter_parent(tmp_path):
    proc = fake_proc(tmp_path, "4:memory:/docker/abc\n3:cpu:/\n")
    root = tmp_path / "cg"
    leaf = root / "memory" / "docker" / "abc"
    leaf.mkdir(parents=True)
    (leaf / "memory.limit_in_bytes").write_text(str(2**63 - 4096))  # no limit of its own
    (leaf / "memory.usage_in_bytes").write_text(str(GiB))
    (root / "memory" / "memory.limit_in_bytes").write_text(str(3 * GiB))
    (root / "memory" / "memory.usage_in_bytes").write_text(str(GiB))
    (root / "memory" / "memory.stat").write_text(f"total_inactive_file {GiB // 2}\n")
    assert memory.cgroup_available_bytes(proc, root) == 2 * GiB + GiB // 2


def test_no_cgroup_files_means_no_limit_and_the_machine_decides(tmp_path):
    proc = fake_proc(tmp_path, "0::/\n", available_kib=1024)
    assert memory.cgroup_available_bytes(proc, tmp_path / "none") == memory.UNLIMITED
    assert memory.machine_available_bytes(proc) == 2**20
    assert memory.machine_available_bytes(tmp_path / "nowhere") == memory.UNLIMITED


def test_this_machine_reports_something_sensible():
    have = memory.available_memory_bytes()
    # Read a moment apart: on a busy machine the free memory moves in between (a loaded
    # run saw 135 kB), so the two agree only within a margin.
    assert 0 < have <= memory.machine_available_bytes() + 256 * 2**20


def test_format_bytes_never_says_zero_gib():
    assert memory.format_bytes(3 * GiB) == "3.0 GiB"
    assert memory.format_bytes(5 * 2**20) == "5 MiB"
    assert memory.format_bytes(5000) == "5 KiB"
    assert memory.format_bytes(12) == "12 bytes"


@pytest.mark.parametrize("chunk", [7, 64, 1 << 24])
@pytest.mark.parametrize("encoding", ["utf-8", "utf-8-sig", "utf-16", "utf-16-le"])
@pytest.mark.parametrize("newline", ["\n", "\r\n"])
def test_counting_lines_agrees_with_the_file_whatever_the_block_size(
    tmp_path, monkeypatch, chunk, encoding, newline
):
    monkeypatch.setattr(obj_size, "CHUNK", chunk)
    rng = np.random.default_rng(0)
    lines = ["# a comment", "vn 0 0 1", "vt 0 0"]
    lines += [f"v {x:.3f} 0 1" for x in rng.random(50)]
    lines += ["f 1 2 3", "f\t1 2 3 4", "usemtl fog", "g floor"] * 7
    path = tmp_path / "m.obj"
    path.write_bytes(newline.join(lines).encode(encoding))
    c = count_obj_lines(path)
    assert (c.vertices, c.faces) == (50, 14)
    assert c.nbytes == path.stat().st_size
    assert c.import_bytes > c.nbytes
