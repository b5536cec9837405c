"""The judge names an epsilon bound it finds broken by the goal's label, as the Violations
tab and the report show it, not by the goal's id in project files (issue #29, minor)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from lightinv_core.goals import goal_spec
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.project import OperatorSettings, load_project
from lightinv_core.report.tables import rules_table
from lightinv_core.study import prepare

PROJECTS = Path(__file__).resolve().parents[2] / "resources" / "projects"


def test_a_broken_epsilon_bound_is_named_by_its_goals_label():
    project = load_project(PROJECTS / "experiment5.json")
    project = replace(
        project,
        scene=replace(project.scene, resolution=0.7),
        operator=OperatorSettings(rank=200, rays=256),
    )
    prepared = prepare(project)
    # An unreachable bound on the light power: every layout breaks it.
    problem = DesignProblem(project.design, prepared.light, epsilon=(("max_light_power", 1e12),))
    sol = problem.solution(problem.vars.initial())
    (broken,) = [v for v in sol.violations if v.constraint == "epsilon"]
    label = goal_spec("max_light_power").label.lower()
    assert broken.name == f"epsilon {label}" == "epsilon reflected light power"
    assert "max_light_power" not in broken.name
    assert broken.bound == 1e12 and broken.value < 1e12 and broken.units == "lm"
    # The report's rules table says which way the bound goes: at least, a maximised goal.
    table = rules_table(sol, project.design, prepared.patches)
    (row,) = [r for r in table.rows if r[1] == "epsilon"]
    assert row[0].startswith("epsilon reflected light power ≥ "), row
