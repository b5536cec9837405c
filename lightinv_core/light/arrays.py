"""Light of luminaire arrays, precomputed so a candidate layout costs O(receivers).

A luminaire's light is linear in its dimming and varies smoothly with its position on
the ceiling. So, for each array's zone, product and rotation, the responses of one
luminaire at the nodes of a lattice over the zone (``lattice_step``: 0.25 to 0.5 m
apart, finer the nearer the receivers) are computed once at the receivers the optimiser
reads (intention patches, work-plane points; ``operator/luminaire_basis.py``), and a
luminaire anywhere is the bicubic (Catmull-Rom) blend of the 4 x 4 nodes around it. A
batch of m layouts is one sparse weight matrix W (L, m) and one product R @ W with R
(receivers, L); ``bench/luminaire_arrays.py`` measures the blend against exact placement.

Luminaires are mounted on their zone's surface, their photometric centre
``MOUNT_OFFSET`` below it, aimed along the surface normal (into the room), with the
C0 plane along the zone's u axis (rotation 0) or v axis (rotation 90).
"""

from __future__ import annotations

import copy
import math
import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from lightinv_core.design.arrays import ArrayShapes, luminaire_positions
from lightinv_core.design.model import LuminaireArray, Workplane
from lightinv_core.design.variables import ArrayLayout
from lightinv_core.errors import DesignError, LightInvError
from lightinv_core.light.catmull_rom import catmull_rom, taps
from lightinv_core.luminaires import Photometry, builtin_catalogue, read_photometry
from lightinv_core.luminaires.formats import is_photometry_reference, split_reference
from lightinv_core.operator.luminaire_basis import luminaire_responses
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.scene.patches import Patches
from lightinv_core.scene.zone_grid import zone_grid
from lightinv_core.transport.escape import luminaire_escape_warnings
from lightinv_core.transport.formfactors import DEFAULT_RAYS, form_factor_matrix
from lightinv_core.transport.luminaires import PlacedLuminaire
from lightinv_core.transport.point_sets import PointSet, as_point_set
from lightinv_core.transport.raycast import RayCaster

LATTICE, LATTICE_MAX = 0.25, 0.5
"""Finest and coarsest lattice steps (m) of the precomputed positions."""
STEP_PER_THROW = 0.15
"""Lattice step per metre of throw (least distance from the zone's plane to a receiver):
light d m away changes over about d. Against exact placement, the 0.34 m step of the
classroom's work plane (d = 2.25 m, 12 panel layouts) errs at most 0.11% on Em, 0.0003
on U0; the office benchmark's batwing strips (60 layouts, 640 placements instead of 900)
0.07% on Em, 0.11% on U0, as at 0.25 m. 0.22 x d let the batwing's U0 err 0.43%, near
the search's 0.5% margin (``optimize/judge.py``; docs/photometry.md)."""
MOUNT_OFFSET = 0.02
"""Photometric centre below the mounting surface, m."""
DEFAULT_PLANE_HEIGHT = 0.8
"""Work-plane height (m) above the lowest floor for the SHR rule when the design has no
work plane (EN 12464-1's usual desk height)."""

_FF_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_RESPONSES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
KEEP_RESPONSES = 4  # array precomputes remembered per operator (epsilon sweeps reuse one)
_FIELDS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # arrays_field's responses
KEEP_FIELDS = 16  # a layout's arrays, each control group's, at grids, sensors and patches
_CASTERS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


@dataclass(frozen=True, eq=False)
class Product:
    """A luminaire product: its photometry, rated input power ``watts`` (W) and rated
    flux ``lumens`` (lm, the photometry's own)."""

    name: str
    photometry: Photometry
    watts: float

    @property
    def lumens(self) -> float:
        """Luminous flux of one luminaire at full output, lm."""
        return float(self.photometry.flux())

    @property
    def opening(self) -> tuple[float, float]:
        """(width, length) of the luminous opening, m (IES shape codes taken as sizes)."""
        w, length = (abs(float(x)) for x in self.photometry.opening[:2])
        return w, length

    @property
    def symmetric(self) -> bool:
        """Whether rotating it about its aim changes nothing (one C plane)."""
        return len(self.photometry.c_angles) == 1 and self.opening[0] == self.opening[1]


def resolve_product(name: str, watts: float | None = None) -> Product:
    """The catalogue product called ``name``, or the photometric file at path ``name``
    (IES, EULUMDAT, or ``FILE.gldf#VARIANT``; its input watts, else ``watts``).
    ``watts`` overrides the rated power."""
    for entry in builtin_catalogue():
        if entry.name == name:
            return Product(name, entry.photometry(), float(watts or entry.watts))
    path, _ = split_reference(name) or (Path(name), None)
    if not is_photometry_reference(name):
        known = "; ".join(e.name for e in builtin_catalogue())
        raise DesignError(
            f"product {name!r} is neither a catalogue luminaire ({known}) nor an "
            ".ies/.ldt/.gldf file"
        )
    if not path.is_file():
        raise DesignError(f"product {name!r}: no such photometric file")
    phot = read_photometry(name)
    power = watts if watts is not None else phot.input_watts
    if not power:
        raise DesignError(
            f"product {name!r}: the file gives no input watts; give the array's watts"
        )
    return Product(phot.name or path.stem, phot, float(power))


@dataclass(frozen=True)
class ZoneFrame:
    """An emitter zone's origin, unit u/v axes, inward normal and size (w, h), m."""

    origin: np.ndarray
    u: np.ndarray
    v: np.ndarray
    normal: np.ndarray
    size: tuple[float, float]

    def point(self, u: np.ndarray, v: np.ndarray, lift: float = 0.0) -> np.ndarray:
        """World points (..., 3) of zone coordinates, ``lift`` m off the surface."""
        u, v = np.asarray(u, float), np.asarray(v, float)
        return self.origin + u[..., None] * self.u + v[..., None] * self.v + lift * self.normal


def zone_frame(patches: Patches, zone: str) -> ZoneFrame:
    """The frame of emitter zone ``zone``."""
    try:
        g = zone_grid(patches, zone)
    except LightInvError:
        raise DesignError(f"no emitter zone {zone!r} in the scene") from None
    first = g.patch[0, 0]
    e1, e2 = patches.edge1[first], patches.edge2[first]
    return ZoneFrame(
        np.asarray(patches.origin[first], float),
        e1 / np.linalg.norm(e1),
        e2 / np.linalg.norm(e2),
        np.asarray(patches.normal[first], float),
        g.size,
    )


def placed(
    array: LuminaireArray, product: Product, frame: ZoneFrame, prefix: str = ""
) -> list[PlacedLuminaire]:
    """The luminaires of ``array`` (as written) in the room."""
    c0 = frame.u if array.rotation == 0 else frame.v
    return [
        PlacedLuminaire(
            f"{prefix or array.name}.{k + 1}",
            frame.point(u, v, MOUNT_OFFSET),
            product.photometry,
            aim=frame.normal,
            c0=c0,
            dimming=array.dimming,
        )
        for k, (u, v) in enumerate(array.positions())
    ]


def caster_for(patches: Patches) -> RayCaster:
    """One ray caster per patch set (building one costs a BVH)."""
    caster = _CASTERS.get(patches)
    if caster is None:
        caster = _CASTERS[patches] = RayCaster(patches)
    return caster


def form_factors(patches: Patches, op: RadiosityOperator) -> sp.csr_matrix:
    """The operator's traced form factors: kept by the operator when it has them, else
    traced again with its rays and seed (the same F, bit for bit) and remembered."""
    F = getattr(op, "F", None)
    if F is not None:
        return F
    F = _FF_CACHE.get(op)
    if F is None:
        rays, seed = int(op.info.get("rays", DEFAULT_RAYS)), int(op.info.get("seed", 0))
        F = _FF_CACHE[op] = form_factor_matrix(patches, rays, seed=seed)
    return F


@dataclass(frozen=True)
class _Lattice:
    """Placements of one (zone, product, rotation): nodes (nu, nv) spaced (du, dv) m,
    response columns ``start`` .. start + nu * nv (node (i, k) at start + i * nv + k)."""

    start: int
    nu: int
    nv: int
    du: float
    dv: float


class ArrayLight:
    """Responses of a design's arrays at receiver patches ``rows`` and ``points`` (up
    facing (q, 3), or a ``PointSet``), and the light of candidate layouts there."""

    def __init__(
        self,
        patches: Patches,
        op: RadiosityOperator,
        arrays: Sequence[LuminaireArray],
        free_rotation: Sequence[bool],
        rows: np.ndarray,
        points: np.ndarray | PointSet | None = None,
        lattice: float = LATTICE,
        progress: Callable[[float], None] | None = None,
        cancel: Callable[[], bool] | None = None,
    ):
        self.arrays = tuple(arrays)
        self.products = [resolve_product(a.product, a.watts) for a in self.arrays]
        self.frames = [zone_frame(patches, a.zone) for a in self.arrays]
        self.outlines = tuple(patches.zone_outline(a.zone) for a in self.arrays)
        self.rows = np.asarray(rows, dtype=np.int64)
        ps = as_point_set(points)
        pts = ps.at
        self.n_points = ps.size
        placements: list[PlacedLuminaire] = []
        lattices: dict[tuple, _Lattice] = {}
        self._lattice: list[dict[int, _Lattice]] = []
        for a, prod, frame, free in zip(
            self.arrays, self.products, self.frames, free_rotation, strict=True
        ):
            turns = {0, 90} if free else {a.rotation}
            per: dict[int, _Lattice] = {}
            step = lattice_step(frame, self.rows, pts, patches, lattice)
            for rot in sorted(turns):
                turn = 0 if prod.symmetric else rot
                key = (a.zone, a.product, prod.watts, turn)
                if key not in lattices:
                    lattices[key] = self._add_lattice(placements, prod, frame, turn, step)
                per[rot] = lattices[key]
            self._lattice.append(per)
        if not placements:
            raise DesignError("no luminaire array to light")
        self.placements = len(placements)
        resp = luminaire_responses(
            patches,
            form_factors(patches, op),
            op.lowrank,
            placements,
            self.rows,
            ps,
            caster=caster_for(patches),
            rays=int(op.info.get("rays", DEFAULT_RAYS)),
            progress=progress,
            cancel=cancel,
        )
        self.R = np.ascontiguousarray(np.vstack([resp.at_rows, resp.at_points]))
        self.shapes_opening = np.array([p.opening for p in self.products]).reshape(-1, 2)

    @staticmethod
    def _add_lattice(
        placements: list, prod: Product, frame: ZoneFrame, rot: int, step: float
    ) -> _Lattice:
        w, h = frame.size
        nu = max(2, math.ceil(w / step - 1e-9) + 1)
        nv = max(2, math.ceil(h / step - 1e-9) + 1)
        du, dv = w / (nu - 1), h / (nv - 1)
        start = len(placements)
        c0 = frame.u if rot == 0 else frame.v
        for i in range(nu):
            for k in range(nv):
                placements.append(
                    PlacedLuminaire(
                        f"lattice{start + i * nv + k}",
                        frame.point(i * du, k * dv, MOUNT_OFFSET),
                        prod.photometry,
                        aim=frame.normal,
                        c0=c0,
                    )
                )
        return _Lattice(start, nu, nv, du, dv)

    def for_arrays(self, arrays: Sequence[LuminaireArray]) -> ArrayLight:
        """This precompute for other arrays of the same zones, products and rotations
        (their maintenance factors and ranges may differ)."""
        if tuple(arrays) == self.arrays:
            return self
        twin = copy.copy(self)
        twin.arrays = tuple(arrays)
        return twin

    def shapes(self, mount_height: np.ndarray) -> ArrayShapes:
        """The arrays' shapes for the geometric rules, given their mounting heights (m)."""
        size = np.array([f.size for f in self.frames], dtype=float).reshape(-1, 2)
        return ArrayShapes(
            size, self.shapes_opening, np.asarray(mount_height, float), self.outlines
        )

    def weights(self, layout: ArrayLayout, maintained: bool = True) -> np.ndarray:
        """W (L, m) float32: each lattice node's share of the candidates' luminaires,
        times their dimming (and maintenance factor when ``maintained``)."""
        m = layout.rows.shape[0]
        L = self.placements
        flat_idx, flat_w = [], []
        for j, a in enumerate(self.arrays):
            u, v, mask = luminaire_positions(layout, j)
            scale = layout.dimming[:, j] * (a.maintenance_factor if maintained else 1.0)
            for rot, lat in self._lattice[j].items():
                sel = mask & (layout.rotation[:, j] == rot)[:, None]
                if not sel.any():
                    continue
                fu = np.clip(u / lat.du, 0, lat.nu - 1)
                fv = np.clip(v / lat.dv, 0, lat.nv - 1)
                i0 = np.minimum(np.floor(fu).astype(np.int64), lat.nu - 2)
                k0 = np.minimum(np.floor(fv).astype(np.int64), lat.nv - 2)
                taps_u = taps(i0, catmull_rom(fu - i0), lat.nu)
                taps_v = taps(k0, catmull_rom(fv - k0), lat.nv)
                cand = np.broadcast_to(np.arange(m)[:, None], u.shape)
                for iu, wu in taps_u:
                    for kv, wv in taps_v:
                        node = lat.start + iu * lat.nv + kv
                        flat_idx.append((node * m + cand)[sel])
                        flat_w.append((wu * wv * scale[:, None])[sel])
        if not flat_idx:
            return np.zeros((L, m), np.float32)
        W = np.bincount(np.concatenate(flat_idx), np.concatenate(flat_w), minlength=L * m)
        return W.reshape(L, m).astype(np.float32)

    def illuminance(self, layout: ArrayLayout, maintained: bool = True) -> np.ndarray:
        """(rows + points, m) illuminance (lux) of the candidates' arrays: first at the
        receiver patches, then at the points."""
        return self.R @ self.weights(layout, maintained)

    def electric_power(self, layout: ArrayLayout) -> np.ndarray:
        """Power drawn (W) by the arrays of each candidate: count x watts x dimming."""
        watts = np.array([p.watts for p in self.products])
        return (layout.count * layout.dimming) @ watts

    def installed_power(self, layout: ArrayLayout) -> np.ndarray:
        """Rated power (W) of the arrays of each candidate at full output."""
        watts = np.array([p.watts for p in self.products])
        return layout.count @ watts


def lattice_step(
    frame: ZoneFrame, rows: np.ndarray, points: np.ndarray, patches: Patches, finest: float
) -> float:
    """A zone's lattice step (m): ``STEP_PER_THROW`` x its least distance to a receiver."""
    where = np.vstack([patches.centroid[rows], np.asarray(points, float).reshape(-1, 3)])
    if not len(where):
        return finest
    throw = float(np.abs((where - frame.origin) @ frame.normal).min())
    return float(np.clip(STEP_PER_THROW * throw, finest, max(finest, LATTICE_MAX)))


def array_light(
    patches: Patches,
    op: RadiosityOperator,
    arrays: Sequence[LuminaireArray],
    rows: np.ndarray,
    points: np.ndarray | PointSet | None = None,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
) -> ArrayLight:
    """``ArrayLight`` of ``arrays`` at ``rows`` and ``points``, remembered per operator:
    designs that differ only in the arrays' variables, rules or goals (an epsilon sweep,
    a rerun) share one precompute."""
    free = [a.free.count("rotation") > 0 for a in arrays]
    pts = as_point_set(points)
    rows = np.asarray(rows, dtype=np.int64)
    key = (
        tuple(
            (a.zone, a.product, a.watts, a.rotation, f) for a, f in zip(arrays, free, strict=True)
        ),
        LATTICE,
        rows.tobytes(),
        pts.key(),
    )
    memo = _RESPONSES.setdefault(op, {})
    found = memo.get(key)
    if found is None:
        found = ArrayLight(patches, op, arrays, free, rows, pts, LATTICE, progress, cancel)
        while len(memo) >= KEEP_RESPONSES:
            memo.pop(next(iter(memo)))
        memo[key] = found
    elif progress is not None:
        progress(1.0)
    return found.for_arrays(arrays)


def array_luminaires(
    patches: Patches, arrays: Sequence[LuminaireArray]
) -> list[tuple[LuminaireArray, Product, list[PlacedLuminaire]]]:
    """Each array (as written) with its product and its luminaires in the room."""
    out = []
    for a in arrays:
        prod = resolve_product(a.product, a.watts)
        out.append((a, prod, placed(a, prod, zone_frame(patches, a.zone))))
    return out


def array_escape_warnings(patches: Patches, arrays: Sequence[LuminaireArray]) -> list[str]:
    """A warning naming each luminaire of ``arrays`` whose light mostly leaves the model
    (``transport.escape``): a zone on a surface facing away, or outside the room."""
    lums = [p for _, _, ps in array_luminaires(patches, arrays) for p in ps]
    return luminaire_escape_warnings(lums, caster_for(patches))


def _products_key(arrays: Sequence[LuminaireArray]) -> tuple:
    """What tells the arrays' photometry apart: each product as written, and for a file
    its size and modification time (a file edited on disk is read again)."""
    out = []
    for a in arrays:
        path = (split_reference(a.product) or (Path(a.product), None))[0]
        st = path.stat() if is_photometry_reference(a.product) and path.is_file() else None
        out.append((a.product, None if st is None else (st.st_size, st.st_mtime_ns)))
    return tuple(out)


def arrays_field(
    patches: Patches,
    op: RadiosityOperator,
    arrays: Sequence[LuminaireArray],
    points: np.ndarray | PointSet | None = None,
    maintained: bool = True,
    cancel: Callable[[], bool] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Illuminance (lux) of the arrays as written, placed exactly (no lattice), on every
    patch (n,) and at ``points`` (q,; up, or a ``PointSet``'s values): views, judging."""
    lums, scale = [], []
    for a, _, ps in array_luminaires(patches, arrays):
        for p in ps:
            lums.append(p)
            scale.append(a.dimming * (a.maintenance_factor if maintained else 1.0))
    pts = as_point_set(points)
    if not lums:
        return np.zeros(patches.n), np.zeros(pts.size)
    # Responses at unit dimming, then weighted: one column per luminaire. They depend on
    # where the luminaires are and what they are, not on their dimming: kept per
    # operator, so a climate or dimming edit does not trace them again (seconds each).
    where = [np.concatenate([p.position, p.aim, p.c0]).astype(float) for p in lums]
    key = (_products_key(arrays), pts.key(), np.asarray(where).tobytes())
    memo = _FIELDS.setdefault(op, {})
    resp = memo.pop(key, None)  # re-inserted below: the least recently used goes first
    if resp is None:
        undimmed = [
            PlacedLuminaire(p.name, p.position, p.photometry, p.aim, p.c0, 1.0) for p in lums
        ]
        resp = luminaire_responses(
            patches,
            form_factors(patches, op),
            op.lowrank,
            undimmed,
            np.arange(patches.n),
            pts,
            caster=caster_for(patches),
            rays=int(op.info.get("rays", DEFAULT_RAYS)),
            cancel=cancel,
        )
        while len(memo) >= KEEP_FIELDS:
            memo.pop(next(iter(memo)))
    memo[key] = resp
    w = np.asarray(scale, np.float32)
    return (resp.at_rows @ w).astype(float), (resp.at_points @ w).astype(float)


def plane_height(patches: Patches, workplanes: Sequence[Workplane]) -> float:
    """World height (m) of the work plane the SHR rule measures from: the first work
    plane's (its floor group's area-weighted height plus its height), else
    ``DEFAULT_PLANE_HEIGHT`` above the lowest upward-facing patch."""
    if workplanes:
        wp = workplanes[0]
        try:
            idx = patches.group_index(wp.group)
        except LightInvError:
            raise DesignError(f"work plane {wp.name!r}: no group {wp.group!r}") from None
        a = patches.area[idx]
        return float(patches.centroid[idx, 2] @ a / a.sum()) + wp.height
    up = patches.normal[:, 2] > 0.999
    z = patches.centroid[up, 2] if up.any() else patches.centroid[:, 2]
    return float(z.min()) + DEFAULT_PLANE_HEIGHT


def array_shapes(
    patches: Patches, arrays: Sequence[LuminaireArray], workplanes: Sequence[Workplane]
) -> ArrayShapes:
    """The shapes the array rules need (zone sizes, openings, mounting heights), without
    precomputing any light."""
    frames = [zone_frame(patches, a.zone) for a in arrays]
    plane = plane_height(patches, workplanes)
    return ArrayShapes(
        np.array([f.size for f in frames], dtype=float).reshape(-1, 2),
        np.array([resolve_product(a.product, a.watts).opening for a in arrays]).reshape(-1, 2),
        np.array([float(f.origin[2]) - plane for f in frames]),
        tuple(patches.zone_outline(a.zone) for a in arrays),
    )
