"""From decoded source parameters to the zone emission matrix, and the power goals.

Each source's exitance (lm/m²) is spread over its zone's grid by overlap area
(vectorised over candidates), giving E over the operator's zone-patch columns:
V (nz, m) float32, the input of every radiosity evaluation.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.design.model import Design, DesignError, Goal, Source
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.zones import zone_grid


class EmissionBuilder:
    """Zone grids, operator columns and exitance rules of a design's sources."""

    def __init__(self, design: Design, scene: Scene, patches: Patches, op: RadiosityOperator):
        self.design, self.op = design, op
        kinds = {z.name: z.kind for z in scene.zones}
        for s in (*design.sources, *design.target_sources):
            if s.zone not in kinds:
                known = ", ".join(kinds) or "none"
                raise DesignError(f"source {s.name!r}: no emitter zone {s.zone!r} (zones: {known})")
            if kinds[s.zone] != s.kind:
                raise DesignError(
                    f"source {s.name!r} is a {s.kind} but zone {s.zone!r} takes {kinds[s.zone]}s"
                )
        self.grids = {
            z: zone_grid(patches, z)
            for z in {s.zone for s in (*design.sources, *design.target_sources)}
        }
        self._cols = {}
        for z, g in self.grids.items():
            cols = op.zone_columns(g.patch.ravel())
            # A zone's grid is usually one contiguous run of columns: a slice avoids a
            # fancy-indexed scatter on every batch.
            run = len(cols) and np.array_equal(cols, np.arange(cols[0], cols[0] + len(cols)))
            self._cols[z] = slice(int(cols[0]), int(cols[0]) + len(cols)) if run else cols

    def zone_sizes(self) -> dict[str, tuple[float, float]]:
        """(width, height) in metres of each zone in use."""
        return {z: g.size for z, g in self.grids.items()}

    def decode_sources(self, sources) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple]:
        """Parameters of fixed sources as a one-candidate stack (for target light)."""
        rect = np.array([[s.rect for s in sources]], dtype=float)
        flux = np.array([[s.flux or 0.0 for s in sources]])
        filt = np.array([[s.filter for s in sources]])
        return rect, flux, filt, tuple(sources)

    def exitance(
        self, s: Source, rect: np.ndarray, flux: np.ndarray, filt: np.ndarray
    ) -> np.ndarray:
        """Exitance (lm/m²) of source s for each candidate (rect (m, 4), flux, filt (m,))."""
        if s.kind == "skylight":
            d = self.design.daylight
            return filt * d.transmittance * d.exterior_lux
        if s.exitance is not None:
            return np.full(len(rect), s.exitance)
        area = np.abs(rect[:, 2] - rect[:, 0]) * np.abs(rect[:, 3] - rect[:, 1])
        return flux / np.maximum(area, 1e-12)

    def matrix(self, rect, flux, filt, sources=None, split_kinds: bool = False):
        """V (nz, m) float32: zone-patch exitances of each candidate; with
        ``split_kinds`` also {kind: V of that kind's sources only}."""
        sources = self.design.sources if sources is None else sources
        m = rect.shape[0]
        nz = len(self.op.zone_patches)
        V = np.zeros((nz, m), np.float32)
        by_kind = {k: np.zeros((nz, m), np.float32) for k in ("skylight", "luminaire")}
        for j, s in enumerate(sources):
            g = self.grids[s.zone]
            ex = self.exitance(s, rect[:, j], flux[:, j], filt[:, j])
            ou = _overlap(rect[:, j, 0], rect[:, j, 2], g.patch.shape[0], g.du)
            ov = _overlap(rect[:, j, 1], rect[:, j, 3], g.patch.shape[1], g.dv)
            block = (ex[:, None, None] * ou[:, :, None] * ov[:, None, :]).reshape(m, -1).T
            cols = self._cols[s.zone]
            V[cols] += block
            if split_kinds:
                by_kind[s.kind][cols] += block
        return (V, by_kind) if split_kinds else V

    def light_power(self, by_kind: dict[str, np.ndarray], goals: tuple[Goal, ...]) -> np.ndarray:
        """Total reflected light power (lm) of the sources the light-power goal counts."""
        kinds = next((g.kinds for g in goals if g.kind == "max_light_power"), ())
        use = kinds or tuple(by_kind)
        V = sum(by_kind[k] for k in use)
        return np.asarray(self.op.total_power(self.op.zone_patches, V), dtype=float)

    def electric_power(self, rect: np.ndarray, flux: np.ndarray) -> np.ndarray:
        """Electric power (W) of the luminaires: flux / efficacy, for each candidate."""
        total = np.zeros(rect.shape[0])
        for j, s in enumerate(self.design.sources):
            if s.kind != "luminaire":
                continue
            if s.exitance is not None:
                area = np.abs(rect[:, j, 2] - rect[:, j, 0]) * np.abs(rect[:, j, 3] - rect[:, j, 1])
                total += s.exitance * area / s.efficacy
            else:
                total += flux[:, j] / s.efficacy
        return total

    def light_power_scale(self) -> float:
        """Light power (lm) with every counted source covering its zone at its largest
        exitance (a luminaire's largest flux): the scale of the light-power goal."""
        total = 0.0
        d = self.design.daylight
        for s in self.design.sources:
            g = self.grids[s.zone]
            w, h = g.size
            if s.kind == "skylight":
                ex = d.exterior_lux * d.transmittance
            else:
                ex = s.exitance if s.exitance is not None else s.flux_range[1] / (w * h)
            idx = g.patch.ravel()
            total += float(self.op.total_power(idx, np.full(len(idx), ex)))
        return max(total, 1e-9)

    def electric_power_scale(self) -> float:
        """Largest electric power (W) of the luminaires: the scale of the power goal."""
        total = 0.0
        for s in self.design.sources:
            if s.kind == "luminaire":
                w, h = self.grids[s.zone].size
                flux = s.exitance * w * h if s.exitance is not None else s.flux_range[1]
                total += flux / s.efficacy
        return max(total, 1e-9)


def _overlap(a: np.ndarray, b: np.ndarray, cells: int, size: float) -> np.ndarray:
    """(m, cells) fraction of each grid cell [k size, (k+1) size] covered by [a, b]."""
    lo, hi = np.minimum(a, b)[:, None], np.maximum(a, b)[:, None]
    edges = np.arange(cells + 1) * size
    return np.clip(np.minimum(edges[1:], hi) - np.maximum(edges[:-1], lo), 0.0, None) / size
