"""``lightinv-cli export`` and the exporter registry (lightinv_core/export/registry.py):
one option per registered format, a plug-in format added and removed at run time."""

from __future__ import annotations

import json

import pytest

from lightinv_core import cli
from lightinv_core.export import ExportedFile, Exporter, exporter, exporters, register, unregister
from lightinv_core.export.design import write_text
from lightinv_core.project import save_project
from tests.export.office import office_project


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    path = tmp_path_factory.mktemp("cli") / "result.json"
    save_project(office_project(), path)
    return path


def run_json(capsys, *argv: str) -> dict:
    assert cli.main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize(
    ("option", "suffix", "counts"),
    [
        ("--ifc", ".ifc", {"luminaires": 4, "glazing": 1, "workplanes": 1, "surfaces": 6}),
        ("--radiance", ".rad", {"luminaires": 4, "glazing": 1, "products": 1}),
        ("--gltf", ".glb", {"groups": 6}),
    ],
)
def test_export_writes_each_format(result, tmp_path, capsys, option, suffix, counts):
    if option == "--ifc":
        pytest.importorskip("ifcopenshell")
    target = tmp_path / f"design{suffix}"
    got = run_json(capsys, "export", str(result), option, str(target))
    assert got["format"] == option[2:] and got["path"] == str(target)
    assert got["solution"] == "saved solution 1 of 1"
    assert counts.items() <= got["counts"].items()
    assert all((tmp_path / f).exists() for f in got["files"])


def test_a_second_solution_that_is_not_there(result, tmp_path, capsys):
    assert (
        cli.main(["export", str(result), "--gltf", str(tmp_path / "x.glb"), "--solution", "2"]) == 2
    )
    assert "--solution 2: the project holds 1 solution(s)" in capsys.readouterr().err


def test_exactly_one_format_is_asked_for(result, tmp_path, capsys):
    with pytest.raises(SystemExit) as info:
        cli.main(["export", str(result), "--gltf", "a.glb", "--ifc", "a.ifc"])
    assert info.value.code == 2
    assert "not allowed with argument" in capsys.readouterr().err


def test_a_registered_format_is_a_cli_option(result, tmp_path, capsys):
    """A plug-in exporter (here a CSV of the luminaires) is an option of the command
    line from its registration alone, and gone after unregister."""

    def write_csv(ex, path) -> ExportedFile:
        rows = [
            f"{f.name},{f.position[0]:.3f},{f.position[1]:.3f},{f.lumens:.1f}" for f in ex.fixtures
        ]
        write_text(path, "\n".join(rows) + "\n")
        return ExportedFile(path, (path,), {"luminaires": len(rows)})

    register(Exporter("csv", (".csv",), "Luminaire CSV", write_csv))
    try:
        assert exporter("csv").filter == "Luminaire CSV (*.csv)"
        got = run_json(capsys, "export", str(result), "--csv", str(tmp_path / "l.csv"))
        assert got["counts"] == {"luminaires": 3}
        assert (tmp_path / "l.csv").read_text().startswith("west.1,")
        with pytest.raises(ValueError, match="already registered"):
            register(Exporter("csv", (".csv",), "again", write_csv))
    finally:
        unregister("csv")
    assert [e.name for e in exporters()] == ["ifc", "radiance", "gltf"]
    with pytest.raises(SystemExit):
        cli.main(["export", str(result), "--csv", str(tmp_path / "l.csv")])
    with pytest.raises(ValueError, match="suffixes"):
        Exporter("bad", ("csv",), "no dot", write_csv)
