"""A design's daylight-linked control groups on its work-plane grids, and their year.

Each group (``design.model.ControlGroup``) holds luminaire sources and arrays and reads
its sensor: the grid points of a work plane inside a plan rectangle. Each occupied hour
its mode (``climate.control_modes``) sets its level from its sensor's mean daylight, its
own target (default ``daylight.target_lux``) and its own luminaires' light there at
full output (the other groups' light is not counted: each sensor is calibrated with its
own group alone, as ``study.control_groups`` does): ``dimming`` tops the daylight up to
the target by the one rule of ``climate.metrics.dimming_level``, down to its
``min_level``; ``switching`` is off while the daylight alone meets the target (with its
``dead_band``: off from target x (1 + band), on again below the target). Energy (kWh a
year) per group and in total (standby counted once, in the total); LENI per group over
the whole floor of the control plane, so the groups' LENIs add up.

``control_plan`` is None for a design whose luminaires all stay in the one default group
without a declared sensor: its dimming is the one-group path of ``light.daylight``, bit
for bit as before groups existed.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from lightinv_core.climate.control_modes import ControlModeSpec, control_mode, mode_levels
from lightinv_core.climate.metrics import lighting_kwh
from lightinv_core.design.model import DEFAULT_CONTROL_GROUP, ControlGroup, Design, DesignError
from lightinv_core.light.daylight_year import DaylightYear, level_sum
from lightinv_core.sources.types import source_type


def sensor_mask(points: np.ndarray, rect: Sequence[float] | None) -> np.ndarray:
    """The points (q, 3) within the plan rectangle (x0, y0, x1, y1), m: the lower edges
    in, the upper edges out, so two regions sharing an edge share no point."""
    pts = np.asarray(points, dtype=float)
    if rect is None:
        return np.ones(len(pts), bool)
    x0, y0, x1, y1 = rect
    lo_x, hi_x, lo_y, hi_y = min(x0, x1), max(x0, x1), min(y0, y1), max(y0, y1)
    return (pts[:, 0] >= lo_x) & (pts[:, 0] < hi_x) & (pts[:, 1] >= lo_y) & (pts[:, 1] < hi_y)


@dataclass(frozen=True, eq=False)
class ControlPlan:
    """The groups that hold luminaires, in the design's order (the undeclared default
    group last): ``names``, ``sensors[k]`` the grid point ids (into ``grids.points``)
    group k reads, ``min_levels``, ``sources[k]`` and ``arrays[k]`` the ids of its
    luminaire sources (into ``design.sources``) and arrays (into ``design.arrays``),
    ``modes[k]`` its control mode, ``targets[k]`` its target (lux: its own, else the
    daylight's) and ``bands[k]`` its dead band (fraction of the target; switching)."""

    names: tuple[str, ...]
    sensors: tuple[np.ndarray, ...]
    min_levels: tuple[float, ...]
    sources: tuple[np.ndarray, ...]
    arrays: tuple[np.ndarray, ...]
    modes: tuple[ControlModeSpec, ...] = ()
    targets: tuple[float | None, ...] = ()
    bands: tuple[float, ...] = ()

    def band(self, k: int) -> float:
        """Group k's dead band (0 for a plan made without bands)."""
        return self.bands[k] if k < len(self.bands) else 0.0

    def target(self, k: int, default: float) -> float:
        """Group k's target (lux), or ``default`` for a plan made without targets."""
        own = self.targets[k] if k < len(self.targets) else None
        return default if own is None else own

    def mode(self, k: int) -> ControlModeSpec:
        """Group k's control mode (dimming when the plan names none)."""
        return self.modes[k] if k < len(self.modes) else control_mode("dimming")

    @property
    def count(self) -> int:
        """Number of groups."""
        return len(self.names)


def default_only(design: Design) -> bool:
    """Whether ``design`` keeps the one default group read on the whole control plane."""
    return not design.control_groups and all(
        x.control_group == DEFAULT_CONTROL_GROUP for x in (*design.sources, *design.arrays)
    )


def control_plan(design: Design, grids) -> ControlPlan | None:
    """The control groups of ``design`` on its ``grids`` (``light.grids.DesignGrids``),
    or None when it keeps the default group alone (``default_only``)."""
    if default_only(design) or grids is None or design.control_plane is None:
        return None
    declared = {c.name: c for c in design.control_groups}
    order = [c.name for c in design.control_groups]
    if DEFAULT_CONTROL_GROUP not in declared:
        order.append(DEFAULT_CONTROL_GROUP)
    lum = [j for j, s in enumerate(design.sources) if source_type(s.kind).electric]
    names, sensors, floors, srcs, arrs, modes, targets, bands = ([] for _ in range(8))
    for name in order:
        s_ids = np.array([j for j in lum if design.sources[j].control_group == name], int)
        a_ids = np.array([j for j, a in enumerate(design.arrays) if a.control_group == name], int)
        if not len(s_ids) and not len(a_ids):
            continue  # a group without luminaires uses no energy
        group = declared.get(name, ControlGroup(name))
        names.append(name)
        sensors.append(_sensor_points(design, grids, group))
        floors.append(design.daylight.min_level if group.min_level is None else group.min_level)
        srcs.append(s_ids)
        arrs.append(a_ids)
        modes.append(control_mode(group.mode))
        d = design.daylight
        targets.append(d.target_lux if group.target_lux is None else group.target_lux)
        bands.append(group.dead_band)
    return ControlPlan(
        tuple(names),
        tuple(sensors),
        tuple(floors),
        tuple(srcs),
        tuple(arrs),
        tuple(modes),
        tuple(targets),
        tuple(bands),
    )


def _sensor_points(design: Design, grids, group: ControlGroup) -> np.ndarray:
    plane = group.workplane or design.control_plane.name
    span = grids.spans[plane]
    ids = span.start + np.flatnonzero(sensor_mask(grids.points[span], group.sensor))
    if not len(ids):
        raise DesignError(
            f"control group {group.name!r}: its sensor {list(group.sensor)} holds no point "
            f"of work plane {plane!r}; draw it over the work plane"
        )
    return ids


@dataclass(frozen=True)
class GroupEnergy:
    """One control group's year: ``luminaires`` (count), ``watts`` (W as laid out),
    ``sensor_points`` read, ``electric_lux`` (its own light on its sensor at full
    output), ``min_level``, ``mean_level`` over the occupied hours, ``energy_kwh`` a
    year, ``leni`` (kWh/m² a over the control plane's floor), ``monthly_kwh`` (12,),
    its control ``mode``, ``target_lux`` (lux) and ``dead_band`` (fraction)."""

    name: str
    luminaires: int
    watts: float
    sensor_points: int
    electric_lux: float
    min_level: float
    mean_level: float
    energy_kwh: float
    leni: float
    monthly_kwh: tuple[float, ...]
    mode: str = "dimming"
    target_lux: float = 500.0
    dead_band: float = 0.0

    def as_dict(self) -> dict:
        """JSON-ready."""
        return {**self.__dict__, "monthly_kwh": list(self.monthly_kwh)}


@dataclass(frozen=True, eq=False)
class GroupLight:
    """Each group's luminaires lit alone at full output (as laid out): ``points`` (K, q)
    lux at every grid point, ``patches`` (K, n) lux on every patch, ``watts`` (K,) W and
    ``counts`` (K,) luminaires."""

    plan: ControlPlan
    points: np.ndarray
    patches: np.ndarray
    watts: np.ndarray
    counts: np.ndarray


def group_light(
    light, design: Design, grids, plan: ControlPlan, sources, arrays, cancel=None
) -> GroupLight:
    """The light of each group of a layout (its ``sources`` as lit and ``arrays``, in the
    design's order), its arrays placed exactly."""
    from lightinv_core.light.arrays import arrays_field, resolve_product
    from lightinv_core.light.grids import grid_light
    from lightinv_core.sources.emission import source_electric_power

    sources, arrays = tuple(sources), tuple(arrays)
    K = plan.count
    at_points, at_patches = np.zeros((K, len(grids.points))), np.zeros((K, light.n))
    watts, counts = np.zeros(K), np.zeros(K, int)
    for k in range(K):
        srcs = tuple(sources[j] for j in plan.sources[k])
        arrs = tuple(arrays[j] for j in plan.arrays[k])
        at_points[k] = grid_light(light, grids, srcs, arrs, design.daylight, cancel)
        if srcs:
            at_patches[k] = light.field(srcs, design.daylight).illuminance
        if arrs:
            at_patches[k] += arrays_field(light.patches, light.op, arrs, cancel=cancel)[0]
        watts[k] = sum(source_electric_power(s) for s in srcs) + sum(
            a.count * resolve_product(a.product, a.watts).watts * a.dimming for a in arrs
        )
        counts[k] = len(srcs) + sum(a.count for a in arrs)
    return GroupLight(plan, at_points, at_patches, watts, counts)


def group_levels(points, year: DaylightYear, lit: GroupLight, target: float) -> np.ndarray:
    """(K, T) each group's level (0-1) in each occupied hour, by its mode; ``points`` the
    layout's ``ScenarioLight`` at the grid points (its daylight), ``target`` (lux) the
    daylight's, for groups without their own."""
    plan = lit.plan
    out = np.empty((plan.count, year.hours))
    for k, ids in enumerate(plan.sensors):
        full = max(float(lit.points[k, ids].mean()), 1e-9)
        b = points.sky[:, ids, 0].mean(axis=1)
        day = np.asarray(b, dtype=float) @ year.exterior
        clear = points.clear_hours(ids)
        if clear is not None:
            day = day + clear.mean(axis=0)
        out[k] = mode_levels(
            plan.mode(k),
            day,
            full,
            plan.target(k, target),
            plan.min_levels[k],
            plan.band(k),
            year.day_starts,
        )
    return out


def group_energies(
    levels: np.ndarray, year: DaylightYear, lit: GroupLight, floor_m2: float
) -> tuple[GroupEnergy, ...]:
    """Each group's year from its hourly ``levels`` (K, T) (``group_levels``)."""
    plan = lit.plan
    hours_year = year.every.shape[1]
    per_month = np.bincount(np.asarray(year.midpoints.month) - 1, minlength=12)
    floor = max(float(floor_m2), 1e-9)
    out = []
    for k, name in enumerate(plan.names):
        w = float(lit.watts[k])
        kwh = float(lighting_kwh(w, levels[k].sum(), 0.0, hours_year))
        monthly = tuple(
            float(lighting_kwh(w, levels[k][year.months == m].sum(), 0.0, per_month[m - 1]))
            for m in range(1, 13)
        )
        out.append(
            GroupEnergy(
                name,
                int(lit.counts[k]),
                w,
                len(plan.sensors[k]),
                float(lit.points[k, plan.sensors[k]].mean()),
                plan.min_levels[k],
                float(levels[k].mean()),
                kwh,
                kwh / floor,
                monthly,
                plan.mode(k).name,
                plan.target(k, 0.0),
                plan.band(k),
            )
        )
    return tuple(out)


# -- batches of candidates (the optimiser) ----------------------------------------------------


class GroupBatch:
    """Each group's mean lux at full output on its sensor and its watts for m candidates
    of a problem: zone sources through the points' zone basis, arrays from their lattice
    (or, judging one layout, placed exactly: ``exact`` (K,) lux)."""

    def __init__(self, plan: ControlPlan, design: Design, grids, arrays_light=None):
        self.plan, self.design = plan, design
        self.phi = [grids.Phi[ids].astype(float).mean(axis=0) for ids in plan.sensors]
        self.R = None
        if arrays_light is not None:
            off = len(arrays_light.rows)
            self.R = [arrays_light.R[off + ids].astype(float).mean(axis=0) for ids in plan.sensors]
            self.array_watts = np.array([p.watts for p in arrays_light.products])
        self.arrays_light = arrays_light

    def full_and_watts(self, light, rect, flux, filt, layout, exact=None):
        """((K, m) lux, (K, m) W) of m candidates (rect (m, S, 4), flux, filt (m, S))."""
        d, plan = self.design, self.plan
        m = rect.shape[0]
        full, watts = np.zeros((plan.count, m)), np.zeros((plan.count, m))
        for k in range(plan.count):
            ids = plan.sources[k]
            if len(ids):
                srcs = [d.sources[j] for j in ids]
                V = light.zone_emission(srcs, rect[:, ids], flux[:, ids], filt[:, ids], d.daylight)
                full[k] += self.phi[k] @ V.astype(float)
                watts[k] += light.electric_power(srcs, rect[:, ids], flux[:, ids])
            a_ids = plan.arrays[k]
            if len(a_ids) and layout is not None:
                on = np.zeros(layout.dimming.shape[1])
                on[a_ids] = 1.0
                if exact is not None:
                    full[k] += exact[k]
                else:
                    mine = replace(layout, dimming=layout.dimming * on)
                    full[k] += self.R[k] @ self.arrays_light.weights(mine).astype(float)
                watts[k] += (layout.count * layout.dimming)[:, a_ids] @ self.array_watts[a_ids]
        return full, watts

    def level_sums(self, parts, offset: int, full: np.ndarray, target: float) -> np.ndarray:
        """(K, m) each group's levels (by its mode) summed over the occupied hours;
        ``parts`` the batch's ``ScenarioLight`` at the level's receivers, grid points from
        ``offset``; ``target`` (lux) the daylight's, for groups without their own."""
        year = parts.year()
        plan = self.plan
        out = np.empty(full.shape)
        for k, ids in enumerate(plan.sensors):
            idx = offset + ids
            b = parts.sky[:, idx].mean(axis=1).T
            clear = parts.clear_hours(idx)
            fixed = None if clear is None else clear.mean(axis=0)
            out[k] = level_sum(
                plan.mode(k),
                year,
                b,
                full[k],
                plan.target(k, target),
                plan.min_levels[k],
                fixed,
                plan.band(k),
            )
        return out


def exact_arrays_at_sensors(light, plan: ControlPlan, grids, arrays) -> np.ndarray:
    """(K,) each group's arrays (``arrays``, placed exactly) mean lux on its sensor."""
    from lightinv_core.light.arrays import arrays_field

    out = np.zeros(plan.count)
    for k, a_ids in enumerate(plan.arrays):
        if len(a_ids):
            mine = [arrays[j] for j in a_ids]
            at = arrays_field(light.patches, light.op, mine, grids.points[plan.sensors[k]])[1]
            out[k] = float(at.mean())
    return out


# -- where the sensors are (the window draws them) -------------------------------------------


@dataclass(frozen=True)
class SensorOutline:
    """Where control group ``name`` reads: ``corners`` (4, 3) m, its plan rectangle on
    the work plane ``workplane`` at that plane's height (the plane's grid extent when it
    reads the whole plane), and whether it is ``whole``."""

    name: str
    workplane: str
    corners: np.ndarray
    whole: bool


def sensor_outlines(design: Design, patches, grids=None) -> tuple[SensorOutline, ...]:
    """The sensor of every control group of ``design`` (the declared ones in order, then
    the default group when it holds luminaires); none for a design that keeps the one
    default group (``default_only``). The height and a whole plane's extent come from the
    work plane's grid points (``grids``, ``light.grids.DesignGrids``) when given, else
    from its floor group's patches (the height above their median, their plan extent
    less the border); a group on a plane that cannot be placed is left out."""
    if default_only(design) or design.control_plane is None:
        return ()
    groups = list(design.control_groups)
    names = {g.name for g in groups}
    lums = [s for s in design.sources if source_type(s.kind).electric]
    members = {x.control_group for x in (*lums, *design.arrays)}
    if DEFAULT_CONTROL_GROUP not in names and DEFAULT_CONTROL_GROUP in members:
        groups.append(ControlGroup(DEFAULT_CONTROL_GROUP))
    planes = {w.name: w for w in design.workplanes}
    out = []
    for g in groups:
        wp = planes.get(g.workplane or design.control_plane.name)
        extent = None if wp is None else _plane_extent(wp, patches, grids)
        if extent is None:
            continue
        x0, y0, x1, y1, z = extent
        if g.sensor is not None:
            x0, y0, x1, y1 = g.sensor
        xy = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)
        corners = np.column_stack([xy, np.full(4, z)])
        out.append(SensorOutline(g.name, wp.name, corners, g.sensor is None))
    return tuple(out)


def _plane_extent(wp, patches, grids) -> tuple[float, float, float, float, float] | None:
    """(x0, y0, x1, y1, z) m of work plane ``wp``: its grid's extent and height, or its
    floor group's (None when the group is not in the scene)."""
    if grids is not None and wp.name in grids.spans:
        pts = grids.points[grids.spans[wp.name]]
        if len(pts):
            lo, hi = pts[:, :2].min(axis=0), pts[:, :2].max(axis=0)
            return (*lo, *hi, float(np.median(pts[:, 2])))
    if wp.group not in patches.group_names:
        return None
    c = patches.centroid[patches.group_index(wp.group)]
    lo, hi = c[:, :2].min(axis=0) + wp.border, c[:, :2].max(axis=0) - wp.border
    lo, hi = np.minimum(lo, hi), np.maximum(lo, hi)
    return (*lo, *hi, float(np.median(c[:, 2])) + wp.height)
