"""Where a reported layout came from: the optimisation run that found it, and its settings.

The window reports "the design on screen", judged afresh (its ``SolutionInfo`` is
empty), so the run is found by the layout: a run's result whose sources (rectangle,
flux, filter) and luminaire arrays (rectangle, rows, columns, rotation, dimming) are
the reported ones, newest run first. A layout edited after it was loaded matches no
run and is reported as given by hand.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from lightinv_core.design.solution import Solution
from lightinv_core.errors import LightInvError
from lightinv_core.optimize.registry import get_method
from lightinv_core.optimize.settings import OptimizerSettings
from lightinv_core.project import Project
from lightinv_core.project.results import RunRecord


@dataclass(frozen=True)
class Provenance:
    """The run behind a layout: ``method`` (registry name), ``run`` (the window's run
    record, None for a command-line result), the ``settings`` it ran with and the
    ``solution`` as the run saved it (its info: seed, evaluations, history)."""

    method: str
    settings: OptimizerSettings
    solution: Solution
    run: RunRecord | None = None


def _close(a, b) -> bool:
    if a is None or b is None:  # a skylight has no flux, a luminaire no filter
        return a is None and b is None
    return bool(np.allclose(np.asarray(a, float), np.asarray(b, float), rtol=1e-7, atol=1e-9))


def same_layout(a: Solution, b: Solution) -> bool:
    """Whether two solutions place the same sources and arrays the same way."""
    sa, sb = {s.name: s for s in a.sources}, {s.name: s for s in b.sources}
    if set(sa) != set(sb) or len(a.arrays) != len(b.arrays):
        return False
    for name, s in sa.items():
        t = sb[name]
        if not (_close(s.rect, t.rect) and _close(s.flux, t.flux) and _close(s.filter, t.filter)):
            return False
    ab = {x.name: x for x in b.arrays}
    for x in a.arrays:
        y = ab.get(x.name)
        if y is None or (x.rows, x.columns, x.rotation) != (y.rows, y.columns, y.rotation):
            return False
        if not (_close(x.rect, y.rect) and _close(x.dimming, y.dimming)):
            return False
    return True


def _results(project: Project):
    """(run or None, solution) of every stored result, newest run first."""
    for run in reversed(project.runs):
        for s in run.results():
            yield run, s
    for s in project.solutions:
        yield None, s
    if project.pareto is not None:
        for s in project.pareto.solutions:
            yield None, s


def provenance(project: Project, solution: Solution) -> Provenance | None:
    """The run that found ``solution``'s layout, or None (a layout given by hand)."""
    found = None
    for run, s in _results(project):
        if s is solution or (s.info.method and same_layout(s, solution)):
            found = (run, s)
            break
    if found is None:
        if not solution.info.method:
            return None
        return Provenance(solution.info.method, project.optimizer, solution)
    run, s = found
    method = (run.method if run is not None else "") or s.info.method or project.optimizer.method
    settings = run.settings if run is not None else project.optimizer
    return Provenance(method, settings, s, run)


def method_label(name: str) -> str:
    """ "vns: Variable Neighbourhood Search" (the registry's label), or the name alone."""
    try:
        label = get_method(name).label
    except LightInvError:
        return name
    if not label or label == name:
        return name
    return label if label.lower().startswith(name.lower()) else f"{name} ({label})"


def _value(v) -> str:
    if v is None:
        return "none"
    if isinstance(v, float):
        return f"{v:g}" if math.isfinite(v) else str(v)
    if isinstance(v, tuple | list):
        return ", ".join(_value(x) for x in v) or "none"
    return f"{v:,}" if isinstance(v, int) and not isinstance(v, bool) else str(v)


def settings_rows(p: Provenance) -> list[tuple[str, str]]:
    """(setting, value) of the run: the method, when it ran, its stopping rules and the
    settings the method reads, how it ended."""
    rows = [("optimiser", method_label(p.method))]
    info = p.solution.info
    if p.run is not None:
        when = p.run.time.replace("T", " ") if p.run.time else "time not recorded"
        rows.append(("run", f"run {p.run.number}, ended {when}"))
    shown = ["max_evals", "time_limit", "stall", "target", "seed"]
    try:
        own = get_method(p.method).settings_from(p.settings)
        shown += [
            f.name
            for f in dataclasses.fields(own)
            if f.name not in shown and hasattr(p.settings, f.name)
        ]
    except LightInvError:
        pass
    names = {
        "max_evals": "evaluation limit",
        "time_limit": "time limit (s)",
        "stall": "stall limit (evaluations)",
        "target": "target",
    }
    if p.run is None:  # a command-line result: the project's settings (options may differ)
        rows.append(("settings", "the project file's (command-line options are not recorded)"))
    for key in shown:
        if key == "seed" and p.run is not None and p.run.seeds:
            rows.append(("seeds", _value(p.run.seeds)))
            continue
        rows.append((names.get(key, key.replace("_", " ")), _value(getattr(p.settings, key))))
    if info.seed is not None:
        rows.append(("seed of this layout", str(info.seed)))
    for key, value in info.extra.items():  # what a method adds (e.g. CMA-ES's share)
        if isinstance(value, int | float) and not isinstance(value, bool):
            rows.append((key.replace("_", " "), _value(value)))
    ended = []
    if info.evaluations is not None:
        ended.append(f"{info.evaluations:,} evaluations")
    if info.seconds is not None:
        ended.append(f"{info.seconds:.1f} s")
    if info.status:
        ended.append(f"stopped by {info.status}")
    if ended:
        rows.append(("this layout's search", ", ".join(ended)))
    if p.run is not None and p.run.evaluations:
        rows.append(
            (
                "whole run",
                f"{p.run.evaluations:,} evaluations, {p.run.seconds:.1f} s, {p.run.status}",
            )
        )
    return rows
