"""``LightField``: the light of one layout on every patch, and what is derived from it.

Units: illuminance H in lux; exitances E (emitted), C = rho * H (reflected) and the
radiosity B = E + C in lm/m²; luminance B / pi in cd/m² (Lambertian surfaces); light
power in lm; electric power in W.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from lightinv_core.design.model import Daylight, Intention, Source
from lightinv_core.light.intentions import (
    BoundCheck,
    IntentionStats,
    bound_checks,
    intention_patches,
    intention_stats,
    offending,
    quantity_values,
)
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.emission import source_electric_power, source_flux


@dataclass(frozen=True)
class IntentionResult:
    """An intention judged on a field: its patches, statistics and each bound's check."""

    intention: Intention
    patches: np.ndarray
    stats: IntentionStats
    checks: tuple[BoundCheck, ...]

    @property
    def met(self) -> bool:
        """Whether every bound holds (to within 0.1%)."""
        return all(bool(c.met[0]) for c in self.checks)


@dataclass(frozen=True, eq=False)
class LightField:
    """The light of ``sources`` (as lit: tied rules applied) on every patch.

    illuminance : (n,) float64, lux
    emission : (n,) float64, exitance E of the emitting patches, lm/m²
    """

    sources: tuple[Source, ...]
    daylight: Daylight
    patches: Patches
    illuminance: np.ndarray
    emission: np.ndarray
    _intentions: dict = field(default_factory=dict, repr=False)

    @property
    def reflected(self) -> np.ndarray:
        """C = rho * H (n,), reflected exitance in lm/m² (the paper's C)."""
        return self.patches.rho * self.illuminance

    @property
    def radiosity(self) -> np.ndarray:
        """B = E + C (n,), total exitance in lm/m²."""
        return self.emission + self.reflected

    @property
    def luminance(self) -> np.ndarray:
        """B / pi (n,), cd/m² of Lambertian surfaces."""
        return self.radiosity / np.pi

    @property
    def reflected_power(self) -> float:
        """Total reflected light power sum_i C_i A_i, lm."""
        return float(np.dot(self.reflected, self.patches.area))

    @property
    def electric_power(self) -> float:
        """Electric power of the luminaires, W."""
        return float(sum(source_electric_power(s) for s in self.sources))

    def source_flux(self, source: Source) -> float:
        """Luminous flux (lm) ``source`` emits under this field's daylight."""
        return source_flux(source, self.daylight)

    def group_stats(self, group: str) -> IntentionStats:
        """Illuminance statistics (lux) of a patch group: min, max, area-weighted
        average and U0 = min / average."""
        idx = self.patches.group_index(group)
        return intention_stats(self.illuminance[idx, None], self.patches.area[idx])

    def intention(self, intention: Intention) -> IntentionResult:
        """``intention`` judged on every one of its patches (each standing for its area)."""
        key = intention
        if key not in self._intentions:
            idx = intention_patches(intention, self.patches)
            q = quantity_values(intention, self.illuminance[idx, None], self.patches.rho[idx])
            stats = intention_stats(q, self.patches.area[idx])
            self._intentions[key] = IntentionResult(
                intention, idx, stats, tuple(bound_checks(intention, stats))
            )
        return self._intentions[key]

    def offending_patches(self, intention: Intention) -> list[tuple[str, np.ndarray]]:
        """(bound, patch ids) for each bound of ``intention`` the field breaks."""
        res = self.intention(intention)
        idx = res.patches
        q = quantity_values(intention, self.illuminance[idx], self.patches.rho[idx])
        avg = float(res.stats.average[0])
        return [
            (str(c.bound), np.unique(idx[offending(c, q, avg)])) for c in res.checks if not c.met[0]
        ]
