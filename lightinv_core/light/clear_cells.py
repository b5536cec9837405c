"""Clear glazing whose shape the optimiser moves: its light traced once per zone cell.

A clear source with free variables (``u0 v0 u1 v1 filter``) changes its light with
every candidate. Its light is linear in how much of each zone patch it covers: a
candidate's clear light is ``sum_c s_c L_c`` over the *cells* c of the clear sources'
zones (the zone patches), s_c = filter x the share of the cell the rectangle covers
(as the zone emission of diffusing glazing, ``sources.emission``) and L_c the light of
the cell fully glazed at the design's transmittance. So the build traces every cell
once, as ``light.clear_build`` traces a fixed source (the same rays, seeds and
reflections; one glazing group per cell), and keeps per cell:

- ``coef`` (C, R, B) float32: lux per unit of each column at the receivers (the patches
  of intentions measured over the year, then the work-plane points), B = the sky
  patches (Tregenza's 145, or Reinhart's at ``daylight.sky_subdivision``) and the
  ground, the sun's reflections on the MF:2 sun bins, the sun's direct light on the
  same bins (0 at the points, whose direct sun is traced hour by hour);
- ``direct`` per cell a sparse (q, H) float32: the direct sun at each work-plane point
  in each hour (lux), traced at the hour's own sun; sparse because a cell puts sun on
  a point in few hours;
- ``glow`` (C, R): the cell with its blinds closed, a diffusing glow of
  ``BLIND_TRANSMITTANCE`` x the transmittance, per lux on its plane; ``over`` (C, R')
  lux per horizontal lux under the CIE overcast sky at every patch the problem reads
  and the points.

Every clear source of a design goes through cells once any of them is free (a fixed one
as one cell; a free one's zone in blocks of patches beyond ``MAX_CELLS``), so the LM-83
blinds close per source in the fewest
combination as before (``light.clear_batch``). A clear zone is black inside over its
whole area (a fixed build blackens only the covered patches): the uncovered part of a
clear zone reflects nothing (docs/daylight.md, "Clear shapes in the optimiser").
"""

from __future__ import annotations

import math
import time
import weakref
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp

from lightinv_core.climate.skydome import SUN_BASIS_MF, sun_bins
from lightinv_core.design.model import Design
from lightinv_core.light.arrays import caster_for
from lightinv_core.light.clear_build import (
    GLASS_SAMPLES,
    POINT_RAYS,
    ROOM_RAYS,
    _binned,
    _closed,
    _reflected,
    _traced,
    _weather,
)
from lightinv_core.light.clear_glazing import (
    BLIND_TRANSMITTANCE,
    clear_sources,
    clear_transmittance,
    is_clear,
)
from lightinv_core.light.grids import GRID_SEED_OFFSET, design_receivers
from lightinv_core.transport.clear_glazing import (
    Glass,
    SkyRays,
    receiver_sky_rays,
    room_sky_rays,
    sun_on_points,
    sun_on_room,
    to_geographic,
    to_scene,
)
from lightinv_core.transport.formfactors import DEFAULT_RAYS
from lightinv_core.transport.receivers import receiver_factors

MAX_CELLS = 36
"""Most cells per free clear source: a zone of more patches is traced in blocks of
patches (a block's light is taken as even over it when partly covered)."""
CHUNK_BYTES = 64 << 20
"""Largest first-hit block (patches x columns x 8 bytes) reflected at once."""
SUN_HOURS_CHUNK = 512
"""Hours of direct sun at the points traced at once."""

_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def moving_clear(design: Design) -> tuple:
    """The design's clear sources with free variables (their shape or filter moves)."""
    return tuple(s for s in design.sources if is_clear(s) and s.free)


def refuse_moving_sunlight(design: Design) -> None:
    """DesignError for an EN 17037 sunlight intention on a design whose clear glazing
    moves: its hours are counted through the glazing as written (not done per shape)."""
    from lightinv_core.design.model import DesignError
    from lightinv_core.quantities import quantity_spec

    for it in design.intentions:
        if it.observers is not None and quantity_spec(it.quantity).from_glare is None:
            raise DesignError(
                f"intention {it.name!r}: EN 17037 sunlight exposure is counted through "
                "clear glazing as drawn; free no clear source's shape or filter with it"
            )


@dataclass(frozen=True, eq=False)
class ClearCells:
    """The clear glazing of a design traced per zone cell (see the module).

    ``source_index`` the clear sources' indices among the design's sources,
    ``cell_source`` (C,) the clear source of each cell, ``blocks`` per clear source None
    (fixed: one cell) or (its zone patches' share of each of its cells (patches, B), those
    cells' indices); ``rows`` the patch rows read (``over`` there), ``year_rows`` those
    of them whose intentions read the year (``coef`` and ``glow`` there), ``points`` the
    work-plane points (receivers after the rows in each); ``weights`` (B,
    H) each column's hourly weight (sky luminance, direct normal lux in the sun's bin),
    ``outside`` (G, H) the exterior lux on each source's plane, ``outward`` (G, 3),
    ``sun_cols`` the direct sun columns, ``over_weights`` (K0 + 1,) the CIE overcast
    sky's weights of the sky and ground columns per horizontal lux; ``seconds`` the
    build's CPU time."""

    source_index: tuple[int, ...]
    cell_source: np.ndarray
    blocks: tuple
    rows: np.ndarray
    year_rows: np.ndarray
    points: int
    coef: np.ndarray
    glow: np.ndarray
    over: np.ndarray
    over_weights: np.ndarray
    direct: tuple
    weights: np.ndarray
    outside: np.ndarray
    outward: np.ndarray
    sun_cols: np.ndarray
    seconds: float
    kept: dict = field(default_factory=dict, repr=False)  # hourly blocks (clear_batch)

    @property
    def count(self) -> int:
        """Number of cells C."""
        return len(self.cell_source)

    @property
    def sources(self) -> int:
        """Number of clear sources G."""
        return len(self.source_index)

    @property
    def nbytes(self) -> int:
        """Memory of the cells' columns, sparse direct sun included (bytes)."""
        total = self.coef.nbytes + self.glow.nbytes + self.over.nbytes + self.weights.nbytes
        return total + sum(d.data.nbytes + d.indices.nbytes + d.indptr.nbytes for d in self.direct)

    def shares(self, light, design: Design, rect: np.ndarray, filt: np.ndarray) -> np.ndarray:
        """(m, C) each cell's glazed share for m candidates (rect (m, S, 4) m, filt (m, S)
        over the design's sources): a free source's cells, the share of their area its
        rectangle covers (a mean over a block's patches); a fixed source's cell, 1."""
        from lightinv_core.sources.emission import _overlap

        m = rect.shape[0]
        out = np.zeros((m, self.count))
        for g, j in enumerate(self.source_index):
            if self.blocks[g] is None:
                out[:, self.cell_source == g] = 1.0
                continue
            agg, cells = self.blocks[g]
            grid = light.emission.grid(design.sources[j].zone)
            nu, nv = grid.patch.shape
            ou = _overlap(rect[:, j, 0], rect[:, j, 2], nu, grid.du)
            ov = _overlap(rect[:, j, 1], rect[:, j, 3], nv, grid.dv)
            s = (filt[:, j, None, None] * ou[:, :, None] * ov[:, None, :]).reshape(m, -1)
            out[:, cells] = np.asarray(agg.T @ s.T).T
        return out


def clear_cells(
    light, design: Design, rows=None, year_rows=None, build: bool = True
) -> ClearCells | None:
    """The cells of ``design``'s clear glazing on ``light`` (a ``LightModel``), with
    the patch ``rows`` read as receivers besides the work-plane points (None: any the
    cells kept have), the year's columns kept at ``year_rows`` of them only (None: all);
    None unless a clear source is free (or, with ``build`` False, unless they are made
    already). Made once per operator, clear sources (a free one by its zone), work
    planes and daylight (and again for rows they lack)."""
    if not moving_clear(design):
        return None
    sources = clear_sources(design)
    zones = tuple((s.zone, s.name) if s.free else s for s in sources)
    key = (zones, tuple(design.workplanes), _traced(design.daylight))
    memo = _CACHE.setdefault(light.op, {})
    got = memo.get(key)
    want = np.zeros(0, np.int64) if rows is None else np.unique(np.asarray(rows, np.int64))
    year = want if year_rows is None else np.unique(np.asarray(year_rows, np.int64))
    if not build:
        return got
    lacks = got is None or not np.isin(want, got.rows).all()
    if lacks or not np.isin(year, got.year_rows).all():
        memo.clear()  # one clear glazing at a time per operator
        memo[key] = _build(light, design, sources, want, np.intersect1d(year, want))
    return memo[key]


def _blocks(nu: int, nv: int, du: float, dv: float) -> tuple[int, int]:
    """Zone patches per cell along u and v: 1 x 1 up to ``MAX_CELLS`` cells, else the
    fewest blocks of about square size that bring the cells down to it."""
    ku = kv = 1
    while math.ceil(nu / ku) * math.ceil(nv / kv) > MAX_CELLS:
        if ku * du <= kv * dv and ku < nu:
            ku += 1
        else:
            kv += 1
    return ku, kv


def _cell_glass(light, design: Design, sources, tau: float):
    """The panes and their cells, sorted by patch id as a fixed build's are (so a
    rectangle covering a whole zone traces the very same rays). A free clear source:
    every patch of its zone at the full transmittance, in cells of one patch (or blocks
    of patches, ``MAX_CELLS``); a fixed one: the patches it covers, at its transmittance
    x filter x the share covered (as ``clear_build.clear_glass``), one cell."""
    from lightinv_core.light.clear_build import clear_glass

    index = {s.name: j for j, s in enumerate(design.sources)}
    ids, trans, cell, src, blocks = [], [], [], [], []
    C = 0
    for g, s in enumerate(sources):
        if not s.free:
            one = clear_glass(light, (s,), tau)
            ids.append(one.idx)
            trans.append(one.transmittance)
            cell.append(np.full(one.count, C))
            src.append(g)
            blocks.append(None)
            C += 1
            continue
        grid = light.emission.grid(s.zone)
        nu, nv = grid.patch.shape
        ku, kv = _blocks(nu, nv, grid.du, grid.dv)
        i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
        bv = math.ceil(nv / kv)
        b = ((i // ku) * bv + j // kv).ravel()  # each patch's block, patch.ravel() order
        B = int(b.max()) + 1
        size = np.bincount(b, minlength=B)
        agg = sp.csr_matrix((1.0 / size[b], (np.arange(nu * nv), b)), shape=(nu * nv, B))
        ids.append(grid.patch.ravel())
        trans.append(np.full(nu * nv, tau))
        cell.append(C + b)
        src += [g] * B
        blocks.append((agg, C + np.arange(B)))
        C += B
    ids, trans, cell = np.concatenate(ids), np.concatenate(trans), np.concatenate(cell)
    order = np.argsort(ids, kind="stable")
    glass = Glass(ids[order], trans[order], cell[order], tuple(str(c) for c in range(C)))
    return glass, np.asarray(src), tuple(blocks), tuple(index[s.name] for s in sources)


def _subset(rays: SkyRays, c0: int, c1: int) -> SkyRays:
    """The rays of cells c0..c1-1, renumbered from 0."""
    on = (rays.group >= c0) & (rays.group < c1)
    return SkyRays(rays.target[on], rays.direction[on], rays.weight[on], rays.group[on] - c0,
                   rays.targets)  # fmt: skip


def _sun_on_room(lit, glass, caster, dirs) -> np.ndarray:
    """(C, n, S) float32 first hit of the beam per cell and sun bin, a few bins at a
    time (the same glass samples each call: the seed draws only those)."""
    C, n, S = len(glass.groups), lit.n, len(dirs)
    out = np.zeros((C, n, S), np.float32)
    step = max(1, CHUNK_BYTES // max(1, 8 * C * n))
    for k in range(0, S, step):
        out[:, :, k : k + step] = sun_on_room(
            lit, glass, caster, dirs[k : k + step], GLASS_SAMPLES, 0
        )
    return out


def _build(light, design: Design, sources, rows: np.ndarray, year: np.ndarray) -> ClearCells:
    from lightinv_core.climate.sky_luminance import cie_overcast, scaled_sky
    from lightinv_core.climate.skydome import reinhart

    t0 = time.process_time()
    d = design.daylight
    patches, op = light.patches, light.op
    glass, src, blocks, index = _cell_glass(light, design, sources, clear_transmittance(d))
    C = len(glass.groups)
    rho = patches.rho.copy()
    rho[glass.idx] = 0.0  # a clear zone is black inside (see the module)
    lit = replace(patches, rho=rho)
    caster = caster_for(patches)
    dome = reinhart(d.sky_subdivision)  # Tregenza's 145 patches at MF:1, as the fixed build
    K0, north = len(dome.solid_angles), d.north_deg

    def bins(dirs):
        k = dome.patch_of(to_geographic(dirs, north))
        return np.where(k < 0, K0, k)

    sky_w, geo, dn, up = _weather(d, dome)
    H = len(dn)
    mean, hour_bin = sun_bins(geo, up, SUN_BASIS_MF)
    S = len(mean)
    hours = np.flatnonzero(up)
    sun_w = np.zeros((S, H))
    sun_w[hour_bin[hours], hours] = dn[hours]
    B = K0 + 1 + 2 * S
    room = room_sky_rays(lit, glass, caster, ROOM_RAYS, 0)
    H_sun = _sun_on_room(lit, glass, caster, to_scene(mean, north))
    # Closed blinds per source: its exterior lux every hour and its outward normal.
    one = Glass(glass.idx, glass.transmittance, src[glass.group], tuple(s.name for s in sources))
    _, outside, outward = _closed(light, design, sources, one)
    grids = design_receivers(light, design)
    q = 0 if grids is None else grids.samples.size
    coef = np.zeros((C, len(year) + q, B), np.float32)
    glow = np.zeros((C, len(year) + q), np.float32)
    over = np.zeros((C, len(rows) + q), np.float32)
    over0 = np.concatenate([scaled_sky(dome, cie_overcast, 1.0), [d.ground_reflectance / math.pi]])
    Fp = pts = nrm = own = None
    if grids is not None:
        samples = grids.samples
        pts, nrm = samples.points, samples.normals
        rays = max(POINT_RAYS, int(op.info.get("rays", DEFAULT_RAYS)))
        seed = int(op.info.get("seed", 0)) + GRID_SEED_OFFSET
        Fp = receiver_factors(pts, nrm, caster, patches.n, rays, seed)
        seen = receiver_sky_rays(pts, nrm, lit, glass, caster, GLASS_SAMPLES, 0)
        own = _binned(seen, C, bins, K0 + 1)  # (C, q_samples, K0 + 1)
    step = max(1, CHUNK_BYTES // (8 * patches.n * (K0 + 2 + S)))
    for c0 in range(0, C, step):
        c1 = min(C, c0 + step)
        first = np.concatenate(
            [_binned(_subset(room, c0, c1), c1 - c0, bins, K0 + 1), H_sun[c0:c1]], axis=2
        )  # (c, n, K0 + 1 + S)
        E = np.zeros((patches.n, c1 - c0))
        on = (glass.group >= c0) & (glass.group < c1)
        E[glass.idx[on], glass.group[on] - c0] = BLIND_TRANSMITTANCE * glass.transmittance[on]
        flat = np.moveaxis(first, 0, 1).reshape(patches.n, -1)
        flat = np.concatenate([flat, np.asarray(op.F @ E)], axis=1)
        got = flat + _reflected(light, rho, flat)
        lit_H = got[:, : -(c1 - c0)].reshape(patches.n, c1 - c0, -1)
        closed_H = got[:, -(c1 - c0) :]
        for c in range(c0, c1):
            k = c - c0
            block = np.zeros((patches.n, B))
            block[:, : K0 + 1 + S] = lit_H[:, k]
            block[:, K0 + 1 : K0 + 1 + S] -= H_sun[c]  # reflected only: the beam is direct
            block[:, K0 + 1 + S :] = H_sun[c]
            coef[c, : len(year)] = block[year]
            glow[c, : len(year)] = closed_H[year, k]
            over[c, : len(rows)] = block[rows, : K0 + 1] @ over0
            if grids is not None:
                at = np.asarray(Fp @ (rho[:, None] * lit_H[:, k]))
                at[:, : K0 + 1] += own[c]
                coef[c, len(year) :, : K0 + 1 + S] = samples.values(at)
                e = np.asarray(Fp @ (E[:, k] + rho * closed_H[:, k]))
                glow[c, len(year) :] = samples.values(e)
    direct = _direct(pts, nrm, lit, glass, caster, geo, hours, dn, north, grids, H)
    over[:, len(rows) :] = coef[:, len(year) :, : K0 + 1] @ over0.astype(np.float32)
    weights = np.concatenate([sky_w, sun_w, sun_w], axis=0).astype(np.float32)
    sun_cols = np.arange(K0 + 1 + S, B)
    return ClearCells(
        index, src, blocks, rows, year, q, coef, glow, over,
        over0, direct, weights, outside, outward, sun_cols, time.process_time() - t0,
    )  # fmt: skip


def _direct(pts, nrm, lit, glass, caster, geo, hours, dn, north, grids, H) -> tuple:
    """Per cell a sparse (q, H) float32: its direct sun (lux) at the work-plane points
    in every hour, traced at the hour's own sun, a few hundred hours at a time."""
    C = len(glass.groups)
    if grids is None:
        return tuple(sp.csr_matrix((0, H), dtype=np.float32) for _ in range(C))
    q = grids.samples.size
    parts: list[list] = [[] for _ in range(C)]
    for i in range(0, len(hours), SUN_HOURS_CHUNK):
        h = hours[i : i + SUN_HOURS_CHUNK]
        got = sun_on_points(pts, nrm, lit, glass, caster, to_scene(geo[h], north)) * dn[h]
        for c in range(C):
            x = grids.samples.values(got[c])
            r, t = np.nonzero(x)
            parts[c].append((r, h[t], x[r, t]))
    out = []
    for c in range(C):
        r = np.concatenate([p[0] for p in parts[c]]) if parts[c] else np.zeros(0, int)
        t = np.concatenate([p[1] for p in parts[c]]) if parts[c] else np.zeros(0, int)
        v = np.concatenate([p[2] for p in parts[c]]) if parts[c] else np.zeros(0)
        out.append(sp.csr_matrix((v.astype(np.float32), (r, t)), shape=(q, H)))
    return tuple(out)
