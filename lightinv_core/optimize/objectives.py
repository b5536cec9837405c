"""The goals of a design as a problem scores them: the goal list, their scales, their
values for a batch of lit candidates (``GoalBatch`` for registered goals), and the
annual goals read from the weather year.

Every goal kind has a value for every candidate (NaN where the design does not ask for
it); a goal is minimised as ``sign * value / scale``, sign -1 for a maximised goal
(``GoalSpec.maximise``), the scale its size for this design (W, lm, kWh, m², a count).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from lightinv_core.climate.metrics import lighting_kwh
from lightinv_core.design.model import Design
from lightinv_core.design.variables import ArrayLayout
from lightinv_core.goals import goal_names, goal_spec, goal_specs
from lightinv_core.kinds import GoalKind
from lightinv_core.light.arrays import ArrayLight
from lightinv_core.light.daylight_year import dimming_sum
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.candidate_light import Lit
from lightinv_core.optimize.levels import Level
from lightinv_core.sources.types import daylit, electric, source_type, source_types


class ScoredProblem(Protocol):
    """What the goals read of their problem (``DesignProblem``); a registered goal's
    ``value`` and ``scale`` get the problem itself."""

    design: Design
    light: LightModel
    products: list
    control: object
    match: object
    C_obj: np.ndarray

    @property
    def arrays(self) -> ArrayLight | None: ...


@dataclass(frozen=True)
class GoalBatch:
    """What a registered goal's ``GoalSpec.value`` reads for m lit candidates: the
    problem, the decoded variables (``rect`` (m, S, 4) m, ``flux`` (m, S) lm, ``filt``
    (m, S)), the arrays' ``layout`` (None without arrays), their light ``lit`` at the
    receivers of ``level``, and the built-in goals' values ``goals`` {kind: (m,)}."""

    problem: ScoredProblem
    rect: np.ndarray
    flux: np.ndarray
    filt: np.ndarray
    layout: ArrayLayout | None
    lit: Lit
    level: Level
    goals: dict[str, np.ndarray]


def wanted_goals(design: Design, epsilon: tuple) -> set[str]:
    """The goal kinds a problem computes: the design's goals and its epsilon bounds'."""
    return {str(g.kind) for g in design.goals} | {k for k, _ in epsilon}


class DesignGoals:
    """The goals of one problem: ``primary`` (the minimised one), ``objectives`` in the
    design's order, ``scales`` {kind: size}, and their values for a batch (``values``).
    ``annual``: a wanted goal needs the weather year."""

    def __init__(self, problem: ScoredProblem, epsilon: tuple):
        design, light, products = problem.design, problem.light, problem.products
        self.problem = problem
        wanted = wanted_goals(design, epsilon)
        self.annual = any(goal_spec(k).annual for k in wanted)
        self.primary = str(design.goals[0].kind)
        self.objectives = tuple(g.kind for g in design.goals)
        self.scales = {
            GoalKind.MAX_LIGHT_POWER: light.power_scale(design.sources, design.daylight),
            GoalKind.MIN_ELECTRIC_POWER: electric_scale(design, light, products),
            GoalKind.MATCH: 1.0,
            GoalKind.MIN_INSTALLED_POWER: electric_scale(design, light, products),
            GoalKind.MIN_LUMINAIRE_COUNT: count_scale(design),
            GoalKind.MIN_ANNUAL_ENERGY: energy_scale(design, light, products),
            GoalKind.MAX_SDA: 1.0,
            GoalKind.MIN_GLAZING_AREA: glazing_scale(design, light),
        }
        # Registered goals compute their own value and scale (``GoalSpec``).
        self.registered = tuple(
            spec for spec in goal_specs() if spec.value is not None and spec.kind in wanted
        )
        for spec in self.registered:
            self.scales[spec.kind] = spec.scale(problem) if spec.scale is not None else 1.0
        self.senses = tuple(
            (str(k), -1.0 if goal_spec(k).maximise else 1.0) for k in self.objectives
        )
        self.sign = -1.0 if goal_spec(self.primary).maximise else 1.0
        self.power_kinds = light_power_kinds(design)
        # What does not change from candidate to candidate, read once.
        self._glazed = [j for j, s in enumerate(design.sources) if source_type(s.kind).daylit]
        self._installed = installed_power(design, light)
        self._count = float(luminaire_sources(design))

    def scaled_primary(self, goals: dict[str, np.ndarray]) -> np.ndarray:
        """The primary goal as minimised, scaled to about [0, 1]."""
        return self.sign * goals[self.primary] / self.scales[self.primary]

    def values(self, rect, flux, filt, level: Level, lay: ArrayLayout | None, lit: Lit) -> dict:
        """{goal kind: (m,)} of m lit candidates, every kind (NaN where not computed)."""
        p = self.problem
        d = p.design
        V, by_kind, cols, H = lit.V, lit.by_kind, lit.cols, lit.H
        m = V.shape[1]
        match = self._match(V, cols, H, level) if p.match is not None else np.zeros(m)
        power_V = sum(by_kind[k] for k in self.power_kinds if k in by_kind)
        watts = p.light.electric_power(d.sources, rect, flux) if d.sources else np.zeros(m)
        installed = self._installed * np.ones(m)
        count = np.full(m, self._count)
        if lay is not None:
            watts = watts + p.arrays.electric_power(lay)
            installed = installed + p.arrays.installed_power(lay)
            count = count + lay.count.sum(axis=1)
        # Plain-string keys: this dict is read on every batch.
        goals = {
            "max_light_power": p.light.reflected_power(power_V),
            "min_electric_power": watts,
            "match": match,
            "min_installed_power": installed,
            "min_luminaire_count": count,
            "min_glazing_area": glazing_area(rect, self._glazed),
            "min_annual_energy": np.full(m, np.nan),
            "max_sda": np.full(m, np.nan),
        }
        if self.annual:
            goals["min_annual_energy"], goals["max_sda"] = self.annual_values(
                lit, level, watts, (rect, flux, filt, lay)
            )
        goals.update(self._registered_values(rect, flux, filt, lay, lit, level, goals))
        return goals

    def _registered_values(self, rect, flux, filt, lay, lit, level, goals) -> dict:
        """The values of the registered goals: the wanted ones from their spec, NaN for
        the others (every goal kind is a key of an evaluation's goals)."""
        m = rect.shape[0]
        out = {k: np.full(m, np.nan) for k in goal_names() if k not in goals}
        if self.registered:
            batch = GoalBatch(self.problem, rect, flux, filt, lay, lit, level, goals)
            for spec in self.registered:
                out[spec.kind] = np.asarray(spec.value(batch), dtype=float)
        return out

    def annual_values(self, lit: Lit, level: Level, watts: np.ndarray, decoded=None):
        """(annual energy kWh, sDA) of m candidates on the control work plane, ``watts``
        (m,) their electric power; with control groups each group is dimmed on its own
        sensor (``decoded``: the candidates' rect, flux, filt and array layout)."""
        p = self.problem
        d, parts, control = p.design.daylight, lit.parts, p.control
        idx = len(level.rows) + np.arange(control.start, control.stop)
        year = parts.year()
        batch = getattr(p, "group_batch", None)
        if batch is not None:
            rect, flux, filt, lay = decoded
            full, group_w = batch.full_and_watts(p.light, rect, flux, filt, lay, lit.control_exact)
            levels = batch.level_sums(parts, len(level.rows), full, d.target_lux)
            hours = year.every.shape[1]
            energy = lighting_kwh(group_w, levels, 0.0, hours).sum(axis=0)
            energy = energy + lighting_kwh(0.0, 0.0, d.standby_w, hours)
            return energy, parts.sda_mark(idx).mean(axis=0)
        full = parts.electric[idx].mean(axis=0)
        # Without skylights there are no sky groups: b is (m, 0) and the daylight zero.
        b = parts.sky[:, idx].mean(axis=1).T
        clear = parts.clear_hours(idx)  # fixed clear glazing's daylight, (points, T)
        fixed = None if clear is None else clear.mean(axis=0)
        levels = dimming_sum(year, b, full, d.target_lux, d.min_level, fixed)
        energy = lighting_kwh(watts, levels, d.standby_w, year.every.shape[1])
        sda = parts.sda_mark(idx).mean(axis=0)
        return energy, sda

    def _match(self, V, cols, H, level: Level) -> np.ndarray:
        """Match error e of m candidates: from the Gram matrix on every patch, else from
        the lux at the level's representatives."""
        p = self.problem
        if level.divisor <= 1:
            p.lighting.tally.gram(len(cols), V.shape[0], V.shape[1])
            return p.match.relative_error(p.light.op.zone_patches[cols], V[cols])
        rows = level.rows[level.match_pos]
        C = p.light.op.rho[rows, None] * H[level.match_pos]
        C_obj = p.C_obj[rows]
        return np.linalg.norm(C - C_obj[:, None], axis=0) / max(np.linalg.norm(C_obj), 1e-30)


def light_power_kinds(design: Design) -> tuple[str, ...]:
    """The source kinds the light-power goal counts: those its goal names, else all."""
    goal = next((g for g in design.goals if g.kind == GoalKind.MAX_LIGHT_POWER), None)
    kinds = (goal.kinds if goal else ()) or tuple(t.kind for t in source_types())
    return tuple(str(k) for k in kinds)


def glazing_area(rect: np.ndarray, sky: list[int]) -> np.ndarray:
    """Total area (m²) of the sources ``sky`` (the daylit ones) of m candidates (rect
    (m, S, 4))."""
    if not sky:
        return np.zeros(rect.shape[0])
    r = rect[:, sky]
    return (np.abs(r[..., 2] - r[..., 0]) * np.abs(r[..., 3] - r[..., 1])).sum(axis=1)


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
    """Electric sources (rectangles) of the design: one luminaire each."""
    return len(electric(design.sources))


def installed_power(design: Design, light: LightModel) -> float:
    """Rated power (W) of the electric sources at their flux as written (free fluxes
    count at their range's top)."""
    total = 0.0
    for s in electric(design.sources):
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
    """Area (m²) of the daylit sources' zones: the scale of the glazing-area goal."""
    zones = {s.zone for s in daylit(design.sources)}
    total = sum(light.zone_size(z)[0] * light.zone_size(z)[1] for z in zones)
    return max(total, 1e-9)
