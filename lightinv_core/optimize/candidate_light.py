"""The light of a batch of candidates at a level's receivers (one GEMM per batch).

``CandidateLight.of`` turns decoded variables into zone emission V (nz, m), split by
source kind, and, where the goals or intentions read it, the lux H at the receivers:
the zone sources' light from the operator plus the luminaire arrays' light blended from
their lattice responses (or, to judge a solution, the arrays placed exactly). Designs
judged in other scenarios than the design daylight get the light in parts: the
electric sources' light and each sky group's daylight per exterior lux
(``light/daylight.py``), at the same cost.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.design.variables import ArrayLayout, Variables
from lightinv_core.kinds import Scenario
from lightinv_core.light.arrays import ArrayLight, arrays_field
from lightinv_core.light.clear_batch import ClearBatch
from lightinv_core.light.clear_glazing import stacked
from lightinv_core.light.control_groups import exact_arrays_at_sensors
from lightinv_core.light.daylight import ScenarioLight
from lightinv_core.light.grids import DesignGrids
from lightinv_core.light.model import LightModel
from lightinv_core.optimize.levels import Level
from lightinv_core.optimize.work_model import LightTally
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.types import source_types


@dataclass(frozen=True)
class Lit:
    """The light of m candidates: ``V`` (nz, m) zone emission in the design scenario,
    ``by_kind`` its parts by source kind, ``cols`` the zone columns any candidate emits
    from; ``H`` (receivers, m) lux in the design scenario (None when no receiver is
    read) and, for designs judged in other scenarios, ``parts``: the electric sources'
    light and each sky group's daylight per exterior lux (``light/daylight.py``);
    ``layout`` the candidates' luminaire arrays (None without), for their glare, and
    ``weights`` their lattice weights (maintained, ``ArrayLight.weights``) when lit
    from the lattice."""

    V: np.ndarray
    by_kind: dict
    cols: np.ndarray
    H: np.ndarray | None
    parts: ScenarioLight | None = None
    layout: ArrayLayout | None = None
    weights: np.ndarray | None = None
    control_exact: np.ndarray | None = None  # (K,) control groups' exact arrays' lux


class LightSource(Protocol):
    """What ``CandidateLight`` reads of its problem (``DesignProblem``)."""

    design: Design
    light: LightModel
    patches: Patches
    vars: Variables
    grids: DesignGrids | None
    split: bool
    sky: object
    match: object

    @property
    def arrays(self) -> ArrayLight | None: ...

    def arrays_at(self, x: np.ndarray) -> tuple: ...


def _kinds_total(by_kind: dict, kinds: tuple[str, ...], shape: tuple) -> np.ndarray:
    """The sum of ``by_kind``'s parts of ``kinds`` (float32 zeros of ``shape`` for none)."""
    parts = [by_kind[k] for k in kinds if k in by_kind]
    if not parts:
        return np.zeros(shape, np.float32)
    total = parts[0]
    for part in parts[1:]:
        total = total + part
    return total


class CandidateLight:
    """The light of candidates of one problem (see the module docstring)."""

    def __init__(self, problem: LightSource, year_box: list):
        self.problem = problem
        self._year_box = year_box  # the weather year, read at the first annual use
        self._clear_at: dict = {}  # the clear glazing's light per level
        types = source_types()
        self._electric = tuple(str(t.kind) for t in types if t.electric)
        self._daylit = tuple(str(t.kind) for t in types if t.daylit)
        self._weights: tuple = (None, None)  # (layout, its lattice weights): the last made
        self.tally = LightTally()  # the light's work, for ``auto``'s shares (work_model)

    def of(
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
        p = self.problem
        d = p.design
        m = rect.shape[0]
        nz = len(p.light.op.zone_patches)
        if p.split:
            return self._split(rect, flux, filt, level, lay, arrays_H)
        if d.sources:
            V, by_kind = p.light.zone_emission(
                d.sources, rect, flux, filt, d.daylight, split_kinds=True
            )
        else:
            V = np.zeros((nz, m), np.float32)
            by_kind = {str(t.kind): V for t in source_types()}
        cols = np.flatnonzero(np.any(V != 0, axis=1))
        H = None
        if self.needs_field(level):
            H = self._receiver_light(V, cols, level, lay, arrays_H)
        return Lit(V, by_kind, cols, H, layout=lay, weights=self._weights_of(lay))

    def needs_field(self, level: Level) -> bool:
        """Whether anything reads the lux at the level's receivers."""
        p = self.problem
        # At the full level the match error comes from the Gram matrix, not the field.
        need = bool(p.design.intentions) or p.split
        need = need or (p.match is not None and level.divisor > 1)
        Phi = level.receivers.Phi_rows
        return need and (Phi is None or Phi.shape[0] > 0)

    def points(self) -> int:
        """Work-plane grid points among the receivers."""
        grids = self.problem.grids
        return 0 if grids is None else len(grids.points)

    def _receiver_light(self, V, cols, level: Level, lay, arrays_H=None) -> np.ndarray:
        """Lux at the level's receivers of emission V (nz, m) plus the arrays' light."""
        H = None
        blend = level.arrays_R is not None and arrays_H is None and lay is not None
        if len(cols) or not (blend or arrays_H is not None):
            H = self.problem.light.illuminance(V, level.receivers, cols)
            self.tally.field(H.shape[0], V.shape[0], len(cols), V.shape[1])
        if blend:
            W = self.problem.arrays.weights(lay)
            self._weights = (lay, W)
            lit = level.arrays_R @ W
            self.tally.product(*level.arrays_R.shape, W.shape[1])
            H = lit if H is None else H + lit
        elif arrays_H is not None:
            H = arrays_H if H is None else H + arrays_H
        return H

    def _weights_of(self, lay) -> np.ndarray | None:
        """The lattice weights last made, if for ``lay`` (the glare reuses them)."""
        return self._weights[1] if lay is not None and self._weights[0] is lay else None

    def _split(self, rect, flux, filt, level: Level, lay, arrays_H) -> Lit:
        """``of`` for designs judged in several scenarios: the electric sources' light
        and each sky group's daylight per exterior lux, computed apart."""
        p = self.problem
        d = p.design
        m = rect.shape[0]
        nz = len(p.light.op.zone_patches)
        ext = d.daylight.exterior_lux
        electric, daylit = self._electric, self._daylit
        if d.sources:
            unit = replace(d.daylight, exterior_lux=1.0)
            _, by_unit = p.light.zone_emission(d.sources, rect, flux, filt, unit, split_kinds=True)
            V_lum = _kinds_total(by_unit, electric, (nz, m))
            V_sky = _kinds_total(by_unit, daylit, (nz, m))
        else:
            by_unit = {}
            V_lum = V_sky = np.zeros((nz, m), np.float32)
        V = V_lum + np.float32(ext) * V_sky
        by_kind = {k: by_unit.get(k, V_lum) for k in electric}
        by_kind |= {k: ext * by_unit.get(k, V_sky) for k in daylit}
        cols = np.flatnonzero(np.any(V != 0, axis=1))
        if not self.needs_field(level):
            return Lit(V, by_kind, cols, None, layout=lay)
        lum_cols = np.flatnonzero(np.any(V_lum != 0, axis=1))
        lux = self._receiver_light(V_lum, lum_cols, level, lay, arrays_H)
        if lux is None:
            lux = np.zeros((len(level.rows) + self.points(), m))
        sky = np.zeros((p.sky.count, *lux.shape))
        for g, gcols in enumerate(p.sky.cols):
            on = gcols[np.any(V_sky[gcols] != 0, axis=1)]
            if not len(on):
                continue
            Vg = V_sky
            if p.sky.count > 1:  # only this group's rows (the product may read all)
                Vg = np.zeros_like(V_sky)
                Vg[on] = V_sky[on]
            sky[g] = p.light.illuminance(Vg, level.receivers, on)
            self.tally.field(lux.shape[0], nz, len(on), m)
        clear = self._clear(level, rect, filt)
        parts = ScenarioLight(d.daylight, p.sky, lux, sky, self._year_box, clear)
        W = self._weights_of(lay)
        return Lit(V, by_kind, cols, parts.lux(Scenario.DESIGN), parts, lay, W)

    def _clear(self, level: Level, rect=None, filt=None):
        """The clear glazing's light at the level's receivers (None without): fixed, or
        the candidates' own when a clear shape moves (``light.clear_batch``)."""
        cells = getattr(self.problem, "clear_cells", None)
        if cells is not None:
            return self._moving(cells, level, rect, filt)
        clear = getattr(self.problem, "clear", None)
        if clear is None:
            return None
        if level.divisor not in self._clear_at:
            self._clear_at[level.divisor] = stacked(clear.patches, level.rows, clear.points)
        return self._clear_at[level.divisor]

    def _moving(self, cells, level: Level, rect, filt) -> ClearBatch:
        """The clear light of the batch (rect, filt) whose clear shapes move."""
        p = self.problem
        if level.divisor not in self._clear_at:
            self._clear_at[level.divisor] = _positions(cells, level.rows)
        if "occupied" not in self._clear_at:
            from lightinv_core.climate.weather import load_weather
            from lightinv_core.light.daylight_year import weather_path

            d = p.design.daylight
            weather = load_weather(weather_path(d))
            self._clear_at["occupied"] = np.asarray(
                weather.occupied(*d.occupancy, weekdays=d.weekdays)
            )
        shares = cells.shares(p.light, p.design, rect, filt)
        (pos, year_pos), occupied = self._clear_at[level.divisor], self._clear_at["occupied"]
        return ClearBatch(cells, shares, pos, year_pos, occupied, getattr(p, "control", None))

    def judged(self, x: np.ndarray, lv: Level) -> Lit:
        """The light of layout x at level ``lv``'s receivers, its arrays placed exactly
        (not blended from the lattice): what a solution is judged on."""
        p = self.problem
        rect, flux, filt = p.vars.decode(x[None])
        if not p.design.arrays:
            return self.of(rect, flux, filt, lv, None)
        points = None if p.grids is None else p.grids.samples
        Hp, Hq = arrays_field(p.patches, p.light.op, p.arrays_at(x), points)
        exact = np.concatenate([Hp[lv.rows], Hq])[:, None]
        lit = self.of(rect, flux, filt, lv, None, arrays_H=exact)
        control = None
        plan = getattr(p, "control_groups", None)
        if plan is not None:  # each control group's arrays, placed exactly, on its sensor
            control = exact_arrays_at_sensors(p.light, plan, p.grids, p.arrays_at(x))
        return replace(lit, layout=p.vars.decode_arrays(x[None]), control_exact=control)


def _positions(cells, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A level's receivers (patch ``rows``, then the work-plane points) among the clear
    cells' receivers: of their overcast factors, and of their year's columns (-1 at a
    patch whose intentions read no year)."""
    at = np.searchsorted(cells.rows, rows)
    if len(at) and not np.array_equal(cells.rows[np.minimum(at, len(cells.rows) - 1)], rows):
        raise ValueError("a level reads patches the clear cells were not traced at")
    pts = np.arange(cells.points)
    year = np.full(len(rows), -1)
    if len(cells.year_rows):
        yr = np.searchsorted(cells.year_rows, rows)
        ok = yr < len(cells.year_rows)
        ok[ok] = cells.year_rows[yr[ok]] == rows[ok]
        year[ok] = yr[ok]
    return np.concatenate([at, len(cells.rows) + pts]), np.concatenate(
        [year, len(cells.year_rows) + pts]
    )
