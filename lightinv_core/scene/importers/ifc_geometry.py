"""Room surfaces from the solids of a BIM model (used by ``ifc_import``).

An element's triangles (metres, world coordinates, faces counter-clockwise seen from
outside the solid) are merged per plane into polygons in the plane's own (u, v)
coordinates; the parts where elements touch or run into each other are cut away;
polygons whose front sees outside the building (or the inside of another element) are
dropped; what remains is cut into rectangles where it can be. shapely is passed in by
the caller, which imports it only when an IFC file is read (the core works without it).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from lightinv_core.scene.importers.geometry import perpendicular

PLANE_TOL = 1e-3  # m (and unit-normal components): faces this close share a plane
MIN_PIECE = 1e-4  # m²: pieces smaller than a square centimetre are dropped
MIN_TRIANGLE = 1e-8  # m²: smaller triangles of the element meshes are slivers, ignored
GRID = 1e-6  # m: precision of the plane polygons
RAYS = 16  # rays per sample point for the inside/outside test
SAMPLES = 3  # sample points per piece side (plus a point on the surface)
RAY_OFFSET = 1e-3  # m: rays start this far in front of the face
INSIDE = 0.75  # a piece is kept when at least this share of its rays hit a front face


@dataclass
class Element:
    """One building element's triangles (world coordinates, metres) and what it is."""

    id: int
    ifc_class: str
    name: str
    vertices: np.ndarray
    triangles: np.ndarray
    ceiling: bool = False  # an IfcCovering of type CEILING
    roof_host: bool = False  # a window in an opening of a roof or roof slab


@dataclass(frozen=True)
class Part:
    """A part merged into the element of the window it makes up (a frame, a pane): its
    id, class and name, and the window's id in the file."""

    id: int
    ifc_class: str
    name: str
    window: int


@dataclass
class Plane:
    """The faces of one element in one plane: unit normal, offset (n . x), in-plane axes
    u, v (u x v = n), and their outline as a shapely geometry in (u, v) metres."""

    element: int
    normal: np.ndarray
    offset: float
    u: np.ndarray
    v: np.ndarray
    shape: object
    role: str = "wall"
    lo: np.ndarray = field(default_factory=lambda: np.zeros(3))  # bounding box, m
    hi: np.ndarray = field(default_factory=lambda: np.zeros(3))
    pieces: list = field(default_factory=list)


# --- planes and contacts ----------------------------------------------------------------------


def _axes(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """In-plane axes (u, v) with u x v = n: u horizontal on walls, along x on floors."""
    # u horizontal on walls (and sloped faces), along x on floors and ceilings.
    wall = abs(n[2]) < 0.9
    u = np.array([-n[1], n[0], 0.0]) if wall else np.array([1.0, 0.0, 0.0]) - n[0] * n
    if np.linalg.norm(u) < 1e-9:
        u = perpendicular(n)
    u = u / np.linalg.norm(u)
    return u, np.cross(n, u)


def planes_of(elements: list[Element], role: Callable[[Element, np.ndarray], str], shapely):
    """Each element's faces merged per plane into shapely polygons; ``role(element,
    normal)`` names what each plane is (floor, wall, ...)."""
    out = []
    for k, e in enumerate(elements):
        p = e.vertices[e.triangles]
        cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        twice = np.linalg.norm(cross, axis=1)
        ok = twice > 2 * MIN_TRIANGLE
        n = cross[ok] / twice[ok, None]
        p = p[ok]
        d = (n * p[:, 0]).sum(axis=1)
        key = np.round(np.column_stack([n, d]) / PLANE_TOL).astype(np.int64)
        _, pid = np.unique(key, axis=0, return_inverse=True)
        for j in range(pid.max() + 1 if len(pid) else 0):
            rows = np.flatnonzero(pid.ravel() == j)
            w = twice[ok][rows]
            normal = (n[rows] * w[:, None]).sum(axis=0)
            normal /= np.linalg.norm(normal)
            offset = float((d[rows] * w).sum() / w.sum())
            u, v = _axes(normal)
            tris = [shapely.Polygon(np.column_stack([t @ u, t @ v])) for t in p[rows]]
            shape = shapely.union_all(tris, grid_size=GRID)
            box = p[rows].reshape(-1, 3)
            plane = Plane(k, normal, offset, u, v, shape, role(e, normal))
            plane.lo, plane.hi = box.min(axis=0), box.max(axis=0)
            out.append(plane)
    return out


def cut_contacts(planes: list[Plane], shapely, failed: list | None = None) -> float:
    """Cut from every plane the faces of planes lying on it facing the other way (two
    elements touching, a window in its opening); returns the area cut (m²). A cut that
    shapely cannot make is skipped (the plane kept whole) and recorded in ``failed`` as
    ``Failure``."""
    from scipy.spatial import cKDTree

    if not planes:
        return 0.0
    keys = np.array([[*p.normal, p.offset] for p in planes])
    tree = cKDTree(keys)
    before = sum(p.shape.area for p in planes)
    cut = []
    lo = np.array([p.lo for p in planes]) - PLANE_TOL
    hi = np.array([p.hi for p in planes]) + PLANE_TOL
    for i, p in enumerate(planes):
        # Opposite planes in the same infinite plane, whose boxes overlap this one's.
        near = np.array(tree.query_ball_point(-keys[i], 2 * PLANE_TOL), dtype=int)
        near = near[np.all((lo[near] <= hi[i]) & (hi[near] >= lo[i]), axis=1)]
        others = [int(j) for j in near if j != i]
        if not others:
            cut.append(p.shape)
            continue
        touching = [_project(planes[j], p, shapely) for j in others]
        try:
            cut.append(
                p.shape.difference(shapely.union_all(touching, grid_size=GRID), grid_size=GRID)
            )
        except shapely.errors.GEOSException as exc:
            cut.append(p.shape)
            _record(failed, p.element, planes[others[0]].element, "contact", exc)
    for p, shape in zip(planes, cut, strict=True):
        p.shape = shape
    return before - sum(p.shape.area for p in planes)


def _project(q: Plane, p: Plane, shapely):
    """Plane ``q``'s outline in plane ``p``'s (u, v) coordinates (the planes coincide)."""
    origin = q.offset * q.normal

    def to_p(coords: np.ndarray) -> np.ndarray:
        xyz = origin + coords[:, :1] * q.u + coords[:, 1:2] * q.v
        return np.column_stack([xyz @ p.u, xyz @ p.v])

    return shapely.transform(q.shape, to_p)


def cut_sections(
    planes: list[Plane], elements: list[Element], shapely, failed: list | None = None
) -> float:
    """Cut from every plane what other elements occupy just in front of it (a slab
    running into a wall, a wall through a slab): each element near the plane is sliced
    ``SECTION_OFFSET`` in front of it and the section's inside (even-odd) is removed;
    returns the area cut (m²). A section shapely cannot cut away is skipped (that part
    of the plane kept) and recorded in ``failed`` as ``Failure``."""
    if not planes:
        return 0.0
    lo = np.array([e.vertices.min(axis=0) for e in elements])
    hi = np.array([e.vertices.max(axis=0) for e in elements])
    edges = [_edges(e) for e in elements]
    before = sum(p.shape.area for p in planes)
    for p in planes:
        if p.shape.is_empty:
            continue
        level = p.offset + SECTION_OFFSET
        # Elements whose box reaches the slicing plane within this plane's box.
        reach = (lo <= p.hi + SECTION_OFFSET) & (hi >= p.lo - SECTION_OFFSET)
        corners = np.stack([lo, hi], axis=1)  # (n, 2, 3): the boxes' extreme corners
        near = np.all(reach, axis=1)
        near[p.element] = False
        sections = []
        for k in np.flatnonzero(near):
            if not _straddles(corners[k], p.normal, level):
                continue
            try:
                section = _section(elements[k], edges[k], p, level, shapely)
                if section is not None and section.intersects(p.shape):
                    sections.append((int(k), section))
            except shapely.errors.GEOSException as exc:
                _record(failed, p.element, int(k), "section", exc)
        if sections:
            p.shape = _cut_away(p, sections, shapely, failed)
    return before - sum(p.shape.area for p in planes)


@dataclass(frozen=True)
class Failure:
    """A cut shapely could not make: plane of element ``element`` against element
    ``other`` (indices into the element list), at ``stage`` ("contact", "section"), with
    GEOS's message."""

    element: int
    other: int
    stage: str
    message: str


def _record(failed: list | None, element: int, other: int, stage: str, exc: Exception) -> None:
    if failed is None:
        raise exc
    failed.append(Failure(element, other, stage, " ".join(str(exc).split())[:120]))


def _cut_away(p: Plane, sections: list[tuple[int, object]], shapely, failed):
    """``p.shape`` less the sections (element index, area): all at once, or, when
    shapely fails on that, one by one, skipping those it cannot cut."""
    try:
        union = shapely.union_all([s for _, s in sections], grid_size=GRID)
        return p.shape.difference(union, grid_size=GRID)
    except shapely.errors.GEOSException:
        pass
    shape = p.shape
    for k, section in sections:
        try:
            shape = shape.difference(section, grid_size=GRID)
        except shapely.errors.GEOSException as exc:
            _record(failed, p.element, k, "section", exc)
    return shape


SECTION_OFFSET = 0.73e-3
"""m: elements are sliced this far in front of a face. Small against any building part,
large against rounding; an odd value so that vertices modelled in whole millimetres
never lie on the slicing plane."""


def _straddles(box: np.ndarray, n: np.ndarray, level: float) -> bool:
    """Whether the axis-aligned box (2, 3) has corners on both sides of the plane."""
    lo_d = np.where(n > 0, box[0], box[1]) @ n
    hi_d = np.where(n > 0, box[1], box[0]) @ n
    return lo_d < level < hi_d


def _edges(e: Element) -> tuple[np.ndarray, np.ndarray]:
    """The element's unique edges (m, 2) and, per triangle, its three edges' indices."""
    t = e.triangles
    pairs = np.stack([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]], axis=1).reshape(-1, 2)
    pairs.sort(axis=1)
    unique, index = np.unique(pairs, axis=0, return_inverse=True)
    return unique, index.reshape(-1, 3)


def _section(e: Element, edges, p: Plane, level: float, shapely):
    """Where element ``e`` is cut by plane ``p`` moved to ``level``, as a shapely area in
    ``p``'s (u, v) coordinates (even-odd of the closed section loops), or None."""
    unique, per_tri = edges
    dist = e.vertices @ p.normal - level
    a, b = unique[:, 0], unique[:, 1]
    crossing = dist[a] * dist[b] < 0
    tri = np.flatnonzero(crossing[per_tri].sum(axis=1) == 2)
    if len(tri) < 3:
        return None
    # The crossing point of each edge, computed once so neighbours share it exactly.
    ends = np.flatnonzero(crossing)
    w = dist[a[ends]] / (dist[a[ends]] - dist[b[ends]])
    xyz = e.vertices[a[ends]] + w[:, None] * (e.vertices[b[ends]] - e.vertices[a[ends]])
    point = np.full((len(unique), 2), np.nan)
    point[ends] = np.column_stack([xyz @ p.u, xyz @ p.v])
    seg = per_tri[tri][crossing[per_tri[tri]]].reshape(-1, 2)
    area = None
    for ring in _rings(seg.tolist()):
        # A ring that runs out and back along itself (a zero-thickness part of the
        # element) is made valid as lines besides areas: only the areas are a section.
        face = polygons(shapely.make_valid(shapely.Polygon(point[ring])))
        if not face:
            continue
        face = shapely.union_all(face, grid_size=GRID)
        area = face if area is None else area.symmetric_difference(face, grid_size=GRID)
    return area


def _rings(segments: list[list[int]]) -> list[list[int]]:
    """The closed loops of segments joined end to end (each a pair of edge ids, each edge
    shared by two segments on a closed mesh); loops that do not close are dropped."""
    at: dict[int, list[int]] = {}
    for k, (a, b) in enumerate(segments):
        at.setdefault(a, []).append(k)
        at.setdefault(b, []).append(k)
    used = [False] * len(segments)
    rings = []
    for start in range(len(segments)):
        if used[start]:
            continue
        used[start] = True
        first, here = segments[start]
        ring = [first]
        while here != first:
            ring.append(here)
            nxt = [k for k in at.get(here, ()) if not used[k]]
            if len(nxt) != 1:
                break
            used[nxt[0]] = True
            a, b = segments[nxt[0]]
            here = b if a == here else a
        if here == first and len(ring) >= 3:
            rings.append(ring)
    return rings


# --- inside or outside --------------------------------------------------------------------


def centre_of(elements: list[Element]) -> np.ndarray:
    pts = np.concatenate([e.vertices for e in elements])
    return 0.5 * (pts.min(axis=0) + pts.max(axis=0))


def _hemisphere(count: int) -> np.ndarray:
    """``count`` cosine-weighted directions about +z (a Fibonacci spiral), fixed."""
    k = np.arange(count) + 0.5
    r = np.sqrt(k / count)
    phi = k * math.pi * (3.0 - math.sqrt(5.0))
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(1.0 - r * r)])


def _samples(poly, shapely) -> np.ndarray:
    """Points inside the polygon: one on its surface and those of a small grid inside."""
    pts = [np.array(poly.point_on_surface().coords[0])]
    x0, y0, x1, y1 = poly.bounds
    g = (np.arange(SAMPLES) + 0.5) / SAMPLES
    xx, yy = np.meshgrid(x0 + g * (x1 - x0), y0 + g * (y1 - y0))
    inside = shapely.contains_xy(poly, xx.ravel(), yy.ravel())
    pts += list(np.column_stack([xx.ravel(), yy.ravel()])[inside])
    return np.array(pts)


def cull_outside(
    planes: list[Plane],
    elements: list[Element],
    centre: np.ndarray,
    shapely,
    keep: Callable[[Plane], bool] | None = None,
) -> float:
    """Split each plane into its polygons and keep those that see the inside of the
    building: at least ``INSIDE`` of the rays from their front hit a front face (rays
    that escape, or that start inside an element and hit a back face, do not); planes
    for which ``keep(plane)`` is true are kept without the test. Returns the area left
    out (m²)."""
    from embreex import rtcore_scene as rtcs
    from embreex.mesh_construction import TriangleMesh

    tri = np.concatenate([e.vertices[e.triangles] for e in elements]) - centre
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    scene = rtcs.EmbreeScene()
    flat = np.ascontiguousarray(tri.reshape(-1, 3), dtype=np.float32)
    TriangleMesh(scene, flat, np.arange(len(flat), dtype=np.int32).reshape(-1, 3))
    local = _hemisphere(RAYS)
    pieces, origins, dirs, owner = [], [], [], []
    for p in planes:
        kept = keep is not None and keep(p)
        for poly in polygons(p.shape):
            if poly.area < MIN_PIECE:
                continue
            if kept:
                p.pieces.append(poly)
                continue
            uv = _samples(poly, shapely)
            xyz = p.offset * p.normal + uv[:, :1] * p.u + uv[:, 1:2] * p.v - centre
            d = local @ np.array([p.u, p.v, p.normal])
            origins.append(np.repeat(xyz + RAY_OFFSET * p.normal, RAYS, axis=0))
            dirs.append(np.tile(d, (len(xyz), 1)))
            owner.append(np.full(len(xyz) * RAYS, len(pieces)))
            pieces.append((p, poly))
    if not pieces:
        return 0.0
    o = np.ascontiguousarray(np.concatenate(origins), dtype=np.float32)
    d = np.ascontiguousarray(np.concatenate(dirs), dtype=np.float32)
    hit = scene.run(o, d, query="INTERSECT")
    front = np.zeros(len(hit), bool)
    ok = hit >= 0
    front[ok] = (normals[hit[ok]] * d[ok]).sum(axis=1) < 0
    owner = np.concatenate(owner)
    share = np.bincount(owner, weights=front) / np.bincount(owner)
    left = 0.0
    for (p, poly), s in zip(pieces, share, strict=True):
        if s >= INSIDE:
            p.pieces.append(poly)
        else:
            left += poly.area
    return left


def polygons(shape) -> list:
    """The polygons of a shapely geometry (a polygon, a multi-polygon, a collection)."""
    if shape.is_empty:
        return []
    if shape.geom_type == "Polygon":
        return [shape]
    return [g for part in getattr(shape, "geoms", []) for g in polygons(part)]


def rectangles(poly, shapely) -> list:
    """``poly`` as polygons without holes, as rectangles where it can: cut into strips
    across its longest edge at every corner, it becomes rectangles when its edges run
    at right angles (a wall with a window opening becomes four); otherwise only holes
    are cut out that way, and a piece still holed is triangulated."""
    poly = shapely.simplify(poly, GRID, preserve_topology=True)
    if _is_rectangle(poly) or poly.area < MIN_PIECE:
        return [poly]
    ring = np.array(poly.exterior.coords)
    edges = np.diff(ring, axis=0)
    longest = edges[np.argmax(np.hypot(edges[:, 0], edges[:, 1]))]
    turn = math.atan2(longest[1], longest[0])
    flat = shapely.affinity.rotate(poly, -turn, origin=(0, 0), use_radians=True)
    corners = np.concatenate([np.array(r.coords)[:, 0] for r in (flat.exterior, *flat.interiors)])
    every = np.unique(np.round(corners / GRID) * GRID)
    parts = _strips(flat, every, shapely) if len(every) <= MAX_STRIPS else None
    if parts is None or not all(_is_rectangle(q) for q in parts):
        if not poly.interiors:
            return [poly]
        holes = {x for h in flat.interiors for x in h.bounds[0::2]}
        parts = _strips(flat, sorted(holes | {flat.bounds[0], flat.bounds[2]}), shapely)
    out = []
    for part in parts:
        back = shapely.affinity.rotate(part, turn, origin=(0, 0), use_radians=True)
        if back.interiors:
            out += polygons(shapely.constrained_delaunay_triangles(back))
        else:
            out.append(back)
    return out


MAX_STRIPS = 64
"""A polygon with more distinct corner positions along its longest edge is not cut into
strips (unless it has holes): the OBJ importer's grid cutter meshes it instead."""


def _strips(flat, cuts, shapely) -> list:
    """The pieces of ``flat`` between consecutive ``cuts`` along x (simplified)."""
    _, y0, _, y1 = flat.bounds
    out = []
    for a, b in itertools.pairwise(cuts):
        strip = flat.intersection(shapely.box(a, y0 - 1, b, y1 + 1), grid_size=GRID)
        for part in polygons(strip):
            if part.area >= MIN_PIECE * 1e-2:
                out.append(shapely.simplify(part, GRID, preserve_topology=True))
    return out


def _is_rectangle(poly) -> bool:
    """Whether ``poly`` (no holes) fills its smallest enclosing rectangle."""
    if poly.interiors or len(poly.exterior.coords) != 5:
        return False
    return poly.area >= (1 - 1e-9) * poly.minimum_rotated_rectangle.area
