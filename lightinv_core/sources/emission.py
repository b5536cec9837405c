"""From sources to emission: zone grids, exitances and the zone emission matrix.

Each rectangular source's exitance (lm/m²) is spread over its zone's grid by overlap
area (vectorised over candidates), giving E over the operator's zone-patch columns:
V (nz, m) float32, the input of every radiosity evaluation. Also here: what a source
emits (lm) and draws (W), the per-source facts every view reports.

What each kind of source emits and draws is its ``SourceType`` (types.py).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from lightinv_core.design.model import Daylight, Source
from lightinv_core.errors import DesignError
from lightinv_core.kinds import source_kind_names
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches
from lightinv_core.scene.zone_grid import ZoneGrid, zone_grid
from lightinv_core.sources.types import source_type


def source_stack(sources: Sequence[Source]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The parameters of ``sources`` as a one-candidate stack: rectangles (1, S, 4) in m,
    fluxes (1, S) in lm (0 where none) and filters (1, S)."""
    rect = np.array([[s.rect for s in sources]], dtype=float).reshape(1, len(sources), 4)
    flux = np.array([[s.flux or 0.0 for s in sources]]).reshape(1, len(sources))
    filt = np.array([[s.filter for s in sources]], dtype=float).reshape(1, len(sources))
    return rect, flux, filt


def source_flux(s: Source, daylight: Daylight) -> float:
    """Luminous flux (lm) a source emits (its type's rule: a luminaire's flux, a panel's
    or a skylight's exitance x area)."""
    return source_type(s.kind).flux(s, daylight)


def source_electric_power(s: Source) -> float:
    """Electric power (W) a source draws as placed (0 for daylight)."""
    rect, flux, _ = source_stack((s,))
    return float(source_type(s.kind).electric_power(s, rect[:, 0], flux[:, 0])[0])


def electric_power(sources: Sequence[Source], rect: np.ndarray, flux: np.ndarray) -> np.ndarray:
    """Electric power (W) of ``sources`` for each candidate (rect (m, S, 4), flux (m, S))."""
    total = np.zeros(rect.shape[0])
    for j, s in enumerate(sources):
        t = source_type(s.kind)
        if t.electric:
            total += t.electric_power(s, rect[:, j], flux[:, j])
    return total


class ZoneEmission:
    """The emitter zones of a scene as the operator sees them: each zone's grid and
    its columns in the zone basis, built on first use."""

    def __init__(self, scene: Scene, patches: Patches, op: RadiosityOperator):
        self.patches, self.op = patches, op
        self.kinds = {z.name: z.kind for z in scene.zones}
        self._grids: dict[str, ZoneGrid] = {}
        self._cols: dict[str, slice | np.ndarray] = {}

    def check(self, sources: Sequence[Source]) -> None:
        """DesignError unless every source names a zone of the scene of its own kind."""
        for s in sources:
            if s.zone not in self.kinds:
                known = ", ".join(self.kinds) or "none"
                raise DesignError(f"source {s.name!r}: no emitter zone {s.zone!r} (zones: {known})")
            if self.kinds[s.zone] != s.kind:
                raise DesignError(
                    f"source {s.name!r} is a {s.kind} but zone {s.zone!r} "
                    f"takes {self.kinds[s.zone]}s"
                )

    def grid(self, zone: str) -> ZoneGrid:
        """The zone's patch grid (u, v cells of ``du`` x ``dv`` metres)."""
        if zone not in self._grids:
            g = zone_grid(self.patches, zone)
            cols = self.op.zone_columns(g.patch.ravel())
            # A zone's grid is usually one contiguous run of columns: a slice avoids a
            # fancy-indexed scatter on every batch.
            run = len(cols) and np.array_equal(cols, np.arange(cols[0], cols[0] + len(cols)))
            self._grids[zone] = g
            self._cols[zone] = slice(int(cols[0]), int(cols[0]) + len(cols)) if run else cols
        return self._grids[zone]

    def zone_size(self, zone: str) -> tuple[float, float]:
        """(width, height) in metres of an emitter zone."""
        return self.grid(zone).size

    def columns(self, zone: str) -> slice | np.ndarray:
        """The zone's patches' columns among the operator's zone patches."""
        self.grid(zone)
        return self._cols[zone]

    def matrix(
        self,
        sources: Sequence[Source],
        rect: np.ndarray,
        flux: np.ndarray,
        filt: np.ndarray,
        daylight: Daylight,
        split_kinds: bool = False,
    ):
        """V (nz, m) float32: zone-patch exitances (lm/m²) of each candidate; with
        ``split_kinds`` also {kind: V of that kind's sources only}."""
        m = rect.shape[0]
        nz = len(self.op.zone_patches)
        V = np.zeros((nz, m), np.float32)
        by_kind = {k: np.zeros((nz, m), np.float32) for k in source_kind_names()}
        for j, s in enumerate(sources):
            g = self.grid(s.zone)
            ex = source_type(s.kind).exitance(s, rect[:, j], flux[:, j], filt[:, j], daylight)
            ou = _overlap(rect[:, j, 0], rect[:, j, 2], g.patch.shape[0], g.du)
            ov = _overlap(rect[:, j, 1], rect[:, j, 3], g.patch.shape[1], g.dv)
            block = (ex[:, None, None] * ou[:, :, None] * ov[:, None, :]).reshape(m, -1).T
            cols = self._cols[s.zone]
            V[cols] += block
            if split_kinds:
                by_kind[s.kind][cols] += block
        return (V, by_kind) if split_kinds else V

    def full_exitance(self, s: Source, daylight: Daylight) -> float:
        """The exitance (lm/m²) of source s covering its whole zone at its largest
        setting (a luminaire's largest flux): the scale of the light-power goal."""
        return source_type(s.kind).largest_exitance(s, self.zone_size(s.zone), daylight)

    def full_electric_power(self, s: Source) -> float:
        """Electric power (W) of source s at its largest setting over its whole zone:
        the scale of the power goal."""
        return source_type(s.kind).largest_electric_power(s, self.zone_size(s.zone))


def _overlap(a: np.ndarray, b: np.ndarray, cells: int, size: float) -> np.ndarray:
    """(m, cells) fraction of each grid cell [k size, (k+1) size] covered by [a, b]."""
    lo, hi = np.minimum(a, b)[:, None], np.maximum(a, b)[:, None]
    edges = np.arange(cells + 1) * size
    return np.clip(np.minimum(edges[1:], hi) - np.maximum(edges[:-1], lo), 0.0, None) / size
