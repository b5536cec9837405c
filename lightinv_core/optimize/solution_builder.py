"""One layout judged on every patch: the ``Solution`` a run returns, and where its light
breaks the intentions.

A search reads its candidates at a level's representatives with the arrays blended from
their lattice; its answer is judged again here on every patch, the arrays placed
exactly, at the judging tolerance, with every violation listed.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Protocol

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.design.solution import Solution, SolutionInfo
from lightinv_core.goals import goal_specs
from lightinv_core.light.arrays import arrays_field
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.candidate_light import CandidateLight
from lightinv_core.optimize.judge import Judge
from lightinv_core.optimize.levels import Level
from lightinv_core.optimize.objectives import DesignGoals, wanted_goals
from lightinv_core.scene.patches import Patches


class JudgedProblem(Protocol):
    """What the builder reads of its problem (``DesignProblem``)."""

    design: Design
    light: LightModel
    patches: Patches
    epsilon: tuple
    goals: DesignGoals
    judge: Judge
    lighting: CandidateLight
    vars: object

    def layout_of(self, X: np.ndarray): ...

    def level(self, divisor: int = 1) -> Level: ...

    def evaluate(self, X: np.ndarray, level: Level | None = None): ...

    def rule_violations(self, X: np.ndarray) -> np.ndarray: ...

    def sources_at(self, x: np.ndarray) -> tuple: ...

    def arrays_at(self, x: np.ndarray) -> tuple: ...


def build_solution(
    problem: JudgedProblem, x: np.ndarray, info: SolutionInfo | None = None
) -> Solution:
    """A ``Solution`` for x judged on ALL patches, with every violation listed."""
    x = np.asarray(x, dtype=float)
    design, judge, goal_set = problem.design, problem.judge, problem.goals
    lv = problem.level(1)
    ev = problem.evaluate(x[None], lv)
    viol = judge.rule_breaches(ev.G[0])
    penalty = float("inf")
    goals = ev.goals
    if ev.ok[0]:
        judged = None
        if design.intentions or (goal_set.annual and design.arrays):
            judged = problem.lighting.judged(x, lv)
        if goal_set.annual and design.arrays:
            # The year's goals from the arrays placed exactly, as the intentions.
            decoded = (*problem.vars.decode(x[None]), problem.layout_of(x[None]))
            energy, sda = goal_set.annual_values(
                judged, lv, ev.goals["min_electric_power"], decoded
            )
            goals = {**ev.goals, "min_annual_energy": energy, "max_sda": sda}
        more, penalty = judge.verdict(judged, lv, goals)
        viol += more
    wanted = wanted_goals(design, problem.epsilon)
    objectives = {s.kind: float(goals[s.kind][0]) for s in goal_specs() if s.kind in wanted}
    return Solution(
        problem.sources_at(x),
        objectives,
        penalty,
        tuple(viol),
        tuple(float(v) for v in x),
        info if info is not None else SolutionInfo(),
        problem.arrays_at(x),
    )


def offending_patches(problem: JudgedProblem, x: np.ndarray) -> list[tuple[str, str, np.ndarray]]:
    """Where the light of layout x breaks the intentions, judged on all patches:
    (intention name, bound, patch ids) for each violated bound (see
    ``LightField.offending_patches``). Empty when a geometric rule fails."""
    x = np.asarray(x, dtype=float)
    design = problem.design
    patch_intentions = [it for it in design.intentions if it.grid is None and it.observers is None]
    if not patch_intentions or np.any(problem.rule_violations(x[None]) > 0):
        return []
    field = problem.light.field(problem.sources_at(x), design.daylight)
    if design.arrays:
        H, _ = arrays_field(problem.patches, problem.light.op, problem.arrays_at(x))
        field = replace(field, illuminance=field.illuminance + H)
    return [
        (it.name, bound, ids)
        for it in patch_intentions
        for bound, ids in field.offending_patches(it)
    ]
