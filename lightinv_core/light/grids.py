"""Work-plane grids of a design: their points and the zone sources' light there.

A grid point takes light from the patches it sees and gives none back
(``transport/receivers.py``): with F_p its traced form factors to the patches, the
light of zone emission e (lm/m² on the emitter-zone patches) at the points is

    H_p = F_p[:, zone] e + F_p R Phi e,

so the zone basis at the points, Phi_p = F_p[:, zone] + F_p R Phi (q, nz), is
precomputed once and a candidate costs O(q) per emitting zone patch, like a patch
receiver. Phi's rows are made only where the points see patches, a block at a time.

Each work plane's grid follows the rule of its EN 12464-1 edition (``GRID_RULES``): both
take the largest cell p = 0.2 x 5^log10(d) m; EN 12464-1:2011 takes d from the longer
side (the shorter when the longer is twice it or more) and rounds each side's
side / p up on its own (``transport.workplane.grid_counts``); EN 12464-1:2021 takes d
from the longer side and rounds side / p to the nearest whole number (F. Rudawski's
Lighting Toolbox ``egrid``, mode "std", cites EN 12464-1:2021 for it; Fagerhult's
EN 12464-1 pages: "d - is the longer length of the surface"). On an 8 x 6 m room with
a 0.5 m border (7 x 5 m): p = 0.780 m, 2011 gives 9 x 7 points, 2021 9 x 6.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from lightinv_core.design.model import (
    CalcObject,
    Daylight,
    Design,
    LuminaireArray,
    Source,
    Workplane,
)
from lightinv_core.errors import LightInvError, SceneError
from lightinv_core.light.arrays import arrays_field, caster_for
from lightinv_core.light.model import LightModel
from lightinv_core.operator.radiosity import BASIS_BYTES
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.emission import source_stack
from lightinv_core.transport.formfactors import DEFAULT_RAYS
from lightinv_core.transport.point_sets import PointSet, as_point_set, stack
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors
from lightinv_core.transport.workplane import GRID_RULES as GRID_RULES  # re-exported
from lightinv_core.transport.workplane import (
    Grid,
    WorkPlane,
    grid_counts,
    grid_statistics,
    work_plane_grid,
)
from lightinv_core.transport.workplane import grid_counts_2021 as grid_counts_2021

GRID_SEED_OFFSET = 7  # the points' rays draw from a stream of their own


def edition_grid(patches: Patches, caster: RayCaster, wp: Workplane) -> Grid:
    """The grid of work plane ``wp`` by its edition's rule (``work_plane_grid`` lays the
    rule's counts over the floor and keeps the points by its tests). Should another rule
    keep no point where 2011's keeps some, the 2011 grid keeps the plane usable."""
    plane = WorkPlane(wp.height, wp.border, wp.group, wp.name)
    rule = GRID_RULES[wp.edition]
    if rule is grid_counts:
        return work_plane_grid(patches, caster, plane)
    try:
        return work_plane_grid(patches, caster, plane, rule)
    except SceneError:
        raise  # the plane is not inside its room: no rule helps
    except LightInvError:
        return work_plane_grid(patches, caster, plane)


@dataclass(frozen=True)
class DesignGrids:
    """The grids of a design's work planes, then its calculation objects' values,
    stacked: ``points`` (q, 3) m where each value is read, ``spans`` {work plane name:
    slice of the points}, ``grids`` {name: Grid}, ``floor_z`` {name: height of its
    floor, m}, ``Phi`` (q, nz) float32, the zone basis at the points (lux per lm/m² of
    each emitter-zone patch); ``calc_spans`` {calculation object: slice} and
    ``receivers``, the samples the values are made of (``transport.point_sets``: a
    cylinder's ring of vertical samples; None when every value is an upward sample)."""

    points: np.ndarray
    spans: dict[str, slice]
    grids: dict[str, Grid]
    floor_z: dict[str, float]
    Phi: np.ndarray
    calc_spans: dict[str, slice] = field(default_factory=dict)
    receivers: PointSet | None = None

    def plane_height(self, name: str) -> float:
        """World height (m) of work plane ``name``."""
        span = self.spans[name]
        return float(self.points[span][0, 2])

    def span(self, name: str) -> slice:
        """The slice of the points of work plane or calculation object ``name``."""
        return self.spans[name] if name in self.spans else self.calc_spans[name]

    def has(self, name: str) -> bool:
        """Whether ``name`` is one of its work planes or calculation objects."""
        return name in self.spans or name in self.calc_spans

    @property
    def samples(self) -> PointSet:
        """The receiver samples (upward points of the grids when no object needs more)."""
        return self.receivers if self.receivers is not None else as_point_set(self.points)


_GRIDS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def design_grids(
    light: LightModel,
    workplanes: Sequence[Workplane],
    calc_objects: Sequence[CalcObject] = (),
) -> DesignGrids:
    """Lay out each work plane's EN 12464-1 grid and each calculation object's points,
    and precompute their zone basis (remembered per operator, work planes and objects)."""
    memo = _GRIDS.setdefault(light.op, {})
    key = (tuple(workplanes), tuple(calc_objects))
    if key not in memo:
        memo.clear()  # one set of work planes at a time per operator
        memo[key] = _design_grids(light, *key)
    return memo[key]


def design_receivers(light: LightModel, design: Design) -> DesignGrids | None:
    """The grids of ``design``'s work planes and calculation objects (None without any)."""
    if not design.workplanes and not design.calc_objects:
        return None
    return design_grids(light, design.workplanes, design.calc_objects)


def _design_grids(
    light: LightModel, workplanes: Sequence[Workplane], calc_objects: Sequence[CalcObject]
) -> DesignGrids:
    patches, op = light.patches, light.op
    caster = caster_for(patches)
    grids, spans, floor_z, chunks = {}, {}, {}, []
    start = 0
    for wp in workplanes:
        g = edition_grid(patches, caster, wp)
        grids[wp.name] = g
        spans[wp.name] = slice(start, start + len(g.points))
        floor_z[wp.name] = float(g.points[0, 2] - wp.height)
        start += len(g.points)
        chunks.append(g.points)
    sets = [as_point_set(np.vstack(chunks))] if chunks else []
    calc_spans = {}
    for obj in calc_objects:
        ps = obj.spec.readings(obj, patches, caster)
        calc_spans[obj.name] = slice(start, start + ps.size)
        start += ps.size
        sets.append(ps)
    samples = stack(sets)
    receivers = samples if calc_objects else None
    points = samples.at
    nz = len(op.zone_patches)
    if not len(points):
        return DesignGrids(
            points, spans, grids, floor_z, np.zeros((0, nz), np.float32), calc_spans, receivers
        )
    rays = int(op.info.get("rays", DEFAULT_RAYS))
    seed = int(op.info.get("seed", 0)) + GRID_SEED_OFFSET
    Fp = receiver_factors(samples.points, samples.normals, caster, patches.n, rays, seed)
    Fp = Fp.tocsc()
    seen = np.flatnonzero(np.diff(Fp.indptr))
    Phi = np.zeros((len(samples.points), nz), np.float32)
    R = (Fp[:, seen].multiply(op.rho[seen][None, :])).tocsr().astype(np.float32)
    # The rows of the basis the points see, a block at a time (memory O(block x nz)).
    block = max(1, BASIS_BYTES // (8 * max(nz, 1)))
    for a in range(0, len(seen), block):
        Phi += np.asarray(R[:, a : a + block] @ op.phi_rows(seen[a : a + block]))
    Phi += Fp[:, op.zone_patches].toarray().astype(np.float32)
    Phi = samples.values(Phi)
    # Shared by every problem and view of these work planes: nobody may change them.
    for a in (points, Phi):
        a.setflags(write=False)
    return DesignGrids(points, spans, grids, floor_z, Phi, calc_spans, receivers)


def grid_light(
    light: LightModel,
    grids: DesignGrids,
    sources: Sequence[Source],
    arrays: Sequence[LuminaireArray],
    daylight: Daylight,
    cancel: Callable[[], bool] | None = None,
) -> np.ndarray:
    """Illuminance (lux, maintained) at every grid point of a layout: its zone sources
    through the points' zone basis, its arrays placed exactly (no lattice); ``cancel()``
    asked between the arrays' luminaires (``arrays_field``)."""
    lux = np.zeros(len(grids.points))
    if sources:
        V = light.zone_emission(sources, *source_stack(sources), daylight)[:, 0]
        lux += grids.Phi.astype(float) @ V.astype(float)
    if arrays:
        _, at_points = arrays_field(light.patches, light.op, arrays, grids.samples, cancel=cancel)
        lux += at_points
    return lux


def grid_results(
    light: LightModel,
    grids: DesignGrids,
    sources: Sequence[Source],
    arrays: Sequence[LuminaireArray],
    daylight: Daylight,
) -> dict[str, dict[str, float]]:
    """EN 12464-1 values (points, Em, Emin, Emax lux, U0) of each work plane and
    calculation object."""
    lux = grid_light(light, grids, sources, arrays, daylight)
    spans = grids.spans | grids.calc_spans
    return {name: grid_statistics(lux[span]) for name, span in spans.items()}
