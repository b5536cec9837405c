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
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from lightinv_core.light.clear_cells import ClearCells

MAX_KEPT = 8
"""Hourly cell blocks kept per cells object (receiver set x hour mask x kind)."""


def _key(idx) -> tuple:
    if isinstance(idx, slice):
        return ("slice", idx.start, idx.stop, idx.step)
    a = np.asarray(idx)
    return ("rows", a.dtype.str, a.tobytes())


def cell_hours(cells: ClearCells, rec: np.ndarray, mask: np.ndarray, sun_only: bool) -> np.ndarray:
    """(C, R', T) float32 each cell's light (lux, blinds open, no glow) at receivers
    ``rec`` (indices into the cells' receivers) in the hours of ``mask``: the direct sun
    alone with ``sun_only``. Kept on ``cells`` (the same for every batch)."""
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
    off = len(cells.rows)
    on = rec >= off  # work-plane points: their direct sun is traced hour by hour
    for c in range(cells.count):
        coef = cells.coef[c, rec]
        if sun_only:
            out[c] = coef[:, cells.sun_cols] @ W[cells.sun_cols]
        else:
            out[c] = coef @ W
        if on.any():
            out[c, on] += cells.direct[c][rec[on] - off][:, hours].toarray()
    memo[key] = out
    return out


class ClearBatch:
    """The clear light of m candidates (``shares`` (m, C)) at a level's receivers:
    ``pos`` maps each level receiver to the cells' receivers; ``occupied`` (H,) the
    schedule's hours (the blinds close only then); ``control`` the control work
    plane's points among the cells' points (None: blinds stay open)."""

    per_layout = True

    def __init__(self, cells: ClearCells, shares, pos, occupied, control=None):
        self.cells = cells
        self.shares = np.asarray(shares, dtype=np.float32)
        self.pos = np.asarray(pos, dtype=np.int64)
        self.occupied = np.asarray(occupied, bool)
        self.control = control
        self.columns = SimpleNamespace(outward=cells.outward)
        self._memo: dict = {}
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

    def _sum(self, blocks: np.ndarray, mine, s) -> np.ndarray:
        """(m, R', T) the candidates' sum of the cells' ``blocks`` (C, R', T)."""
        C, R, T = blocks[mine].shape
        return (s @ blocks[mine].reshape(C, R * T)).reshape(-1, R, T)

    @property
    def closed(self) -> np.ndarray:
        """(m, G, H) each candidate's LM-83 blinds per clear source and hour."""
        if self._closed is None:
            from lightinv_core.climate.sun_metrics import blinds_schedule

            c = self.cells
            H = c.weights.shape[1]
            closed = np.zeros((self.m, c.sources, H), bool)
            if self.control is not None and self.occupied.any():
                rec = len(c.rows) + np.arange(c.points)[self.control]
                sun = cell_hours(c, rec, self.occupied, True)
                per = np.stack([self._sum(sun, mine, s) for _, mine, s in self._by_source()], 1)
                for j in range(self.m):  # (G, q, T) each
                    closed[j][:, self.occupied] = blinds_schedule(per[j])
            self._closed = closed
        return self._closed

    def overcast(self, idx=slice(None)) -> np.ndarray:
        """(R', m) lux per horizontal exterior lux under the CIE overcast sky."""
        return self.cells.over[:, self.pos[idx]].T.astype(float) @ self.shares.T.astype(float)

    def _light(self, idx, mask, blinds: bool, sun_only: bool = False) -> np.ndarray:
        """(R', m, T) the candidates' clear light at receivers idx in ``mask``'s hours."""
        key = (_key(idx), np.asarray(mask).tobytes(), blinds, sun_only)
        if key in self._memo:
            return self._memo[key]
        rec = self.pos[idx]
        mask = np.asarray(mask, bool)
        blocks = cell_hours(self.cells, rec, mask, sun_only)
        out = np.zeros((self.m, len(rec), int(mask.sum())), np.float32)
        for g, mine, s in self._by_source():
            part = self._sum(blocks, mine, s)
            if blinds and not sun_only:
                shut = self.closed[:, g][:, mask][:, None, :]  # (m, 1, T)
                glow = s @ self.cells.glow[mine][:, rec]  # (m, R')
                outside = self.cells.outside[g][mask].astype(np.float32)
                part = np.where(shut, glow[:, :, None] * outside, part)
            out += part
        got = np.ascontiguousarray(np.moveaxis(out, 0, 1))
        if len(self._memo) >= 6:
            self._memo.clear()
        self._memo[key] = got
        return got

    def hours(self, idx, mask: np.ndarray, sun_only: bool = False) -> np.ndarray:
        """(R', m, T) lux at receivers idx in the hours of ``mask``, with the LM-83
        blinds (the direct sun alone, blinds open, with ``sun_only``)."""
        return self._light(idx, mask, not sun_only, sun_only)

    def open_hours(self, idx, mask: np.ndarray) -> np.ndarray:
        """(R', m, T) lux at receivers idx in ``mask``'s hours with every blind open."""
        return self._light(idx, mask, False)

    def band(self, band, idx, mask: np.ndarray) -> np.ndarray:
        """(R', m) an annual metric (``quantities.HourBand``) of this light alone."""
        lux = self.hours(idx, mask, band.direct_sun)
        R, m, T = lux.shape
        return band.of_hours(lux.reshape(R * m, T)).reshape(R, m)

    def lux(self, idx=slice(None), hours=slice(None)) -> np.ndarray:
        """(R', m, h) the clear light (lux) in ``hours`` (indices or a slice of the
        year), with the LM-83 blinds."""
        mask = np.zeros(self.cells.weights.shape[1], bool)
        mask[hours] = True
        order = np.argsort(np.argsort(np.arange(len(mask))[hours]))
        return self.hours(idx, mask)[:, :, order]
