"""The report names each work plane's EN 12464-1 edition with its preset's values and
checks Ra against the Ra the chosen products state (issue #31 item 3), read back from
the PDF's text; the products' stated Ra is read from real EULUMDAT files."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

from lightinv_core.design.en12464 import EDITION_2021, preset_intention, ra_warnings
from lightinv_core.editing import DocumentModel
from lightinv_core.luminaires.rendering import product_ra, ra_from_text, stated_ra
from lightinv_core.operator.cache import get_operator
from lightinv_core.project import project_from_dict
from lightinv_core.report import write_report
from lightinv_core.report.criteria import workplane_criteria
from tests.core.test_report_client import line_with, pdf_text

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "photometry"
LDT = sorted(DATA.glob("*.ldt"))


@pytest.mark.parametrize("path", LDT, ids=[p.name for p in LDT])
def test_the_stated_ra_of_real_eulumdat_files(path):
    # Independently of line 31, the lamp type (line 28) says "CRI >= 90".
    lines = path.read_bytes().decode("latin-1").splitlines()
    said = lines[27].split("CRI >=")[1].strip()
    assert stated_ra(path) == float(said) == 90.0
    assert product_ra(str(path)) == 90.0


def test_what_a_product_states_and_what_it_does_not():
    # The built-in catalogue's files leave the field empty: not stated.
    assert product_ra("Panel 600 x 600 3600 lm 30 W") is None
    assert product_ra(str(DATA / "rab-round-4.ies")) is None  # an IES without CRI
    assert product_ra("no such product") is None
    assert [ra_from_text(t) for t in ("80", "Ra>=80", "1A", "2B", "", "4000K")] == [
        80.0,
        80.0,
        90.0,
        60.0,
        None,
        None,
    ]


@pytest.fixture(scope="module")
def office():
    """The office of office-arrays.json, its work plane under EN 12464-1:2021 asking
    the office preset; west array a LEDVANCE panel (Ra 90), east the catalogue's
    batwing (Ra not stated). Coarse mesh: this is about words, not light."""
    data = json.loads((ROOT / "resources" / "projects" / "office-arrays.json").read_text())
    data["scene"]["resolution"] = 1.0
    data["workplanes"][0]["edition"] = EDITION_2021
    data["intentions"] = []
    data["arrays"][0]["product"] = str(DATA / "ledvance-panel-600.ldt")
    data["arrays"][0]["watts"] = 40.0
    for a in data["arrays"]:  # fixed layouts: no placements to precompute
        a["free"] = []
    project = project_from_dict(data, ROOT / "resources" / "projects")
    it = preset_intention("office", "wp", edition=EDITION_2021)
    design = dataclasses.replace(project.design, intentions=(it,))
    doc = DocumentModel()
    doc.set_project(dataclasses.replace(project, design=design))
    doc.set_operator(get_operator(doc.patches, doc.project.operator).operator)
    return doc, doc.design_solution()


def test_the_criteria_name_the_edition_and_check_ra(office):
    doc, sol = office
    table = workplane_criteria(doc.design, sol, None)
    rows = {r[2]: r for r in table.rows}
    assert rows["Em (night)"][0] == "wp (EN 12464-1:2021)"
    assert rows["Em (night)"][3] == "≥ 500 lux"
    assert rows["UGR_L"][3] == "≤ 19"
    # One product states no Ra: the verdict is open, "not stated".
    assert rows["Ra"][3:] == ("≥ 80", "not stated", "—")
    assert "EN 12464-1:2021, writing, typing, reading, data processing (ref. 34.2)" in table.note
    assert "Em 500 lux (modified 1000), U0 0.60, UGR_L 19, Ra 80" in table.note
    assert ra_warnings(doc.design) == [
        "Linear batwing 4000 lm 32 W states no Ra: Writing, typing, reading, data "
        "processing asks Ra ≥ 80"
    ]
    # Both arrays the LEDVANCE panel: Ra 90 >= 80 passes.
    panel = str(DATA / "ledvance-panel-600.ldt")
    arrays = tuple(dataclasses.replace(a, product=panel, watts=40.0) for a in doc.design.arrays)
    both = dataclasses.replace(doc.design, arrays=arrays)
    rows = {r[2]: r for r in workplane_criteria(both, sol, None).rows}
    assert rows["Ra"][3:] == ("≥ 80", "Ra 90", "pass")
    assert ra_warnings(both) == []


@pytest.mark.slow
def test_the_pdf_names_the_edition(office, tmp_path):
    doc, sol = office
    path = tmp_path / "office.pdf"
    write_report(doc.project, doc.prepared(), path, solution=sol)
    text = pdf_text(path)
    assert line_with(text, "wp (EN 12464-1:2021)", "office", "Em (night)", "≥ 500 lux")
    assert line_with(text, "wp (EN 12464-1:2021)", "office", "Ra", "≥ 80", "not stated")
    squashed = " ".join(text.split())
    assert "EN 12464-1:2021, writing, typing, reading, data processing (ref. 34.2)" in squashed
    u0 = line_with(text, "wp (EN 12464-1:2021)", "office", "U0 (night)")
    assert u0 and len(u0.split()[-2].split(".")[-1]) == 3, u0  # achieved, three decimals
