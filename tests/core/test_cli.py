"""``lightinv-cli`` end to end, through ``cli.main``: output, files and exit statuses."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lightinv_core import cli
from lightinv_core.cli import scenes as cli_scenes
from lightinv_core.cli import simulate as cli_simulate

MODELS = Path(__file__).resolve().parents[2] / "resources" / "models"
ROOM = str(MODELS / "meeting_room.obj")
ROOM_MATERIALS = str(MODELS / "meeting_room-materials.json")
CSV_HEADER = ["id", "group", "cx", "cy", "cz", "nx", "ny", "nz", "area", "rho", "E", "B", "lux"]


@pytest.fixture(autouse=True)
def cache_dir(tmp_path, monkeypatch):
    """Keep any operator the command line builds out of the user's cache."""
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))


def run_json(capsys, *argv: str) -> dict:
    assert cli.main([*argv, "--json"]) == 0
    out, err = capsys.readouterr()
    assert err == ""
    return json.loads(out)


def check_groups(stats: list[dict]) -> None:
    for s in stats:
        assert 0 <= s["min_lux"] <= s["avg_lux"] <= s["max_lux"], s


def test_scenes_lists_the_builtin_scenes(capsys):
    scenes = run_json(capsys, "scenes")["scenes"]
    assert [s["name"] for s in scenes] == [
        "cornell",
        "office",
        "patio",
        "corridor",
        "building",
        "sidelit",
        "toplit",
        "flagship",
    ]
    for s in scenes:
        assert isinstance(s["patches"], int) and s["patches"] > 0
        assert s["resolution"] > 0 and s["description"]


def test_scene_info_of_a_builtin_scene(capsys):
    info = run_json(capsys, "scene-info", "office", "--resolution", "0.5")
    assert {"name", "patches", "area_m2", "groups", "zones"} <= set(info)
    assert info["name"] == "office" and info["resolution"] == 0.5
    assert info["patches"] == sum(g["patches"] for g in info["groups"])
    assert info["area_m2"] == pytest.approx(sum(g["area_m2"] for g in info["groups"]))
    assert "skylight" in {z["kind"] for z in info["zones"]}


def test_scene_info_of_the_example_obj(capsys):
    info = run_json(capsys, "scene-info", ROOM, "--materials", ROOM_MATERIALS)
    assert info["name"] == "meeting_room"
    assert info["warnings"] == []
    groups = {g["name"]: g for g in info["groups"]}
    assert list(groups) == ["floor", "walls", "ceiling", "table", "skylight", "downlights"]
    assert groups["floor"]["area_m2"] == pytest.approx(24.0)
    assert groups["walls"]["area_m2"] == pytest.approx(2 * (6 + 4) * 2.8)
    # 24 m² of ceiling: the two zones and the five rectangles around them.
    assert groups["ceiling"]["area_m2"] == pytest.approx(24.0 - 2.0 - 1.0)
    assert info["patches"] == sum(g["patches"] for g in info["groups"])
    zones = {z["name"]: z for z in info["zones"]}
    assert {n: z["kind"] for n, z in zones.items()} == {
        "skylight": "skylight",
        "downlights": "luminaire",
    }
    assert zones["skylight"]["size_m"] == pytest.approx([2.0, 1.0])
    assert zones["downlights"]["size_m"] == pytest.approx([2.0, 0.5])
    for z in zones.values():
        assert z["normal"] == pytest.approx([0.0, 0.0, -1.0])  # facing down into the room
        assert z["origin"][2] == pytest.approx(2.8)


def test_scene_info_text_output(capsys):
    assert cli.main(["scene-info", ROOM, "--resolution", "0.5"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("meeting_room: ")
    assert "skylight   skylight  2.00 x 1.00 m" in out
    assert "downlights luminaire 2.00 x 0.50 m" in out


def test_simulate_cornell_with_patch_csv(capsys, tmp_path):
    path = tmp_path / "patches.csv"
    result = run_json(
        capsys, "simulate", "cornell", "--emit", "light=1000", "--patches-csv", str(path)
    )
    assert result["method"] == "reference"
    assert result["energy"]["emitted_lm"] == pytest.approx(1000.0)
    assert result["lost_fraction"] < 1e-4
    check_groups(result["groups"])
    assert {s["group"] for s in result["groups"]} >= {"floor", "light", "ceiling"}
    with path.open(newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == CSV_HEADER
    assert len(rows) - 1 == result["patches"]
    assert [int(r[0]) for r in rows[1:]] == list(range(result["patches"]))


def test_simulate_the_example_obj_with_its_skylight(capsys):
    result = run_json(
        capsys,
        "simulate",
        ROOM,
        "--materials",
        ROOM_MATERIALS,
        "--resolution",
        "0.5",
        "--emit",
        "skylight=5000",
    )
    assert result["scene"] == "meeting_room"
    assert result["energy"]["emitted_lm"] == pytest.approx(5000.0)
    assert result["lost_fraction"] < 1e-4  # the room is closed
    assert abs(result["energy"]["imbalance"]) < 0.02
    stats = {s["group"]: s for s in result["groups"]}
    assert set(stats) == {"floor", "walls", "ceiling", "table", "skylight", "downlights"}
    check_groups(result["groups"])
    assert stats["table"]["avg_lux"] > 0 and stats["floor"]["avg_lux"] > 0


def broken_obj(tmp_path) -> str:
    path = tmp_path / "broken.obj"
    path.write_text("v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n")
    return str(path)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["scene-info", "nowhere"], "'nowhere' is neither a built-in scene"),
        (["simulate", "cornell", "--emit", "nosuch=100"], "no group 'nosuch'"),
        (["simulate", "cornell"], "nothing emits"),
        (["scene-info", "BROKEN"], "broken.obj line 2: vertex coordinate 'nan' is not finite"),
        (["scene-info", "MISSING"], "missing.obj' does not exist; check the path"),
    ],
)
def test_user_errors_exit_2_with_one_line(capsys, tmp_path, argv, message):
    files = {"BROKEN": broken_obj(tmp_path), "MISSING": str(tmp_path / "missing.obj")}
    argv = [files.get(a, a) for a in argv]
    assert cli.main(argv) == 2
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("lightinv-cli: error: ")
    assert message in lines[0]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["simulate", "cornell", "--emit", "light"], "expected GROUP=LUMENS, got 'light'"),
        (["simulate", "cornell", "--emit", "light=abc"], "expected GROUP=LUMENS"),
        (["scene-info", "office", "--resolution", "-0.5"], "expected a positive number"),
        (["scene-info", "office", "--resolution", "0"], "expected a positive number"),
        (["simulate", "cornell", "--seed", "-1"], "expected an integer seed from 0"),
        (["precompute", "cornell", "--seed", "-1"], "expected an integer seed from 0"),
        (["solve", "project.json", "--seed", "-1"], "expected an integer seed from 0"),
        (["solve", "project.json", "--seed", str(2**70)], "to 2**63 - 1, got 1180591"),
        (["solve", "project.json", "--max-evals", "0"], "expected an integer >= 1, got 0"),
        (["precompute", "cornell", "--rays", str(2**70)], "from 1 to 65,536 rays per patch"),
        (["simulate", "cornell", "--rays", str(2**70)], "from 1 to 65,536 rays per patch"),
        (["simulate", "cornell", "--rays", "0"], "from 1 to 65,536 rays per patch, got 0"),
        (["solve", "project.json", "--max-evals", "-5"], "expected an integer >= 1, got -5"),
    ],
)
def test_bad_arguments_exit_2_without_traceback(capsys, argv, message):
    with pytest.raises(SystemExit) as exc:
        cli.main(argv)
    assert exc.value.code == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert "Traceback" not in err
    # One line, like every other user error, naming the subcommand and the argument.
    lines = err.strip().splitlines()
    assert len(lines) == 1
    assert lines[0].startswith(f"lightinv-cli: error: lightinv-cli {argv[0]}: argument ")
    assert message in lines[0]


def small_front_project(tmp_path) -> str:
    projects = Path(__file__).resolve().parents[2] / "resources" / "projects"
    src = json.loads((projects / "experiment5.json").read_text())
    src["scene"]["resolution"] = 0.7
    src["operator"] = {"rank": 150, "rays": 256}
    path = tmp_path / "front.json"
    path.write_text(json.dumps(src))
    return str(path)


def test_solve_chooses_the_method_and_reports_the_front_quality(capsys, tmp_path):
    path = small_front_project(tmp_path)
    out = run_json(capsys, "solve", path, "--method", "nsga2", "--max-evals", "800")
    assert out["method"] == "nsga2" and out["status"] == "feasible"
    q = out["front_quality"]
    assert 0.0 < q["hypervolume"] < 1.0 and q["points"] == len(out["pareto"]) >= 2
    assert q["spacing"] >= 0.0 and q["reference"] == [1.0, 0.0]
    assert cli.main(["solve", path, "--method", "nsga2", "--max-evals", "800"]) == 0
    text = capsys.readouterr().out
    assert f"hypervolume {q['hypervolume']:.4f}" in text
    with pytest.raises(SystemExit) as exc:
        cli.main(["solve", path, "--method", "simplex"])
    assert exc.value.code == 2
    assert "--method: invalid choice: 'simplex'" in capsys.readouterr().err


def _engine_imports_started(pid: int) -> bool:
    """Whether process ``pid`` has loaded numpy's core extension: ``lightinv_core.console``
    imports it only after its Ctrl-C handler is in place (Linux: /proc/PID/maps)."""
    try:
        return "_multiarray_umath" in Path(f"/proc/{pid}/maps").read_text()
    except OSError:
        return False


@pytest.mark.skipif(not Path("/proc/self/maps").exists(), reason="needs Linux's /proc")
@pytest.mark.parametrize("after", [0.0, 0.05, 0.2, 0.4])
def test_ctrl_c_at_any_moment_prints_one_line_not_a_traceback(tmp_path, after):
    # The installed entry point (lightinv_core.console), as a user runs it. "Any moment"
    # is any moment once the program runs: a Ctrl-C during the interpreter's own start-up,
    # before the entry point's first line (site and the venv's .pth files: tens of ms,
    # 0.2 s and more on a loaded machine), is Python's, which prints "Fatal Python error:
    # init_import_site" and a KeyboardInterrupt traceback; no program can act on it. So the
    # signal is timed from the start of the engine's imports, which the entry point makes
    # only once its handler is set, not from the process start.
    proc = subprocess.Popen(
        [str(Path(sys.executable).parent / "lightinv-cli"), "precompute", "cornell"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "LIGHTINV_CACHE_DIR": str(tmp_path / "cache")},
    )
    deadline = time.monotonic() + 60
    while not _engine_imports_started(proc.pid):
        assert proc.poll() is None and time.monotonic() < deadline, "no engine imports"
        time.sleep(0.002)
    time.sleep(after)  # during the imports (0.5 s on a quiet machine), or the build
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert "Traceback" not in err
    assert proc.returncode == 130 and err.strip() == "lightinv-cli: cancelled"


VALUES = st.sampled_from(
    ["-1", "0", "1", "0.5", "64", "-0.5", "1e400", "nan", "inf", "abc", "", str(2**70), "2**3"]
)
OPTIONS = st.sampled_from(
    [
        "--seed",
        "--rays",
        "--rank",
        "--tol",
        "--resolution",
        "--emit",
        "--max-evals",
        "--time-limit",
        "--method",
        "--scale",
        "--materials",
        "--patches-csv",
        "-o",
    ]
)
COMMANDS = st.sampled_from(
    [
        ["scenes"],
        ["scene-info", "cornell"],
        ["simulate", "cornell", "--emit", "light=100"],
        ["precompute", "cornell"],
        ["solve", "PROJECT"],
        ["report", "PROJECT"],
        ["bogus"],
        [],
    ]
)


@settings(
    max_examples=int(os.environ.get("LIGHTINV_FUZZ_EXAMPLES", 120)),
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(command=COMMANDS, pairs=st.lists(st.tuples(OPTIONS, VALUES), max_size=3))
def test_fuzz_arguments_give_one_clear_line_never_a_traceback(
    capsys, tmp_path, monkeypatch, command, pairs
):
    monkeypatch.chdir(tmp_path)  # "-o 1" and "--patches-csv inf" write where they are told
    project = tmp_path / "p.json"
    if not project.exists():
        project.write_text('{"schema": 1, "scene": {"builtin": "cornell"}}')
    argv = [str(project) if a == "PROJECT" else a for a in command]
    for option, value in pairs:
        argv += [option, value]
    if "--resolution" not in argv and command[:1] in (["simulate"], ["precompute"]):
        argv += ["--resolution", "0.5"]  # keep every accepted run small
    try:
        status = cli.main([*argv, "--json"] if command[:1] == ["scenes"] else argv)
    except SystemExit as exc:  # argparse: usage errors and --help
        status = exc.code
    out, err = capsys.readouterr()
    assert "Traceback" not in err and "Traceback" not in out
    assert status in (0, 2), (argv, status, err)
    if status == 2:
        lines = err.strip().splitlines()
        assert (lines and lines[-1].startswith("lightinv-cli: error: ")) or "usage:" in err, err


def test_an_unwritable_output_is_refused_before_any_work(capsys, tmp_path):
    path = small_front_project(tmp_path)
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    t0 = time.perf_counter()
    for argv in (
        ["solve", path, "-o", str(blocker / "out.json")],  # its "folder" is a file
        ["solve", path, "-o", str(tmp_path)],  # a folder
        ["simulate", "cornell", "--emit", "light=100", "--patches-csv", "/proc/x.csv"],
        ["report", path, "-o", "/proc/r.pdf"],
        ["report", path, "-o", str(tmp_path / "r.pdf"), "--png-dir", str(blocker / "png")],
    ):
        assert cli.main(argv) == 2, argv
        out, err = capsys.readouterr()
        assert out == "" and err.startswith("lightinv-cli: error: cannot write "), err
        assert len(err.strip().splitlines()) == 1
    assert time.perf_counter() - t0 < 5  # refused before the operator or the optimiser ran


def test_a_failed_final_write_keeps_the_result(capsys, tmp_path, monkeypatch):
    """The disk fills up while the optimiser runs: the solved project goes beside the
    asked path, the summary is printed, status 2."""
    import errno

    import lightinv_core.project as project_module
    from lightinv_core.project import load_project

    path = small_front_project(tmp_path)
    target = tmp_path / "solved.json"
    real_save = project_module.save_project

    def full_disk(project, where):
        if Path(where) == target:
            raise OSError(errno.ENOSPC, "No space left on device")
        return real_save(project, where)

    monkeypatch.setattr(project_module, "save_project", full_disk)
    argv = ["solve", path, "--method", "nsga2", "--max-evals", "800", "-o", str(target)]
    assert cli.main([*argv, "--json"]) == 2
    out, err = capsys.readouterr()
    (rescued,) = tmp_path.glob("solved.unsaved-*.json")
    summary = json.loads(out)
    assert summary["saved"] == str(rescued) and summary["status"] == "feasible"
    assert "No space left on device" in err and f"written to {rescued} instead" in err
    assert not target.exists()
    assert len(load_project(rescued).pareto.solutions) == len(summary["pareto"])
    # The patch values of a simulation are kept the same way.
    real_csv = cli_simulate.write_patch_csv

    def csv_full(where, *rest):
        if Path(where) == tmp_path / "p.csv":
            raise OSError(errno.ENOSPC, "No space left on device")
        return real_csv(where, *rest)

    monkeypatch.setattr(cli_simulate, "write_patch_csv", csv_full)
    argv = ["simulate", "cornell", "--emit", "light=100", "--patches-csv", str(tmp_path / "p.csv")]
    assert cli.main([*argv, "--resolution", "0.5"]) == 2
    out, err = capsys.readouterr()
    (kept,) = tmp_path.glob("p.unsaved-*.csv")
    assert f"patch values written to {kept}" in out and "No space left" in err
    with open(kept) as fh:
        assert next(csv.reader(fh)) == CSV_HEADER


def test_a_stray_numpy_warning_is_one_line(capsys, monkeypatch):
    """A number the engine did not catch reaches the user as one line, not numpy's
    two-line warning with a library's source line."""
    import numpy as np

    real = cli_scenes.cmd_scenes

    def noisy(args):
        np.log(np.zeros(1))  # RuntimeWarning: divide by zero
        return real(args)

    parser = cli.build_parser()
    monkeypatch.setattr(cli, "build_parser", lambda: parser)
    parser._subparsers._group_actions[0].choices["scenes"].set_defaults(func=noisy)
    assert cli.main(["scenes"]) == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "RuntimeWarning: divide by zero" in err
