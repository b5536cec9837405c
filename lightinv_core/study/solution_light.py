"""The light of one solution of a project, for the report, the CLI's ``solve`` and the
window: every figure they show comes from here, each computed once when first asked.

- ``field``: illuminance on every patch in the design scenario (the ``LightModel``'s
  field of the solution's sources, its luminaire arrays placed exactly);
- ``daylight``: the layout in every scenario (``light.daylight.LayoutDaylight``: DF,
  the weather year, dimming energy);
- ``grids`` and ``grid_lux``: the work planes' EN 12464-1 grids and their illuminance;
  ``grid_stats`` their Em, Emin, Emax and U0 per work plane; ``calc_stats`` the same
  of each calculation object.
"""

from __future__ import annotations

from dataclasses import replace
from functools import cached_property

import numpy as np

from lightinv_core.design.model import Design
from lightinv_core.design.solution import Solution
from lightinv_core.light.arrays import arrays_field
from lightinv_core.light.daylight import LayoutDaylight, layout_daylight
from lightinv_core.light.field import LightField
from lightinv_core.light.grids import DesignGrids, design_receivers, grid_light
from lightinv_core.light.model import LightModel
from lightinv_core.transport.workplane import grid_statistics


class SolutionLight:
    """The light of ``sources`` and ``arrays`` (a solution's) of ``design`` in ``light``'s
    scene (see the module)."""

    def __init__(self, light: LightModel, design: Design, sources, arrays) -> None:
        self.light, self.design = light, design
        self.sources, self.arrays = tuple(sources), tuple(arrays)

    @cached_property
    def field(self) -> LightField:
        """Illuminance (lux) on every patch, design scenario, arrays placed exactly."""
        field = self.light.field(self.sources, self.design.daylight)
        if self.arrays:
            # Luminaire arrays placed exactly (not the optimiser's lattice).
            H, _ = arrays_field(self.light.patches, self.light.op, self.arrays)
            field = replace(field, illuminance=field.illuminance + H)
        return field

    @cached_property
    def daylight(self) -> LayoutDaylight:
        """The layout's light in every scenario, its daylight and annual energy."""
        return layout_daylight(self.light, self.design, self.sources, self.arrays)

    @cached_property
    def grids(self) -> DesignGrids | None:
        """The design's work-plane grids and calculation objects (None without any)."""
        return design_receivers(self.light, self.design)

    @cached_property
    def grid_lux(self) -> np.ndarray | None:
        """Illuminance (lux) at every grid point (None without work planes)."""
        if self.grids is None:
            return None
        return grid_light(self.light, self.grids, self.sources, self.arrays, self.design.daylight)

    @property
    def grid_stats(self) -> dict[str, dict[str, float]]:
        """EN 12464-1 values (points, Em, Emin, Emax lux, U0) of each work plane."""
        if self.grids is None:
            return {}
        return {n: grid_statistics(self.grid_lux[s]) for n, s in self.grids.spans.items()}

    @property
    def calc_stats(self) -> dict[str, dict[str, float]]:
        """The values of each calculation object in the design scenario: points, mean
        ("Em"), min, max (lux: E, Ez or Esc as its kind reads) and U0 = min / mean."""
        if self.grids is None:
            return {}
        return {n: grid_statistics(self.grid_lux[s]) for n, s in self.grids.calc_spans.items()}


def solution_light(prepared, design: Design, solution: Solution) -> SolutionLight:
    """The light of ``solution`` of ``design`` in a prepared project (``Prepared``)."""
    return SolutionLight(prepared.light, design, solution.sources, solution.arrays)
