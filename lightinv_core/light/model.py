"""``LightModel``: the one place where a layout becomes light.

Bound to a scene, its patches and their radiosity operator, it turns sources (with a
daylight condition) into illuminance and everything derived from it, in two forms:

- one layout on every patch, as a ``LightField`` (the window, reports, the CLI,
  diagnostics): ``field(sources, daylight)``, or ``design_field(design)`` for a design
  as written with its tied rules (mirror, centred) applied;
- batches of candidate layouts at chosen receiver patches (the optimizer):
  ``zone_emission`` -> ``illuminance`` (one GEMM through the zone basis), plus the
  scalar goals that need no field: ``reflected_power`` (O(nz)) and ``electric_power``.

Light is linear in the emission and every source lives in an emitter zone, so H =
Phi[:, cols] @ V over the zone columns the layout touches (see docs/operator.md).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from lightinv_core.design.model import Daylight, Design, Source
from lightinv_core.design.variables import Variables
from lightinv_core.errors import DesignError
from lightinv_core.light.field import LightField
from lightinv_core.operator.radiosity import MatchTarget, RadiosityOperator
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.emission import ZoneEmission, electric_power, source_stack


@dataclass(frozen=True)
class Receivers:
    """Patches at which a batch's illuminance is wanted: ``rows`` (p,) patch ids, and the
    zone-basis rows (p, nz) float32 Fortran-ordered so a batch's columns are contiguous
    (None when every patch is a receiver)."""

    rows: np.ndarray
    Phi_rows: np.ndarray | None


class LightModel:
    """Light of layouts in one scene: sources -> illuminance and derived quantities."""

    def __init__(self, scene: Scene, patches: Patches, operator: RadiosityOperator):
        if operator.n != patches.n or operator.digest != patches.digest():
            raise DesignError("the radiosity operator was built for another scene")
        self.scene, self.patches, self.op = scene, patches, operator
        self.emission = ZoneEmission(scene, patches, operator)

    @property
    def n(self) -> int:
        """Number of patches."""
        return self.patches.n

    def check(self, sources: Sequence[Source]) -> None:
        """DesignError unless every source names a zone of the scene of its own kind."""
        self.emission.check(sources)

    def zone_size(self, zone: str) -> tuple[float, float]:
        """(width, height) in metres of an emitter zone."""
        return self.emission.zone_size(zone)

    # -- batches (the optimizer) --------------------------------------------------------------
    def zone_emission(
        self,
        sources: Sequence[Source],
        rect: np.ndarray,
        flux: np.ndarray,
        filt: np.ndarray,
        daylight: Daylight,
        split_kinds: bool = False,
    ):
        """V (nz, m) float32, zone-patch exitances (lm/m²) of m candidate layouts of
        ``sources`` (rect (m, S, 4) m, flux (m, S) lm, filt (m, S)); with ``split_kinds``
        also {source kind: V of that kind's sources}."""
        return self.emission.matrix(sources, rect, flux, filt, daylight, split_kinds)

    def receivers(self, rows: np.ndarray) -> Receivers:
        """A receiver set for ``illuminance`` at patches ``rows``."""
        rows = np.asarray(rows, dtype=np.int64)
        # Column-major so a batch's columns are contiguous; None when every row is needed.
        Phi_rows = None if len(rows) == self.n else np.asfortranarray(self.op.Phi[rows])
        return Receivers(rows, Phi_rows)

    def illuminance(
        self, V: np.ndarray, receivers: Receivers | None = None, cols: np.ndarray | None = None
    ) -> np.ndarray:
        """H (lux) at the receivers (default: every patch) for the batch V (nz, m), one GEMM.
        ``cols`` are the zone columns any candidate emits from (found when not given)."""
        Phi = self.op.Phi if receivers is None or receivers.Phi_rows is None else receivers.Phi_rows
        if cols is None:
            cols = np.flatnonzero(np.any(V != 0, axis=1))
        if 3 * len(cols) > V.shape[0]:
            return Phi @ V
        return Phi[:, cols] @ V[cols]

    def reflected_power(self, V: np.ndarray) -> np.ndarray:
        """Total reflected light power sum_i C_i A_i (lm) of each candidate of V (nz, m)."""
        return np.asarray(self.op.total_power(self.op.zone_patches, V), dtype=float)

    def electric_power(
        self, sources: Sequence[Source], rect: np.ndarray, flux: np.ndarray
    ) -> np.ndarray:
        """Electric power (W) of the luminaires among ``sources``, per candidate."""
        return electric_power(sources, rect, flux)

    def power_scale(self, sources: Sequence[Source], daylight: Daylight) -> float:
        """Reflected light power (lm) with every source covering its zone at its largest
        exitance: the scale of the light-power goal."""
        total = 0.0
        for s in sources:
            idx = self.emission.grid(s.zone).patch.ravel()
            ex = self.emission.full_exitance(s, daylight)
            total += float(self.op.total_power(idx, np.full(len(idx), ex)))
        return max(total, 1e-9)

    def match_target(
        self, sources: Sequence[Source], daylight: Daylight
    ) -> tuple[MatchTarget, np.ndarray]:
        """The match-error evaluator for the light of ``sources`` (paper eq. 11) and that
        light's reflected exitance C_obj (n,) in lm/m²."""
        e_obj = self.zone_emission(sources, *source_stack(sources), daylight)[:, 0]
        return (
            self.op.match_target(self.op.zone_patches, e_obj),
            self.op.rho * (self.op.Phi @ e_obj),
        )

    # -- one layout (views, reports, diagnostics) ---------------------------------------------
    def field(self, sources: Sequence[Source], daylight: Daylight) -> LightField:
        """The light of ``sources`` (placed as given) on every patch."""
        sources = tuple(sources)
        self.check(sources)
        E = np.zeros(self.n)
        if not sources:
            return LightField(sources, daylight, self.patches, np.zeros(self.n), E)
        V = self.zone_emission(sources, *source_stack(sources), daylight)[:, 0]
        cols = np.flatnonzero(V)
        H = self.op.Phi[:, cols] @ V[cols]
        E[self.op.zone_patches] = V
        return LightField(sources, daylight, self.patches, H.astype(np.float64), E)

    def emission_field(self, E: np.ndarray) -> LightField:
        """The light of a dense emission E (n,) in lm/m² on any patches (not sources):
        zone patches go through the zone basis, others through the plain low-rank
        operator, which blurs their direct light over clusters (docs/operator.md)."""
        E = np.asarray(E, dtype=np.float64)
        H = np.asarray(self.op.illuminance(E), dtype=np.float64)
        return LightField((), Daylight(), self.patches, H, E.copy())

    def layout(self, design: Design, sources: Sequence[Source] | None = None) -> tuple:
        """``sources`` (default: the design's) as lit: the design's tied rules (mirror,
        centred) applied to the rectangles, fluxes and filters as written."""
        sources = tuple(design.sources if sources is None else sources)
        if not sources:
            return ()
        design = design if sources == design.sources else _with_sources(design, sources)
        self.check(sources)
        vars_ = Variables(design, {s.zone: self.zone_size(s.zone) for s in sources})
        return vars_.sources_at(vars_.initial())

    def design_field(self, design: Design, sources: Sequence[Source] | None = None) -> LightField:
        """The light of a design as written (or of other ``sources`` under its rules)."""
        return self.field(self.layout(design, sources), design.daylight)


def _with_sources(design: Design, sources: tuple) -> Design:
    """``design`` with other sources, keeping only the rules that still apply to them."""
    names = {s.name for s in sources}
    rules = tuple(r for r in design.rules if set(r.sources) <= names)
    return replace(design, sources=sources, rules=rules)
