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

The parts live apart: the receivers of each level (``levels.py``), the candidates'
light (``candidate_light.py``), the goals and their scales (``objectives.py``), the
constraints and penalty (``judge.py``) and the answer judged on every patch
(``solution_builder.py``). Their public names are importable from here too.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lightinv_core.design.geometry import rule_violations
from lightinv_core.design.model import Design, DesignError
from lightinv_core.design.solution import Solution, SolutionInfo
from lightinv_core.design.variables import ArrayLayout, Variables
from lightinv_core.goals import goal_names, goal_spec
from lightinv_core.kinds import GoalKind, Scenario
from lightinv_core.light.arrays import ArrayLight, array_light, array_shapes, resolve_product
from lightinv_core.light.clear_build import clear_light
from lightinv_core.light.clear_cells import clear_cells, moving_clear, refuse_moving_sunlight
from lightinv_core.light.control_groups import GroupBatch, control_plan
from lightinv_core.light.daylight_year import sky_groups
from lightinv_core.light.dgp_observers import eye_daylight
from lightinv_core.light.en17037_sun import sunlight_values
from lightinv_core.light.glare import Glare
from lightinv_core.light.grids import DesignGrids, design_receivers
from lightinv_core.light.intentions import FEASIBILITY_TOL, intention_patches
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.candidate_light import CandidateLight, Lit
from lightinv_core.optimize.judge import ARRAY_MARGIN, EPSILON_WEIGHT, Constraint, Judge
from lightinv_core.optimize.levels import Level, build_level, representatives
from lightinv_core.optimize.objectives import (
    DesignGoals,
    GoalBatch,
    count_scale,
    electric_scale,
    energy_scale,
    glazing_scale,
    installed_power,
    luminaire_sources,
    wanted_goals,
)
from lightinv_core.optimize.solution_builder import build_solution, offending_patches
from lightinv_core.quantities import quantity_spec
from lightinv_core.scenarios import scenario_spec

__all__ = [
    "ARRAY_MARGIN",
    "EPSILON_WEIGHT",
    "FEASIBILITY_TOL",
    "Constraint",
    "DesignProblem",
    "Evaluation",
    "GoalBatch",
    "Level",
    "Lit",
    "count_scale",
    "electric_scale",
    "energy_scale",
    "glazing_scale",
    "installed_power",
    "luminaire_sources",
    "representatives",
]


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
        self.grids: DesignGrids | None = design_receivers(light, design)
        # Glare at the design's observers (UGR intentions, ``light/glare.py``).
        ugr = any(i.observers and quantity_spec(i.quantity).from_glare for i in design.intentions)
        self.glare = Glare(light, design) if ugr else None
        self._eyes = any(i.observers for i in design.intentions)
        # Grid intentions read points, not patches: no patch set. An intention at
        # observers is read at its eyes (``Glare``): a level keeps one receiver for it,
        # the patch its eyes see most of (unread).
        self.intent_sets = [
            None
            if i.grid is not None
            else self._eye_anchor(i)
            if i.observers is not None
            else intention_patches(i, self.patches)
            for i in design.intentions
        ]
        self._arrays: ArrayLight | None = None
        self._array_progress = (progress, cancel)
        self.array_shapes = (
            array_shapes(self.patches, design.arrays, design.workplanes) if design.arrays else None
        )
        self.products = [resolve_product(a.product, a.watts) for a in design.arrays]
        self.epsilon = tuple((str(k), float(b)) for k, b in epsilon)
        self.annual_goals = any(goal_spec(k).annual for k in wanted_goals(design, self.epsilon))
        # Scenarios other than the paper's design daylight need the light split into
        # the luminaires' and each sky group's (same GEMM columns, so the same cost).
        self.split = self.annual_goals or any(
            it.scenario != Scenario.DESIGN for it in design.intentions
        )
        # Fixed clear glazing: its light is computed once, added to every candidate's;
        # once a clear shape is free, every clear source's light is traced per zone cell
        # and summed per candidate (``light.clear_cells``, ``light.clear_batch``).
        if moving_clear(design):
            refuse_moving_sunlight(design)
        self.clear_cells = clear_cells(light, design, self._patch_rows(), self._year_rows())
        self.clear = None if self.clear_cells is not None else clear_light(light, design)
        self.split = self.split or self.clear is not None or self.clear_cells is not None
        self.sky = sky_groups(light, design) if self.split else None
        plane = design.control_plane
        self.control = None if plane is None or self.grids is None else self.grids.spans[plane.name]
        # Several daylight-linked control groups (None: all luminaires dimmed as one).
        self.control_groups = control_plan(design, self.grids)
        self._group_batch: GroupBatch | None = None
        if self.annual_goals and self.control is None:
            raise DesignError(
                "the annual energy and sDA goals are measured on a work plane: add one"
            )
        self.match = None
        if any(g.kind == GoalKind.MATCH for g in design.goals):
            self.match, self.C_obj = light.match_target(design.target_sources, design.daylight)
        self.goals = DesignGoals(self, self.epsilon)
        self.primary, self.objectives = self.goals.primary, self.goals.objectives
        self.scales = self.goals.scales
        glare = self._glare_values if self._eyes else None
        self.judge = Judge(design, light, self.epsilon, glare)
        self.constraints: tuple[Constraint, ...] = self.judge.constraints
        self._year_box: list = []  # the weather year, read at the first annual use
        self.lighting = CandidateLight(self, self._year_box)
        self._levels: dict[int, Level] = {}

    def _patch_rows(self) -> np.ndarray:
        """Every patch any level may read: the patch intentions' (and the match goal's)."""
        sets = [s for s in self.intent_sets if s is not None]
        if self.glare is not None:  # the arrays' light where the eyes look: the background
            sets.append(self.glare.seen)
        if any(g.kind == GoalKind.MATCH for g in self.design.goals):
            sets.append(np.arange(self.patches.n))
        return np.unique(np.concatenate(sets)) if sets else np.zeros(0, np.int64)

    def _year_rows(self) -> np.ndarray:
        """The patches of intentions measured over the weather year (the clear cells keep
        their hourly columns there only; elsewhere a patch reads their overcast factor)."""
        sets = [
            s
            for s, it in zip(self.intent_sets, self.design.intentions, strict=True)
            if s is not None
            and it.observers is None
            and scenario_spec(quantity_spec(it.quantity).scenario or it.scenario).weather
        ]
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
                None if self.grids is None else self.grids.samples,
                progress,
                cancel,
            )
        return self._arrays

    @property
    def group_batch(self) -> GroupBatch | None:
        """The control groups' light for batches (None with the default group alone)."""
        if self.control_groups is not None and self._group_batch is None:
            plan, grids = self.control_groups, self.grids
            self._group_batch = GroupBatch(plan, self.design, grids, self.arrays)
        return self._group_batch

    def _glare_values(self, intention, lit: Lit) -> np.ndarray:
        """UGR (observers, m) at an intention's observers for a batch's light, or a
        figure of the fixed glazing there (EN 17037 sunlight exposure, the same for
        every candidate)."""
        if quantity_spec(intention.quantity).from_eyes is not None:  # simplified DGP
            return eye_daylight(self.light, self.design).values(intention, lit)
        if quantity_spec(intention.quantity).from_glare is None:
            hours = sunlight_values(self.light, self.design, intention.observers)
            return np.repeat(hours[:, None], lit.V.shape[1], axis=1)
        return self.glare.values(intention, lit, self.arrays)

    def _eye_anchor(self, intention) -> np.ndarray:
        """The one receiver a level keeps for an intention at observers (unread)."""
        if self.glare is not None and quantity_spec(intention.quantity).from_glare:
            return self.glare.anchor(intention)
        return np.zeros(1, dtype=np.int64)

    def layout_of(self, X: np.ndarray) -> ArrayLayout | None:
        """The luminaire arrays of candidates X (None without arrays)."""
        return self.vars.decode_arrays(X) if self.design.arrays else None

    def rule_violations(self, X: np.ndarray) -> np.ndarray:
        """(m, R) relative violations of the geometric rules (sources and arrays) of X."""
        rect, _, _ = self.vars.decode(X)
        lay = self.layout_of(X)
        arrays = None if lay is None else (lay, self.array_shapes)
        return rule_violations(self.design, rect, self.zone_size, arrays, self.outlines)

    def level(self, divisor: int = 1) -> Level:
        """The representative receivers for divisor d (1 = every patch)."""
        if divisor not in self._levels:
            self._levels[divisor] = build_level(self, divisor)
        return self._levels[divisor]

    # -- evaluation ---------------------------------------------------------------------------
    def _light(self, rect, flux, filt, level: Level, lay, arrays_H=None) -> Lit:
        """The light of m candidates (``CandidateLight.of``; tests read it here)."""
        return self.lighting.of(rect, flux, filt, level, lay, arrays_H)

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
        return Evaluation(value, penalty, ok, goals, len(good), geo, lighting, self.goals.senses)

    def _score(self, rect, flux, filt, level: Level, lay: ArrayLayout | None = None):
        """Value, penalty, goals and lighting constraint columns (c - tol, each (m,)) of
        m lit candidates."""
        lit = self.lighting.of(rect, flux, filt, level, lay)
        goals = self.goals.values(rect, flux, filt, level, lay, lit)
        lighting, n_intent = self.judge.search_columns(lit, level, goals)
        penalty = self.judge.penalty(lighting, n_intent, rect.shape[0])
        value = self.goals.scaled_primary(goals) + penalty
        return value, penalty, goals, tuple(lighting)

    # -- one layout, judged on every patch ----------------------------------------------------
    def sources_at(self, x: np.ndarray) -> tuple:
        """The design's sources with the parameters of x filled in (tied rules applied)."""
        return self.vars.sources_at(x)

    def arrays_at(self, x: np.ndarray) -> tuple:
        """The design's luminaire arrays with the parameters of x filled in."""
        return self.vars.arrays_at(x)

    def offending_patches(self, x: np.ndarray) -> list[tuple[str, str, np.ndarray]]:
        """Where the light of layout x breaks the intentions, judged on all patches
        (``solution_builder.offending_patches``)."""
        return offending_patches(self, x)

    def solution(self, x: np.ndarray, info: SolutionInfo | None = None) -> Solution:
        """A ``Solution`` for x judged on ALL patches, with every violation listed."""
        return build_solution(self, x, info)
