"""Atomic writes: all or nothing, and ordinary file permissions."""

from __future__ import annotations

import pytest

from lightinv_core.atomic import atomic_writer


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
