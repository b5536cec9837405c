"""The clear glazing's light of a batch of candidates whose clear shapes move.

``ClearBatch`` is what ``ScenarioLight.clear`` holds when the clear glazing moves
(``light.clear_cells``): the same questions as a fixed ``ClearLight`` (the overcast
factor, the hourly light with the LM-83 blinds, the direct sun, the light with every
blind open, an annual band), answered per candidate, with one more axis: (R', m, ...)
where a fixed glazing's answer is (R', ...), the same for every layout.

How: a candidate's light is ``sum_c s_c L_c`` over the cells (``ClearCells.shares``).
Per receiver set and hour mask the cells' hourly light (C, R', T) is made once and
kept on the cells (``ClearCells`` are built once per problem), so a batch costs one
(m, C) x (C, R' T) product per source. The blinds are each candidate's own: its direct
sun at the control work plane's points in the occupied hours, through
``climate.sun_metrics.blinds_schedule`` (the fewest sources closed, as a fixed design).

Speed, exactly (docs/daylight.md, "Clear shapes in the optimiser"): the product's
(m, R', T) float32 is what every reader gets (no float64 copy: ``hours`` is a view);
a band is one comparison per threshold pair on float32 with the bounds that give the
float64 answer (``hour_counts``), remembered (DA and sDA share a count); the direct
sun (ASE, the one-source blinds) is read only where some cell has any
(``SunSupport``, a few % of the point-hours); the closed blinds' glow is a float32
outer product written over the candidate's closed hours.

Decision: every occupied hour, always. Replacing the hours by K representative ones
(k-means on the cells' hourly light) was measured on 200 random rectangles
(``bench/clear_shapes.py``, ``hour_reduction``): even at K = 800 (30% of the hours)
sDA moved by up to 1.2 points and ASE by 3.7 (one to three of 81 points cross its
250-hour line) and the dimming sum by 5%; at the K that a 3x target would need
(about 100) sDA moved by 5 points. That is beyond the ~1 point allowed, so no
reduction is offered.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
import scipy.sparse as sp

from lightinv_core.light.clear_cells import ClearCells

MAX_KEPT = 8
"""Hourly cell blocks kept per cells object (receiver set x hour mask x kind)."""


def cell_hours(cells: ClearCells, rec: np.ndarray, mask: np.ndarray, sun_only: bool):
    """(C, R', T) float32 each cell's light (lux, blinds open, no glow) at receivers
    ``rec`` (indices into the cells' receivers) in the hours of ``mask``; with
    ``sun_only`` the direct sun alone, where any cell has some (``SunSupport``). Kept
    on ``cells`` (the same for every batch)."""
    memo = cells.kept
    key = (np.asarray(rec).tobytes(), np.asarray(mask).tobytes(), sun_only)
    if key in memo:
        return memo[key]
    if len(memo) >= MAX_KEPT:
        memo.pop(next(iter(memo)))
    hours = np.flatnonzero(mask)
    W = cells.weights[:, hours]
    rec = np.asarray(rec)
    out = np.empty((cells.count, len(rec), len(hours)), np.float32)
    off = len(cells.year_rows)
    on = rec >= off  # work-plane points: their direct sun is traced hour by hour
    for c in range(cells.count):
        coef = cells.coef[c, rec]
        if sun_only:
            out[c] = coef[:, cells.sun_cols] @ W[cells.sun_cols]
        else:
            out[c] = coef @ W
        if on.any():
            out[c, on] += cells.direct[c][rec[on] - off][:, hours].toarray()
    if sun_only:  # the sun reaches a point through a cell in few hours: sparse
        flat = sp.csr_matrix(out.reshape(cells.count, -1))
        at = np.unique(flat.indices)
        out = SunSupport(at, flat[:, at].toarray().astype(np.float32), len(rec), len(hours))
    memo[key] = out
    return out


@dataclass(frozen=True, eq=False)
class SunSupport:
    """The cells' direct sun at R' receivers in T hours, kept only where some cell has
    any: ``at`` (n,) the flat indices r T + t (increasing), ``values`` (C, n) lux. A
    candidate's sun is 0 elsewhere, so its counts above a positive bound read n values,
    not R' T."""

    at: np.ndarray
    values: np.ndarray
    R: int
    T: int

    @property
    def nbytes(self) -> int:
        """Memory of the support and its values (bytes)."""
        return self.at.nbytes + self.values.nbytes

    def onto(self, axis: int) -> sp.csr_matrix:
        """(n, R') or (n, T) sparse: which receiver (axis 0) or hour (axis 1) each
        value is at (a sum over the other axis is a product with it)."""
        key = "_rows" if axis == 0 else "_hours"
        got = self.__dict__.get(key)
        if got is None:
            size = self.R if axis == 0 else self.T
            where = self.at // self.T if axis == 0 else self.at % self.T
            ones = np.ones(len(self.at), np.float32)
            got = sp.csr_matrix((ones, (np.arange(len(self.at)), where)), (len(self.at), size))
            object.__setattr__(self, key, got)
        return got

    def dense(self, v: np.ndarray) -> np.ndarray:
        """(m, R', T) float32 from the values ``v`` (m, n) at the support."""
        out = np.zeros((len(v), self.R * self.T), np.float32)
        out[:, self.at] = v
        return out.reshape(len(v), self.R, self.T)


def _below32(x: float) -> np.float32:
    """The largest float32 at most ``x``."""
    t = np.float32(x)
    return t if float(t) <= x else np.nextafter(t, np.float32(-np.inf))


def hour_counts(lux: np.ndarray, lo: float, hi: float, above: bool) -> np.ndarray:
    """(..., ) hours (last axis) with ``lo`` <= lux <= ``hi`` (``lo`` < lux with
    ``above``) of a float32 ``lux``: the float32 bounds are chosen so that the count
    is the one of the float64 comparison (``HourBand.of_hours``), exactly."""
    lux = np.asarray(lux)
    if lux.dtype != np.float32:
        lux = lux.astype(np.float32)
    if above:
        hit = lux > _below32(lo)
    else:
        low = _below32(lo)
        low = low if float(low) == lo else np.nextafter(low, np.float32(np.inf))
        hit = lux >= low
    if hi != np.inf:
        hit &= lux <= _below32(hi)
    # bool viewed as bytes, summed in int32: several times faster than bool.sum()
    return hit.view(np.uint8).sum(axis=-1, dtype=np.int32)


def band_of_counts(band, counts: np.ndarray, hours: int) -> np.ndarray:
    """``band.of_hours``'s value from the hours counted (``hour_counts``) of ``hours``."""
    if band.point_hours is not None:
        return (counts > band.point_hours).astype(float)
    if band.point_share is None:
        return counts / max(hours, 1)
    need = math.ceil(band.point_share * hours - 1e-9)
    return (counts >= need).astype(float)


class ClearBatch:
    """The clear light of m candidates (``shares`` (m, C)) at a level's receivers:
    ``pos`` maps each level receiver to the cells' receivers of ``over``, ``year_pos``
    to those of the year's columns (-1: a patch whose intentions read no year);
    ``occupied`` (H,) the
    schedule's hours (the blinds close only then); ``control`` the control work
    plane's points among the cells' points (None: blinds stay open)."""

    per_layout = True

    def __init__(self, cells: ClearCells, shares, pos, year_pos, occupied, control=None):
        self.cells = cells
        self.shares = np.asarray(shares, dtype=np.float32)
        self.pos = np.asarray(pos, dtype=np.int64)
        self.year_pos = np.asarray(year_pos, dtype=np.int64)
        self.occupied = np.asarray(occupied, bool)
        self.control = control
        self.columns = SimpleNamespace(outward=cells.outward)
        self._memo: dict = {}
        self._counts: dict = {}
        self._closed = None

    @property
    def m(self) -> int:
        """Number of candidates."""
        return self.shares.shape[0]

    def _by_source(self):
        """Per clear source: (its cells, their shares (m, C_g))."""
        for g in range(self.cells.sources):
            mine = np.flatnonzero(self.cells.cell_source == g)
            yield g, mine, self.shares[:, mine]

    def _sum(self, blocks, mine, s, R: int, T: int) -> np.ndarray:
        """(m, R, T) float32 the candidates' sum of the cells' ``blocks`` (C, R, T), or
        of a ``SunSupport`` (the direct sun). A source's cells are consecutive, so its
        block is a view (no copy of the (C, R, T) block)."""
        if isinstance(blocks, SunSupport):
            return blocks.dense(s @ blocks.values[mine])
        if len(mine) and mine[-1] - mine[0] + 1 == len(mine):
            part = blocks[mine[0] : mine[-1] + 1]
        else:
            part = blocks[mine]
        return (s @ part.reshape(len(mine), R * T)).reshape(-1, R, T)

    def _sun(self, rec, mask) -> tuple[SunSupport, np.ndarray]:
        """(the cells' sun support at receivers ``rec`` in ``mask``'s hours, the
        candidates' direct sun there (m, n) float32, every source's summed)."""
        rec = np.asarray(rec, dtype=np.int64)
        key = ("sun", rec.tobytes(), np.asarray(mask, bool).tobytes())
        if key not in self._memo:
            sup = cell_hours(self.cells, rec, mask, True)
            self._memo[key] = (sup, self.shares @ sup.values)
        return self._memo[key]

    def _sun_counts(self, rec, mask, lo: float, axis: int) -> np.ndarray | None:
        """(m, R') hours (axis 0) or (m, T) receivers (axis 1) whose direct sun is above
        ``lo`` (> 0: the sun's zeros never count), read on the support only."""
        sup, v = self._sun(rec, mask)
        hit = (v > _below32(lo)).astype(np.float32)
        return np.rint(sup.onto(axis).T.dot(hit.T).T).astype(np.int32)

    @property
    def closed(self) -> np.ndarray:
        """(m, G, H) each candidate's LM-83 blinds per clear source and hour: with one
        source closed in the hours when more than 2% of the control plane's points get
        direct sun of 1,000 lux or more (``sun_metrics.blinds_closed``, vectorised over
        the batch); with several, ``blinds_schedule`` (hour by hour, a few candidates'
        hours in one call)."""
        if self._closed is None:
            from lightinv_core.climate.sun_metrics import (
                BLINDS_LUX,
                BLINDS_SHARE,
                blinds_schedule,
            )

            c = self.cells
            H = c.weights.shape[1]
            closed = np.zeros((self.m, c.sources, H), bool)
            occ = self.occupied
            if self.control is not None and occ.any():
                rec = len(c.year_rows) + np.arange(c.points)[self.control]
                if c.sources == 1:  # the whole batch at once; shared with ASE's sun
                    # "1,000 lux or more": above the float32 just below 1,000
                    lo = float(np.nextafter(np.float32(BLINDS_LUX), np.float32(0)))
                    hit = self._sun_counts(rec, occ, lo, 1)  # (m, T) points in the sun
                    closed[:, 0, occ] = hit / len(rec) > BLINDS_SHARE
                else:
                    blocks, T = cell_hours(c, rec, occ, True), int(occ.sum())
                    per = [
                        self._sum(blocks, mine, s, len(rec), T) for _, mine, s in self._by_source()
                    ]
                    per = np.stack(per, 1)  # (m, G, q, T)
                    # Each hour is judged alone: a few candidates' hours side by side
                    # make one call (G, q, k T).
                    for j in range(0, self.m, 8):
                        k = per[j : j + 8]
                        side = np.moveaxis(k, 0, 2).reshape(k.shape[1], k.shape[2], -1)
                        got = blinds_schedule(side).reshape(k.shape[1], len(k), -1)
                        closed[j : j + 8][:, :, occ] = np.moveaxis(got, 1, 0)
            self._closed = closed
        return self._closed

    def overcast(self, idx=slice(None)) -> np.ndarray:
        """(R', m) lux per horizontal exterior lux under the CIE overcast sky."""
        return self.cells.over[:, self.pos[idx]].T.astype(float) @ self.shares.T.astype(float)

    def _light(self, idx, mask, blinds: bool, sun_only: bool = False) -> np.ndarray:
        """(m, R', T) float32 the candidates' clear light at receivers idx in ``mask``'s
        hours."""
        return self._light_rec(self._rec(idx), mask, blinds, sun_only)

    def _rec(self, idx) -> np.ndarray:
        """The cells' receivers of level receivers idx (their year's columns)."""
        rec = self.year_pos[idx]
        if np.any(rec < 0):
            raise ValueError("the year's clear light is read at patches it was not traced at")
        return rec

    def _light_rec(self, rec, mask, blinds: bool, sun_only: bool) -> np.ndarray:
        """``_light`` at the cells' receivers ``rec``: (m, R', T) float32, candidates
        first (the product's own layout: no copy; every reader takes float32)."""
        rec = np.asarray(rec, dtype=np.int64)
        mask = np.asarray(mask, bool)
        key = (rec.tobytes(), mask.tobytes(), blinds, sun_only)
        if key in self._memo:
            return self._memo[key]
        blocks = cell_hours(self.cells, rec, mask, sun_only)
        T = int(mask.sum())
        out = None
        for g, mine, s in self._by_source():
            part = self._sum(blocks, mine, s, len(rec), T)
            if blinds and not sun_only:  # closed hours: the source's glow instead
                shut = self.closed[:, g][:, mask]  # (m, T)
                glow = s @ self.cells.glow[mine][:, rec]  # (m, R')
                outside = self.cells.outside[g][mask].astype(np.float32)
                for j in np.flatnonzero(shut.any(axis=1)):
                    cols = np.flatnonzero(shut[j])
                    # float32 outer product: half the bytes of float64, one rounding
                    part[j][:, cols] = np.multiply.outer(glow[j], outside[cols])
            if out is None:
                out = part
            else:
                out += part
        if len(self._memo) >= 6:
            self._memo.clear()
        self._memo[key] = out
        return out

    def hours(self, idx, mask: np.ndarray, sun_only: bool = False) -> np.ndarray:
        """(R', m, T) float32 lux at receivers idx in the hours of ``mask``, with the
        LM-83 blinds (the direct sun alone, blinds open, with ``sun_only``): a view of
        the (m, R', T) block."""
        return np.moveaxis(self._light(idx, mask, not sun_only, sun_only), 0, 1)

    def open_hours(self, idx, mask: np.ndarray) -> np.ndarray:
        """(R', m, T) float32 lux at receivers idx in ``mask``'s hours with every blind
        open."""
        return np.moveaxis(self._light(idx, mask, False), 0, 1)

    def band(self, band, idx, mask: np.ndarray) -> np.ndarray:
        """(R', m) an annual metric (``quantities.HourBand``) of this light alone,
        counted on the float32 light (thresholds as the float32 bounds that give
        ``band.of_hours``'s float64 answer) and remembered per threshold pair: DA and
        sDA share one count."""
        if band.direct_sun and band.above and band.lo >= 0 and band.hi == np.inf:
            rec = self._rec(idx)  # the sun's zeros never count: its support alone
            counts = self._sun_counts(rec, mask, band.lo, 0)
            return band_of_counts(band, counts, int(np.sum(mask))).T
        lux = self._light(idx, mask, not band.direct_sun, band.direct_sun)
        key = (id(lux), band.lo, band.hi, band.above)
        counts = self._counts.get(key)
        if counts is None or counts[0] is not lux:
            counts = (lux, hour_counts(lux, band.lo, band.hi, band.above))
            self._counts[key] = counts
        return band_of_counts(band, counts[1], lux.shape[2]).T

    def lux(self, idx=slice(None), hours=slice(None)) -> np.ndarray:
        """(R', m, h) the clear light (lux) in ``hours`` (indices or a slice of the
        year), with the LM-83 blinds."""
        mask = np.zeros(self.cells.weights.shape[1], bool)
        mask[hours] = True
        order = np.argsort(np.argsort(np.arange(len(mask))[hours]))
        return self.hours(idx, mask)[:, :, order]
