"""The judge: which constraints a candidate breaks, by how much, and its penalty.

The columns of G (``Constraint``): each geometric rule's relative violation, then each
intention bound's and each epsilon bound's relative violation c. The search reads the
lighting columns as c minus the 0.1% tolerance (``FEASIBILITY_TOL``; with luminaire
arrays plus ``ARRAY_MARGIN``); a solution is judged on every patch at ``JUDGED_TOL``,
each broken bound listed as a ``Violation``. The penalty (paper eq. 3) is
P = sum W * max(0, G)^pow over the lighting columns, W the intention's weight
(``EPSILON_WEIGHT`` for epsilon bounds), pow the design's penalty power: one function,
``penalty``. The search feeds it its columns (c less the tolerance, plus the arrays'
margin); a solution's penalty, the number the window, the results table and the report
show, feeds it the relative violations c of the bounds it breaks, so it can be checked
from the solution's violations (``Violation.amount``): P = sum W * amount^pow.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.design.geometry import rule_names
from lightinv_core.design.model import Design
from lightinv_core.design.solution import Violation
from lightinv_core.goals import goal_spec
from lightinv_core.kinds import Bound
from lightinv_core.light.intentions import (
    FEASIBILITY_TOL,
    JUDGED_TOL,
    BoundCheck,
    bound_checks,
    bounds_set,
    intention_stats,
    quantity_values,
)
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.candidate_light import Lit
from lightinv_core.optimize.levels import Level

EPSILON_WEIGHT = 100.0
ARRAY_MARGIN = 0.005
"""Relative margin the search keeps on every intention bound when luminaire arrays are
lit from their lattice: the blend's error on the office benchmark's work plane is at most
0.07% on Em and 0.15% on U0 over 60 random layouts off the nodes
(bench/luminaire_arrays.py), well within it."""


def penalty(columns: list, weights: list, power: int, m: int = 1) -> np.ndarray:
    """P = sum_j W_j max(0, G_j)^power (paper eq. 3) of columns G_j (each (m,)),
    weights W_j; the one penalty formula, for the search and for solutions."""
    P = np.zeros(m)
    for g, w in zip(columns, weights, strict=True):
        P = P + w * np.maximum(0.0, g) ** power
    return P


@dataclass(frozen=True)
class Constraint:
    """One column of G: ``kind`` "geometry", "intention" or "epsilon"; ``name`` says which
    (rule label, intention name, goal kind), ``bound`` which of its bounds; ``weight`` is
    its penalty weight (0 for geometric rules, which reject instead)."""

    kind: str
    name: str
    bound: str
    weight: float


class Judge:
    """The constraints of one design (its rules, intentions and ``epsilon`` bounds, pairs
    (goal kind, bound)) and how candidates meet them."""

    def __init__(self, design: Design, light: LightModel, epsilon: tuple, glare=None):
        self.design, self.light, self.epsilon = design, light, epsilon
        # glare(intention, lit) -> (observers, m): the quantity at an intention's
        # observers (UGR, ``light/glare.py``); None when no intention names observers.
        self.glare = glare
        rules = rule_names(design)
        self.n_rules = len(rules)
        cols = [Constraint("geometry", n, "", 0.0) for n in rules]
        for it in design.intentions:
            cols += [Constraint("intention", it.name, str(b), it.weight) for b in bounds_set(it)]
        for kind, _ in epsilon:
            cols.append(Constraint("epsilon", kind, "epsilon", EPSILON_WEIGHT))
        self.constraints = tuple(cols)
        self.weights = [c.weight for c in self.constraints if c.kind != "geometry"]

    def checks(self, lit: Lit, level: Level) -> list[BoundCheck]:
        """Every intention's bound checks on the batch's light at the level's rows."""
        out = []
        rho = self.light.op.rho
        for i, it in enumerate(self.design.intentions):
            pos = level.intent_pos[i]
            if it.observers is not None:  # at eyes, not at the level's receivers
                q = self.glare(it, lit)
                out += bound_checks(it, intention_stats(q, np.ones(len(q))))
                continue
            # Grid points have no reflectance: they take illuminance and daylight metrics.
            r = None if it.grid is not None else rho[level.rows[pos]]
            if lit.parts is not None:
                q = lit.parts.quantity(it, pos, r)
            elif it.grid is not None:
                q = lit.H[pos]
            else:
                q = quantity_values(it, lit.H[pos], r)
            out += bound_checks(it, intention_stats(q, level.intent_w[i]))
        return out

    def epsilon_terms(self, goals: dict):
        """(goal kind, bound, relative violation c (m,)) of each epsilon bound."""
        for kind, bound in self.epsilon:
            if goal_spec(kind).maximise:
                c = (bound - goals[kind]) / max(abs(bound), 1e-12)
            else:
                c = (goals[kind] - bound) / max(abs(bound), 1e-12)
            yield kind, bound, c

    def penalty(self, lighting: list, n_intent: int, m: int) -> np.ndarray:
        """P (m,) of the lighting columns (intentions, then epsilon): ``penalty``."""
        return penalty(lighting, self.weights, self.design.penalty_power, m)

    def search_columns(self, lit: Lit, level: Level, goals: dict) -> tuple[list, int]:
        """The lighting columns of G the search reads (c - tolerance, each (m,)) and how
        many of them are the intentions'."""
        checks = self.checks(lit, level) if self.design.intentions else []
        # With arrays the search reads the lattice blend: it keeps a margin for the
        # blend's error, so the layout also holds judged with the luminaires placed exactly.
        margin = ARRAY_MARGIN if self.design.arrays else 0.0
        lighting = [chk.c - FEASIBILITY_TOL + margin for chk in checks]
        lighting += [c - FEASIBILITY_TOL for _, _, c in self.epsilon_terms(goals)]
        return lighting, len(checks)

    def rule_breaches(self, G: np.ndarray) -> list[Violation]:
        """The geometric rules one candidate breaks, from its row of G."""
        n = self.n_rules
        return [
            Violation(c.name, "geometry", float(g), float("nan"), float("nan"), "")
            for c, g in zip(self.constraints[:n], G[:n], strict=True)
            if g > 0
        ]

    def verdict(self, lit: Lit | None, level: Level, goals: dict) -> tuple[list, float]:
        """One candidate judged at ``JUDGED_TOL`` (``lit`` its light at ``level``, None
        without intentions; ``goals`` its values): its intention and epsilon violations
        and its penalty, from one computation: ``penalty`` of the broken bounds' relative
        violations, so P = sum W * amount^pow over the violations listed."""
        viol: list[Violation] = []
        excess: list[np.ndarray] = []
        if self.design.intentions:
            checks = self.checks(lit, level)
            excess += [np.where(chk.c > JUDGED_TOL, chk.c, 0.0) for chk in checks]
            for chk in checks:
                if chk.c[0] > JUDGED_TOL:
                    units = "" if chk.bound == Bound.UNIFORMITY else chk.units
                    viol.append(
                        Violation(
                            chk.intention.name,
                            str(chk.bound),
                            float(chk.c[0]),
                            float(chk.value[0]),
                            float(chk.limit),
                            units,
                        )
                    )
        for kind, bound, c in self.epsilon_terms(goals):
            excess.append(np.where(c > JUDGED_TOL, c, 0.0))
            if c[0] > JUDGED_TOL:
                value = float(goals[kind][0])
                spec = goal_spec(kind)
                # Named for people (the Violations tab, the report): the goal's label.
                name = f"epsilon {spec.label.lower()}"
                viol.append(Violation(name, "epsilon", float(c[0]), value, bound, spec.unit))
        return viol, float(penalty(excess, self.weights, self.design.penalty_power)[0])
