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
Phi[:, cols] @ V over the zone columns the layout touches (see docs/operator.md). The
operator keeps Phi as factors: a batch reads Phi's rows at its receivers, made once per
receiver set (``receivers``); one layout on every patch comes from sparse products
(``RadiosityOperator.zone_field``), so memory grows with n k + receivers x nz, not n nz.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from lightinv_core.design.model import Daylight, Design, Source
from lightinv_core.design.variables import Variables
from lightinv_core.errors import DesignError
from lightinv_core.light.field import LightField
from lightinv_core.operator.radiosity import BASIS_BYTES, MatchTarget, RadiosityOperator
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.emission import ZoneEmission, electric_power, source_stack

DISPLAY_BYTES = 1 << 30
"""Largest whole zone basis (n x nz float32) a light model keeps for showing one layout on
every patch (1 GiB: office takes 30 MB, patio about 300 MB, the 200,000-patch building
would take 19 GB and is lit from the factors instead)."""


@dataclass(frozen=True)
class Receivers:
    """Patches at which a batch's illuminance is wanted: ``rows`` (p,) patch ids, and the
    zone-basis rows (p, nz) float32 Fortran-ordered so a batch's columns are contiguous
    (None when they would exceed ``BASIS_BYTES``: each batch is then lit from the
    operator's factors, O(nnz(F) + n k) per candidate)."""

    rows: np.ndarray
    Phi_rows: np.ndarray | None


class LightModel:
    """Light of layouts in one scene: sources -> illuminance and derived quantities."""

    def __init__(self, scene: Scene, patches: Patches, operator: RadiosityOperator):
        if operator.n != patches.n or operator.digest != patches.digest():
            raise DesignError("the radiosity operator was built for another scene")
        self.scene, self.patches, self.op = scene, patches, operator
        self.emission = ZoneEmission(scene, patches, operator)
        self._every: Receivers | None = None

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
        """A receiver set for ``illuminance`` at patches ``rows``: Phi's rows there, made
        once (O(nnz(F)) per row or per zone patch, whichever side is smaller), unless
        they would exceed ``BASIS_BYTES`` (then None: lit from the factors per batch).
        The set of every patch is kept for the model's lifetime."""
        rows = np.asarray(rows, dtype=np.int64)
        every = len(rows) == self.n and np.array_equal(rows, np.arange(self.n))
        if every and self._every is not None:
            return self._every
        fits = 4 * len(rows) * len(self.op.zone_patches) <= BASIS_BYTES
        got = Receivers(rows, self.op.phi_rows(rows) if fits else None)
        if every:
            self._every = got
        return got

    def illuminance(
        self, V: np.ndarray, receivers: Receivers | None = None, cols: np.ndarray | None = None
    ) -> np.ndarray:
        """H (lux) at the receivers (default: every patch) for the batch V (nz, m), one GEMM
        over Phi's rows (or sparse products over the factors when those rows were not
        made). ``cols`` are the zone columns any candidate emits from (found when not given)."""
        receivers = receivers or self.receivers(np.arange(self.n))
        Phi = receivers.Phi_rows
        if Phi is None:
            return self.op.zone_field(V, receivers.rows)
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
            self.op.rho * self.op.zone_field(e_obj),
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
        H = self._whole_field(V)
        E[self.op.zone_patches] = V
        return LightField(sources, daylight, self.patches, H.astype(np.float64), E)

    def _whole_field(self, V: np.ndarray) -> np.ndarray:
        """H (n,) lux of zone emission V (nz,): through the whole basis kept in memory when
        it is at most ``DISPLAY_BYTES`` (an editor relights on every edit: 1 ms instead of
        the factors' 30 ms on office), else from the factors."""
        if 4 * self.n * len(self.op.zone_patches) > DISPLAY_BYTES:
            return self.op.zone_field(V)
        Phi = self.receivers(np.arange(self.n)).Phi_rows
        cols = np.flatnonzero(V)
        return Phi[:, cols] @ V[cols]

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
        zones = {s.zone for s in sources} | {a.zone for a in design.arrays}
        vars_ = Variables(design, {z: self.zone_size(z) for z in zones})
        return vars_.sources_at(vars_.initial())

    def design_field(self, design: Design, sources: Sequence[Source] | None = None) -> LightField:
        """The light of a design as written (or of other ``sources`` under its rules)."""
        return self.field(self.layout(design, sources), design.daylight)


def _with_sources(design: Design, sources: tuple) -> Design:
    """``design`` with other sources, keeping only the rules that still apply to them."""
    names = {s.name for s in sources}
    rules = tuple(r for r in design.rules if set(r.sources) <= names)
    return replace(design, sources=sources, rules=rules)
