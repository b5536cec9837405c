"""Photometry warnings reach the user, and the CLI's luminaire summary states flux and
power at one dimming state.

A file's warnings (``Photometry.warnings``: a lamp-tilt table not applied, a light
output ratio above 100%, extra lamp sets) are listed once per file by
``light_warnings``; ``lightinv-cli simulate`` prints them on stderr and in ``--json``'s
``warnings``, the report's luminaire schedule in its note (the window: in
tests/app/test_luminaires_gui.py).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from lightinv_core import cli
from lightinv_core.design.model import LuminaireArray
from lightinv_core.luminaires import downlight, read_photometry
from lightinv_core.luminaires.formats import write_photometry
from lightinv_core.luminaires.photometry import light_warnings
from lightinv_core.report.luminaires import luminaire_table

REAL = Path(__file__).resolve().parents[1] / "data" / "photometry" / "rab-round-4.ies"
# LM-63's own example of an included lamp-tilt table (13 angles, factors 0.87 to 1).
TILT = (
    "TILT=INCLUDE\r\n1\r\n13\r\n0 15 30 45 60 75 90 105 120 135 150 165 180\r\n"
    "1.0 .95 .94 .90 .88 .87 .98 .87 .88 .90 .94 .95 1.0\r\n"
)
TILT_WARNING = (
    "TILT=INCLUDE: the lamp-tilt factors (13 angles, 0.87 to 1) are not applied; the "
    "light is computed with the lamp as photometered"
)


def tilted_file(folder: Path) -> Path:
    """The real round high bay with a lamp-tilt table included (as HID files have)."""
    text = REAL.read_bytes().decode("latin-1")
    assert text.count("TILT=NONE\r\n") == 1
    path = folder / "tilted.ies"
    path.write_bytes(text.replace("TILT=NONE\r\n", TILT).encode("latin-1"))
    return path


def test_light_warnings_name_each_file_once(tmp_path):
    ph = read_photometry(tilted_file(tmp_path))
    assert ph.warnings == (TILT_WARNING,)
    again = read_photometry(tmp_path / "tilted.ies")
    plain = downlight(2000.0, watts=20.0)
    assert light_warnings([ph, again, plain]) == [f"{tmp_path / 'tilted.ies'}: {TILT_WARNING}"]


def _schedule(tmp_path: Path) -> Path:
    """Two luminaires in the office: the tilted high bay at 50%, a downlight at full."""
    tilted_file(tmp_path)
    write_photometry(downlight(2000.0, watts=20.0), tmp_path / "down.ldt")
    csv = tmp_path / "lums.csv"
    csv.write_text(
        "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z,dimming\n"
        "H1,3,2,2.95,tilted.ies,0,0,-1,1,0,0,0.5\n"
        "D1,9,6,2.95,down.ldt,0,0,-1,0,1,0,1\n"
    )
    return csv


def test_cli_prints_lumens_and_watts_at_the_same_dimming_and_the_warnings(
    tmp_path, capsys, monkeypatch
):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    csv = _schedule(tmp_path)
    argv = ["simulate", "office", "--resolution", "0.5", "--luminaires", str(csv)]
    assert cli.main(argv) == 0
    captured = capsys.readouterr()
    high = read_photometry(tmp_path / "tilted.ies").flux()  # 5,820 lm, 88.7 W
    low = downlight(2000.0, watts=20.0).flux()  # 2,001 lm, 20 W
    dimmed = f"{0.5 * high + low:.0f} lm, {0.5 * 88.7 + 20.0:.1f} W at the set dimming"
    rated = f"(rated {high + low:.0f} lm, {88.7 + 20.0:.1f} W)"
    assert f"2 luminaire(s): {dimmed} {rated}" in captured.out
    path = tmp_path / "tilted.ies"
    assert f"lightinv-cli: warning: {path}: {TILT_WARNING}\n" in captured.err

    assert cli.main([*argv, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert f"{path}: {TILT_WARNING}" in out["warnings"]
    h1, d1 = out["luminaires"]
    assert (h1["watts"], h1["watts_at_dimming"], h1["dimming"]) == (88.7, 44.35, 0.5)
    assert h1["lumens"] == pytest.approx(0.5 * h1["lumens_rated"])
    assert h1["warnings"] == [TILT_WARNING] and d1["warnings"] == []
    assert (d1["watts"], d1["watts_at_dimming"]) == (20.0, 20.0)


def test_cli_says_full_output_and_counts_files_without_watts(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    write_photometry(downlight(2000.0, watts=20.0), tmp_path / "down.ldt")
    no_watts = REAL.read_bytes().replace(b"1 1 88.7", b"1 1 0")
    (tmp_path / "nowatts.ies").write_bytes(no_watts)
    (tmp_path / "lums.csv").write_text(
        "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z\n"
        "D1,3,2,2.95,down.ldt,0,0,-1,1,0,0\nN1,9,6,2.95,nowatts.ies,0,0,-1,1,0,0\n"
    )
    argv = ["simulate", "office", "--resolution", "0.5", "--luminaires"]
    assert cli.main([*argv, str(tmp_path / "lums.csv")]) == 0
    text = capsys.readouterr().out
    flux = downlight(2000.0, watts=20.0).flux() + read_photometry(REAL).flux()
    assert (
        f"2 luminaire(s): {flux:.0f} lm, 20.0 W at full output; 1 with no input watts in "
        "the file, not counted in W"
    ) in text


def test_the_report_schedule_notes_the_products_warnings(tmp_path):
    path = tilted_file(tmp_path)
    arrays = [
        LuminaireArray("A1", "lum_west", str(path), (0.0, 0.0, 2.0, 4.0), rows=2),
        LuminaireArray("A2", "lum_east", str(path), (0.0, 0.0, 2.0, 4.0), dimming=0.5),
        LuminaireArray("A3", "lum_east", "Downlight 2000 lm 20 W", (0.0, 0.0, 2.0, 4.0)),
    ]
    table = luminaire_table(arrays)
    assert table.note.endswith(f" Warning: {path}: {TILT_WARNING}.")
    assert table.note.count("Warning:") == 1  # one file, listed once
    plain = luminaire_table(arrays[2:])
    assert "Warning" not in plain.note
