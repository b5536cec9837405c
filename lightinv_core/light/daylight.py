"""The light of one layout in every scenario, and its daylight and energy figures.

A ``ScenarioLight`` holds, at a set of receivers (patches or work-plane points), the
luminaires' light (lux, at the layout's fluxes and dimming) and per sky group the
daylight per lux on the group's outside (``daylight_year``); every scenario is a sum
of those (docs/daylight.md):

- ``design``: luminaires + skylights at the design exterior lux (the paper's model);
- ``night``: luminaires only;
- ``overcast``: luminaires + the CIE overcast sky of ``overcast_lux`` on the glazing,
  each group by its orientation (ground reflection included);
- daylight factor DF = overcast daylight / horizontal exterior lux x 100 (%);
- annual: DA300, UDI 100-3000 and sDA over the occupied hours of the weather year,
  and daylight-linked dimming's annual energy (kWh) and LENI (kWh/m² a).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from lightinv_core.climate.metrics import lighting_kwh
from lightinv_core.design.model import Daylight, Design, DesignError, Intention
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Quantity
from lightinv_core.light.annual_energy import AnnualEnergy, annual_energy
from lightinv_core.light.clear_glazing import ClearLight
from lightinv_core.light.clear_layout import laid_clear
from lightinv_core.light.continuous_da import cda as continuous_da
from lightinv_core.light.daylight_year import (
    DaylightYear,
    SkyGroups,
    band_values,
    daylight_year,
)
from lightinv_core.light.dgp_observers import eyed_values, layout_eye_daylight
from lightinv_core.light.en17037_plane import plane_score, reach_shares
from lightinv_core.light.en17037_sun import observer_sunlight
from lightinv_core.light.intentions import (
    BoundCheck,
    bound_checks,
    intention_patches,
    intention_stats,
)
from lightinv_core.quantities import HourBand, quantity_spec
from lightinv_core.scenarios import scenario_spec
from lightinv_core.sources.emission import source_electric_power
from lightinv_core.sources.types import diffusing, source_type


def _per_layout(x: np.ndarray) -> np.ndarray:
    """(R', m) from the clear glazing's (R',) (the same for every layout) or (R', m)."""
    return x[:, None] if x.ndim == 1 else x


SDA_SHARE = 0.5
"""A point counts towards sDA300/50% when its DA300 is at least this share."""


@dataclass(frozen=True, eq=False)
class ScenarioLight:
    """Light of m layouts at R receivers: ``electric`` (R, m) lux from the luminaires,
    ``sky`` (G, R, m) lux per exterior lux on each sky group's plane (diffusing glazing)
    and ``clear`` the fixed clear glazing's light there (``light.clear_glazing``; the
    same for every layout), None without clear glazing."""

    daylight: Daylight
    groups: SkyGroups
    electric: np.ndarray
    sky: np.ndarray
    _year: list = field(default_factory=list, repr=False)
    clear: ClearLight | None = None

    def year(self) -> DaylightYear:
        """The weather year of the sky groups (read once, see ``daylight_year``)."""
        if not self._year:
            self._year.append(daylight_year(self.groups, self.daylight))
        return self._year[0]

    def lux(self, scenario: str, idx=slice(None)) -> np.ndarray:
        """Illuminance (lux) in a scenario (``scenarios.ScenarioSpec.lux``) at receivers idx."""
        spec = scenario_spec(scenario)
        if spec.lux is None:
            raise ValueError(f"no illuminance in scenario {scenario!r}")
        return spec.lux(self, idx)

    def overcast_daylight(self, idx=slice(None)) -> np.ndarray:
        """Daylight per horizontal exterior lux under the CIE overcast sky (DF / 100)."""
        out = np.zeros(self.electric[idx].shape)
        if self.groups.count:
            out = out + np.tensordot(self.groups.overcast, self.sky[:, idx], axes=1)
        if self.clear is not None:
            out = out + _per_layout(self.clear.overcast(idx))
        return out

    def design_daylight(self, idx=slice(None)) -> np.ndarray:
        """(R', m) daylight (lux) of the ``design`` scenario: every diffusing skylight at
        ``exterior_lux`` on its outside, clear glazing under the CIE overcast sky of
        ``exterior_lux`` horizontal."""
        ext = self.daylight.exterior_lux
        out = ext * self.sky[:, idx].sum(axis=0)
        if self.clear is not None:
            out = out + ext * _per_layout(self.clear.overcast(idx))
        return out

    @property
    def daylit(self) -> bool:
        """Whether any daylight reaches the receivers (a sky group or clear glazing)."""
        return bool(self.groups.count) or self.clear is not None

    def hour_daylight(self, hour: int) -> np.ndarray:
        """(R,) daylight (lux) of the first layout in hour ``hour`` of the weather file."""
        y = self.year()
        day = np.zeros(self.electric.shape[0])
        if self.groups.count:
            day = day + np.tensordot(y.every[:, hour], self.sky[:, :, 0], axes=1)
        if self.clear is not None:
            got = self.clear.lux(slice(None), [hour])
            day = day + got.reshape(len(got), -1)[:, 0]
        return day

    def clear_hours(self, idx=slice(None)) -> np.ndarray | None:
        """(R', T) the clear glazing's daylight (lux) in the occupied hours, or None;
        (R', m, T) when the clear glazing moves with the layouts (``light.clear_batch``)."""
        if self.clear is None:
            return None
        return self.clear.hours(idx, np.asarray(self.year().occupied))

    def coefficients(self, idx=slice(None)) -> np.ndarray:
        """(R', m, G): daylight per exterior lux on each group, at receivers idx."""
        return np.moveaxis(self.sky[:, idx], 0, -1)

    def band(self, band: HourBand, idx=slice(None)) -> np.ndarray:
        """An annual daylight metric's values (``quantities.HourBand``) at receivers idx,
        (R', m): the share of occupied hours in the band, or its 0/1 point mark."""
        if self.clear is not None:
            return self._clear_band(band, idx)
        if not self.groups.count:
            return np.zeros(self.electric[idx].shape)
        return band_values(self.year(), self.coefficients(idx), band)

    def _clear_band(self, band: HourBand, idx) -> np.ndarray:
        """``band`` with the clear glazing's light: its own (the same for every layout)
        when it is the only daylight or the band reads the direct sun, else hour by
        hour with the diffusing groups' light added."""
        year = self.year()
        mask = np.asarray(year.occupied)
        m = self.electric.shape[1]
        moving = getattr(self.clear, "per_layout", False)
        if band.direct_sun or not self.groups.count:
            own = self.clear.band(band, idx, mask)
            return own if moving else np.repeat(own[:, None], m, axis=1)
        fixed = self.clear.hours(idx, mask)
        a = self.coefficients(idx)  # (R', m, G)
        out = np.empty(a.shape[:2])
        for r in range(a.shape[0]):
            out[r] = band.of_hours(a[r] @ year.exterior + fixed[r])
        return out

    def en17037_score(self, idx=slice(None)) -> np.ndarray:
        """(R', m) EN 17037 daylight provision of receivers idx as one work plane: the
        level score (``light.en17037_plane``), the same at each receiver."""
        return plane_score(self, idx)

    def en17037_reach(self, idx=slice(None), lux: float = 300.0) -> np.ndarray:
        """(R', m) the share of EN 17037's daylight hours with at least ``lux`` of
        daylight (every blind open) at receivers idx."""
        return reach_shares(self, idx, (lux,))[0]

    def cda(self, idx=slice(None)) -> np.ndarray:
        """cDA300 (0-1) at receivers idx, (R', m) (``light.continuous_da``)."""
        return continuous_da(self, idx)

    def da(self, idx=slice(None)) -> np.ndarray:
        """DA300 (share of occupied hours, 0-1) at receivers idx, (R', m)."""
        return self.band(quantity_spec(Quantity.DA).hours, idx)

    def sda_mark(self, idx=slice(None)) -> np.ndarray:
        """Whether DA300 >= 50% (the points sDA300/50% counts) at receivers idx, (R', m)."""
        return self.band(quantity_spec(Quantity.SDA).hours, idx).astype(bool)

    def udi(self, idx=slice(None)) -> np.ndarray:
        """UDI 100-3000 (share of occupied hours, 0-1) at receivers idx, (R', m)."""
        return self.band(quantity_spec(Quantity.UDI).hours, idx)

    def quantity(self, intention: Intention, idx=slice(None), rho=None) -> np.ndarray:
        """The intention's quantity at receivers idx (R', m): lux or C in its scenario
        (``rho`` the receivers' reflectances for C), DF (%), DA, UDI or the sDA mark."""
        spec = quantity_spec(intention.quantity)
        if spec.hours is not None:
            return self.band(spec.hours, idx)
        if spec.from_scenarios is not None:
            return spec.from_scenarios(self, idx)
        return spec.from_lux(self.lux(intention.scenario, idx), rho)


@dataclass(frozen=True, eq=False)
class LayoutDaylight:
    """One layout's light in every scenario: ``patches`` at every patch (R = n, m = 1),
    ``points`` at the work-plane grid points (None without work planes, ``grids`` their
    layout), ``installed_w`` its luminaires' electric power (W) as designed and
    ``control`` the work plane the dimming reads (None without work planes)."""

    design: Design
    patches: ScenarioLight
    points: ScenarioLight | None
    grids: object | None
    installed_w: float
    control: str | None
    floor_m2: float
    surface: object = None  # the scene's Patches
    observed: dict | None = None  # {observer: UGR} (``light/glare.py``), None without
    observed_error: str = ""  # why the observers could not be rated (one outside the room)
    groups: object = None  # ``light.control_groups.GroupLight``: None for the default group
    groups_error: str = ""  # why the control groups cannot be read (a sensor on no point)
    sunlit: dict | None = None  # {observer: EN 17037 sunlight figures}, None without
    sunlit_error: str = ""  # why the sunlight could not be counted (no minimum altitude)
    glared: dict | None = None  # {observer: simplified DGP figures}, ``light.dgp_observers``
    glared_error: str = ""  # why the DGP could not be computed (an eye outside the room)
    eyed: dict | None = None  # {quantity: {observer: value}} of the ``from_eyes`` quantities

    @cached_property
    def _levels(self) -> np.ndarray:
        """(K, T) each control group's dimming level in each occupied hour."""
        from lightinv_core.light.control_groups import group_levels

        year = self.patches.year()
        return group_levels(self.points, year, self.groups, self.design.daylight.target_lux)

    def at_eyes(self, intention: Intention) -> np.ndarray:
        """(k,) the intention's quantity at its observers: UGR, or the hours of sun
        (EN 17037 sunlight exposure, ``light.en17037_sun``), or a figure of the daylight
        at the eyes (simplified DGP exceedance, ``light.dgp_observers``)."""
        spec = quantity_spec(intention.quantity)
        if spec.from_eyes is not None:
            return eyed_values(self.eyed, self.glared_error, intention)
        if spec.from_glare is None:
            if self.sunlit is None:
                why = self.sunlit_error or "no sunlight was counted"
                raise DesignError(f"intention {intention.name!r}: {why}")
            return np.array([self.sunlit[o]["hours"] for o in intention.observers])
        if not self.observed:
            why = self.observed_error or "no observers were rated"
            raise DesignError(f"intention {intention.name!r}: {why}")
        return np.array([self.observed[o] for o in intention.observers], dtype=float)

    def quantity(self, intention: Intention) -> tuple[np.ndarray, np.ndarray]:
        """(values (R,), weights (R,)) of the intention's quantity in its scenario at its
        receivers: grid points (weight 1) or patches (weight = area, m²); at observers
        the values at each eye (weight 1)."""
        if intention.observers is not None:
            q = self.at_eyes(intention)
            return q, np.ones(len(q))
        if intention.grid is not None:
            if self.points is None or not self.grids.has(intention.grid):
                raise DesignError(f"intention {intention.name!r}: no work plane {intention.grid!r}")
            span = self.grids.span(intention.grid)
            q = self.points.quantity(intention, span)[:, 0]
            return q, np.ones(len(q))
        idx = intention_patches(intention, self.surface)
        q = self.patches.quantity(intention, idx, self.surface.rho[idx])[:, 0]
        return q, self.surface.area[idx]

    def checks(self, intention: Intention) -> list[BoundCheck]:
        """The intention's bound checks on this layout, in its scenario (see
        ``light.intentions.bound_checks``; values in the quantity's units)."""
        q, w = self.quantity(intention)
        return bound_checks(intention, intention_stats(q[:, None], w))

    def energy(self) -> AnnualEnergy:
        """Daylight-linked dimming over the weather year (reads the weather file); LENI
        per m² of the control work plane's floor group."""
        if self.points is None or self.control is None:
            raise DesignError("annual energy is measured on a work plane: add one")
        span = self.grids.spans[self.control]
        if self.groups_error:
            raise DesignError(self.groups_error)
        if self.groups is not None:
            return self._groups_energy()
        return annual_energy(self.points, span, self.installed_w, self.floor_m2)

    def _groups_energy(self) -> AnnualEnergy:
        """``energy`` with several control groups: each dimmed on its own sensor."""
        from lightinv_core.light.control_groups import group_energies

        y, d = self.patches.year(), self.design.daylight
        levels = self._levels
        groups = group_energies(levels, y, self.groups, self.floor_m2)
        hours_year = y.every.shape[1]
        standby = float(lighting_kwh(0.0, 0.0, d.standby_w, hours_year))
        energy = sum(g.energy_kwh for g in groups) + standby
        per_month = np.bincount(np.asarray(y.midpoints.month) - 1, minlength=12)
        monthly = tuple(
            sum(g.monthly_kwh[i] for g in groups) + d.standby_w * per_month[i] / 1000.0
            for i in range(12)
        )
        full_kwh = lighting_kwh(self.installed_w, y.hours, d.standby_w, hours_year)
        watts = self.groups.watts
        mean = float((watts @ levels.mean(axis=1)) / max(watts.sum(), 1e-9))
        floor = max(float(self.floor_m2), 1e-9)
        return AnnualEnergy(
            float(energy),
            float(energy / floor),
            float(full_kwh),
            monthly,
            mean,
            float(self.floor_m2),
            groups,
        )

    def hour_lux(self, hour: int) -> np.ndarray:
        """Illuminance (lux, (n,)) on every patch in hour ``hour`` (0-based, of the
        weather file's year): daylight of that hour plus the luminaires dimmed as the
        control rules set them (off outside the occupancy schedule)."""
        p = self.patches
        y = p.year()
        if not 0 <= hour < y.every.shape[1]:
            raise DesignError(f"hour {hour} is outside the year (0-{y.every.shape[1] - 1})")
        return self.hour_electric(hour) + p.hour_daylight(hour)

    def hour_electric(self, hour: int, at_points: bool = False) -> np.ndarray:
        """The luminaires' light (lux) in hour ``hour`` on every patch (or at the grid
        points), each control group dimmed by its own sensor."""
        light = self.points if at_points else self.patches
        if self.groups is None:
            return light.electric[:, 0] * self.level_at(hour)
        levels = self.group_levels_at(hour)
        each = self.groups.points if at_points else self.groups.patches
        return levels @ each

    def group_levels_at(self, hour: int) -> np.ndarray:
        """(K,) each control group's level (0-1) in hour ``hour``: 0 when unoccupied."""
        y = self.patches.year()
        if not y.occupied[hour]:
            return np.zeros(self.groups.plan.count)
        t = int(np.count_nonzero(y.occupied[:hour]))
        return self._levels[:, t]

    def level_at(self, hour: int) -> float:
        """The luminaires' dimming level (0-1) in hour ``hour``: 0 when unoccupied."""
        y = self.patches.year()
        if not y.occupied[hour]:
            return 0.0
        d = self.design.daylight
        if self.points is None or self.control is None:
            return 1.0
        if self.groups is not None:  # the groups' levels weighted by their power
            w = self.groups.watts
            return float(w @ self.group_levels_at(hour) / max(w.sum(), 1e-9))
        span = self.grids.spans[self.control]
        full = float(self.points.electric[span, 0].mean())
        day = 0.0
        if self.points.groups.count:
            b = self.points.sky[:, span, 0].mean(axis=1)
            day = float(b @ y.every[:, hour])
        if self.points.clear is not None:
            day += float(self.points.clear.lux(span, [hour])[:, 0].mean())
        return float(np.clip((d.target_lux - day) / max(full, 1e-9), d.min_level, 1.0))


def layout_daylight(
    light,
    design: Design,
    sources=None,
    arrays=None,
    progress: Callable[[float], None] | None = None,
) -> LayoutDaylight:
    """The light of one layout of ``design`` (its sources as lit, tied rules applied;
    default: the design as written) in every scenario, on ``light``'s patches and the
    design's work planes. ``progress(fraction)`` (0-1) is called between its steps and
    between the luminaires of its arrays; an exception it raises (a ``CancelledError``)
    stops it (the window's Cancel, as ``clear_build.clear_light``)."""
    from lightinv_core.light.arrays import arrays_field, resolve_product
    from lightinv_core.light.control_groups import control_plan, group_light
    from lightinv_core.light.daylight_year import sky_groups
    from lightinv_core.light.glare import layout_glare
    from lightinv_core.light.grids import design_receivers, grid_light

    step = progress or (lambda f: None)

    def asking(fraction: float) -> Callable[[], bool]:
        # arrays_field's cancel(): asks ``progress``, which raises to stop.
        def cancel() -> bool:
            step(fraction)
            return False

        return cancel

    sources = light.layout(design) if sources is None else tuple(sources)
    arrays = design.arrays if arrays is None else tuple(arrays)
    groups = sky_groups(light, design)
    lum = tuple(s for s in sources if not source_type(s.kind).daylit)
    unit = replace(design.daylight, exterior_lux=1.0)
    electric = light.field(lum, design.daylight).illuminance.copy()
    step(0.02)
    grids = design_receivers(light, design)
    step(0.1)
    arrays_at_points = None
    if arrays:
        # Once for the patches and the grid points (grid_light would place them again:
        # the same call, the same light), a luminaire at a time between cancel checks.
        points = None if grids is None else grids.samples
        Hp, arrays_at_points = arrays_field(
            light.patches, light.op, arrays, points, cancel=asking(0.1)
        )
        electric += Hp
    step(0.35)
    sky = np.zeros((groups.count, light.n))
    per_group = []
    for g, zones in enumerate(groups.zones):
        group = tuple(s for s in diffusing(sources) if s.zone in zones)
        per_group.append(group)
        sky[g] = light.field(group, unit).illuminance
    as_laid = replace(design, sources=sources) if sources != design.sources else design
    clear, clear_points = laid_clear(light, design, sources, as_laid)
    at_patches = ScenarioLight(
        design.daylight,
        groups,
        electric[:, None],
        sky[:, :, None],
        clear=clear,
    )
    at_points = None
    if grids is not None:
        e_pts = grid_light(light, grids, lum, (), design.daylight)
        if arrays_at_points is not None:
            e_pts += arrays_at_points
        s_pts = np.zeros((groups.count, len(grids.points)))
        for g, grp in enumerate(per_group):
            s_pts[g] = grid_light(light, grids, grp, (), unit)
        at_points = ScenarioLight(
            design.daylight,
            groups,
            e_pts[:, None],
            s_pts[:, :, None],
            at_patches._year,
            clear_points,
        )
    watts = float(sum(source_electric_power(s) for s in lum))
    for a in arrays:
        watts += a.count * resolve_product(a.product, a.watts).watts * a.dimming
    plane = design.control_plane
    floor = 0.0
    if plane is not None:
        floor = float(light.patches.area[light.patches.group_index(plane.group)].sum())
    control_light, plan, groups_error = None, None, ""
    try:
        plan = None if grids is None else control_plan(design, grids)
    except DesignError as exc:  # the rest of the light stands; the energy says why
        groups_error = str(exc)
    step(0.4)
    if plan is not None:
        control_light = group_light(light, design, grids, plan, sources, arrays, asking(0.4))
    step(0.8)
    observed, observed_error, sunlit = None, "", None
    eyes = [it for it in design.intentions if it.observers is not None]
    if any(quantity_spec(it.quantity).from_glare for it in eyes):
        try:
            observed = layout_glare(light, design, sources, arrays, asking(0.8))
        except DesignError as exc:  # the rest of the light stands; the glare says why
            observed_error = str(exc)
    step(0.95)
    sunlit_error = ""
    specs = [quantity_spec(it.quantity) for it in eyes]
    if any(q.from_glare is None and q.from_eyes is None for q in specs):
        try:
            sunlit = observer_sunlight(light, as_laid)
        except LightInvError as exc:  # the rest of the light stands; the intention says why
            sunlit_error = str(exc)
    eye_daylight = layout_eye_daylight(light, design, sources, specs)  # glared, its error, eyed
    step(1.0)
    return LayoutDaylight(
        design,
        at_patches,
        at_points,
        grids,
        watts,
        None if plane is None else plane.name,
        floor,
        light.patches,
        observed,
        observed_error,
        control_light,
        groups_error,
        sunlit,
        sunlit_error,
        *eye_daylight,
    )
