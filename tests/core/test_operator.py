"""The low-rank radiosity operator: accuracy against the reference, equality of the fast
paths, rank choice, progress/cancel, cache integrity and the CLI."""

from __future__ import annotations

import itertools
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.operator import build as build_mod
from lightinv_core.operator import cache as oc
from lightinv_core.operator.accuracy import sample_emissions
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.operator.zone_basis import exact_bounces, zone_basis
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.scene.zone_grid import random_zone_emissions
from lightinv_core.transport.formfactors import form_factor_matrix
from lightinv_core.transport.solver import group_emission, solve_dense

RES = 0.5  # office at 0.5 m: ~1,400 patches


@pytest.fixture(scope="module")
def office():
    return mesh_patches(builtin_scene("office", RES))


@pytest.fixture(scope="module")
def office_op(office):
    return build_operator(office, OperatorSettings(tol=0.01, rays=1024, seed=0))


@pytest.fixture(scope="module")
def office_F(office):
    return form_factor_matrix(office, 1024, seed=0)


def _dense(p, idx, val):
    E = np.zeros(p.n)
    np.add.at(E, idx, val)
    return E


def test_accuracy_against_the_reference_solver(office, office_op, office_F):
    assert office_op.info["estimated_rel_error"] <= 0.01
    E = sample_emissions(office, 8, seed=99)  # independent of the build's samples
    for q in range(E.shape[1]):
        ref = solve_dense(office_F, office.rho, E[:, q])
        C = office.rho * office_op.illuminance(E[:, q])
        assert np.linalg.norm(C - ref.C) / np.linalg.norm(ref.C) < 0.01


def test_fast_paths_equal_the_full_path(office, office_op):
    op = office_op
    cands = random_zone_emissions(office, 6, seed=1)
    rows = np.arange(0, office.n, 7)
    part = op.restrict(rows)
    idx = np.unique(np.concatenate([c[0] for c in cands]))
    V = np.stack([_dense(office, *c)[idx] for c in cands], axis=1)
    batch_H = op.zone_illuminance(idx, V)
    batch_part = part.zone_illuminance(idx, V)
    obj = cands[0]
    target = op.match_target(*obj)
    C_obj = office.rho * op.illuminance(_dense(office, *obj))
    batch_err = target.error(idx, V)
    batch_power = op.total_power(idx, V)
    for m, (ci, cv) in enumerate(cands):
        H = op.illuminance(_dense(office, ci, cv))
        C = office.rho * H
        scale = np.abs(H).max()
        np.testing.assert_allclose(op.zone_illuminance(ci, cv), H, atol=1e-5 * scale)
        np.testing.assert_allclose(batch_H[:, m], H, atol=1e-5 * scale)
        np.testing.assert_allclose(op.reflected(ci, cv, rows), C[rows], atol=1e-5 * scale)
        np.testing.assert_allclose(part.zone_illuminance(ci, cv), H[rows], atol=1e-5 * scale)
        np.testing.assert_allclose(batch_part[:, m], H[rows], atol=1e-5 * scale)
        power = float(np.dot(C, office.area))
        assert op.total_power(ci, cv) == pytest.approx(power, rel=1e-5)
        assert batch_power[m] == pytest.approx(power, rel=1e-5)
        err = float(np.linalg.norm(C - C_obj))
        tol = 1e-4 * np.linalg.norm(C_obj)
        assert abs(target.error(ci, cv) - err) < tol
        assert abs(batch_err[m] - err) < tol
        assert abs(op.match_error(ci, cv, *obj) - err) < tol
    assert target.relative_error(*obj) < 1e-3


def test_the_factored_basis_equals_the_dense_basis(office, office_op):
    """Phi made densely as before (all zone columns through the exact bounces, then the
    low-rank remainder) equals its rows read from the left (fewer rows than zone
    patches), from the right (all rows), the field of a batch and the power weights,
    to 1e-5 of the largest entry (float32 products summed in another order)."""
    op = office_op
    exact, last = exact_bounces(op.F, office.rho, op.zone_patches)
    Phi = zone_basis(exact, last, op.lowrank)
    scale = np.abs(Phi).max()
    rows = np.arange(3, office.n, 17)
    assert len(rows) < op.nz < office.n
    np.testing.assert_allclose(op.phi_rows(rows), Phi[rows], rtol=0, atol=1e-5 * scale)
    np.testing.assert_allclose(op.phi_rows(), Phi, rtol=0, atol=1e-5 * scale)
    V = np.random.default_rng(3).random((op.nz, 4)).astype(np.float32)
    want = Phi @ V
    np.testing.assert_allclose(op.zone_field(V), want, rtol=0, atol=1e-5 * np.abs(want).max())
    np.testing.assert_allclose(
        op.zone_field(V, rows), want[rows], rtol=0, atol=1e-5 * np.abs(want).max()
    )
    power = (office.area * office.rho) @ Phi.astype(np.float64)
    np.testing.assert_allclose(op.power, power, rtol=1e-5)
    # What the operator holds: F, F[:, zone], Y (n x k), G (k x nz) and, once a match
    # goal asked for it, the nz x nz Gram matrix: no n x nz array.
    sparse = sum(m.data.nbytes + m.indices.nbytes + m.indptr.nbytes for m in (op.F, op.Fz))
    held = sparse + op.lowrank.Y.nbytes + op.G.nbytes + op.power.nbytes
    assert op.nbytes() - held in (0, 8 * op.nz**2) and op.G.shape == (op.k, op.nz)


def test_over_the_basis_budget_receivers_are_lit_from_the_factors(office, office_op, monkeypatch):
    from lightinv_core.light.model import LightModel
    from lightinv_core.operator import radiosity

    scene = builtin_scene("office", RES)
    light = LightModel(scene, office, office_op)
    rows = np.arange(0, office.n, 5)
    made = light.receivers(rows)
    V = np.random.default_rng(4).random((office_op.nz, 3)).astype(np.float32)
    monkeypatch.setattr("lightinv_core.light.model.BASIS_BYTES", 1000)
    monkeypatch.setattr(radiosity, "BASIS_BYTES", 1000)
    lazy = light.receivers(rows)
    assert made.Phi_rows is not None and lazy.Phi_rows is None
    want = light.illuminance(V, made)
    np.testing.assert_allclose(light.illuminance(V, lazy), want, atol=1e-5 * np.abs(want).max())
    op = office_op
    fresh = radiosity.RadiosityOperator(op.lowrank, op.zone_patches, op.F, op.G, op.power, "")
    with pytest.raises(LightInvError, match=r"Gram matrix needs the zone basis.*limit"):
        _ = fresh.gram
    with pytest.raises(LightInvError, match="whole zone basis"):
        _ = fresh.Phi


def test_emission_outside_zones_uses_the_coarser_low_rank_path(office, office_op, office_F):
    E = group_emission(office, {"floor": 10000.0})
    ref = solve_dense(office_F, office.rho, E)
    C = office.rho * office_op.illuminance(E)
    assert np.linalg.norm(C - ref.C) / np.linalg.norm(ref.C) < 0.1
    with pytest.raises(LightInvError, match="outside the emitter zones"):
        office_op.zone_illuminance(office.group_index("floor")[:3], np.ones(3))


def test_rank_override_and_bad_settings(office):
    op = build_operator(office, OperatorSettings(rank=150, rays=64))
    assert op.info["rank"] == 150 and 100 <= op.k <= 150
    with pytest.raises(LightInvError, match="rank"):
        build_operator(office, OperatorSettings(rank=0, rays=16))
    with pytest.raises(LightInvError, match="tol"):
        build_operator(office, OperatorSettings(tol=2.0, rays=16))


def test_progress_and_cancel(office):
    seen = []
    build_operator(office, OperatorSettings(rank=100, rays=64), progress=seen.append)
    assert seen[-1] == pytest.approx(1.0)
    assert all(a <= b + 1e-12 for a, b in itertools.pairwise(seen))
    with pytest.raises(CancelledError):
        build_operator(office, OperatorSettings(rank=100, rays=64), cancel=lambda: True)


def test_memory_guard_names_the_numbers(office, monkeypatch):
    monkeypatch.setattr(build_mod, "available_memory_bytes", lambda: 1 << 20)
    with pytest.raises(LightInvError, match=r"(GiB|MiB) is available.*--resolution"):
        build_operator(office, OperatorSettings(rays=64))


def test_cache_round_trip_corruption_and_staleness(office, tmp_path, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path))
    warnings = []
    first = oc.get_operator(office, OperatorSettings(rank=120, rays=64), warn=warnings.append)
    assert not first.from_cache and first.path.exists()
    second = oc.get_operator(office, OperatorSettings(rank=120, rays=64), warn=warnings.append)
    assert second.from_cache and second.path == first.path and not warnings
    _assert_same_operator(second.operator, first.operator)
    assert second.operator.phi_rows(np.arange(5)).flags.f_contiguous
    assert second.operator.info == json.loads(json.dumps(first.operator.info))
    # Flip one payload byte: detected by the checksum, rebuilt, rewritten.
    raw = bytearray(first.path.read_bytes())
    raw[-100] ^= 0xFF
    first.path.write_bytes(bytes(raw))
    third = oc.get_operator(office, OperatorSettings(rank=120, rays=64), warn=warnings.append)
    assert not third.from_cache and "checksum" in warnings[-1]
    assert oc.get_operator(office, OperatorSettings(rank=120, rays=64)).from_cache
    # Truncated file.
    first.path.write_bytes(first.path.read_bytes()[:-10])
    fourth = oc.get_operator(office, OperatorSettings(rank=120, rays=64), warn=warnings.append)
    assert not fourth.from_cache and "truncated" in warnings[-1]
    # Other settings live in another file; no temporary files are left behind.
    other = oc.get_operator(office, OperatorSettings(rank=120, rays=32))
    assert other.path != first.path
    assert sorted(p.suffix for p in tmp_path.iterdir()) == [".lrr", ".lrr"]
    with pytest.raises(oc.CacheError, match="stale"):
        oc.load_operator(first.path, "another key")


def _assert_same_operator(a, b) -> None:
    """Every stored array of two operators is equal, bit for bit."""
    for name in ("G", "power", "zone_patches"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    np.testing.assert_array_equal(a.lowrank.Y, b.lowrank.Y)
    assert (a.F != b.F).nnz == 0 and a.F.dtype == b.F.dtype == np.float32


def _poison(path, edit) -> None:
    """Rewrite a cache file's JSON header with ``edit(header)``; the payload is kept, so
    its checksum still matches (what a buggy or hostile writer could leave)."""
    raw = path.read_bytes()
    start = len(oc.MAGIC) + 8
    size = int.from_bytes(raw[len(oc.MAGIC) : start], "little")
    header = json.loads(raw[start : start + size])
    edit(header)
    new = json.dumps(header).encode()
    path.write_bytes(oc.MAGIC + len(new).to_bytes(8, "little") + new + raw[start + size :])


POISONS = {
    "a petabyte payload": lambda h: h.update(payload_bytes=10**15),
    "a missing array": lambda h: h.update(arrays=[t for t in h["arrays"] if t["name"] != "Y"]),
    "an object dtype": lambda h: h["arrays"][0].update(dtype="|O"),
    "an array past the end": lambda h: h["arrays"][-1].update(offset=h["payload_bytes"]),
    "a wrong shape": lambda h: [t.update(shape=[3, 7]) for t in h["arrays"] if t["name"] == "G"],
    "an empty header": lambda h: h.clear(),
    "info that is a number": lambda h: h.update(info=7),
}


@pytest.mark.parametrize("poison", POISONS, ids=list(POISONS))
def test_a_poisoned_cache_header_is_rebuilt_not_a_traceback(office, tmp_path, monkeypatch, poison):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path))
    settings = OperatorSettings(rank=120, rays=64)
    first = oc.get_operator(office, settings)
    _poison(first.path, POISONS[poison])
    warnings = []
    again = oc.get_operator(office, settings, warn=warnings.append)
    assert not again.from_cache and len(warnings) == 1 and "rebuilding" in warnings[0]
    _assert_same_operator(again.operator, first.operator)
    assert oc.get_operator(office, settings).from_cache  # rewritten whole


def test_form_factor_indices_out_of_range_are_a_corrupt_cache(office, tmp_path, monkeypatch):
    """A payload whose checksum matches but whose sparse F points past the patches (what
    a buggy writer could leave) is refused by the CSR check, not used."""
    import hashlib

    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path))
    settings = OperatorSettings(rank=120, rays=64)
    first = oc.get_operator(office, settings)
    raw = bytearray(first.path.read_bytes())
    start = len(oc.MAGIC) + 8
    size = int.from_bytes(raw[len(oc.MAGIC) : start], "little")
    header = json.loads(raw[start : start + size])
    entry = next(t for t in header["arrays"] if t["name"] == "F_indices")
    at = start + size + entry["offset"]
    raw[at : at + 4] = np.array([office.n + 5], dtype=entry["dtype"]).tobytes()[:4]
    payload = bytes(raw[start + size :])
    header["payload_sha256"] = hashlib.sha256(payload).hexdigest()
    new = json.dumps(header).encode()
    first.path.write_bytes(oc.MAGIC + len(new).to_bytes(8, "little") + new + payload)
    with pytest.raises(oc.CacheError, match="inconsistent arrays"):
        oc.load_operator(first.path, oc.operator_key(office, settings))


def test_cli_precompute_and_lrr_simulation(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path))
    args = ["precompute", "office", "--resolution", str(RES), "--json"]
    assert cli.main(args) == 0
    out = json.loads(capsys.readouterr().out)
    for key in (
        "n",
        "k",
        "seconds",
        "from_cache",
        "cache_path",
        "estimated_rel_error",
        "peak_rss_mb",
    ):
        assert key in out
    assert out["from_cache"] is False and out["estimated_rel_error"] <= 0.01
    assert cli.main(args) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["from_cache"] is True and again["seconds"] < 2.0
    sim = ["simulate", "office", "--resolution", str(RES), "--emit", "roof=48000", "--json"]
    assert cli.main([*sim, "--method", "lrr"]) == 0
    lrr = json.loads(capsys.readouterr().out)
    assert cli.main([*sim, "--method", "reference"]) == 0
    ref = json.loads(capsys.readouterr().out)
    assert lrr["from_cache"] is True and lrr["emitted_outside_zones_lm"] == pytest.approx(0.0)
    for a, b in zip(lrr["groups"], ref["groups"], strict=True):
        assert a["group"] == b["group"]
        assert a["avg_lux"] == pytest.approx(b["avg_lux"], rel=0.02)


def test_an_open_scene_is_reported(tmp_path, monkeypatch):
    from lightinv_core.scene.model import Rect, Scene, Surface

    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path))
    # A floor and one wall, no ceiling: most light leaves the model.
    scene = Scene(
        "open",
        (
            Surface("floor", "floor", 0.5, rect=Rect((0, 0, 0), (2, 0, 0), (0, 2, 0))),
            Surface("wall", "wall", 0.5, rect=Rect((0, 0, 0), (0, 0, 2), (2, 0, 0))),
        ),
        resolution=0.5,
    )
    patches = mesh_patches(scene)
    warnings = []
    got = oc.get_operator(patches, OperatorSettings(rank=2, rays=64), warn=warnings.append)
    assert got.operator.info["lost_fraction"] > 0.5
    assert "escapes the model" in warnings[0]
    oc.get_operator(
        patches, OperatorSettings(rank=2, rays=64), warn=warnings.append
    )  # from the cache too
    assert len(warnings) == 2
    closed = []
    oc.get_operator(
        mesh_patches(builtin_scene("cornell", 0.5)),
        OperatorSettings(rank=20, rays=64),
        warn=closed.append,
    )
    assert closed == []


def test_an_unusable_or_full_cache_folder_still_gives_the_operator(tmp_path, monkeypatch):
    patches = mesh_patches(builtin_scene("cornell", 0.5))
    settings = OperatorSettings(rank=40, rays=64)
    # The cache folder is a file: it cannot be created.
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("")
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(blocker / "cache"))
    warnings: list[str] = []
    got = oc.get_operator(patches, settings, warn=warnings.append)
    assert got.operator.k > 0 and not got.from_cache
    assert len(warnings) == 1 and warnings[0].startswith("could not write the operator cache")
    # A full disk: the write fails at fsync; the build is kept, no temporary is left.
    folder = tmp_path / "full"
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(folder))

    def no_space(fd):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("lightinv_core.atomic.os.fsync", no_space)
    warnings.clear()
    got = oc.get_operator(patches, settings, warn=warnings.append)
    assert got.operator.k > 0 and "No space left on device" in warnings[0]
    assert list(folder.iterdir()) == []


def test_a_killed_builds_leftover_is_swept_when_the_cache_opens(tmp_path, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path))
    leftover = tmp_path / ".0123abcd.lrr.tmp-x1y2z3"
    leftover.write_bytes(b"half an operator")
    os.utime(leftover, (0, 0))
    patches = mesh_patches(builtin_scene("cornell", 0.5))
    oc.get_operator(patches, OperatorSettings(rank=40, rays=64))
    assert not leftover.exists() and len(list(tmp_path.glob("*.lrr"))) == 1


def test_two_processes_building_the_same_cache_at_once(tmp_path):
    env = {**os.environ, "LIGHTINV_CACHE_DIR": str(tmp_path)}
    cmd = [sys.executable, "-m", "lightinv_core.console", "precompute", "cornell"]
    cmd += ["--resolution", "0.4", "--rank", "60", "--json"]
    procs = [
        subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        for _ in range(2)
    ]
    outs = [p.communicate(timeout=120) for p in procs]
    assert [p.returncode for p in procs] == [0, 0], outs
    # Usually both build and race to write; on a busy machine the second may start
    # after the first has written and read it: either way one whole file, no leftover.
    assert any(not json.loads(out)["from_cache"] for out, _ in outs)
    files = list(tmp_path.iterdir())
    assert len(files) == 1 and files[0].suffix == ".lrr"  # one whole file, no temporary
    again = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=120)
    assert again.returncode == 0 and json.loads(again.stdout)["from_cache"]
