"""PDF reports: pages, their text, PNG pages, cancel, and the views' camera and culling."""

from __future__ import annotations

import shutil
import subprocess
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure
from matplotlib.image import imread

from lightinv_core.design.model import CORNERS, Design, Goal, Intention, Rule, Source
from lightinv_core.design.solution import ParetoFront, Solution
from lightinv_core.errors import CancelledError, LightInvError
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.quality import front_quality, front_scales
from lightinv_core.optimize.search import random_start
from lightinv_core.project import OperatorSettings, OptimizerSettings, Project, SceneSpec
from lightinv_core.report import (
    intention_table,
    render_view,
    solution_field,
    source_outlines,
    source_table,
    write_report,
)
from lightinv_core.report.figures import _levels, convergence_figure
from lightinv_core.report.layout import compose, draw_page, table_block
from lightinv_core.report.tables import Table, fmt
from lightinv_core.report.views import visible_patches, zone_frame
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import prepare, solve

pytestmark = pytest.mark.slow  # PDF reports rendered and read back

SCENE = SceneSpec(builtin="office", resolution=0.6)
FAST = OperatorSettings(rank=120, rays=256)
SINGLE_SECTIONS = [
    "title",
    "room",
    "luminaires",
    "views",
    "sources",
    "intentions",
    "convergence",
]


def office_design(goals: tuple[Goal, ...] | None = None) -> Design:
    lum = Source(
        "L1",
        "lum_west",
        "luminaire",
        (0.5, 1.5, 1.5, 4.5),
        free=(*CORNERS, "flux"),
        flux=8000.0,
        flux_range=(0.0, 30000.0),
        efficacy=120.0,
    )
    mirror = replace(lum, name="L2", zone="lum_east", free=())
    sky = Source("S1", "skylight", "skylight", (1.0, 0.5, 3.0, 1.5), filter=0.2)
    intentions = (
        Intention("desks", group="desks", average=300.0, uniformity=0.3),
        # Met by any layout, and impossible with weight 0 (listed, not optimised):
        Intention("no glare", group="floor", max=1e6),
        Intention("bright walls", group="walls", min=1e5, weight=0.0),
    )
    rules = (Rule("mirror", ("L2", "L1"), axis="u"), Rule("aspect", ("L1",), max=4.0))
    goals = goals or (Goal("min_electric_power"),)
    return Design((lum, mirror, sky), goals, rules, intentions)


@pytest.fixture(scope="module")
def single():
    """An office project solved briefly (VNS, 600 evaluations), with its history."""
    project = Project("Report test office", SCENE, office_design(), FAST, OptimizerSettings())
    prepared = prepare(project)
    best = solve(project, prepared, max_evals=600).best
    assert best.info.history
    return replace(project, solutions=(best,)), prepared


@pytest.fixture(scope="module")
def multi(single):
    """A two-goal office project whose results are a small hand-made Pareto front."""
    _, prepared = single
    design = office_design((Goal("min_electric_power"), Goal("max_light_power")))
    problem = DesignProblem(design, prepared.light)
    sols = [
        problem.solution(random_start(problem, np.random.default_rng(s)), {"seed": s})
        for s in range(3)
    ]
    front = ParetoFront(
        ("min_electric_power", "max_light_power"), tuple(sols[:2]), "test", tuple(sols)
    )
    project = Project("Report test MOP", SCENE, design, FAST, pareto=front)
    return project, prepared


def pdf_text(path: Path) -> str:
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext (Debian package poppler-utils) is not installed")
    out = subprocess.run(
        ["pdftotext", "-layout", str(path), "-"], capture_output=True, text=True, check=True
    )
    return out.stdout


def pdf_page_count(path: Path) -> int:
    """Pages of a matplotlib PDF: its page objects are written as "/Type /Page " (the
    page tree is "/Type /Pages")."""
    return path.read_bytes().count(b"/Type /Page ")


def squash(text: str) -> str:
    return " ".join(text.split())


@pytest.fixture(scope="module")
def single_report(single, tmp_path_factory):
    project, prepared = single
    out = tmp_path_factory.mktemp("report")
    fractions = []
    info = write_report(
        project, prepared, out / "r.pdf", png_dir=out / "png", progress=fractions.append
    )
    return info, fractions


def test_single_objective_report_pages_and_png_files(single_report):
    info, fractions = single_report
    assert list(info.sections) == SINGLE_SECTIONS
    assert info.pages[0] == "title" and set(info.pages) <= {
        f"{s}{k}" for s in SINGLE_SECTIONS for k in ("", "-2", "-3")
    }
    assert info.solution == "saved solution 1 of 1"
    assert pdf_page_count(info.path) == len(info.pages)
    assert len(info.pages) < len(SINGLE_SECTIONS)  # flow layout: sections share pages
    assert fractions[-1] == 1.0 and fractions == sorted(fractions)
    assert [p.name for p in info.png_files] == [
        f"{i + 1:02d}-{n}.png" for i, n in enumerate(info.pages)
    ]
    for png in info.png_files:  # each a real picture: not blank, not all white
        img = imread(png)[..., :3]
        assert img.std() > 0.02 and img.min() < 0.9, png.name


def lines_with(text: str, *words: str) -> list[str]:
    """The lines of ``pdftotext -layout`` output holding every one of ``words``."""
    return [line for line in text.splitlines() if all(w in line for w in words)]


def test_single_objective_report_text(single, single_report):
    project, prepared = single
    info, _ = single_report
    raw = pdf_text(info.path)
    text = squash(raw)
    sol = project.solutions[0]
    assert project.name in text
    failed = len(sol.violations)
    assert ("Every criterion is met" if sol.feasible else "criteria are not met") in text
    assert failed > 0  # the "bright walls" intention cannot be met
    watts = fmt(sol.objectives["min_electric_power"])
    assert lines_with(raw, "Electric power (optimised goal)", f"{watts} W")
    # Every source row's name, corners (as the table formats them), flux and power.
    for row in source_table(sol, project.design).rows:
        for cell in (row[0], row[3], row[6], row[8]):
            assert all(part in text for part in cell.split()), cell
    # Every bound of every intention with its verdict, on one line.
    table = intention_table(sol, project.design, solution_field(project, prepared, sol))
    results = {r[0] + " " + r[2]: r[-1] for r in table.rows}
    assert results["no glare max ≤ 1,000,000 lux"] == "pass"
    assert results["bright walls min ≥ 100,000 lux"].startswith("FAIL")
    for row in table.rows:
        assert lines_with(raw, row[0], row[2].split()[0], row[-1].split()[0]), row
    meta = subprocess.run(["pdfinfo", str(info.path)], capture_output=True, text=True).stdout
    assert "Creator: LightInv" in squash(meta) and f"LightInv report: {project.name}" in meta


def test_multi_objective_report_marks_the_pareto_front(multi, tmp_path):
    project, prepared = multi
    info = write_report(project, prepared, tmp_path / "mop.pdf")
    assert list(info.sections) == [*SINGLE_SECTIONS[:-1], "pareto"]
    assert info.solution == "Pareto front solution 1 of 2" and info.png_files == ()
    assert pdf_page_count(info.path) == len(info.pages)
    text = squash(pdf_text(info.path))
    assert "Pareto front (test): 2 non-dominated of 3 solutions" in text
    q = front_quality(project.pareto.solutions, front_scales(project.design, prepared.light))
    assert f"hypervolume {q.hypervolume:.4f}, spacing {q.spacing:.4f} (normalised)" in text
    sol = project.pareto.solutions[0]
    assert "Electric power" in text and "Reflected light power" in text
    for row in source_table(sol, project.design).rows:
        assert row[3] in text
    # Another front solution can be chosen explicitly.
    other = write_report(project, prepared, tmp_path / "b.pdf", project.pareto.solutions[1])
    assert other.solution == "Pareto front solution 2 of 2"


def test_report_field_agrees_with_the_solution(single):
    project, prepared = single
    sol = project.solutions[0]
    H = solution_field(project, prepared, sol).illuminance
    walls = prepared.patches.group_index("walls")
    v = next(v for v in sol.violations if v.name == "bright walls")
    assert H[walls].min() == pytest.approx(v.value, rel=1e-4)
    # Sources are taken by name: another order gives the same light.
    shuffled = replace(sol, sources=tuple(reversed(sol.sources)))
    again = solution_field(project, prepared, shuffled).illuminance
    np.testing.assert_allclose(again, H, rtol=1e-5)


def test_cancel_and_failure_leave_no_file(single, tmp_path):
    project, prepared = single
    calls = iter(range(100))
    old = tmp_path / "old.pdf"
    old.write_bytes(b"previous report")
    with pytest.raises(CancelledError):
        write_report(
            project, prepared, old, png_dir=tmp_path / "png", cancel=lambda: next(calls) >= 3
        )
    assert old.read_bytes() == b"previous report"
    assert sorted(p.name for p in tmp_path.rglob("*") if p.is_file()) == ["old.pdf"]


def test_a_project_without_results_is_refused(single, tmp_path):
    project, prepared = single
    with pytest.raises(LightInvError, match="lightinv-cli solve"):
        write_report(replace(project, solutions=()), prepared, tmp_path / "x.pdf")
    assert not (tmp_path / "x.pdf").exists()


def test_views_cull_faces_turned_away_and_paint_far_to_near(single):
    _, prepared = single
    p = prepared.patches
    groups = np.array(p.group_names)[p.group_id]
    top = visible_patches(p, "top")
    assert set(groups[top]) == {"floor", "desks"}  # no ceiling, roof or (edge-on) walls
    front = visible_patches(p, "front")
    assert np.all(p.normal[front, 1] < 0)  # the north wall, not the near south wall
    assert np.all(np.diff(p.centroid[front, 1]) <= 1e-9)  # far (large y) first
    iso = visible_patches(p, "iso")
    assert "floor" in set(groups[iso]) and "ceiling" not in set(groups[iso])


def test_source_outlines_follow_the_zone_axes(single):
    _, prepared = single
    p = prepared.patches
    _, u, v, (w, h) = zone_frame(p, "lum_west")
    assert np.linalg.norm(u) == pytest.approx(1.0) and abs(u @ v) < 1e-9
    idx = p.zone_index("lum_west")
    corners = np.concatenate([p.origin[idx], p.origin[idx] + p.edge1[idx] + p.edge2[idx]])
    whole = Source("all", "lum_west", "luminaire", (0.0, 0.0, w, h), flux=1.0)
    [zone, src] = source_outlines(p, [whole])
    assert zone.kind == "zone" and src.kind == "source"
    np.testing.assert_allclose(src.points.min(axis=0), corners.min(axis=0), atol=1e-9)
    np.testing.assert_allclose(src.points.max(axis=0), corners.max(axis=0), atol=1e-9)
    np.testing.assert_allclose(src.points, zone.points)


def test_render_view_draws_25k_patches(tmp_path):
    patches = mesh_patches(builtin_scene("patio"))
    assert patches.n > 20_000
    values = patches.centroid[:, 2] * 50.0
    fig = render_view(patches, values, "iso")  # its time: bench/report.py, not a test
    fig.savefig(tmp_path / "iso.png", dpi=100)
    assert isinstance(fig, Figure)
    img = imread(tmp_path / "iso.png")[..., :3]
    assert img.std() > 0.05
    with pytest.raises(LightInvError, match="unknown view"):
        render_view(patches, values, "side")


def test_long_tables_continue_on_the_next_page():
    rows = tuple((f"s{i}", f"{i:.2f}") for i in range(120))
    long = Table("Sources", ("source", "value"), rows)
    short = Table("Rules", ("rule", "result"), (("area s1", "pass"),), ("pass",))
    pages = compose([table_block(long, "sources"), table_block(short, "rules")])
    assert len(pages) == 3  # 120 rows over two and a half pages, the short table after
    figs = [draw_page(page, k + 1, len(pages), "footer").figure for k, page in enumerate(pages)]
    texts = [[t.get_text() for sf in fig.subfigs for t in sf.texts] for fig in figs]
    assert texts[0][0] == "Sources" and texts[1][0] == "Sources (continued)"
    assert texts[2][0] == "Sources (continued)" and "Rules" in texts[2]
    shown = [t for page in texts for t in page if t.startswith("s") and t[1:].isdigit()]
    assert shown == [f"s{i}" for i in range(120)]  # every row once, in order
    assert [t.get_text() for t in figs[1].texts] == ["footer", "page 2 of 3"]


def test_convergence_of_a_multilevel_history():
    rows = [[1, 0.5, 2.0, 10.0], [40, 0.2, 0.0, 30.0], [1, 3.0, 5.0, 28.0], [25, 0.1, 0.0, 29.0]]
    sol = Solution((), {"max_light_power": 29.0}, 0.0, info={"history": rows})
    fig = convergence_figure(sol, "max_light_power")
    ax1, ax2 = fig.axes
    assert ax2.get_yscale() == "symlog" and "light power" in ax1.get_ylabel()
    # Stage 2 starts after stage 1's last improvement, or exactly with the stage counts.
    assert _levels(np.array(rows))[1] == [40.0]
    assert _levels(np.array(rows), [300, 100])[1] == [300.0]
    texts = [t.get_text() for t in ax2.texts]
    assert texts == ["feasible from 65 evaluations"]
    assert convergence_figure(replace(sol, info={}), "max_light_power") is None
