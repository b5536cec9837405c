"""Scene description: named surfaces with materials, and emitter zones.

Units: metres. Reflectance is the diffuse (Lambertian) reflectance, 0 <= rho < 1.
Coordinates are right-handed with z up. A surface's front side is the side its
normal points to; light arrives and leaves only on the front side.
"""

from __future__ import annotations

import math
import numbers
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from lightinv_core.errors import SceneError
from lightinv_core.kinds import SourceKind, source_kind_names
from lightinv_core.scene.zone_outline import check_outline

ZONE_KINDS = tuple(str(k) for k in SourceKind)
"""Emitter zones take the kinds of source placed in them: these are the built-in ones (the
docs' field table); checks read ``kinds.source_kind_names()``, which also holds the kinds
a ``sources.types.register_source_type`` added."""


def check_reflectance(value: float, where: str) -> float:
    """Return ``value`` as a float if it is a valid diffuse reflectance, else raise SceneError."""
    try:
        rho = float(value)
    except (TypeError, ValueError):
        raise SceneError(f"{where}: reflectance {value!r} is not a number") from None
    if not math.isfinite(rho) or rho < 0.0 or rho >= 1.0:
        raise SceneError(
            f"{where}: reflectance {value!r} is outside [0, 1); "
            "use a value such as 0.2 (dark floor) to 0.85 (white ceiling)"
        )
    return rho


def _vec3(value, where: str) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        arr = np.full(0, np.nan)
    if arr.shape != (3,) or not np.all(np.isfinite(arr)):
        raise SceneError(f"{where}: expected 3 finite coordinates, got {value!r}")
    return arr


@dataclass(frozen=True, eq=False)
class Rect:
    """A planar rectangle ``origin + s*u + t*v`` for s, t in [0, 1].

    ``u`` and ``v`` are the full edge vectors (m) and must be orthogonal; the
    front normal is ``u x v`` normalised. Zone coordinates (u, v) in metres run
    along these edges from ``origin``.
    """

    origin: np.ndarray
    u: np.ndarray
    v: np.ndarray

    def __post_init__(self) -> None:
        o = _vec3(self.origin, "rectangle origin")
        u = _vec3(self.u, "rectangle u edge")
        v = _vec3(self.v, "rectangle v edge")
        lu, lv = np.linalg.norm(u), np.linalg.norm(v)
        if lu <= 1e-9 or lv <= 1e-9:
            raise SceneError(f"rectangle at {o.tolist()} has a zero-length edge")
        if abs(np.dot(u, v)) > 1e-6 * lu * lv:
            raise SceneError(f"rectangle at {o.tolist()} has non-orthogonal edges")
        object.__setattr__(self, "origin", o)
        object.__setattr__(self, "u", u)
        object.__setattr__(self, "v", v)

    @property
    def size(self) -> tuple[float, float]:
        """Edge lengths (|u|, |v|) in metres."""
        return float(np.linalg.norm(self.u)), float(np.linalg.norm(self.v))

    @property
    def area(self) -> float:
        """Area in m²."""
        su, sv = self.size
        return su * sv

    @property
    def normal(self) -> np.ndarray:
        """Unit front normal."""
        n = np.cross(self.u, self.v)
        return n / np.linalg.norm(n)

    def point(self, s: float, t: float) -> np.ndarray:
        """3D point at fractional coordinates (s, t) in [0, 1]²."""
        return self.origin + s * self.u + t * self.v

    def sub(self, s0: float, t0: float, s1: float, t1: float) -> Rect:
        """The sub-rectangle between fractional corners (s0, t0) and (s1, t1)."""
        return Rect(self.point(s0, t0), (s1 - s0) * self.u, (t1 - t0) * self.v)


@dataclass(frozen=True, eq=False)
class Surface:
    """A named piece of geometry with one material.

    Exactly one of ``rect`` (a planar rectangle, meshed as a regular grid) or
    ``triangles`` ((t, 3, 3) corner coordinates, meshed by regular subdivision)
    is given. ``grid`` fixes a rectangle's cell counts (nu, nv) regardless of
    the scene resolution; ``subdivide=False`` makes each triangle one patch (the
    importer's polygon mesher has already sized them). ``group`` is the lighting
    group the patches belong to (floor, walls, ceiling, desks, panels, ...); several
    surfaces may share a group.
    """

    name: str
    group: str
    reflectance: float
    rect: Rect | None = None
    triangles: np.ndarray | None = None
    grid: tuple[int, int] | None = None
    subdivide: bool = True

    def __post_init__(self) -> None:
        if self.grid is not None:
            grid = tuple(self.grid) if isinstance(self.grid, tuple | list) else ()
            whole = all(isinstance(c, numbers.Integral) and not isinstance(c, bool) for c in grid)
            if self.rect is None or len(grid) != 2 or not whole or min(grid) < 1:
                raise SceneError(
                    f"surface {self.name!r}: a fixed grid needs a rectangle and two whole "
                    f"counts >= 1, got {self.grid!r}"
                )
            object.__setattr__(self, "grid", (int(grid[0]), int(grid[1])))
        if not (isinstance(self.name, str) and self.name and isinstance(self.group, str)):
            raise SceneError(f"a surface needs a non-empty name and group, got {self.name!r}")
        if not self.group:
            raise SceneError(f"surface {self.name!r}: the group must be a non-empty name")
        if self.rect is not None and not isinstance(self.rect, Rect):
            raise SceneError(f"surface {self.name!r}: rect must be a Rect")
        object.__setattr__(
            self, "reflectance", check_reflectance(self.reflectance, f"surface {self.name!r}")
        )
        if (self.rect is None) == (self.triangles is None):
            raise SceneError(f"surface {self.name!r}: give either a rectangle or triangles")
        if self.triangles is not None:
            try:
                tri = np.asarray(self.triangles, dtype=float)
            except (TypeError, ValueError, OverflowError):
                tri = np.zeros(0)
            if tri.ndim != 3 or tri.shape[1:] != (3, 3) or len(tri) == 0:
                raise SceneError(f"surface {self.name!r}: triangles must have shape (t, 3, 3)")
            if not np.all(np.isfinite(tri)):
                raise SceneError(f"surface {self.name!r}: triangle coordinates must be finite")
            object.__setattr__(self, "triangles", tri)

    @property
    def area(self) -> float:
        """Area in m²."""
        if self.rect is not None:
            return self.rect.area
        t = self.triangles
        return float(
            0.5 * np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1).sum()
        )


@dataclass(frozen=True, eq=False)
class EmitterZone:
    """A planar rectangle where skylights or luminaires may be placed.

    The zone's patches are those of the rectangular surface ``surface``; its
    (u, v) axes in metres are that rectangle's edges. ``outline``, if given, is a
    polygon (k, 2) in those (u, v) metres inside the rectangle: sources must then lie
    inside the polygon (``zone_outline``), not merely inside the rectangle.
    """

    name: str
    kind: str
    surface: str
    outline: np.ndarray | None = None

    def __post_init__(self) -> None:
        if self.kind not in source_kind_names():
            raise SceneError(
                f"emitter zone {self.name!r}: kind {self.kind!r} is not one of "
                f"{source_kind_names()}"
            )
        if self.outline is not None:
            outline = check_outline(self.outline, f"emitter zone {self.name!r}")
            outline.setflags(write=False)
            object.__setattr__(self, "outline", outline)


@dataclass(frozen=True, eq=False)
class Scene:
    """A complete interior: surfaces, emitter zones and the target patch size.

    ``resolution`` is the target patch edge length in metres used when meshing.
    """

    name: str
    surfaces: tuple[Surface, ...]
    zones: tuple[EmitterZone, ...] = ()
    resolution: float = 0.25
    description: str = ""
    info: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "surfaces", tuple(self.surfaces))
        object.__setattr__(self, "zones", tuple(self.zones))
        if not self.surfaces:
            raise SceneError(f"scene {self.name!r} has no surfaces")
        check_resolution(self.resolution)
        counts = Counter(s.name for s in self.surfaces)
        dup = sorted(n for n, c in counts.items() if c > 1)
        if dup:
            raise SceneError(f"scene {self.name!r}: duplicate surface names {dup}")
        by_name = {s.name: s for s in self.surfaces}
        znames = [z.name for z in self.zones]
        if len(set(znames)) != len(znames):
            raise SceneError(f"scene {self.name!r}: duplicate emitter zone names")
        for z in self.zones:
            surf = by_name.get(z.surface)
            if surf is None:
                raise SceneError(f"emitter zone {z.name!r}: no surface named {z.surface!r}")
            if surf.rect is None:
                raise SceneError(
                    f"emitter zone {z.name!r}: surface {z.surface!r} is not a planar rectangle"
                )
            if z.outline is not None:
                su, sv = surf.rect.size
                lo, hi = z.outline.min(axis=0), z.outline.max(axis=0)
                if lo.min() < -1e-6 or hi[0] > su + 1e-6 or hi[1] > sv + 1e-6:
                    raise SceneError(
                        f"emitter zone {z.name!r}: its outline runs outside its surface "
                        f"{z.surface!r}, (0, 0)-({su:g}, {sv:g}) m"
                    )

    @property
    def groups(self) -> tuple[str, ...]:
        """Group names in first-appearance order."""
        return tuple(dict.fromkeys(s.group for s in self.surfaces))

    def surface(self, name: str) -> Surface:
        """The surface called ``name`` (SceneError if none)."""
        for s in self.surfaces:
            if s.name == name:
                return s
        raise SceneError(f"scene {self.name!r} has no surface {name!r}")

    def zone(self, name: str) -> EmitterZone:
        """The emitter zone called ``name`` (SceneError listing the zones if none)."""
        for z in self.zones:
            if z.name == name:
                return z
        known = ", ".join(z.name for z in self.zones) or "none"
        raise SceneError(f"scene {self.name!r} has no emitter zone {name!r} (zones: {known})")

    def zone_rect(self, name: str) -> Rect:
        """The rectangle of emitter zone ``name``."""
        return self.surface(self.zone(name).surface).rect

    @property
    def area(self) -> float:
        """Total surface area in m²."""
        return float(sum(s.area for s in self.surfaces))


MIN_RESOLUTION = 0.005


def check_resolution(resolution: float) -> float:
    """Validate a target patch size in metres."""
    try:
        r = float(resolution)
    except (TypeError, ValueError):
        raise SceneError(f"resolution {resolution!r} is not a number") from None
    if not math.isfinite(r) or r < MIN_RESOLUTION:
        raise SceneError(
            f"resolution {resolution!r} m is not a usable patch size; "
            f"give a positive size of at least {MIN_RESOLUTION} m (e.g. 0.25)"
        )
    return r
