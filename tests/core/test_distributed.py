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
from threadpoolctl import threadpool_limits

from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.operator import distributed as dist
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.lowrank import ASSEMBLE_BLOCK, INNER_BLOCK, times_inverse
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


def test_a_cluster_build_above_the_blas_block_is_the_local_build_bit_for_bit(cluster):
    # k = 587 clusters: Y = W M^-1 sums more terms than OpenBLAS's block (GEMM_Q, 448
    # here), which it cuts one way on this process's threads and another on a worker's
    # one thread. Summed whole, 278,105 of Y's 1,706,996 entries differed.
    patches = mesh_patches(builtin_scene("office", 0.35))
    settings = OperatorSettings(rank=600, rays=128, seed=1)
    local = build_operator(patches, settings)
    assert local.k > 448
    _same(local, build_operator(patches, settings, scheduler=cluster.scheduler_address))


@pytest.mark.parametrize("rows", [1, 981, 2 * ASSEMBLE_BLOCK + 7])
@pytest.mark.parametrize("k", [40, INNER_BLOCK, 587, 1042])
def test_the_rows_of_y_do_not_depend_on_the_blas_threads(rows, k):
    rng = np.random.default_rng(k)
    W = rng.random((rows, k), dtype=np.float32)
    Minv = rng.standard_normal((k, k), dtype=np.float32)
    with threadpool_limits(limits=1, user_api="blas"):
        one = times_inverse(W, Minv)
    for threads in (2, 4):
        with threadpool_limits(limits=threads, user_api="blas"):
            np.testing.assert_array_equal(times_inverse(W, Minv), one)
    if k <= INNER_BLOCK:  # one product per row block on one thread: the same bits
        with threadpool_limits(limits=1, user_api="blas"):
            blocks = [W[s : s + ASSEMBLE_BLOCK] @ Minv for s in range(0, rows, ASSEMBLE_BLOCK)]
        np.testing.assert_array_equal(one, np.vstack(blocks))


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
