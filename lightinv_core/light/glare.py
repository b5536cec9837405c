"""Glare at the design's observers: CIE 117's UGR of many candidate layouts at once.

    UGR = 8 log10( 0.25 / Lb * sum_i L_i² omega_i / p_i² )      (luminaires/ugr.py)

at each observer's eye, looking along its view, for the electric light of the design's
luminaire arrays (photometric products). Skylights and windows are not glare sources
here and their daylight is left out of the background (UGR rates the installation, CIE
117). Zone luminaires (Lambertian rectangles without a photometric file) are refused:
the light model spreads their flux over the zone's patches, which keeps the light right
but not the luminance of a rectangle smaller than a patch.

- **Glare sum**: each luminaire's luminance towards the eye from its photometry
  (``ugr.luminance``: the intensity over the luminous opening projected across the
  line of sight), the solid angle of that projected opening, Guth's position index;
  the luminaires of every candidate at once ((m, P) numpy arrays, the positions of
  ``design.arrays.luminaire_positions``).
- **Background** Lb = E_ind / pi (CIE 117), E_ind the indirect illuminance on a plane
  at the eye facing the view: the eye is a receiver point like a work-plane grid point
  (``transport/receivers.py``: its traced form factors F_e to the patches), and E_ind =
  F_e (rho H) is the light the room's surfaces reflect to it, H the luminaires' light
  on the patches (direct and interreflected); the luminaires' own direct light on the
  eye is not in it. For the optimiser this is one row per eye, ``F_e rho R``, over the
  arrays' lattice responses R (their rows hold every patch an eye sees), so a batch
  costs one (k, L) x (L, m) product.

Values are as new (no maintenance factor, on the luminance and the background alike;
CIE 190's tables are for the luminaire's rated flux): a conservative choice, as a
maintenance factor MF would lower UGR by 8 log10(1 / MF) (0.78 at 0.8).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from lightinv_core.design.arrays import luminaire_positions
from lightinv_core.design.model import Design, DesignError, Intention, Observer
from lightinv_core.design.variables import ArrayLayout
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Quantity
from lightinv_core.light.arrays import (
    MOUNT_OFFSET,
    ArrayLight,
    array_luminaires,
    arrays_field,
    caster_for,
    resolve_product,
)
from lightinv_core.light.model import LightModel
from lightinv_core.luminaires.ugr import (
    glare_terms,
    in_field,
    luminance,
    luminous_area,
    position_index,
    projected_area,
)
from lightinv_core.quantities import quantity_spec
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.types import source_type
from lightinv_core.transport.formfactors import DEFAULT_RAYS
from lightinv_core.transport.receivers import receiver_factors

EYE_SEED_OFFSET = 11  # the eyes' rays draw from a stream of their own
EYE_RAYS = 4
"""The eyes' form factors use this many times the operator's rays per point: a handful
of points, and the background is what UGR is most sensitive to (8 log10 of it)."""


@dataclass(frozen=True)
class Eyes:
    """The observers' eyes: ``names``, ``points`` (k, 3) m and unit ``views`` (k, 3)."""

    names: tuple[str, ...]
    points: np.ndarray
    views: np.ndarray

    def frame(self, i: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(forward, up, side) unit vectors of eye i (CIE 117's R, H and T axes)."""
        f = self.views[i]
        up = np.array([0.0, 0.0, 1.0]) - f[2] * f
        up /= np.linalg.norm(up)
        return f, up, np.cross(f, up)


def _floor_under(patches: Patches, ob: Observer) -> float:
    """Height (m) of the floor-group patch under the observer's (x, y); DesignError
    when none of its patches lies there (the eye is outside the room)."""
    try:
        idx = patches.group_index(ob.group)
    except LightInvError:
        raise DesignError(
            f"observer {ob.name!r}: no group {ob.group!r} in the scene "
            f"(groups: {', '.join(patches.group_names)})"
        ) from None
    x, y = ob.position
    o, e1, e2 = patches.origin[idx], patches.edge1[idx], patches.edge2[idx]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    ok = np.abs(det) > 1e-12
    dx, dy = x - o[:, 0], y - o[:, 1]
    s = np.where(ok, (dx * e2[:, 1] - dy * e2[:, 0]) / np.where(ok, det, 1.0), -1.0)
    t = np.where(ok, (e1[:, 0] * dy - e1[:, 1] * dx) / np.where(ok, det, 1.0), -1.0)
    eps = 1e-9
    inside = ok & (s >= -eps) & (t >= -eps)
    tri = patches.is_triangle[idx]
    inside &= np.where(tri, s + t <= 1 + eps, (s <= 1 + eps) & (t <= 1 + eps))
    if not inside.any():
        lo = np.minimum.reduce([o, o + e1, o + e2, o + e1 + e2]).min(axis=0)
        hi = np.maximum.reduce([o, o + e1, o + e2, o + e1 + e2]).max(axis=0)
        raise DesignError(
            f"observer {ob.name!r}: ({x:g}, {y:g}) is outside the room: not over floor "
            f"group {ob.group!r} (x {lo[0]:g} to {hi[0]:g}, y {lo[1]:g} to {hi[1]:g} m)"
        )
    k = np.flatnonzero(inside)[0]
    z = o[k, 2] + s[k] * e1[k, 2] + t[k] * e2[k, 2]
    return float(z)


def observer_eyes(patches: Patches, observers: Sequence[Observer]) -> Eyes:
    """The eyes of ``observers`` in the scene: ``height`` m over the floor patch under
    each; DesignError when one is outside the room (not over its floor group, or above
    the top of the scene)."""
    points, views = [], []
    corners = np.concatenate(
        [patches.origin, patches.origin + patches.edge1, patches.origin + patches.edge2]
    )
    top = float(corners[:, 2].max())
    for ob in observers:
        z = _floor_under(patches, ob) + ob.height
        if z >= top:
            raise DesignError(
                f"observer {ob.name!r}: its eye at z = {z:g} m is above the room (the scene's "
                f"top is at {top:g} m): lower its height"
            )
        points.append((ob.position[0], ob.position[1], z))
        views.append(ob.view)
    pts = np.array(points, dtype=float).reshape(-1, 3)
    return Eyes(tuple(o.name for o in observers), pts, np.array(views, float).reshape(-1, 3))


def eye_factors(light: LightModel, eyes: Eyes) -> sp.csr_matrix:
    """(k, n) form factors from each eye (a point facing its view) to the patches."""
    op = light.op
    rays = EYE_RAYS * int(op.info.get("rays", DEFAULT_RAYS))
    seed = int(op.info.get("seed", 0)) + EYE_SEED_OFFSET
    caster = caster_for(light.patches)
    return receiver_factors(eyes.points, eyes.views, caster, light.n, rays, seed).tocsr()


def array_glare_sums(arrays: ArrayLight, layout: ArrayLayout, eyes: Eyes) -> np.ndarray:
    """(k, m) glare sums sum L² omega / p² (cd²/m⁴ sr) of the candidates' arrays at each
    eye (dimming included, no maintenance factor): ``ugr.glare_terms`` for every
    luminaire of every candidate at once."""
    m = layout.rows.shape[0]
    out = np.zeros((len(eyes.names), m))
    for j, (prod, frame) in enumerate(zip(arrays.products, arrays.frames, strict=True)):
        ph = prod.photometry
        u, v, mask = luminaire_positions(layout, j)
        pos = frame.point(u, v, MOUNT_OFFSET)  # (m, P, 3)
        c0 = np.where((layout.rotation[:, j] == 90)[:, None], frame.v, frame.u)[:, None, :]
        c90 = np.cross(-frame.normal, c0)
        for i in range(len(eyes.names)):
            fwd, up, side = eyes.frame(i)
            vec = pos - eyes.points[i]
            dist = np.maximum(np.linalg.norm(vec, axis=-1), 1e-12)
            r, h, t = vec @ fwd, vec @ up, vec @ side
            rr = np.where(r > 0, r, 1.0)
            on = mask & (r > 0) & in_field(h / rr, t / rr)
            to_eye = -vec / dist[..., None]
            gamma = np.degrees(np.arccos(np.clip(to_eye @ frame.normal, -1.0, 1.0)))
            c = np.degrees(np.arctan2((to_eye * c90).sum(-1), (to_eye * c0).sum(-1))) % 360.0
            area = projected_area(ph.opening, c, gamma)
            lum = layout.dimming[:, j, None] * luminance(ph, c, gamma)
            on &= (lum > 0) & (area > 0)
            p = position_index(h / rr, t / rr)
            term = lum**2 * (area / dist**2) / p**2
            out[i] += np.where(on, term, 0.0).sum(axis=1)
    return out


class Glare:
    """The glare of a problem's candidates at the design's observers (the module)."""

    def __init__(self, light: LightModel, design: Design):
        self.light, self.design = light, design
        zoned = [s.name for s in design.sources if source_type(s.kind).electric]
        if zoned:
            raise DesignError(
                f"UGR is rated for luminaire arrays (photometric products); zone luminaires "
                f"{zoned} have no photometry: make them arrays, or bound UGR without them"
            )
        self.eyes = observer_eyes(light.patches, design.observers)
        for a in design.arrays:
            ph = resolve_product(a.product, a.watts).photometry
            if luminous_area(ph.opening) <= 0:
                raise DesignError(
                    f"array {a.name!r}: its product {a.product!r} gives no luminous opening, "
                    "so its luminance and UGR are undefined; use a file that states it"
                )
        F = eye_factors(light, self.eyes)
        op = light.op
        self.taps = sp.csr_matrix(F.multiply(op.rho[None, :]))
        self.seen = np.unique(F.indices).astype(np.int64)
        self._index = {n: i for i, n in enumerate(self.eyes.names)}
        self._arrays: tuple | None = None
        self._scale: tuple | None = None

    def anchor(self, intention: Intention) -> np.ndarray:
        """(1,) the patch the intention's eyes see most of: the one receiver a search
        level keeps for it (its values come from the eyes' own responses)."""
        rows = self.taps[[self._index[o] for o in intention.observers]]
        weight = np.asarray(rows.sum(axis=0)).reshape(-1)
        return np.array([int(np.argmax(weight))], dtype=np.int64)

    def _array_rows(self, arrays: ArrayLight) -> np.ndarray:
        """(k, L) indirect lux at each eye per lattice placement at unit dimming."""
        if self._arrays is None or self._arrays[0] is not arrays.R:
            at = np.searchsorted(arrays.rows, self.seen)
            if not np.array_equal(arrays.rows[np.minimum(at, len(arrays.rows) - 1)], self.seen):
                raise DesignError("the arrays' responses lack the patches the observers see")
            E = np.asarray(self.taps[:, self.seen] @ arrays.R[at].astype(float))
            self._arrays = (arrays.R, E)
        return self._arrays[1]

    def _node_scale(self, arrays: ArrayLight) -> np.ndarray | None:
        """(L,) 1 / the maintenance factor of each lattice node's array, so maintained
        weights give the light as new; None when arrays of different maintenance
        factors share a lattice (then the weights are made again, unmaintained)."""
        if self._scale is None or self._scale[0] is not arrays:
            scale = np.zeros(arrays.placements)
            ok = True
            for a, per in zip(arrays.arrays, arrays._lattice, strict=True):
                for lat in per.values():
                    nodes = slice(lat.start, lat.start + lat.nu * lat.nv)
                    mf = 1.0 / a.maintenance_factor
                    ok &= bool(np.all((scale[nodes] == 0) | np.isclose(scale[nodes], mf)))
                    scale[nodes] = mf
            self._scale = (arrays, scale if ok else None)
        return self._scale[1]

    def sums(
        self, arrays: ArrayLight, layout: ArrayLayout, weights: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(glare sums, backgrounds Lb cd/m²), each (k, m), of the candidates' arrays
        ``layout`` at every eye; ``weights``: their maintained lattice weights, when
        already made (the candidates' light made them)."""
        total = array_glare_sums(arrays, layout, self.eyes)
        rows = self._array_rows(arrays)
        scale = self._node_scale(arrays) if weights is not None else None
        if scale is not None:
            indirect = (rows * scale) @ weights.astype(float)
        else:
            indirect = rows @ arrays.weights(layout, maintained=False).astype(float)
        return total, indirect / np.pi

    def values(self, intention: Intention, lit, arrays: ArrayLight | None) -> np.ndarray:
        """The intention's quantity (UGR) at each of its observers, (k', m), for a
        batch's light ``lit`` (``optimize.candidate_light.Lit``: its arrays' layout and
        lattice weights); without arrays nothing glares (UGR_FLOOR)."""
        layout = getattr(lit, "layout", None)
        idx = [self._index[o] for o in intention.observers]
        spec = quantity_spec(intention.quantity)
        if arrays is None or layout is None:
            return np.full((len(idx), lit.V.shape[1]), spec.from_glare(0.0, 1.0))
        total, lb = self.sums(arrays, layout, getattr(lit, "weights", None))
        return spec.from_glare(total[idx], lb[idx])


def layout_glare(
    light: LightModel, design: Design, sources, arrays, cancel: Callable[[], bool] | None = None
) -> dict[str, float]:
    """UGR at every observer of one layout (``arrays`` as written, each luminaire placed
    exactly): {observer name: UGR}. The background from the patches' light of the
    arrays (``arrays_field``, no maintenance factor), the glare sums from
    ``ugr.glare_terms``. ``sources``: the zone sources as lit (electric ones refused)."""
    if not design.observers:
        return {}
    zoned = [s.name for s in sources if source_type(s.kind).electric]
    if zoned:
        raise DesignError(f"UGR is rated for luminaire arrays; zone luminaires {zoned} are not")
    eyes = observer_eyes(light.patches, design.observers)
    taps = sp.csr_matrix(eye_factors(light, eyes).multiply(light.op.rho[None, :]))
    spec = quantity_spec(Quantity.UGR)
    if not arrays:
        return {n: float(spec.from_glare(0.0, 1.0)) for n in eyes.names}
    H = arrays_field(light.patches, light.op, arrays, maintained=False, cancel=cancel)[0]
    placed = [p for _, _, ps in array_luminaires(light.patches, arrays) for p in ps]
    lb = np.asarray(taps @ H).reshape(-1) / np.pi
    total = [glare_terms(eyes.points[i], eyes.views[i], placed).total for i in range(len(lb))]
    values = spec.from_glare(np.array(total), lb)
    return {n: float(v) for n, v in zip(eyes.names, values, strict=True)}
