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
- luminaire arrays (``design.arrays``) add their light from precomputed lattice
  responses (``light/arrays.py``) at the same receivers, and work-plane grids
  (``design.workplanes``) add their points as receivers (``light/grids.py``), so a
  candidate still costs O(receivers);
- the penalty (paper eq. 3) P = sum W * max(0, G)^pow over the lighting columns, W the
  intention's weight (``EPSILON_WEIGHT`` for epsilon bounds), pow the design's penalty
  power (default 2); the minimised value is the primary goal scaled to about [0, 1]
  plus P, so P dominates.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from lightinv_core.climate.metrics import lighting_kwh
from lightinv_core.design.geometry import rule_names, rule_violations
from lightinv_core.design.model import Design, DesignError
from lightinv_core.design.solution import Solution, SolutionInfo, Violation
from lightinv_core.design.variables import ArrayLayout, Variables
from lightinv_core.goals import goal_names, goal_spec, goal_specs
from lightinv_core.kinds import Bound, GoalKind, Scenario, SourceKind
from lightinv_core.light.arrays import (
    ArrayLight,
    array_light,
    array_shapes,
    arrays_field,
    resolve_product,
)
from lightinv_core.light.daylight import ScenarioLight
from lightinv_core.light.daylight_year import dimming_sum, sky_groups
from lightinv_core.light.grids import DesignGrids, design_grids
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
ARRAY_MARGIN = 0.005
"""Relative margin the search keeps on every intention bound when luminaire arrays are
lit from their lattice: the blend's error on the office benchmark's work plane is at most
0.07% on Em and 0.15% on U0 over 60 random layouts off the nodes
(bench/luminaire_arrays.py), well within it."""

__all__ = [
    "EPSILON_WEIGHT",
    "FEASIBILITY_TOL",
    "Constraint",
    "DesignProblem",
    "Evaluation",
    "GoalBatch",
]


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

    ``rows`` are patch ids; ``intent_pos[i]`` indexes the receivers for intention i and
    ``intent_w[i]`` holds the area each representative stands for (1 per grid point);
    ``match_pos`` indexes the representatives of all patches (match goal). The
    receivers are the ``rows`` then every work-plane grid point; ``arrays_R`` holds the
    luminaire arrays' responses at them (None without arrays).
    """

    divisor: int
    receivers: Receivers
    intent_pos: tuple[np.ndarray, ...]
    intent_w: tuple[np.ndarray, ...]
    match_pos: np.ndarray
    arrays_R: np.ndarray | None = None

    @property
    def rows(self) -> np.ndarray:
        """Patch ids of the representatives."""
        return self.receivers.rows


@dataclass(frozen=True)
class Lit:
    """The light of m candidates: ``V`` (nz, m) zone emission in the design scenario,
    ``by_kind`` its parts by source kind, ``cols`` the zone columns any candidate emits
    from; ``H`` (receivers, m) lux in the design scenario (None when no receiver is
    read) and, for designs judged in other scenarios, ``parts``: the luminaires' light
    and each sky group's daylight per exterior lux (``light/daylight.py``)."""

    V: np.ndarray
    by_kind: dict
    cols: np.ndarray
    H: np.ndarray | None
    parts: ScenarioLight | None = None


@dataclass(frozen=True)
class GoalBatch:
    """What a registered goal's ``GoalSpec.value`` reads for m lit candidates: the
    problem, the decoded variables (``rect`` (m, S, 4) m, ``flux`` (m, S) lm, ``filt``
    (m, S)), the arrays' ``layout`` (None without arrays), their light ``lit`` at the
    receivers of ``level``, and the built-in goals' values ``goals`` {kind: (m,)}."""

    problem: DesignProblem
    rect: np.ndarray
    flux: np.ndarray
    filt: np.ndarray
    layout: ArrayLayout | None
    lit: Lit
    level: Level
    goals: dict[str, np.ndarray]


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

    A design with luminaire arrays precomputes their responses at its first evaluation
    (tens of seconds for a room, so a window can make the problem at once and let the
    run's thread pay: ``progress(fraction)`` reports it, ``cancel()`` returning True
    stops it with ``CancelledError``); see ``light/arrays.py``.

    ``epsilon`` adds constraints on other goals for the epsilon-constraint method
    (paper eq. 10): pairs (goal kind, bound) meaning light power >= bound (lm) or
    electric power <= bound (W).
    """

    def __init__(
        self,
        design: Design,
        light: LightModel,
        epsilon: tuple = (),
        progress: Callable[[float], None] | None = None,
        cancel: Callable[[], bool] | None = None,
    ):
        self.design, self.light = design, light
        self.patches = light.patches
        sources = design.sources
        light.check((*sources, *design.target_sources))
        zones = {s.zone for s in sources} | {a.zone for a in design.arrays}
        self.vars = Variables(design, {z: light.zone_size(z) for z in zones})
        self.zone_size = self.vars.zone_size
        outlines = [self.patches.zone_outline(s.zone) for s in sources]
        self.outlines = tuple(outlines) if any(o is not None for o in outlines) else ()
        self.grids: DesignGrids | None = (
            design_grids(light, design.workplanes) if design.workplanes else None
        )
        # Grid intentions read points, not patches: no patch set.
        self.intent_sets = [
            None if i.grid is not None else intention_patches(i, self.patches)
            for i in design.intentions
        ]
        self._arrays: ArrayLight | None = None
        self._array_progress = (progress, cancel)
        self.array_shapes = (
            array_shapes(self.patches, design.arrays, design.workplanes) if design.arrays else None
        )
        self.products = [resolve_product(a.product, a.watts) for a in design.arrays]
        self.epsilon = tuple((str(k), float(b)) for k, b in epsilon)
        wanted = {str(g.kind) for g in design.goals} | {k for k, _ in self.epsilon}
        self.annual_goals = any(goal_spec(k).annual for k in wanted)
        # Scenarios other than the paper's design daylight need the light split into
        # the luminaires' and each sky group's (same GEMM columns, so the same cost).
        self.split = self.annual_goals or any(
            it.scenario != Scenario.DESIGN for it in design.intentions
        )
        self.sky = sky_groups(light, design) if self.split else None
        self._year_box: list = []  # the weather year, read at the first annual use
        plane = design.control_plane
        self.control = None if plane is None or self.grids is None else self.grids.spans[plane.name]
        if self.annual_goals and self.control is None:
            raise DesignError(
                "the annual energy and sDA goals are measured on a work plane: add one"
            )
        self.primary = str(design.goals[0].kind)
        self.objectives = tuple(g.kind for g in design.goals)
        self.scales = {
            GoalKind.MAX_LIGHT_POWER: light.power_scale(sources, design.daylight),
            GoalKind.MIN_ELECTRIC_POWER: electric_scale(design, light, self.products),
            GoalKind.MATCH: 1.0,
            GoalKind.MIN_INSTALLED_POWER: electric_scale(design, light, self.products),
            GoalKind.MIN_LUMINAIRE_COUNT: count_scale(design),
            GoalKind.MIN_ANNUAL_ENERGY: energy_scale(design, light, self.products),
            GoalKind.MAX_SDA: 1.0,
            GoalKind.MIN_GLAZING_AREA: glazing_scale(design, light),
        }
        # Registered goals compute their own value and scale (``GoalSpec``).
        self._registered = tuple(
            spec for spec in goal_specs() if spec.value is not None and spec.kind in wanted
        )
        for spec in self._registered:
            self.scales[spec.kind] = spec.scale(self) if spec.scale is not None else 1.0
        self.constraints = self._constraint_columns()
        self._weights = [c.weight for c in self.constraints if c.kind != "geometry"]
        self._senses = tuple(
            (str(k), -1.0 if goal_spec(k).maximise else 1.0) for k in self.objectives
        )
        self._sign = -1.0 if goal_spec(self.primary).maximise else 1.0
        light_goal = next((g for g in design.goals if g.kind == GoalKind.MAX_LIGHT_POWER), None)
        # The light-power goal counts its kinds' sources (all kinds when it names none).
        kinds = (light_goal.kinds if light_goal else ()) or tuple(SourceKind)
        self._power_kinds = tuple(str(k) for k in kinds)
        self._levels: dict[int, Level] = {}
        self.match = None
        if any(g.kind == GoalKind.MATCH for g in design.goals):
            self.match, self.C_obj = light.match_target(design.target_sources, design.daylight)

    def _patch_rows(self) -> np.ndarray:
        """Every patch any level may read: the patch intentions' (and the match goal's)."""
        sets = [s for s in self.intent_sets if s is not None]
        if any(g.kind == GoalKind.MATCH for g in self.design.goals):
            sets.append(np.arange(self.patches.n))
        return np.unique(np.concatenate(sets)) if sets else np.zeros(0, np.int64)

    @property
    def arrays(self) -> ArrayLight | None:
        """The luminaire arrays' precomputed responses (None without arrays), computed on
        first use: the first evaluation, in the thread that runs the search."""
        if self.design.arrays and self._arrays is None:
            progress, cancel = self._array_progress
            self._arrays = array_light(
                self.patches,
                self.light.op,
                self.design.arrays,
                self._patch_rows(),
                None if self.grids is None else self.grids.points,
                progress,
                cancel,
            )
        return self._arrays

    def layout_of(self, X: np.ndarray) -> ArrayLayout | None:
        """The luminaire arrays of candidates X (None without arrays)."""
        return self.vars.decode_arrays(X) if self.design.arrays else None

    def rule_violations(self, X: np.ndarray) -> np.ndarray:
        """(m, R) relative violations of the geometric rules (sources and arrays) of X."""
        rect, _, _ = self.vars.decode(X)
        lay = self.layout_of(X)
        arrays = None if lay is None else (lay, self.array_shapes)
        return rule_violations(self.design, rect, self.zone_size, arrays, self.outlines)

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
        sets = [s for s in self.intent_sets if s is not None]
        if self.match is not None:
            sets.append(np.arange(n))
        reps = [representatives(self.patches, s, labels) for s in sets]
        rows = np.unique(np.concatenate([r for r, _ in reps])) if reps else np.zeros(0, int)
        patch_pos = [np.searchsorted(rows, r) for r, _ in reps]
        match_pos = patch_pos.pop() if self.match is not None else np.zeros(0, int)
        patch_w = [w for _, w in reps][: len(patch_pos)]
        pos, weights = [], []
        for it in self.design.intentions:
            if it.grid is None:
                pos.append(patch_pos.pop(0))
                weights.append(patch_w.pop(0))
            else:
                span = self.grids.spans[it.grid]
                pos.append(len(rows) + np.arange(span.start, span.stop))
                weights.append(np.ones(span.stop - span.start))
        receivers = self.light.receivers(rows)
        if self.grids is not None and len(self.grids.points):
            top = receivers.Phi_rows
            if top is None:  # over the basis budget: the rows from the factors, once
                top = self.light.op.phi_rows(rows)
            receivers = Receivers(rows, np.asfortranarray(np.vstack([top, self.grids.Phi])))
        arrays_R = None
        if self.arrays is not None:
            at = np.searchsorted(self.arrays.rows, rows)
            q = self.arrays.n_points
            idx = np.concatenate([at, len(self.arrays.rows) + np.arange(q)])
            arrays_R = np.ascontiguousarray(self.arrays.R[idx])
        lv = Level(divisor, receivers, tuple(pos), tuple(weights), match_pos, arrays_R)
        self._levels[divisor] = lv
        return lv

    # -- evaluation ---------------------------------------------------------------------------
    def evaluate(self, X: np.ndarray, level: Level | None = None) -> Evaluation:
        """Score the candidates X (m, nvar) at ``level`` (default: all patches)."""
        level = level or self.level(1)
        X = np.atleast_2d(np.asarray(X, dtype=float))
        m = len(X)
        rect, flux, filt = self.vars.decode(X)
        lay = self.layout_of(X)
        arrays = None if lay is None else (lay, self.array_shapes)
        geo = rule_violations(self.design, rect, self.zone_size, arrays, self.outlines)
        ok = ~np.any(geo > 0, axis=1)
        good = np.flatnonzero(ok)
        if len(good) == m:
            # Every candidate was lit (the usual case): no scatter into full arrays.
            value, penalty, goals, lighting = self._score(rect, flux, filt, level, lay)
        else:
            value, penalty = np.full(m, np.inf), np.full(m, np.inf)
            goals = {k: np.full(m, np.nan) for k in goal_names()}
            lighting = ()
            if len(good):
                sub = None if lay is None else lay.take(good)
                v, p, g, lighting = self._score(rect[good], flux[good], filt[good], level, sub)
                value[good], penalty[good] = v, p
                for k in goals:
                    goals[k][good] = g[k]
        return Evaluation(value, penalty, ok, goals, len(good), geo, lighting, self._senses)

    def _light(
        self,
        rect,
        flux,
        filt,
        level: Level,
        lay: ArrayLayout | None,
        arrays_H: np.ndarray | None = None,
    ) -> Lit:
        """The light of m candidates (see ``Lit``): zone sources plus arrays, lit from
        the lattice blend for ``lay`` or, given, the arrays' exact light ``arrays_H``."""
        d = self.design
        m = rect.shape[0]
        nz = len(self.light.op.zone_patches)
        if self.split:
            return self._split_light(rect, flux, filt, level, lay, arrays_H)
        if d.sources:
            V, by_kind = self.light.zone_emission(
                d.sources, rect, flux, filt, d.daylight, split_kinds=True
            )
        else:
            V = np.zeros((nz, m), np.float32)
            by_kind = {str(k): V for k in SourceKind}
        cols = np.flatnonzero(np.any(V != 0, axis=1))
        H = None
        if self._needs_field(level):
            H = self._receiver_light(V, cols, level, lay, arrays_H)
        return Lit(V, by_kind, cols, H)

    def _needs_field(self, level: Level) -> bool:
        # At the full level the match error comes from the Gram matrix, not the field.
        need = bool(self.design.intentions) or self.split
        need = need or (self.match is not None and level.divisor > 1)
        Phi = level.receivers.Phi_rows
        return need and (Phi is None or Phi.shape[0] > 0)

    def _receiver_light(self, V, cols, level: Level, lay, arrays_H=None) -> np.ndarray:
        """Lux at the level's receivers of emission V (nz, m) plus the arrays' light."""
        H = None
        blend = level.arrays_R is not None and arrays_H is None and lay is not None
        if len(cols) or not (blend or arrays_H is not None):
            H = self.light.illuminance(V, level.receivers, cols)
        if blend:
            lit = level.arrays_R @ self.arrays.weights(lay)
            H = lit if H is None else H + lit
        elif arrays_H is not None:
            H = arrays_H if H is None else H + arrays_H
        return H

    def _split_light(self, rect, flux, filt, level: Level, lay, arrays_H) -> Lit:
        """``_light`` for designs judged in several scenarios: the luminaires' light and
        each sky group's daylight per exterior lux, computed apart."""
        d = self.design
        m = rect.shape[0]
        nz = len(self.light.op.zone_patches)
        ext = d.daylight.exterior_lux
        if d.sources:
            unit = replace(d.daylight, exterior_lux=1.0)
            _, by_unit = self.light.zone_emission(
                d.sources, rect, flux, filt, unit, split_kinds=True
            )
            V_lum, V_sky = by_unit[SourceKind.LUMINAIRE], by_unit[SourceKind.SKYLIGHT]
        else:
            V_lum = V_sky = np.zeros((nz, m), np.float32)
        V = V_lum + np.float32(ext) * V_sky
        by_kind = {SourceKind.LUMINAIRE.value: V_lum, SourceKind.SKYLIGHT.value: ext * V_sky}
        cols = np.flatnonzero(np.any(V != 0, axis=1))
        if not self._needs_field(level):
            return Lit(V, by_kind, cols, None)
        lum_cols = np.flatnonzero(np.any(V_lum != 0, axis=1))
        electric = self._receiver_light(V_lum, lum_cols, level, lay, arrays_H)
        if electric is None:
            electric = np.zeros((len(level.rows) + self._points(), m))
        sky = np.zeros((self.sky.count, *electric.shape))
        for g, gcols in enumerate(self.sky.cols):
            on = gcols[np.any(V_sky[gcols] != 0, axis=1)]
            if not len(on):
                continue
            Vg = V_sky
            if self.sky.count > 1:  # only this group's rows (the product may read all)
                Vg = np.zeros_like(V_sky)
                Vg[on] = V_sky[on]
            sky[g] = self.light.illuminance(Vg, level.receivers, on)
        parts = ScenarioLight(d.daylight, self.sky, electric, sky, self._year_box)
        return Lit(V, by_kind, cols, parts.lux(Scenario.DESIGN), parts)

    def _points(self) -> int:
        return 0 if self.grids is None else len(self.grids.points)

    def _score(self, rect, flux, filt, level: Level, lay: ArrayLayout | None = None):
        """Value, penalty, goals and lighting constraint columns (c - tol, each (m,)) of
        m lit candidates."""
        d = self.design
        lit = self._light(rect, flux, filt, level, lay)
        V, by_kind, cols, H = lit.V, lit.by_kind, lit.cols, lit.H
        m = V.shape[1]
        match = self._match(V, cols, H, level) if self.match is not None else np.zeros(m)
        power_V = sum(by_kind[k] for k in self._power_kinds)
        electric = self.light.electric_power(d.sources, rect, flux) if d.sources else np.zeros(m)
        installed = installed_power(d, self.light) * np.ones(m)
        count = np.full(m, float(luminaire_sources(d)))
        if lay is not None:
            electric = electric + self.arrays.electric_power(lay)
            installed = installed + self.arrays.installed_power(lay)
            count = count + lay.count.sum(axis=1)
        # Plain-string keys: this dict is read on every batch.
        goals = {
            "max_light_power": self.light.reflected_power(power_V),
            "min_electric_power": electric,
            "match": match,
            "min_installed_power": installed,
            "min_luminaire_count": count,
            "min_glazing_area": self._glazing_area(rect),
            "min_annual_energy": np.full(m, np.nan),
            "max_sda": np.full(m, np.nan),
        }
        if self.annual_goals:
            energy, sda = self._annual_goals(lit, level, electric)
            goals["min_annual_energy"], goals["max_sda"] = energy, sda
        goals.update(self._registered_goals(rect, flux, filt, lay, lit, level, goals))
        checks = self._checks(lit, level) if self.design.intentions else []
        # With arrays the search reads the lattice blend: it keeps a margin for the
        # blend's error, so the layout also holds judged with the luminaires placed exactly.
        margin = ARRAY_MARGIN if self.design.arrays else 0.0
        lighting = [chk.c - FEASIBILITY_TOL + margin for chk in checks]
        lighting += [c - FEASIBILITY_TOL for _, _, c in self._epsilon_terms(goals)]
        penalty = self._penalty(lighting, len(checks), m)
        value = self._sign * goals[self.primary] / self.scales[self.primary] + penalty
        return value, penalty, goals, tuple(lighting)

    def _registered_goals(self, rect, flux, filt, lay, lit, level, goals) -> dict:
        """The values of the registered goals: the wanted ones from their spec, NaN for
        the others (every goal kind is a key of an evaluation's goals)."""
        m = rect.shape[0]
        out = {k: np.full(m, np.nan) for k in goal_names() if k not in goals}
        if self._registered:
            batch = GoalBatch(self, rect, flux, filt, lay, lit, level, goals)
            for spec in self._registered:
                out[spec.kind] = np.asarray(spec.value(batch), dtype=float)
        return out

    def _glazing_area(self, rect: np.ndarray) -> np.ndarray:
        """Total area (m²) of the skylight sources of m candidates (rect (m, S, 4))."""
        sky = [j for j, s in enumerate(self.design.sources) if s.kind == SourceKind.SKYLIGHT]
        if not sky:
            return np.zeros(rect.shape[0])
        r = rect[:, sky]
        return (np.abs(r[..., 2] - r[..., 0]) * np.abs(r[..., 3] - r[..., 1])).sum(axis=1)

    def _annual_goals(self, lit: Lit, level: Level, electric: np.ndarray):
        """(annual energy kWh, sDA) of m candidates on the control work plane."""
        d, parts = self.design.daylight, lit.parts
        idx = len(level.rows) + np.arange(self.control.start, self.control.stop)
        year = parts.year()
        full = parts.electric[idx].mean(axis=0)
        # Without skylights there are no sky groups: b is (m, 0) and the daylight zero.
        b = parts.sky[:, idx].mean(axis=1).T
        levels = dimming_sum(year, b, full, d.target_lux, d.min_level)
        energy = lighting_kwh(electric, levels, d.standby_w, year.every.shape[1])
        sda = parts.sda_mark(idx).mean(axis=0)
        return energy, sda

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

    def _checks(self, lit: Lit, level: Level) -> list[BoundCheck]:
        """Every intention's bound checks on the batch's light at the level's rows."""
        out = []
        rho = self.light.op.rho
        for i, it in enumerate(self.design.intentions):
            pos = level.intent_pos[i]
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

    def _epsilon_terms(self, goals):
        for kind, bound in self.epsilon:
            if goal_spec(kind).maximise:
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
        patch_intentions = [it for it in self.design.intentions if it.grid is None]
        if not patch_intentions or np.any(self.rule_violations(x[None]) > 0):
            return []
        field = self.light.field(self.sources_at(x), self.design.daylight)
        if self.design.arrays:
            H, _ = arrays_field(self.patches, self.light.op, self.arrays_at(x))
            field = replace(field, illuminance=field.illuminance + H)
        return [
            (it.name, bound, ids)
            for it in patch_intentions
            for bound, ids in field.offending_patches(it)
        ]

    def _judged_light(self, x: np.ndarray, lv: Level) -> Lit:
        """The light of layout x at level ``lv``'s receivers, its arrays placed exactly
        (not blended from the lattice): what a solution is judged on."""
        rect, flux, filt = self.vars.decode(x[None])
        if not self.design.arrays:
            return self._light(rect, flux, filt, lv, None)
        points = None if self.grids is None else self.grids.points
        Hp, Hq = arrays_field(self.patches, self.light.op, self.arrays_at(x), points)
        exact = np.concatenate([Hp[lv.rows], Hq])[:, None]
        return self._light(rect, flux, filt, lv, None, arrays_H=exact)

    def arrays_at(self, x: np.ndarray) -> tuple:
        """The design's luminaire arrays with the parameters of x filled in."""
        return self.vars.arrays_at(x)

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
        goals = ev.goals
        if ev.ok[0]:
            # Penalty and violations from one computation, at the judging tolerance.
            excess: list[np.ndarray] = []
            judged = None
            if self.design.intentions or (self.annual_goals and self.design.arrays):
                judged = self._judged_light(x, lv)
            if self.annual_goals and self.design.arrays:
                # The year's goals from the arrays placed exactly, as the intentions.
                energy, sda = self._annual_goals(judged, lv, ev.goals["min_electric_power"])
                goals = {**ev.goals, "min_annual_energy": energy, "max_sda": sda}
            if self.design.intentions:
                checks = self._checks(judged, lv)
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
            for kind, bound, c in self._epsilon_terms(goals):
                excess.append(c - JUDGED_TOL)
                if c[0] > JUDGED_TOL:
                    value = float(goals[kind][0])
                    units = goal_spec(kind).unit
                    viol.append(
                        Violation(f"epsilon {kind}", "epsilon", float(c[0]), value, bound, units)
                    )
            penalty = float(self._penalty(excess, n_intent, 1)[0])
        wanted = {g.kind for g in self.design.goals} | {k for k, _ in self.epsilon}
        objectives = {s.kind: float(goals[s.kind][0]) for s in goal_specs() if s.kind in wanted}
        return Solution(
            self.sources_at(x),
            objectives,
            penalty,
            tuple(viol),
            tuple(float(v) for v in x),
            info if info is not None else SolutionInfo(),
            self.arrays_at(x),
        )


def electric_scale(design: Design, light: LightModel, products=()) -> float:
    """Largest electric power (W) of the sources and arrays (their ``products``): the
    scale of the power goals."""
    total = 0.0
    for s in design.sources:
        total += light.emission.full_electric_power(s)
    if products:
        for a, prod in zip(design.arrays, products, strict=True):
            total += a.rows_range[1] * a.columns_range[1] * prod.watts
    return max(total, 1e-9)


def count_scale(design: Design) -> float:
    """Most luminaires the design can have: the scale of the count goal."""
    most = luminaire_sources(design) + sum(
        a.rows_range[1] * a.columns_range[1] for a in design.arrays
    )
    return float(max(most, 1))


def luminaire_sources(design: Design) -> int:
    """Luminaire sources (rectangles) of the design: one luminaire each."""
    return sum(1 for s in design.sources if s.kind == SourceKind.LUMINAIRE)


def installed_power(design: Design, light: LightModel) -> float:
    """Rated power (W) of the luminaire sources at their flux as written (free fluxes
    count at their range's top)."""
    total = 0.0
    for s in design.sources:
        if s.kind != SourceKind.LUMINAIRE:
            continue
        if "flux" in s.free:
            total += light.emission.full_electric_power(s)
        elif s.flux is not None:
            total += s.flux / s.efficacy
        else:
            total += light.emission.full_electric_power(s)
    return total


def energy_scale(design: Design, light: LightModel, products=()) -> float:
    """Energy (kWh) of every luminaire at full output all year plus standby: the scale
    of the annual-energy goal."""
    hours = 8760.0
    return max(
        (electric_scale(design, light, products) + design.daylight.standby_w) * hours / 1e3, 1e-9
    )


def glazing_scale(design: Design, light: LightModel) -> float:
    """Area (m²) of the skylight sources' zones: the scale of the glazing-area goal."""
    zones = {s.zone for s in design.sources if s.kind == SourceKind.SKYLIGHT}
    total = sum(light.zone_size(z)[0] * light.zone_size(z)[1] for z in zones)
    return max(total, 1e-9)
