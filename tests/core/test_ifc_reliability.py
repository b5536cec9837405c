"""IFC import on the files of the "Reliability" issue: files cut short, geometry shapely
cannot cut, windows built from parts, coverings in a model without floor slabs. The
real files that are small enough are in tests/data/ifc (SOURCES.md); the structures of
the big ones are rebuilt here with ``ifcopenshell.api``."""

from __future__ import annotations

import gzip
from pathlib import Path

import pytest

from lightinv_core import cli
from lightinv_core.errors import ObjImportError
from lightinv_core.scene.ifc_import import load_ifc
from tests.core.test_ifc_import import ifc_room

ifcopenshell = pytest.importorskip("ifcopenshell")

DATA = Path(__file__).parent.parent / "data" / "ifc"


@pytest.fixture(scope="module")
def open_house(tmp_path_factory) -> Path:
    """IfcOpenShell's IfcOpenHouse (IFC4): 5 windows, each an IfcWindow without a body of
    its own aggregating four IfcMember frames and an IfcPlate pane."""
    path = tmp_path_factory.mktemp("ifc") / "IfcOpenHouse_IFC4.ifc"
    path.write_bytes(gzip.decompress((DATA / "IfcOpenHouse_IFC4.ifc.gz").read_bytes()))
    return path


def cut(src: Path, dst: Path, share: float, end: bool = False) -> Path:
    """The first ``share`` of ``src``; with ``end``, cut at a line end and closed with the
    STEP file's last two lines (a file whose end was pasted back on)."""
    data = src.read_bytes()[: int(src.stat().st_size * share)]
    if end:
        data = data.rsplit(b"\n", 1)[0] + b"\nENDSEC;\nEND-ISO-10303-21;\n"
    dst.write_bytes(data)
    return dst


# --- files cut short (item 4) ------------------------------------------------------------


@pytest.mark.parametrize("share", [0.5, 0.9])
def test_a_file_cut_short_is_refused_with_one_line(open_house, tmp_path, share, capsys):
    """Cut at 50% or 90% of its length, IfcOpenHouse imported with exit 0 and no message:
    a silently partial building. It is refused: a partial building has no use for lighting
    (rooms open, windows missing) and would look like a whole one."""
    path = cut(open_house, tmp_path / "cut.ifc", share)
    with pytest.raises(ObjImportError) as info:
        load_ifc(path)
    message = str(info.value)
    assert message.startswith(
        f"cut.ifc: the file is cut short (it ends after {path.stat().st_size:,} bytes with "
    )
    assert message.endswith(
        "not with END-ISO-10303-21; as every IFC file does), so it holds only part of the "
        "model; copy or export it again"
    )
    assert "\n" not in message
    assert cli.main(["scene-info", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "cut short" in err


@pytest.mark.parametrize("share", [0.5, 0.9])
def test_a_file_cut_short_with_its_end_pasted_back_is_refused(open_house, tmp_path, share):
    """The end marker is there but entities are missing: ifcopenshell logs references it
    cannot resolve, and those refuse the file."""
    path = cut(open_house, tmp_path / "pasted.ifc", share, end=True)
    with pytest.raises(
        ObjImportError,
        match=r"^pasted\.ifc: \d+ reference\(s\) to entities that are not in the file "
        r"\(#\d+ \(used by #\d+\)",
    ) as info:
        load_ifc(path)
    assert str(info.value).endswith("the file is damaged or incomplete, export it again")


def test_the_built_room_cut_short_is_refused_too(tmp_path):
    room = ifc_room(tmp_path / "room.ifc")
    for share in (0.5, 0.9):
        with pytest.raises(ObjImportError, match="cut short"):
            load_ifc(cut(room, tmp_path / "cut.ifc", share))
        with pytest.raises(ObjImportError, match="not in the file"):
            load_ifc(cut(room, tmp_path / "pasted.ifc", share, end=True))
    assert load_ifc(room, resolution=0.5).zones  # the whole file still imports
