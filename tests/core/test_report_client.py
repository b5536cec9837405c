"""The report a lighting designer hands to a client (issue #29, item 9), read back from
the PDF's text: on an imported classroom whose layout came from an optimisation run and
was loaded into the design (the window's "design on screen"), the title page names the
optimiser and its run settings and gives every criterion with its value and verdict;
the room, the luminaires' data sheet, power density and maintenance factor, each work
plane's EN 12464-1 criteria and a filled Sources table are there; the views mark many
luminaires with one numbered marker per array; no page but the last is half empty."""

from __future__ import annotations

import shutil
import subprocess
from dataclasses import replace
from pathlib import Path

import pytest

from lightinv_core.design.en12464 import preset_intention, requirement
from lightinv_core.design.model import Intention, LuminaireArray, Workplane
from lightinv_core.editing import DocumentModel
from lightinv_core.editing.project_file import obj_project
from lightinv_core.kinds import Scenario
from lightinv_core.light.arrays import resolve_product
from lightinv_core.operator.cache import get_operator
from lightinv_core.report import write_report
from lightinv_core.report.chosen import choose_solution
from lightinv_core.report.layout import (
    GAP,
    TEXT_HEIGHT,
    compose,
    drawing,
    heading,
    paragraph,
    table_block,
)
from lightinv_core.report.provenance import provenance
from lightinv_core.report.sections import Context, report_blocks
from lightinv_core.report.tables import Table, rules_table, source_table
from lightinv_core.report.views import luminaire_outlines, marker_legend, render_view
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.study import solution_light, solve
from lightinv_core.value_text import fmt, u0_text
from tests.core.test_zone_on_cut_surface import ROOM  # the 10 x 7 x 3 m classroom

pytestmark = pytest.mark.slow  # a room imported, optimised and reported

PANEL = "Panel 600 x 600 3600 lm 30 W"


def pdf_text(path: Path, page: int | None = None) -> str:
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext (Debian package poppler-utils) is not installed")
    pages = ["-f", str(page), "-l", str(page)] if page else []
    out = subprocess.run(
        ["pdftotext", "-layout", *pages, str(path), "-"],
        capture_output=True,
        text=True,
        check=True,
    )
    return out.stdout


def line_with(text: str, *words: str) -> str:
    """The first line of ``text`` holding every one of ``words`` ("" if none)."""
    return next((ln for ln in text.splitlines() if all(w in ln for w in words)), "")


@pytest.fixture(scope="module")
def classroom(tmp_path_factory):
    """The classroom as the window has it after a run whose best was loaded: (document,
    the design on screen as a solution, the run's best)."""
    folder = tmp_path_factory.mktemp("classroom")
    (folder / "classroom.obj").write_text(ROOM)
    doc = DocumentModel()
    doc.set_project(obj_project(folder / "classroom.obj", resolution=0.5))
    doc.set_user_zones((ZoneEdit("lum", "luminaire", "ceiling", (0.5, 0.5, 6.5, 9.5)),))
    array = LuminaireArray(
        "A1", "lum", PANEL, (0.0, 0.0, 6.0, 9.0), rows=4, columns=3, free=("rows", "columns")
    )
    doc.set_arrays((array,))
    doc.set_workplanes((Workplane("desks", 0.75, 0.5, "floor"),))
    doc.add_intention(preset_intention("classroom", "desks"))
    # Out of reach, so that the status shows a FAIL; weight 0: not optimised.
    doc.add_intention(Intention("bright walls", group="walls", min=5000.0, weight=0.0))
    doc.set_goal("min_installed_power", True)
    doc.set_primary_goal("min_installed_power")
    for g in doc.design.goals:
        if g.kind != "min_installed_power":
            doc.set_goal(g.kind, False)
    doc.set_operator(get_operator(doc.patches, doc.project.operator).operator)
    settings = replace(doc.project.optimizer, method="vns", max_evals=150, seed=3)
    project = replace(doc.project, optimizer=settings)
    result = solve(project, doc.prepared())
    doc.add_run(
        (result.best,),
        None,
        settings=settings,
        status="infeasible",
        evaluations=result.evaluations,
        seconds=result.seconds,
    )
    doc.apply_solution(result.best)
    return doc, doc.design_solution(), result.best


@pytest.fixture(scope="module")
def report(classroom, tmp_path_factory):
    doc, on_screen, _ = classroom
    path = tmp_path_factory.mktemp("report") / "classroom.pdf"
    info = write_report(
        doc.project, doc.prepared(), path, solution=on_screen, label="the design on screen"
    )
    return info, pdf_text(path), pdf_text(path, 1)


def test_a_runs_layout_on_screen_names_its_optimiser_and_run_settings(classroom, report):
    doc, on_screen, best = classroom
    info, text, title = report
    assert not on_screen.info.method  # judged afresh: the solution itself does not say
    found = provenance(doc.project, on_screen)
    assert found is not None and found.run.number == 1 and found.solution is best
    assert info.optimiser == "vns"
    assert "none: the layout as designed" not in title
    assert line_with(title, "optimiser", "VNS")
    assert line_with(title, "run", "run 1, ended")
    assert line_with(title, "evaluation limit", "150")
    assert line_with(title, "seed of this layout", "3")
    assert line_with(title, "this layout's search", f"{best.info.evaluations:,} evaluations")
    assert "Convergence" in text  # the run's history, though the solution on screen has none


def test_a_layout_edited_after_the_run_is_reported_as_designed(classroom, tmp_path):
    doc, on_screen, _ = classroom
    moved = replace(on_screen.arrays[0], rect=(0.5, 0.0, 6.0, 9.0))
    edited = replace(on_screen, arrays=(moved,))
    assert provenance(doc.project, edited) is None
    info = write_report(doc.project, doc.prepared(), tmp_path / "r.pdf", solution=edited)
    assert info.optimiser == ""
    title = pdf_text(info.path, 1)
    assert line_with(title, "optimiser", "none: the layout as designed")


def test_title_page_gives_every_criterion_with_its_value_and_verdict(classroom, report):
    doc, sol, _ = classroom
    _, _, title = report
    assert "Lighting design report" in title and doc.project.name in title
    lay = solution_light(doc.prepared(), doc.design, sol).daylight
    checks = {(it.name, c.bound): c for it in doc.design.intentions for c in lay.checks(it)}
    em = checks[("classroom", "average")]
    u0 = checks[("classroom", "uniformity")]
    walls = checks[("bright walls", "min")]
    assert line_with(title, "work plane desks", "Em (night)", "≥ 300 lux", fmt(em.value[0]))
    assert line_with(title, "work plane desks", "U0 (night)", "≥ 0.6", u0_text(u0.value[0]))
    row = line_with(title, "bright walls", "min illuminance", "≥ 5,000 lux")
    assert row.rstrip().endswith("FAIL") and fmt(walls.value[0]) in row
    for check, words in ((em, "Em (night)"), (u0, "U0 (night)")):
        verdict = "pass" if check.met[0] else "FAIL"
        assert line_with(title, words).rstrip().endswith(verdict)
    assert "criteria are not met" in title
    rules = rules_table(sol, doc.design, doc.patches)
    n = 0 if rules is None else len(rules.rows)
    assert bool(line_with(title, "geometric rules", f"{n} of {n}")) == (rules is not None)


def test_room_surfaces_luminaire_data_sheet_and_maintenance_factor(classroom, report):
    doc, sol, _ = classroom
    info, text, _ = report
    assert {"room", "luminaires", "workplanes", "views", "sources"} <= set(info.sections)
    assert line_with(text, "extent (x × y × z)", "10.00 × 7.00 × 3.00 m")
    assert line_with(text, "floor area", "70.0 m²")
    assert line_with(text, "volume", "210.0 m³")
    for group, area in (("floor", "70.0"), ("walls", "102.0"), ("ceiling", "70.0")):
        assert line_with(text, group, area, "0.50"), group
    # The product's data sheet, from its photometry, and the layout's power.
    p = resolve_product(PANEL)
    count = sum(a.count for a in sol.arrays)
    assert f"Data sheet: {PANEL}" in text
    assert line_with(text, "manufacturer", p.photometry.manufacturer)
    assert line_with(text, "luminous flux", f"{p.lumens:,.0f} lm")
    assert line_with(text, "input power", f"{p.watts:g} W")
    assert line_with(text, "luminous efficacy", f"{p.lumens / p.watts:,.1f} lm/W")
    assert line_with(text, "in this design", f"{count} in A1")
    watts = count * p.watts
    assert line_with(text, "installed power (full output)", f"{fmt(watts)} W")
    assert line_with(text, "power density", f"{fmt(watts / 70.0, 3)} W/m²")
    lay = solution_light(doc.prepared(), doc.design, sol).daylight
    night = float(lay.points.lux(Scenario.NIGHT, lay.grids.spans["desks"]).mean())
    dimmed = sum(a.count * p.watts * a.dimming for a in sol.arrays)
    per_100 = 100 * dimmed / 70.0 / night
    assert line_with(text, "power density per 100 lux", f"{fmt(per_100, 3)} W/m²/100 lx")
    squashed = " ".join(text.split())
    assert "Maintenance factor MF = 0.8" in squashed and "CIE 97:2005" in squashed


def test_work_plane_criteria_of_en_12464(classroom, report):
    _, text, _ = report
    r = requirement("classroom")
    assert line_with(text, "desks", "classroom", "Em (night)", f"≥ {r.em:.0f} lux")
    assert line_with(text, "desks", "classroom", "U0 (night)", f"≥ {r.u0:g}")
    assert line_with(text, "desks", "classroom", "UGR_L", "not calculated")
    # The catalogue panel's EULUMDAT file states no Ra: no verdict, "not stated".
    assert line_with(text, "desks", "classroom", "Ra", f"≥ {r.ra}", "not stated")
    squashed = " ".join(text.split())
    assert f"EN 12464-1:2011, classrooms, tutorial rooms (ref. {r.reference})" in squashed


def test_sources_table_lists_the_arrays(classroom, report):
    doc, sol, _ = classroom
    _, text, _ = report
    table = source_table(sol, doc.design)
    assert table.rows and table.rows[0][:3] == ("A1", "luminaire array", "lum")
    after = text[text.index("Sources\n") :]
    a = sol.arrays[0]
    assert line_with(after, "A1", "luminaire array", "lum", f"{a.rows} x {a.columns}")


def test_many_luminaires_get_one_numbered_marker_and_a_legend(classroom):
    doc, _, _ = classroom
    big = LuminaireArray("A1", "lum", PANEL, (0.0, 0.0, 6.0, 9.0), rows=10, columns=8)
    down = LuminaireArray("B1", "lum", PANEL, (0.5, 0.5, 2.0, 2.0), rows=1, columns=1)
    outlines = luminaire_outlines(doc.patches, (big, down))
    assert len(outlines) == 81
    values = doc.patches.centroid[:, 2]
    fig = render_view(doc.patches, values, "top", outlines=outlines, numbered=True)
    ax = fig.axes[0]
    assert sorted(t.get_text() for t in ax.texts) == ["1", "2"]  # not 81 labels
    legend = marker_legend(outlines)
    assert [r[:2] for r in legend.rows] == [("1", "A1"), ("2", "B1")]
    assert [r[3] for r in legend.rows] == ["80", "1"]


def _used(page) -> float:
    return sum(b.height for b in page) + GAP * (len(page) - 1)


def test_no_page_but_the_last_is_half_empty(classroom):
    doc, sol, _ = classroom
    project = doc.project
    ctx = Context(
        project,
        doc.prepared(),
        choose_solution(project, sol),
        solution_light(doc.prepared(), project.design, sol),
        provenance(project, sol),
    )
    pages = compose(report_blocks(ctx))
    assert len(pages) >= 4
    for page in pages[:-1]:
        assert _used(page) >= 0.5 * TEXT_HEIGHT, [b.section for b in page]
        assert _used(page) <= TEXT_HEIGHT + 1e-9


def test_flow_keeps_headings_with_their_text_and_shrinks_drawings_to_fill():
    rows = tuple((f"r{i}", "x") for i in range(10))
    small = Table("Small", ("a", "b"), rows)
    blocks = [
        drawing(7.0, lambda sf: None, "one"),
        heading("Next section", "two"),
        paragraph("An introduction kept with what follows.", "two", keep_with_next=True),
        drawing(5.0, lambda sf: None, "two"),
        table_block(small, "three"),
    ]
    pages = compose(blocks)
    # The heading does not fit with its paragraph and a drawing of at least 55%: all go
    # to page 2 together; the table follows them there.
    assert [[b.section for b in p] for p in pages] == [["one"], ["two", "two", "two", "three"]]
    # With room for 55% of it, a drawing shrinks to end the page instead.
    blocks = [drawing(6.5, lambda sf: None, "one"), drawing(5.0, lambda sf: None, "two")]
    pages = compose(blocks)
    assert len(pages) == 1
    assert pages[0][1].height == pytest.approx(TEXT_HEIGHT - 6.5 - GAP)
    assert pages[0][1].height >= 0.55 * 5.0
    # A table splits at a page end: its first rows fill the page after the drawing.
    long = Table("Long", ("a", "b"), tuple((f"r{i}", "x") for i in range(60)))
    pages = compose([drawing(6.0, lambda sf: None, "one"), table_block(long, "t")])
    assert [len(p) for p in pages] == [2, 1]
    assert _used(pages[0]) > 0.9 * TEXT_HEIGHT


def test_a_layout_is_matched_with_skylights_and_arrays():
    from lightinv_core.design.model import Design, Goal, Source
    from lightinv_core.design.solution import Solution
    from lightinv_core.project import OptimizerSettings, Project, SceneSpec
    from lightinv_core.project.results import RunRecord
    from lightinv_core.report.provenance import same_layout

    sky = Source("S1", "skylight", "skylight", (1.0, 0.5, 3.0, 1.5), filter=0.2)
    lum = Source("L1", "lum_west", "luminaire", (0.5, 1.5, 1.5, 4.5), flux=8000.0)
    array = LuminaireArray("A1", "lum", PANEL, (0.0, 0.0, 6.0, 9.0), rows=4, columns=3)
    found = Solution((sky, lum), {}, 0.0, info={"method": "vns", "seed": 4}, arrays=(array,))
    on_screen = Solution((lum, sky), {}, 0.0, arrays=(array,))  # judged afresh: no info
    assert same_layout(found, on_screen)
    assert not same_layout(found, replace(on_screen, sources=(lum, replace(sky, filter=0.3))))
    assert not same_layout(found, replace(on_screen, arrays=(replace(array, rows=5),)))
    assert not same_layout(found, replace(on_screen, arrays=(replace(array, dimming=0.5),)))
    design = Design((sky, lum), (Goal("min_electric_power"),))
    run = RunRecord(
        2, "vns", "2026-11-26T10:00:00", OptimizerSettings(max_evals=77), (), solutions=(found,)
    )
    project = Project("p", SceneSpec(builtin="office"), design, runs=(run,))
    got = provenance(project, on_screen)
    assert got is not None and got.run is run and got.solution is found
    assert got.settings.max_evals == 77
    moved = replace(on_screen, sources=(replace(lum, rect=(0.6, 1.5, 1.5, 4.5)), sky))
    assert provenance(project, moved) is None
