"""``DesignProblem``: a design's candidates scored as objectives F and constraints G.

Per batch (m candidates, like pymoo's ``Problem``): decode the variables, check the
geometric rules (no light needed: a candidate breaking one is rejected), get the light
of the others from the ``LightModel`` at the receiver rows the intentions and goals
need (one GEMM), and score:

- ``F`` (m, o): the design's goals in order, each as minimised (W; -lm for the
  light-power goal; the match error e);
- ``G`` (m, c): one column per constraint, met where G <= 0: each geometric rule's
  relative violation, then each intention bound's and each epsilon bound's relative
  violation c minus the 0.1% tolerance (``FEASIBILITY_TOL``). Lighting columns of a
  rejected candidate are +inf (not evaluated);
- the penalty (paper eq. 3) P = sum W * max(0, G)^pow over the lighting columns, W the
  intention's weight (``EPSILON_WEIGHT`` for epsilon bounds), pow the design's penalty
  power (default 2); the minimised value is the primary goal scaled to about [0, 1]
  plus P, so P dominates.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lightinv_core.design.geometry import rule_names, rule_violations
from lightinv_core.design.model import Design
from lightinv_core.design.solution import Solution, SolutionInfo, Violation
from lightinv_core.design.variables import Variables
from lightinv_core.kinds import Bound, GoalKind, SourceKind
from lightinv_core.light.intentions import (
    FEASIBILITY_TOL,
    JUDGED_TOL,
    BoundCheck,
    bound_checks,
    bounds_set,
    intention_patches,
    intention_stats,
    quantity_values,
)
from lightinv_core.light.model import LightModel, Receivers
from lightinv_core.operator.clustering import cluster_patches
from lightinv_core.scene.patches import Patches

EPSILON_WEIGHT = 100.0
GOAL_NAMES = tuple(str(g) for g in GoalKind)
GOAL_UNITS = {GoalKind.MIN_ELECTRIC_POWER: "W", GoalKind.MAX_LIGHT_POWER: "lm", GoalKind.MATCH: ""}

__all__ = ["EPSILON_WEIGHT", "FEASIBILITY_TOL", "Constraint", "DesignProblem", "Evaluation"]


@dataclass(frozen=True)
class Constraint:
    """One column of G: ``kind`` "geometry", "intention" or "epsilon"; ``name`` says which
    (rule label, intention name, goal kind), ``bound`` which of its bounds; ``weight`` is
    its penalty weight (0 for geometric rules, which reject instead)."""

    kind: str
    name: str
    bound: str
    weight: float


@dataclass(frozen=True)
class Level:
    """Receivers of one multilevel stage (divisor d: about n/d representative patches).

    ``rows`` are patch ids; ``intent_pos[i]`` indexes ``rows`` for intention i and
    ``intent_w[i]`` holds the area each representative stands for;
    ``match_pos`` indexes the representatives of all patches (match goal).
    """

    divisor: int
    receivers: Receivers
    intent_pos: tuple[np.ndarray, ...]
    intent_w: tuple[np.ndarray, ...]
    match_pos: np.ndarray

    @property
    def rows(self) -> np.ndarray:
        """Patch ids of the representatives."""
        return self.receivers.rows


@dataclass(frozen=True)
class Evaluation:
    """Scores of a batch of m candidates.

    ``value`` = scaled primary goal + ``penalty`` (inf where a geometric rule fails,
    ``ok`` False); ``goals`` {goal kind: (m,)} in W, lm or e for every goal kind;
    ``F`` (m, o) and ``G`` (m, c) as described in the module (assembled on first use:
    the optimizer's hot loop reads only value and penalty); ``evaluated`` counts the
    light evaluations (the candidates with ``ok``).
    """

    value: np.ndarray
    penalty: np.ndarray
    ok: np.ndarray
    goals: dict[str, np.ndarray]
    evaluated: int
    geometry: np.ndarray
    lighting: tuple[np.ndarray, ...]
    senses: tuple[tuple[str, float], ...]

    @cached_property
    def G(self) -> np.ndarray:
        """(m, c) constraint values, met where <= 0 (+inf: light not computed)."""
        m, ngeo = self.geometry.shape
        G = np.full((m, ngeo + len(self.lighting)), np.inf)
        G[:, :ngeo] = self.geometry
        good = np.flatnonzero(self.ok)
        for j, col in enumerate(self.lighting, ngeo):
            G[good, j] = col
        return G

    @cached_property
    def F(self) -> np.ndarray:
        """(m, o) objectives as minimised (+inf where a geometric rule fails)."""
        F = np.full((len(self.ok), len(self.senses)), np.inf)
        for j, (kind, sign) in enumerate(self.senses):
            F[self.ok, j] = sign * self.goals[kind][self.ok]
        return F

    @property
    def feasible(self) -> np.ndarray:
        """Candidates meeting every constraint (G <= 0 everywhere), (m,) bool."""
        return np.all(self.G <= 0, axis=1)


def representatives(patches: Patches, idx: np.ndarray, labels: np.ndarray):
    """For the patches ``idx``: one representative per cluster (the member nearest the
    members' mean centroid) and the area it stands for."""
    lab = labels[idx]
    order = np.argsort(lab, kind="stable")
    idx, lab = idx[order], lab[order]
    starts = np.flatnonzero(np.r_[True, lab[1:] != lab[:-1]])
    area = patches.area[idx]
    c = patches.centroid[idx]
    sums = np.add.reduceat(c * area[:, None], starts, axis=0)
    tot = np.add.reduceat(area, starts)
    mean = sums / tot[:, None]
    group = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, len(idx)]))
    d = np.linalg.norm(c - mean[group], axis=1)
    best = np.lexsort((d, group))
    first = best[np.r_[True, group[best][1:] != group[best][:-1]]]
    return idx[first], tot


class DesignProblem:
    """A design bound to the light model of its scene.

    ``epsilon`` adds constraints on other goals for the epsilon-constraint method
    (paper eq. 10): pairs (goal kind, bound) meaning light power >= bound (lm) or
    electric power <= bound (W).
    """

    def __init__(self, design: Design, light: LightModel, epsilon: tuple = ()):
        self.design, self.light = design, light
        self.patches = light.patches
        sources = design.sources
        light.check((*sources, *design.target_sources))
        self.vars = Variables(design, {s.zone: light.zone_size(s.zone) for s in sources})
        self.zone_size = self.vars.zone_size
        self.intent_sets = [intention_patches(i, self.patches) for i in design.intentions]
        self.epsilon = tuple((str(k), float(b)) for k, b in epsilon)
        self.primary = str(design.goals[0].kind)
        self.objectives = tuple(GoalKind(g.kind) for g in design.goals)
        self.scales = {
            GoalKind.MAX_LIGHT_POWER: light.power_scale(sources, design.daylight),
            GoalKind.MIN_ELECTRIC_POWER: electric_scale(design, light),
            GoalKind.MATCH: 1.0,
        }
        self.constraints = self._constraint_columns()
        self._weights = [c.weight for c in self.constraints if c.kind != "geometry"]
        self._senses = tuple(
            (str(k), -1.0 if k == GoalKind.MAX_LIGHT_POWER else 1.0) for k in self.objectives
        )
        self._sign = -1.0 if self.primary == GoalKind.MAX_LIGHT_POWER else 1.0
        light_goal = next((g for g in design.goals if g.kind == GoalKind.MAX_LIGHT_POWER), None)
        # The light-power goal counts its kinds' sources (all kinds when it names none).
        kinds = (light_goal.kinds if light_goal else ()) or tuple(SourceKind)
        self._power_kinds = tuple(str(k) for k in kinds)
        self._levels: dict[int, Level] = {}
        self.match = None
        if any(g.kind == GoalKind.MATCH for g in design.goals):
            self.match, self.C_obj = light.match_target(design.target_sources, design.daylight)

    def _constraint_columns(self) -> tuple[Constraint, ...]:
        cols = [Constraint("geometry", n, "", 0.0) for n in rule_names(self.design)]
        for it in self.design.intentions:
            cols += [Constraint("intention", it.name, str(b), it.weight) for b in bounds_set(it)]
        for kind, _ in self.epsilon:
            cols.append(Constraint("epsilon", kind, "epsilon", EPSILON_WEIGHT))
        return tuple(cols)

    # -- levels -------------------------------------------------------------------------------
    def level(self, divisor: int = 1) -> Level:
        """The representative receivers for divisor d (1 = every patch)."""
        if divisor in self._levels:
            return self._levels[divisor]
        n = self.patches.n
        if divisor <= 1:
            labels = np.arange(n)
        else:
            labels = cluster_patches(self.patches, max(1, n // divisor))[0]
        sets = list(self.intent_sets)
        if self.match is not None:
            sets.append(np.arange(n))
        reps = [representatives(self.patches, s, labels) for s in sets]
        rows = np.unique(np.concatenate([r for r, _ in reps])) if reps else np.zeros(0, int)
        pos = [np.searchsorted(rows, r) for r, _ in reps]
        match_pos = pos.pop() if self.match is not None else np.zeros(0, int)
        weights = [w for _, w in reps][: len(pos)]
        lv = Level(divisor, self.light.receivers(rows), tuple(pos), tuple(weights), match_pos)
        self._levels[divisor] = lv
        return lv

    # -- evaluation ---------------------------------------------------------------------------
    def evaluate(self, X: np.ndarray, level: Level | None = None) -> Evaluation:
        """Score the candidates X (m, nvar) at ``level`` (default: all patches)."""
        level = level or self.level(1)
        X = np.atleast_2d(np.asarray(X, dtype=float))
        m = len(X)
        rect, flux, filt = self.vars.decode(X)
        geo = rule_violations(self.design, rect, self.zone_size)
        ok = ~np.any(geo > 0, axis=1)
        good = np.flatnonzero(ok)
        if len(good) == m:
            # Every candidate was lit (the usual case): no scatter into full arrays.
            value, penalty, goals, lighting = self._score(rect, flux, filt, level)
        else:
            value, penalty = np.full(m, np.inf), np.full(m, np.inf)
            goals = {k: np.full(m, np.nan) for k in GOAL_NAMES}
            lighting = ()
            if len(good):
                v, p, g, lighting = self._score(rect[good], flux[good], filt[good], level)
                value[good], penalty[good] = v, p
                for k in goals:
                    goals[k][good] = g[k]
        return Evaluation(value, penalty, ok, goals, len(good), geo, lighting, self._senses)

    def _score(self, rect, flux, filt, level: Level):
        """Value, penalty, goals and lighting constraint columns (c - tol, each (m,)) of
        m lit candidates."""
        d = self.design
        V, by_kind = self.light.zone_emission(
            d.sources, rect, flux, filt, d.daylight, split_kinds=True
        )
        cols = np.flatnonzero(np.any(V != 0, axis=1))
        m = V.shape[1]
        # At the full level the match error comes from the Gram matrix, not the field.
        need_field = bool(self.intent_sets) or (self.match is not None and level.divisor > 1)
        H = None
        if need_field and len(level.rows):
            H = self.light.illuminance(V, level.receivers, cols)
        match = self._match(V, cols, H, level) if self.match is not None else np.zeros(m)
        power_V = sum(by_kind[k] for k in self._power_kinds)
        # Plain-string keys: this dict is read on every batch.
        goals = {
            "max_light_power": self.light.reflected_power(power_V),
            "min_electric_power": self.light.electric_power(d.sources, rect, flux),
            "match": match,
        }
        checks = self._checks(H, level) if self.intent_sets else []
        lighting = [chk.c - FEASIBILITY_TOL for chk in checks]
        lighting += [c - FEASIBILITY_TOL for _, _, c in self._epsilon_terms(goals)]
        penalty = self._penalty(lighting, len(checks), m)
        value = self._sign * goals[self.primary] / self.scales[self.primary] + penalty
        return value, penalty, goals, tuple(lighting)

    def _penalty(self, lighting: list, n_intent: int, m: int) -> np.ndarray:
        """P = sum W max(0, G)^pow over the lighting columns: intentions, then epsilon."""
        pw, weights = self.design.penalty_power, self._weights
        P = np.zeros(m)
        for j in range(n_intent):
            P += weights[j] * np.maximum(0.0, lighting[j]) ** pw
        P_eps = 0.0
        for j in range(n_intent, len(lighting)):
            P_eps = P_eps + weights[j] * np.maximum(0.0, lighting[j]) ** pw
        return P + P_eps

    def _match(self, V, cols, H, level: Level) -> np.ndarray:
        if level.divisor <= 1:
            return self.match.relative_error(self.light.op.zone_patches[cols], V[cols])
        rows = level.rows[level.match_pos]
        C = self.light.op.rho[rows, None] * H[level.match_pos]
        C_obj = self.C_obj[rows]
        return np.linalg.norm(C - C_obj[:, None], axis=0) / max(np.linalg.norm(C_obj), 1e-30)

    def _checks(self, H: np.ndarray, level: Level) -> list[BoundCheck]:
        """Every intention's bound checks on the batch's field H at the level's rows."""
        out = []
        rho = self.light.op.rho
        for i, it in enumerate(self.design.intentions):
            pos = level.intent_pos[i]
            q = quantity_values(it, H[pos], rho[level.rows[pos]])
            out += bound_checks(it, intention_stats(q, level.intent_w[i]))
        return out

    def _epsilon_terms(self, goals):
        for kind, bound in self.epsilon:
            if kind == GoalKind.MAX_LIGHT_POWER:
                c = (bound - goals[kind]) / max(abs(bound), 1e-12)
            else:
                c = (goals[kind] - bound) / max(abs(bound), 1e-12)
            yield kind, bound, c

    # -- one layout, judged on every patch ----------------------------------------------------
    def sources_at(self, x: np.ndarray) -> tuple:
        """The design's sources with the parameters of x filled in (tied rules applied)."""
        return self.vars.sources_at(x)

    def offending_patches(self, x: np.ndarray) -> list[tuple[str, str, np.ndarray]]:
        """Where the light of layout x breaks the intentions, judged on all patches:
        (intention name, bound, patch ids) for each violated bound (see
        ``LightField.offending_patches``). Empty when a geometric rule fails."""
        x = np.asarray(x, dtype=float)
        rect, _, _ = self.vars.decode(x[None])
        if not self.intent_sets or np.any(rule_violations(self.design, rect, self.zone_size) > 0):
            return []
        field = self.light.field(self.sources_at(x), self.design.daylight)
        return [
            (it.name, bound, ids)
            for it in self.design.intentions
            for bound, ids in field.offending_patches(it)
        ]

    def solution(self, x: np.ndarray, info: SolutionInfo | None = None) -> Solution:
        """A ``Solution`` for x judged on ALL patches, with every violation listed."""
        x = np.asarray(x, dtype=float)
        lv = self.level(1)
        ev = self.evaluate(x[None], lv)
        ngeo = len(rule_names(self.design))
        viol = [
            Violation(c.name, "geometry", float(g), float("nan"), float("nan"), "")
            for c, g in zip(self.constraints[:ngeo], ev.G[0, :ngeo], strict=True)
            if g > 0
        ]
        penalty = float("inf")
        if ev.ok[0]:
            # Penalty and violations from one computation, at the judging tolerance.
            excess: list[np.ndarray] = []
            if self.intent_sets:
                rect, flux, filt = self.vars.decode(x[None])
                d = self.design
                V = self.light.zone_emission(d.sources, rect, flux, filt, d.daylight)
                H = self.light.illuminance(V, lv.receivers, np.arange(V.shape[0]))
                checks = self._checks(H, lv)
                excess += [chk.c - JUDGED_TOL for chk in checks]
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
            n_intent = len(excess)
            for kind, bound, c in self._epsilon_terms(ev.goals):
                excess.append(c - JUDGED_TOL)
                if c[0] > JUDGED_TOL:
                    value = float(ev.goals[kind][0])
                    units = GOAL_UNITS[GoalKind(kind)]
                    viol.append(
                        Violation(f"epsilon {kind}", "epsilon", float(c[0]), value, bound, units)
                    )
            penalty = float(self._penalty(excess, n_intent, 1)[0])
        wanted = {g.kind for g in self.design.goals} | {k for k, _ in self.epsilon}
        objectives = {str(k): float(ev.goals[k][0]) for k in GoalKind if k in wanted}
        return Solution(
            self.sources_at(x),
            objectives,
            penalty,
            tuple(viol),
            tuple(float(v) for v in x),
            info if info is not None else SolutionInfo(),
        )


def electric_scale(design: Design, light: LightModel) -> float:
    """Largest electric power (W) of the sources: the scale of the power goal."""
    total = 0.0
    for s in design.sources:
        total += light.emission.full_electric_power(s)
    return max(total, 1e-9)
