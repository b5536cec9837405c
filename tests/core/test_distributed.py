"""The operator's precompute on a Dask cluster (a LocalCluster of two worker processes):
the same operator bit for bit as a local build, progress, cancel across the workers, and
one-line errors for a missing extra or a bad address."""

from __future__ import annotations

import itertools
import sys
import threading
import time

import numpy as np
import pytest
from distributed import Client, LocalCluster

from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.operator import distributed as dist
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches


@pytest.fixture(scope="module")
def cluster():
    # Worker processes: every piece and its inputs cross a process boundary, as on a
    # real cluster.
    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as c:
        yield c


@pytest.fixture(scope="module")
def office():
    return mesh_patches(builtin_scene("office", 0.6))


def _same(a, b) -> None:
    assert (a.F != b.F).nnz == 0
    np.testing.assert_array_equal(a.lowrank.Y, b.lowrank.Y)
    np.testing.assert_array_equal(a.lowrank.labels, b.lowrank.labels)
    np.testing.assert_array_equal(a.G, b.G)
    np.testing.assert_array_equal(a.power, b.power)


def test_a_cluster_build_is_the_local_build_bit_for_bit(cluster, office):
    # tol, not rank: the clusters are doubled once, so every step runs twice.
    settings = OperatorSettings(tol=0.01, rays=256, seed=3)
    local = build_operator(office, settings)
    seen: list[float] = []
    remote = build_operator(
        office, settings, progress=seen.append, scheduler=cluster.scheduler_address
    )
    _same(local, remote)
    assert len(local.info["tries"]) == 2
    assert [t["mean_rel_error"] for t in remote.info["tries"]] == [
        t["mean_rel_error"] for t in local.info["tries"]
    ]
    assert remote.info["scheduler"] == cluster.scheduler_address
    assert local.info["scheduler"] is None
    assert seen[-1] == 1.0 and all(a <= b for a, b in itertools.pairwise(seen))


def test_get_operator_on_a_cluster_caches_what_a_local_build_reads(
    cluster, office, tmp_path, monkeypatch
):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path))
    settings = OperatorSettings(rank=60, rays=128, seed=1)
    built = get_operator(office, settings, scheduler=cluster.scheduler_address)
    again = get_operator(office, settings)  # the scheduler is not part of the cache key
    assert not built.from_cache and again.from_cache
    _same(built.operator, again.operator)


def test_a_cancel_stops_the_pieces_on_every_worker(cluster):
    patches = mesh_patches(builtin_scene("patio", 0.5))  # ~6,000 patches: many ray batches
    flag = threading.Event()
    done: dict = {}

    def progress(fraction: float) -> None:
        if fraction > 0.2:
            flag.set()

    def run() -> None:
        try:
            build_operator(
                patches,
                OperatorSettings(rank=200, rays=2048),
                progress=progress,
                cancel=flag.is_set,
                scheduler=cluster.scheduler_address,
            )
        except BaseException as exc:
            done["error"] = exc
        done["end"] = time.perf_counter()

    thread = threading.Thread(target=run)
    thread.start()
    assert flag.wait(timeout=60)
    t_cancel = time.perf_counter()
    thread.join(timeout=30)
    assert isinstance(done.get("error"), CancelledError), done
    assert done["end"] - t_cancel < 2.0
    # Nothing of the build is left on the cluster: no task waiting, running or held.
    with Client(cluster.scheduler_address, set_as_default=False) as client:
        deadline = time.time() + 10
        while time.time() < deadline and client.run_on_scheduler(
            lambda dask_scheduler: len(dask_scheduler.tasks)
        ):
            time.sleep(0.1)
        left = client.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.tasks))
    assert left == 0


def test_a_missing_extra_or_a_bad_address_is_one_line(office, monkeypatch):
    with pytest.raises(LightInvError, match=r"not of the form tcp://host:port"):
        build_operator(office, OperatorSettings(rank=20, rays=16), scheduler="localhost:8786")
    monkeypatch.setattr(dist, "CONNECT_TIMEOUT", 0.5)
    with pytest.raises(LightInvError, match=r"cannot reach the Dask scheduler at tcp://127"):
        dist.runner("tcp://127.0.0.1:9")
    monkeypatch.setitem(sys.modules, "distributed", None)  # as if the extra were absent
    with pytest.raises(LightInvError, match=r"pip install 'lightinv\[cluster\]'"):
        dist.runner("tcp://127.0.0.1:8786")


def test_cli_precompute_on_a_cluster(cluster, tmp_path, monkeypatch, capsys):
    import json

    from lightinv_core import cli

    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path))
    args = ["precompute", "cornell", "--resolution", "0.5", "--rank", "40", "--rays", "64"]
    assert cli.main([*args, "--scheduler", cluster.scheduler_address, "--json"]) == 0
    built = json.loads(capsys.readouterr().out)
    assert built["from_cache"] is False
    assert cli.main([*args, "--json"]) == 0  # the local run reads what the cluster built
    assert json.loads(capsys.readouterr().out)["from_cache"] is True
    with pytest.raises(SystemExit) as bad:  # argparse's usage error
        cli.main([*args, "--scheduler", "localhost:8786"])
    assert bad.value.code == 2
    assert "not of the form tcp://host:port" in capsys.readouterr().err
