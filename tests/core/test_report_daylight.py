"""The report's daylight and energy section, intentions judged in their scenarios, and a
Pareto front of climate goals.

References: ``layout_daylight`` of the reported layout (DF, DA300, sDA, energy, LENI)
and, for the UDI bands, ``climate.metrics.daylight_metrics`` on the hourly daylight at
the grid points (coefficients times the weather year's exterior lux, hour by hour).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from matplotlib.image import imread

from lightinv_core.climate.metrics import daylight_metrics
from lightinv_core.design.model import Design, Goal, Intention, Workplane
from lightinv_core.design.solution import ParetoFront
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.quality import front_quality, front_scales
from lightinv_core.project import OperatorSettings, Project, SceneSpec
from lightinv_core.report import intention_table, pareto_figure, solution_field, write_report
from lightinv_core.report.daylight import (
    daylight_section,
    df_figures,
    energy_figure,
    pct,
)
from lightinv_core.report.tables import fmt, objective_text
from lightinv_core.study import prepare
from tests.core.test_report import pdf_page_count, pdf_text, squash
from tests.core.test_scenarios import DAYLIGHT, LUM, SKY

pytestmark = pytest.mark.slow  # PDF reports rendered and read back

SCENE = SceneSpec(builtin="office", resolution=0.5)
FAST = OperatorSettings(rays=256)
INTENTIONS = (
    Intention("desks", group="desks", average=100.0),
    Intention("night", grid="wp", average=150.0, scenario="night"),
    Intention("df", grid="wp", quantity="df", average=1.0),
    Intention("sda", grid="wp", quantity="sda", average=0.99),
)
CLIMATE = ("min_annual_energy", "min_glazing_area")
SECTION_PAGES = ["daylight", "energy", "df-plan", "da-plan"]


def _design(sources=(SKY, LUM), intentions=INTENTIONS, daylight=DAYLIGHT) -> Design:
    return Design(
        sources=sources,
        goals=tuple(Goal(g) for g in CLIMATE),
        intentions=intentions,
        workplanes=(Workplane("wp"),),
        daylight=daylight,
    )


def _project(design: Design, name: str, prepared=None):
    """A project holding the design's initial layout as its solution."""
    project = Project(name, SCENE, design, FAST)
    prepared = prepared or prepare(project)
    problem = DesignProblem(design, prepared.light)
    sol = problem.solution(problem.vars.initial())
    return replace(project, solutions=(sol,)), prepared


@pytest.fixture(scope="module")
def daylit(tmp_path_factory):
    """The office with a roof light and a luminaire, a small climate front, reported."""
    project, prepared = _project(_design(), "Daylight report office")
    problem = DesignProblem(project.design, prepared.light)
    x = problem.vars.initial()
    sols = []
    for corners in ([1.0, 0.5, 3.0, 1.5], [0.5, 0.25, 3.5, 1.75], [1.5, 0.75, 2.5, 1.25]):
        y = x.copy()
        y[:4] = corners
        sols.append(problem.solution(y))
    project = replace(project, pareto=ParetoFront(CLIMATE, tuple(sols), "test", tuple(sols)))
    out = tmp_path_factory.mktemp("daylight-report")
    info = write_report(project, prepared, out / "r.pdf", png_dir=out / "png")
    return project, prepared, info


def test_section_numbers_are_the_layouts(daylit):
    project, prepared, info = daylit
    sol = project.solutions[0]
    assert info.sections[-5:] == (*SECTION_PAGES, "pareto")
    assert pdf_page_count(info.path) == len(info.pages)
    lay = layout_daylight(prepared.light, project.design, sol.sources, sol.arrays)
    span = lay.grids.spans["wp"]
    df = 100 * lay.points.overcast_daylight(span)[:, 0]
    da = lay.points.da(span)[:, 0]
    energy = lay.energy()
    year = lay.points.year()
    section = daylight_section(lay, [SKY])
    [plane] = section.planes
    assert plane.df_mean == pytest.approx(df.mean(), rel=1e-12)
    assert plane.df_median == pytest.approx(np.median(df), rel=1e-12)
    assert plane.df_min == pytest.approx(df.min(), rel=1e-12)
    assert plane.da_mean == pytest.approx(da.mean(), rel=1e-12)
    assert plane.sda == pytest.approx((da >= 0.5).mean())
    assert section.energy == energy and section.hours == year.hours
    assert 0 < plane.sda < 1 and 0 < energy.energy_kwh < energy.full_kwh  # not trivial
    # UDI bands against the reference metrics on the hourly daylight, hour by hour.
    hourly = lay.points.coefficients(span)[:, 0, :] @ year.exterior
    ref = daylight_metrics(hourly)
    np.testing.assert_allclose(plane.udi, ref.udi, atol=1.5 / year.hours)
    assert plane.sda == pytest.approx(ref.sda, abs=1.5 / len(da))

    text = squash(pdf_text(info.path))
    assert f"weather site {year.site}" in text and f"occupied hours a year {year.hours:,}" in text
    assert "weather data TMY3, 8,760 hours, hour ending, local standard time" in text
    assert "daylight illuminance hundreds of lux in the file, multiplied by 100" in text
    row = [fmt(df.mean(), 3), fmt(np.median(df), 3), fmt(df.min(), 3)]
    row += [pct(da.mean()), pct((da >= 0.5).mean()), *(pct(u) for u in plane.udi_mean)]
    assert f"wp {len(df)} " + " ".join(row) in text
    assert f"annual energy with dimming {fmt(energy.energy_kwh)} kWh" in text
    assert f"annual energy at full output {fmt(energy.full_kwh)} kWh" in text
    saved = pct(1 - energy.energy_kwh / energy.full_kwh)
    assert f"savings by dimming {saved}%" in text
    assert f"LENI {fmt(energy.leni)} kWh/m² a (over {fmt(96.0)} m² of floor)" in text
    assert f"mean {fmt(df.mean(), 3)}%" in text  # the DF plan's title
    goal, value = objective_text("min_annual_energy", sol.objectives["min_annual_energy"]).split(
        ": "
    )
    lines = pdf_text(info.path).splitlines()
    assert any(goal in line and value in line for line in lines)  # the title page's row


def test_monthly_chart_and_plans_are_drawn(daylit):
    project, prepared, info = daylit
    sol = project.solutions[0]
    lay = layout_daylight(prepared.light, project.design, sol.sources, sol.arrays)
    section = daylight_section(lay, [SKY])
    fig = energy_figure(section)
    heights = [b.get_height() for b in fig.axes[-1].patches]
    np.testing.assert_allclose(heights, section.energy.monthly_kwh)
    [plan] = df_figures(section)
    shown = plan.axes[0].collections[0].get_array()
    np.testing.assert_allclose(shown, section.planes[0].df)
    assert len(info.png_files) == len(info.pages)
    for png in info.png_files:
        img = imread(png)[..., :3]
        assert img.std() > 0.02 and img.min() < 0.9, png.name


def test_intentions_are_judged_in_their_scenarios(daylit):
    project, prepared, info = daylit
    sol = project.solutions[0]
    design = project.design
    lay = layout_daylight(prepared.light, design, sol.sources, sol.arrays)
    table = intention_table(sol, design, solution_field(project, prepared, sol), lay)
    rows = {r[0]: r for r in table.rows}
    assert [rows[n][3] for n in ("desks", "night", "df", "sda")] == [
        "design",
        "night",
        "overcast, DF",
        "annual, sDA300/50%",
    ]
    for it in design.intentions:
        [chk] = lay.checks(it)
        units = {"lux": " lux", "df": " %"}.get(it.quantity, "")
        assert rows[it.name][4] == f"{fmt(chk.value[0])}{units}"
        assert rows[it.name][-1].startswith("pass" if chk.met[0] else "FAIL")
    assert rows["sda"][-1].startswith("FAIL")  # 99% of the plane is out of reach
    # Night: the luminaires alone, less than with the daylight.
    night = lay.points.lux("night", lay.grids.spans["wp"])[:, 0].mean()
    assert rows["night"][4] == f"{fmt(night)} lux"
    assert night < lay.points.lux("design", lay.grids.spans["wp"])[:, 0].mean()
    raw = pdf_text(info.path)
    text = squash(raw)
    for row in table.rows:  # each bound's name, requirement, value and verdict on a line
        words = (row[0], row[2].split()[0], row[4].split()[0], row[-1].split()[0])
        assert any(all(w in line for w in words) for line in raw.splitlines()), row
    assert "night Em ≥ 150 (night)" not in text and "Em ≥ 150 (night)" in text


def test_a_climate_front_is_plotted_on_its_own_goals(daylit):
    project, prepared, info = daylit
    front = project.pareto
    fig = pareto_figure(front, project.solutions[0])
    ax = fig.axes[0]
    assert ax.get_xlabel() == "annual lighting energy (kWh)"
    assert ax.get_ylabel() == "glazing area (m²)"
    line = ax.lines[0]
    want = sorted((s.objectives[CLIMATE[0]], s.objectives[CLIMATE[1]]) for s in front.solutions)
    np.testing.assert_allclose(np.column_stack(line.get_data()), want)
    assert len({w[1] for w in want}) == 3  # three glazing areas
    text = squash(pdf_text(info.path))
    assert "Pareto front (test): 3 non-dominated of 3 solutions" in text
    q = front_quality(front.solutions, front_scales(project.design, prepared.light))
    assert q.objectives == CLIMATE
    assert f"hypervolume {q.hypervolume:.4f}, spacing {q.spacing:.4f} (normalised)" in text


def test_no_skylights_no_section(daylit, tmp_path):
    _, prepared, _ = daylit
    night = Intention("night", grid="wp", average=150.0, scenario="night")
    project, _ = _project(_design((LUM,), (INTENTIONS[0], night)), "No roof light", prepared)
    info = write_report(project, prepared, tmp_path / "r.pdf")
    assert not set(SECTION_PAGES) & set(info.sections)
    assert "workplanes" in info.sections
    text = squash(pdf_text(info.path))
    assert "Daylight per work plane" not in text and "dimming energy" not in text


def test_unreadable_weather_file_is_said_in_text(daylit, tmp_path):
    _, prepared, _ = daylit
    bad = tmp_path / "broken.epw"
    bad.write_text("not a weather file\n")
    # Solved with the weather, reported after the file broke.
    project, _ = _project(_design(), "Broken weather", prepared)
    design = replace(project.design, daylight=replace(DAYLIGHT, weather=str(bad)))
    project = replace(project, design=design)
    info = write_report(project, prepared, tmp_path / "r.pdf", png_dir=tmp_path / "png")
    assert "daylight" in info.sections and "df-plan" in info.sections
    assert "energy" not in info.sections and "da-plan" not in info.sections
    text = squash(pdf_text(info.path))
    assert "The weather year could not be used: broken.epw: an EPW file starts" in text
    assert "annual metrics (DA300, sDA, UDI) and the dimming energy are not shown" in text
    sol = project.solutions[0]
    lay = layout_daylight(prepared.light, design, sol.sources, sol.arrays)
    df = 100 * lay.points.overcast_daylight(lay.grids.spans["wp"])[:, 0]
    assert f"mean {fmt(df.mean(), 3)}%" in text  # the DF plan is still there
    assert "Not measured (sda)" in text
