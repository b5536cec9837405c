"""The goal and quantity registries are the only place a new goal or intention quantity
goes: this module registers both from here alone — a goal the optimiser evaluates from
its spec (least total luminaire flux, lm) and a quantity derived from illuminance
(luminance L = rho H / pi, cd/m²) — and sees them through project loading, ``solve``,
the CLI's text and JSON, the report's goal and intention tables and the editing model's
result labels, with no edit anywhere else."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.design.model import Goal
from lightinv_core.design.solution import SolutionInfo
from lightinv_core.editing import result_label
from lightinv_core.goals import (
    GoalSpec,
    goal_spec,
    register_goal,
    unregister_goal,
)
from lightinv_core.kinds import GoalKind, Quantity
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.project import load_project
from lightinv_core.quantities import (
    QuantitySpec,
    quantity_spec,
    register_quantity,
    unregister_quantity,
)
from lightinv_core.report.tables import fmt, goal_label, intention_table, objective_text
from lightinv_core.study import prepare
from lightinv_core.value_text import goal_value

FLUX = "min_total_flux"
LUMINANCE = "luminance"


def _luminaires(design) -> list[int]:
    return [j for j, s in enumerate(design.sources) if s.kind == "luminaire"]


def _total_flux(batch) -> np.ndarray:
    """The goal's batch value: the luminaire sources' flux summed, (m,) lm."""
    return batch.flux[:, _luminaires(batch.problem.design)].sum(axis=1)


def _flux_scale(problem) -> float:
    design = problem.design
    return max(sum(design.sources[j].flux_range[1] for j in _luminaires(design)), 1e-9)


@pytest.fixture
def registered():
    register_goal(
        GoalSpec(
            FLUX,
            "Total luminous flux",
            "Least total luminous flux",
            "least total flux",
            "total flux",
            "lm",
            "{:10.0f} lm",
            bound_format="{:,.0f} lm of flux",
            value=_total_flux,
            scale=_flux_scale,
        )
    )
    register_quantity(
        QuantitySpec(
            LUMINANCE,
            "luminance",
            "luminance L (cd/m²)",
            "cd/m²",
            "luminance, cd/m²",
            high=1e6 / math.pi,
            from_lux=lambda lux, rho: lux * (rho[:, None] if lux.ndim == 2 else rho) / math.pi,
            needs_reflectance=True,
        )
    )
    yield
    unregister_goal(FLUX)
    unregister_quantity(LUMINANCE)


def _project(tmp_path) -> str:
    data = {
        "schema": 1,
        "name": "extension",
        "scene": {"builtin": "cornell", "resolution": 0.3},
        "operator": {"rank": 60, "rays": 64},
        "sources": [
            {
                "name": "lamp",
                "zone": "light",
                "kind": "luminaire",
                "rect": [0.0, 0.0, 0.5, 0.5],
                "free": ["flux"],
                "flux": 2000.0,
                "flux_range": [100.0, 5000.0],
            }
        ],
        "intentions": [
            {"name": "floor L", "group": "floor", "quantity": LUMINANCE, "average": 10.0},
            {
                "name": "dark floor",
                "group": "floor",
                "quantity": LUMINANCE,
                "max": 1e-3,
                "weight": 0,
            },
        ],
        "goals": [{"kind": FLUX}],
        "optimizer": {"method": "vns", "seed": 0, "max_evals": 300},
    }
    path = tmp_path / "extension.json"
    path.write_text(json.dumps(data))
    return str(path)


def test_a_registered_goal_and_quantity_run_through_every_view(registered, tmp_path, capsys):
    path = _project(tmp_path)
    project = load_project(path)
    assert project.design.goals[0].kind == FLUX
    assert project.design.intentions[0].quantity == LUMINANCE

    # The CLI: JSON and text, the goal optimised and the quantity's unit in the violation.
    assert cli.main(["solve", path, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["objective_kind"] == FLUX
    flux = out["objective"]
    assert 100.0 <= flux <= 5000.0 and out["objectives"] == {FLUX: flux}
    assert out["sources"][0]["flux_lm"] == pytest.approx(flux)
    dark = [v for v in out["violations"] if v["name"] == "dark floor"]
    assert [v["units"] for v in dark] == ["cd/m²"]
    assert not any(v["name"] == "floor L" for v in out["violations"])
    assert cli.main(["solve", path]) == 0
    text = capsys.readouterr().out
    assert f"{FLUX}: {flux:.6g}" in text
    assert "vs 0.001 cd/m²)" in text
    assert goal_value(FLUX, 1234.4) == "      1234 lm"

    # The optimiser read the quantity: the floor's mean luminance meets its bound, just.
    prepared = prepare(project)
    problem = DesignProblem(project.design, prepared.light)
    sol = problem.solution(np.array([flux]))
    field = prepared.light.field(sol.sources, project.design.daylight)
    res = field.intention(project.design.intentions[0])
    assert res.stats.average[0] == pytest.approx(10.0, rel=0.02)
    assert sol.objectives == {FLUX: pytest.approx(flux)}

    # The report: the goal's line and axis label, the quantity's unit in the intentions.
    assert objective_text(FLUX, flux) == f"Total luminous flux: {fmt(flux)} lm"
    assert goal_label(FLUX) == "total luminous flux (lm)"
    table = intention_table(sol, project.design, field)
    rows = {r[0]: r for r in table.rows}
    assert any("cd/m²" in cell for cell in rows["floor L"])

    # The editing model: an epsilon result bounded on the new goal is labelled by its spec.
    power = replace(project.design, goals=(Goal(GoalKind.MIN_ELECTRIC_POWER),))
    eps = DesignProblem(power, prepared.light, epsilon=((FLUX, 3000.0),))
    s = eps.solution(np.array([flux]), SolutionInfo(method="epsilon", epsilon=3000.0))
    assert set(s.objectives) == {"min_electric_power", FLUX}
    assert result_label(s) == "epsilon 3,000 lm of flux"


def test_unregistered_names_are_refused_and_builtins_stay(registered):
    with pytest.raises(ValueError, match="already registered"):
        register_goal(goal_spec(FLUX))
    with pytest.raises(ValueError, match="built in"):
        unregister_goal(GoalKind.MATCH)
    with pytest.raises(ValueError, match="built in"):
        unregister_quantity(Quantity.LUX)
    assert quantity_spec(LUMINANCE).default_scenario == "design"
