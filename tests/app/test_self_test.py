"""``lightinv --self-test`` passes in this installation (the bundle runs the same check)."""

from __future__ import annotations

import json
import os
import subprocess
import sys


def test_self_test_passes_without_a_display(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    env["LIGHTINV_CACHE_DIR"] = str(tmp_path)
    out = subprocess.run(
        [sys.executable, "-m", "app", "--self-test"],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
        check=False,
    )
    assert out.returncode == 0, out.stdout + out.stderr
    report = json.loads(out.stdout)
    assert report["ok"] and report["render_std"] > 5 and report["max_lux"] > 0
