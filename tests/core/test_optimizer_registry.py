"""The optimizer seam: a method registered from this module alone (pure random search,
with its own settings) runs through ``study.solve`` and the CLI's ``solve`` by its
name, with no edit anywhere else; and the registry's own promises."""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np
import pytest

from lightinv_core import cli
from lightinv_core.errors import DesignError
from lightinv_core.optimize import registry
from lightinv_core.optimize.method import MethodSpec, RunContext
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.result import OptimizationResult
from lightinv_core.optimize.search import best_of, better, first_point, judged
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.project import load_project
from lightinv_core.study import prepare, solve

PROJECTS = Path(__file__).resolve().parents[2] / "resources" / "projects"


@dataclass(frozen=True)
class RandomSettings:
    """The toy's own setting, unknown to project files: layouts drawn per batch."""

    batch: int = 16


def random_search(problem: DesignProblem, context: RunContext) -> OptimizationResult:
    """Pure random search: batches of uniform layouts, the best by the shared rule."""
    rng = np.random.default_rng(context.seed)
    level = problem.level(1)
    x, budget = first_point(problem, context.x0, rng, level, context.stop, context.cancel)
    lo, hi = problem.vars.lo, problem.vars.hi
    batch, iters = context.options(RandomSettings).batch, 0
    while (why := budget.why()) is None:
        X = lo + rng.random((batch, len(lo))) * (hi - lo)
        ev = problem.evaluate(X, level)
        budget.evals += ev.evaluated
        iters += 1
        j = best_of(ev)
        if better(ev.value[j], ev.penalty[j], *budget.best[:2]):
            x = X[j]
            budget.improve(ev, j)
        if context.progress is not None:
            context.progress(budget.snapshot(iters, 1, x))
    return judged(problem, budget.result(x, iters, why), "random", context.seed)


TOY = MethodSpec("random", "Random search", random_search, RandomSettings)


@pytest.fixture
def toy():
    registry.register(TOY)
    yield TOY
    registry.unregister(TOY.name)


@pytest.fixture
def small_project(tmp_path, monkeypatch) -> Path:
    """Experiment 1 (the patio) at a coarse resolution, run by the toy."""
    monkeypatch.setenv("LIGHTINV_CACHE_DIR", str(tmp_path / "cache"))
    src = json.loads((PROJECTS / "experiment1.json").read_text())
    src["scene"]["resolution"] = 0.7
    src["operator"] = {"rank": 100, "rays": 128}
    src["optimizer"] = {"method": "random", "seed": 3, "max_evals": 400}
    path = tmp_path / "toy.json"
    path.write_text(json.dumps(src))
    return path


def test_a_registered_method_runs_through_study_solve(toy, small_project):
    project = load_project(small_project)
    assert project.optimizer.method == "random"
    prepared = prepare(project)
    snaps = []
    a = solve(project, prepared, progress=snaps.append)
    b = solve(project, prepared)
    assert a.best.info.method == "random" and a.best.info.seed == 3
    assert 400 <= a.evaluations < 400 + 16 and snaps
    assert a.best.objectives == b.best.objectives  # same seed, same answer
    assert registry.get_method("random") is toy and "random" in registry.method_names()


def test_a_registered_method_runs_through_the_cli_by_name(toy, small_project, capsys):
    assert cli.main(["solve", str(small_project), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["method"] == "random" and out["evaluations"] >= 400
    assert cli.main(["solve", str(small_project), "--method", "random", "--max-evals", "64"]) == 0
    assert "random" in capsys.readouterr().out


def test_an_unregistered_method_is_gone(small_project):
    assert "random" not in registry.method_names()
    with pytest.raises(DesignError, match="unknown optimisation method 'random'"):
        registry.get_method("random")
    with pytest.raises(Exception, match="random"):
        load_project(small_project)  # the file's method is checked against the registry


def test_names_clash_and_removal_of_a_built_in_is_refused():
    with pytest.raises(DesignError, match="exists already"):
        registry.register(MethodSpec("vns", "again", random_search))
    with pytest.raises(DesignError, match="no registered"):
        registry.unregister("vns")


def test_each_method_reads_its_own_settings_from_the_project_settings():
    """A method's settings default to the project file's defaults of the same names,
    and are read from a project's settings by name."""
    project = OptimizerSettings()
    for spec in registry.methods():
        own = spec.settings()
        for f in fields(own):
            if hasattr(project, f.name):
                assert getattr(own, f.name) == getattr(project, f.name), (spec.name, f.name)
    changed = OptimizerSettings(trials=8, population=12, divisors=(4, 1))
    assert registry.get_method("vns").settings_from(changed).trials == 8
    assert registry.get_method("nsga2").settings_from(changed).population == 12
    assert registry.get_method("multilevel").settings_from(changed).divisors == (4, 1)


def test_the_settings_and_the_names_load_no_algorithm():
    code = (
        "import sys\n"
        "from lightinv_core.optimize.settings import OptimizerSettings\n"
        "from lightinv_core.optimize.registry import method_names\n"
        "OptimizerSettings(method='nsga2'); method_names()\n"
        "loaded = [m for m in ('pymoo', 'cma', 'lightinv_core.optimize.nsga2',\n"
        "          'lightinv_core.optimize.vns') if m in sys.modules]\n"
        "print(loaded)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_the_settings_check_method_names_without_the_registry():
    code = (
        "import sys\n"
        "from lightinv_core.optimize.settings import OptimizerSettings\n"
        "OptimizerSettings(method='two_step')\n"
        "print('lightinv_core.optimize.registry' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
