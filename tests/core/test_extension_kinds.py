"""The remaining seams of issue #28, each registered from this module alone and seen
through project save/load, ``solve``, the CLI's text and JSON and the report's tables,
with no edit anywhere else: a source type (a diffusing panel that loses a fixed share
of its lamp's flux), an annual daylight metric (DA100: share of occupied hours with at
least 100 lux of daylight), a scenario (emergency: the luminaires at 10 %), an import
format and an optimizer (a toy random search)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from lightinv_core import cli
from lightinv_core.project import load_project, project_from_dict, project_to_dict
from lightinv_core.quantities import (
    HourBand,
    QuantitySpec,
    annual_metrics,
    register_quantity,
    unregister_quantity,
)
from lightinv_core.report.tables import intention_table, source_table
from lightinv_core.scenarios import ScenarioSpec, register_scenario, unregister_scenario
from lightinv_core.sources.types import (
    ZoneLuminaire,
    register_source_type,
    source_type,
    unregister_source_type,
)
from lightinv_core.study import prepare, solve

PANEL, DA100, EMERGENCY = "diffuser_panel", "da100", "emergency"
SHARE = 0.8  # the panel's diffuser passes 80 % of its lamps' flux


class DiffuserPanel(ZoneLuminaire):
    """A luminous panel whose diffuser passes ``SHARE`` of its lamps' flux (lm): the
    exitance and the flux it gives the room are ``SHARE`` of a plain luminaire's at the
    same electric power."""

    kind = PANEL
    label = "Diffuser panel"
    stem = "P"

    def exitance(self, s, rect, flux, filt, daylight):
        return SHARE * super().exitance(s, rect, flux, filt, daylight)

    def largest_exitance(self, s, zone, daylight):
        return SHARE * super().largest_exitance(s, zone, daylight)

    def flux(self, s, daylight):
        return SHARE * super().flux(s, daylight)


@pytest.fixture
def registered():
    register_source_type(DiffuserPanel())
    register_quantity(
        QuantitySpec(
            DA100,
            "daylight autonomy at 100 lux",
            "daylight autonomy DA100 (share of occupied hours, 0-1)",
            "",
            "DA100, a fraction of the occupied hours",
            0.0,
            1.0,
            3,
            (0.3, 1.0, 0.5, 0.3),
            metric="DA100",
            scenario="annual",
            hours=HourBand(100.0),
            uniformity=False,
        )
    )
    register_scenario(
        ScenarioSpec(
            EMERGENCY,
            "emergency: luminaires at 10 %",
            "the luminaires alone at 10 % of their output",
            daylit=False,
            lux=lambda light, idx: 0.1 * light.electric[idx],
        )
    )
    yield
    unregister_scenario(EMERGENCY)
    unregister_quantity(DA100)
    unregister_source_type(PANEL)


def _cornell(tmp_path: Path, kind: str, scenario: str = "design") -> Path:
    data = {
        "schema": 1,
        "name": "extension kinds",
        "scene": {
            "builtin": "cornell",
            "resolution": 0.3,
            # A zone of the kind drawn on the ceiling, beside the built-in light.
            "zones": [
                {
                    "name": "panel_zone",
                    "kind": kind,
                    "surface": "ceiling",
                    "rect": [0.1, 0.1, 0.6, 0.6],
                }
            ],
        },
        "operator": {"rank": 60, "rays": 64},
        "sources": [
            {
                "name": "panel",
                "zone": "panel_zone",
                "kind": kind,
                "rect": [0.0, 0.0, 0.5, 0.5],
                "free": ["flux"],
                "flux": 2000.0,
                "flux_range": [100.0, 5000.0],
            }
        ],
        "intentions": [
            {
                "name": "floor",
                "group": "floor",
                "quantity": "lux",
                "average": 30.0,
                "scenario": scenario,
            }
        ],
        "goals": [{"kind": "min_electric_power"}],
        "optimizer": {"method": "vns", "seed": 0, "max_evals": 300},
    }
    path = tmp_path / f"{kind}-{scenario}.json"
    path.write_text(json.dumps(data))
    return path


def test_a_registered_source_type_runs_through_every_view(registered, tmp_path, capsys):
    path = _cornell(tmp_path, PANEL)
    project = load_project(path)
    assert project.design.sources[0].kind == PANEL
    again = project_from_dict(json.loads(json.dumps(project_to_dict(project))))
    assert again.design.sources[0].kind == PANEL
    plain = _cornell(tmp_path, "luminaire")

    assert cli.main(["solve", str(path), "--json"]) == 0
    panel = json.loads(capsys.readouterr().out)
    assert cli.main(["solve", str(plain), "--json"]) == 0
    lum = json.loads(capsys.readouterr().out)
    assert panel["sources"][0]["kind"] == PANEL
    # Same floor light needs 1 / SHARE the lamp flux, so 1 / SHARE the electric power.
    assert panel["objective"] == pytest.approx(lum["objective"] / SHARE, rel=0.03)
    assert cli.main(["solve", str(path)]) == 0
    text = capsys.readouterr().out
    # The text line writes the setting and power its type has: lumens given, watts drawn.
    assert f"{panel['sources'][0]['flux_lm']:.0f} lm" in text and " W" in text

    prepared = prepare(project)
    result = solve(project, prepared)
    table = source_table(result.best, project.design)
    row = table.rows[0]
    assert PANEL in row and "lm" in " ".join(row)
    assert "Total electric power" in table.note
    assert source_type(PANEL).electric and not source_type(PANEL).daylit


def test_a_registered_scenario_judges_its_intentions(registered, tmp_path, capsys):
    path = _cornell(tmp_path, "luminaire", EMERGENCY)
    project = load_project(path)
    assert project.design.intentions[0].scenario == EMERGENCY
    assert cli.main(["solve", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    normal = _cornell(tmp_path, "luminaire")
    assert cli.main(["solve", str(normal), "--json"]) == 0
    base = json.loads(capsys.readouterr().out)
    # 30 lux at 10 % output needs ten times the flux (within the search's tolerance).
    assert out["sources"][0]["flux_lm"] == pytest.approx(
        10 * base["sources"][0]["flux_lm"], rel=0.05
    )


def test_a_registered_daylight_metric_is_measured_and_reported(registered, tmp_path, capsys):
    assert DA100 in [q.name for q in annual_metrics()]
    src = json.loads(
        (
            Path(__file__).resolve().parents[2] / "resources/projects/office-integrated.json"
        ).read_text()
    )
    src["scene"]["resolution"] = 0.8
    src["operator"] = {"rank": 80, "rays": 64}
    src["intentions"].append(
        {"name": "daylit", "group": "desks", "quantity": DA100, "average": 0.99}
    )
    src["goals"] = [{"kind": "min_glazing_area"}]
    src["optimizer"] = {"method": "vns", "seed": 0, "max_evals": 200}
    path = tmp_path / "da100.json"
    path.write_text(json.dumps(src))
    project = load_project(path)
    assert project.design.intentions[-1].scenario == "annual"
    assert cli.main(["solve", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    daylit = [v for v in out["violations"] if v["name"] == "daylit"]
    assert daylit and 0 < daylit[0]["value"] < 0.99
    prepared = prepare(project)
    result = solve(project, prepared)
    field = prepared.light.field(result.best.sources, project.design.daylight)
    rows = {r[0]: r for r in intention_table(result.best, project.design, field).rows}
    assert "DA100" in " ".join(map(str, rows["daylit"]))


def test_registered_kinds_are_refused_when_gone_and_builtins_stay(registered):
    with pytest.raises(ValueError, match="built in"):
        unregister_source_type("luminaire")
    with pytest.raises(ValueError, match="built in"):
        unregister_scenario("night")
    with pytest.raises(ValueError, match="already registered"):
        register_source_type(DiffuserPanel())
