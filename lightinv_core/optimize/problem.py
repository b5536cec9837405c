"""``DesignProblem``: evaluates f(x) + P(x) for stacks of candidate source layouts.

Per batch (m candidates): decode the variables, reject candidates breaking a
geometric rule (no radiosity), build the zone emission matrix (nz, m), get the
illuminance at the rows the intentions and goals need from the operator's zone
basis in one GEMM, and score.

Penalty (paper eq. 3): P = sum over constraints W * max(0, c - tol)^pow, where
c is the relative violation (0.05 = 5% past the bound), W the intention's
weight (default 100), pow the design's penalty power (default 2) and tol =
``FEASIBILITY_TOL`` = 0.1%, the precision to which a bound counts as met. Each
intention gives one c per bound: its worst patch for min/max, its area-weighted
mean for average, min/mean for uniformity. The minimised value is the primary
goal scaled to about [0, 1] (``goal_scale``) plus P, so P dominates.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightinv_core.design.geometry import rule_violations
from lightinv_core.design.model import Design, DesignError
from lightinv_core.design.variables import Variables
from lightinv_core.operator.clustering import cluster_patches
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.emission import EmissionBuilder

FEASIBILITY_TOL = 1e-3
EPSILON_WEIGHT = 100.0


@dataclass(frozen=True)
class Level:
    """Rows evaluated at one multilevel stage (divisor d: about n/d representatives).

    ``rows`` are patch ids; ``intent_pos[i]`` indexes ``rows`` for intention i and
    ``intent_w[i]`` holds the area each representative stands for;
    ``match_pos`` indexes the representatives of all patches (match goal).
    """

    divisor: int
    rows: np.ndarray
    Phi_rows: np.ndarray | None
    intent_pos: tuple[np.ndarray, ...]
    intent_w: tuple[np.ndarray, ...]
    match_pos: np.ndarray


@dataclass(frozen=True)
class Evaluation:
    """Scores of a batch: ``value`` = scaled primary goal + ``penalty`` (inf where a
    geometric rule fails, ``ok`` False); ``goals`` in their units per goal kind;
    ``evaluated`` counts radiosity evaluations (the candidates with ``ok``)."""

    value: np.ndarray
    penalty: np.ndarray
    ok: np.ndarray
    goals: dict[str, np.ndarray]
    evaluated: int


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
    """A design bound to a scene, its patches and its radiosity operator.

    ``epsilon`` adds constraints on other goals for the epsilon-constraint method
    (paper eq. 10): pairs (goal kind, bound) meaning light power >= bound (lm) or
    electric power <= bound (W).
    """

    def __init__(
        self,
        design: Design,
        scene: Scene,
        patches: Patches,
        operator: RadiosityOperator,
        epsilon: tuple[tuple[str, float], ...] = (),
    ):
        if operator.n != patches.n or operator.digest != patches.digest():
            raise DesignError("the radiosity operator was built for another scene")
        self.design, self.scene, self.patches, self.op = design, scene, patches, operator
        self.emission = EmissionBuilder(design, scene, patches, operator)
        self.vars = Variables(design, self.emission.zone_sizes())
        self.zone_size = self.vars.zone_size
        self.intent_sets = [self._intention_patches(i) for i in design.intentions]
        self.epsilon = tuple((str(k), float(b)) for k, b in epsilon)
        self.primary = design.goals[0].kind
        self.scales = {
            "max_light_power": self.emission.light_power_scale(),
            "min_electric_power": self.emission.electric_power_scale(),
            "match": 1.0,
        }
        self._levels: dict[int, Level] = {}
        self.match = None
        if any(g.kind == "match" for g in design.goals):
            e_obj = self.emission.matrix(*self.emission.decode_sources(design.target_sources))
            self.e_obj = e_obj[:, 0]
            self.match = operator.match_target(operator.zone_patches, self.e_obj)
            self.C_obj = operator.rho * (operator.Phi @ self.e_obj)

    def _intention_patches(self, it) -> np.ndarray:
        if it.patches is not None:
            idx = np.asarray(it.patches, dtype=np.int64)
            bad = idx[(idx < 0) | (idx >= self.patches.n)]
            if len(bad):
                raise DesignError(
                    f"intention {it.name!r}: patch id {int(bad[0])} is not in the scene "
                    f"(ids 0..{self.patches.n - 1}); pick the patches again on this mesh"
                )
            return np.unique(idx)
        if it.group == "*":
            return np.arange(self.patches.n)
        if it.group not in self.patches.group_names:
            known = ", ".join(self.patches.group_names)
            raise DesignError(
                f"intention {it.name!r}: no group {it.group!r} in the scene (groups: {known})"
            )
        return self.patches.group_index(it.group)

    # -- levels -----------------------------------------------------------------------------
    def level(self, divisor: int = 1) -> Level:
        """The representative rows for divisor d (1 = every patch)."""
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
        # Column-major so a batch's columns are contiguous; None when every row is needed.
        Phi_rows = None if len(rows) == n else np.asfortranarray(self.op.Phi[rows])
        lv = Level(divisor, rows, Phi_rows, tuple(pos), tuple(weights), match_pos)
        self._levels[divisor] = lv
        return lv

    # -- evaluation -------------------------------------------------------------------------
    def evaluate(self, X: np.ndarray, level: Level | None = None) -> Evaluation:
        """Score the candidates X (m, nvar) at ``level`` (default: all patches)."""
        level = level or self.level(1)
        X = np.atleast_2d(np.asarray(X, dtype=float))
        m = len(X)
        rect, flux, filt = self.vars.decode(X)
        geo = rule_violations(self.design, rect, self.zone_size)
        ok = ~np.any(geo > 0, axis=1)
        value = np.full(m, np.inf)
        penalty = np.full(m, np.inf)
        goals = {k: np.full(m, np.nan) for k in ("max_light_power", "min_electric_power", "match")}
        good = np.flatnonzero(ok)
        if len(good):
            v, p, g = self._score(rect[good], flux[good], filt[good], level)
            value[good], penalty[good] = v, p
            for k in goals:
                goals[k][good] = g[k]
        return Evaluation(value, penalty, ok, goals, len(good))

    def _score(self, rect, flux, filt, level: Level):
        V, by_kind = self.emission.matrix(rect, flux, filt, split_kinds=True)
        cols = np.flatnonzero(np.any(V != 0, axis=1))
        m = V.shape[1]
        # At the full level the match error comes from the Gram matrix, not the field.
        need_field = bool(self.intent_sets) or (self.match is not None and level.divisor > 1)
        H = self._field(level, V, cols) if need_field and len(level.rows) else None
        goals = {
            "max_light_power": self.emission.light_power(by_kind, self.design.goals),
            "min_electric_power": self.emission.electric_power(rect, flux),
            "match": self._match(V, cols, H, level) if self.match is not None else np.zeros(m),
        }
        penalty = self._intention_penalty(H, level) if self.intent_sets else np.zeros(m)
        penalty = penalty + self._epsilon_penalty(goals)
        sign = -1.0 if self.primary == "max_light_power" else 1.0
        value = sign * goals[self.primary] / self.scales[self.primary] + penalty
        return value, penalty, goals

    def _field(self, level: Level, V: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """H (lux) at the level's rows for the batch V (nz, m), one GEMM."""
        Phi = self.op.Phi if level.Phi_rows is None else level.Phi_rows
        if 3 * len(cols) > V.shape[0]:
            return Phi @ V
        return Phi[:, cols] @ V[cols]

    def _match(self, V, cols, H, level: Level) -> np.ndarray:
        if level.divisor <= 1:
            return self.match.relative_error(self.op.zone_patches[cols], V[cols])
        rows = level.rows[level.match_pos]
        C = self.op.rho[rows, None] * H[level.match_pos]
        C_obj = self.C_obj[rows]
        return np.linalg.norm(C - C_obj[:, None], axis=0) / max(np.linalg.norm(C_obj), 1e-30)

    def _violation_terms(self, H, level: Level):
        """Per intention and bound: (intention, bound name, relative c (m,), value, bound)."""
        out = []
        for i, it in enumerate(self.design.intentions):
            rows = level.rows[level.intent_pos[i]]
            q = H[level.intent_pos[i]].astype(np.float64)
            if it.quantity == "C":
                q = q * self.op.rho[rows, None]
            w = level.intent_w[i][:, None]
            avg = (q * w).sum(axis=0) / w.sum()
            qmin, qmax = q.min(axis=0), q.max(axis=0)
            if it.min is not None and it.min > 0:
                out.append((it, "min", (it.min - qmin) / it.min, qmin, it.min))
            if it.max is not None:
                out.append((it, "max", (qmax - it.max) / max(it.max, 1e-12), qmax, it.max))
            if it.average is not None and it.average > 0:
                out.append((it, "average", (it.average - avg) / it.average, avg, it.average))
            if it.uniformity is not None and it.uniformity > 0:
                u0 = qmin / np.maximum(avg, 1e-30)
                out.append(
                    (it, "uniformity", (it.uniformity - u0) / it.uniformity, u0, it.uniformity)
                )
        return out

    def _intention_penalty(self, H, level: Level) -> np.ndarray:
        pw = self.design.penalty_power
        P = np.zeros(H.shape[1])
        for it, _, c, _, _ in self._violation_terms(H, level):
            P += it.weight * np.maximum(0.0, c - FEASIBILITY_TOL) ** pw
        return P

    def _epsilon_terms(self, goals):
        for kind, bound in self.epsilon:
            if kind == "max_light_power":
                c = (bound - goals[kind]) / max(abs(bound), 1e-12)
            else:
                c = (goals[kind] - bound) / max(abs(bound), 1e-12)
            yield kind, bound, c

    def _epsilon_penalty(self, goals) -> np.ndarray:
        pw = self.design.penalty_power
        P = 0.0
        for _, _, c in self._epsilon_terms(goals):
            P = P + EPSILON_WEIGHT * np.maximum(0.0, c - FEASIBILITY_TOL) ** pw
        return P

    # -- reporting --------------------------------------------------------------------------
    def offending_patches(self, x: np.ndarray) -> list[tuple[str, str, np.ndarray]]:
        """Where the light of layout x breaks the intentions, judged on all patches.

        Returns (intention name, bound, patch ids) for each violated bound: for "min"
        the patches below it, for "max" those above it, for "uniformity" those below
        U0 times the mean, for "average" every patch of the intention (the mean is
        short as a whole). Empty when every intention is met or a geometric rule
        fails (then no light is computed).
        """
        x = np.asarray(x, dtype=float)
        rect, flux, filt = self.vars.decode(x[None])
        if not self.intent_sets or np.any(rule_violations(self.design, rect, self.zone_size) > 0):
            return []
        lv = self.level(1)
        V = self.emission.matrix(rect, flux, filt)
        H = self._field(lv, V, np.arange(V.shape[0]))
        out = []
        for it, bound, c, _, limit in self._violation_terms(H, lv):
            if c[0] <= FEASIBILITY_TOL:
                continue
            i = self.design.intentions.index(it)
            rows = lv.rows[lv.intent_pos[i]]
            q = H[lv.intent_pos[i], 0].astype(np.float64)
            if it.quantity == "C":
                q = q * self.op.rho[rows]
            if bound == "min":
                bad = q < limit
            elif bound == "max":
                bad = q > limit
            elif bound == "uniformity":
                w = lv.intent_w[i]
                bad = q < limit * float((q * w).sum() / w.sum())
            else:
                bad = np.ones(len(q), bool)
            # At level 1 each representative is its patch; the rows are patch ids.
            out.append((it.name, bound, np.unique(rows[bad])))
        return out

    def sources_at(self, x: np.ndarray) -> tuple:
        """The design's sources with the parameters of x filled in."""
        from dataclasses import replace

        rect, flux, filt = self.vars.decode(np.asarray(x, dtype=float)[None])
        out = []
        for j, s in enumerate(self.design.sources):
            kw = {"rect": tuple(float(c) for c in rect[0, j])}
            if s.kind == "skylight":
                kw["filter"] = float(filt[0, j])
            elif s.flux is not None:
                kw["flux"] = float(flux[0, j])
            out.append(replace(s, **kw))
        return tuple(out)

    def solution(self, x: np.ndarray, info: dict | None = None):
        """A ``Solution`` for x judged on ALL patches, with every violation listed."""
        from lightinv_core.design.geometry import rule_names
        from lightinv_core.design.solution import Solution, Violation

        x = np.asarray(x, dtype=float)
        rect, flux, filt = self.vars.decode(x[None])
        viol = []
        geo = rule_violations(self.design, rect, self.zone_size)[0]
        for name, amount in zip(rule_names(self.design), geo, strict=True):
            if amount > 0:
                viol.append(
                    Violation(name, "geometry", float(amount), float("nan"), float("nan"), "")
                )
        ev = self.evaluate(x[None], self.level(1))
        goals = {k: float(v[0]) for k, v in ev.goals.items()}
        if ev.ok[0]:
            lv = self.level(1)
            V = self.emission.matrix(rect, flux, filt)
            H = self._field(lv, V, np.arange(V.shape[0])) if self.intent_sets else None
            if H is not None:
                for it, bound, c, value, limit in self._violation_terms(H, lv):
                    if c[0] > FEASIBILITY_TOL:
                        units = (
                            ""
                            if bound == "uniformity"
                            else ("lux" if it.quantity == "lux" else "lm/m²")
                        )
                        viol.append(
                            Violation(
                                it.name, bound, float(c[0]), float(value[0]), float(limit), units
                            )
                        )
            for kind, bound, c in self._epsilon_terms(ev.goals):
                if c[0] > FEASIBILITY_TOL:
                    units = "lm" if kind == "max_light_power" else "W"
                    viol.append(
                        Violation(
                            f"epsilon {kind}",
                            "epsilon",
                            float(c[0]),
                            float(ev.goals[kind][0]),
                            bound,
                            units,
                        )
                    )
        wanted = {g.kind for g in self.design.goals} | {k for k, _ in self.epsilon}
        objectives = {
            k: goals[k] for k in ("max_light_power", "min_electric_power", "match") if k in wanted
        }
        penalty = float(ev.penalty[0]) if ev.ok[0] else float("inf")
        return Solution(
            self.sources_at(x),
            objectives,
            penalty,
            tuple(viol),
            tuple(float(v) for v in x),
            dict(info or {}),
        )
