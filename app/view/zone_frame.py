"""A rectangle's origin, unit u, v axes and size in the scene: an emitter zone, or a
surface a zone may be drawn on, for 2D (metres along the surface) <-> 3D conversions."""

from __future__ import annotations

import numpy as np

from lightinv_core.scene.patches import Patches
from lightinv_core.scene.zone_grid import zone_grid

OUTLINE_LIFT = 0.01  # m: outlines float 1 cm off their surface (no z-fighting)


class ZoneFrame:
    """A rectangle's origin, unit u/v axes and size (an emitter zone, or a surface a zone
    may be drawn on), for 2D <-> 3D conversions."""

    def __init__(self, patches: Patches | None, name: str, rect=None):
        self.name = name
        if rect is not None:  # a scene Rect
            self.origin = np.asarray(rect.origin, float)
            self.u = rect.u / np.linalg.norm(rect.u)
            self.v = rect.v / np.linalg.norm(rect.v)
            self.normal = rect.normal
            self.size = rect.size
            self.outline = None
            return
        g = zone_grid(patches, name)
        first = g.patch[0, 0]
        self.origin = patches.origin[first]
        self.u = patches.edge1[first] / np.linalg.norm(patches.edge1[first])
        self.v = patches.edge2[first] / np.linalg.norm(patches.edge2[first])
        self.normal = patches.normal[first]
        self.size = g.size
        self.outline = patches.zone_outline(name)

    def to_world(self, u: float, v: float) -> np.ndarray:
        """3D point of zone coordinates (m), lifted off the surface."""
        return self.origin + u * self.u + v * self.v + OUTLINE_LIFT * self.normal

    def from_ray(self, p0: np.ndarray, p1: np.ndarray) -> tuple[float, float] | None:
        """Zone coordinates where the ray p0 -> p1 meets the zone's plane (None if parallel)."""
        d = p1 - p0
        den = float(np.dot(d, self.normal))
        if abs(den) < 1e-12:
            return None
        t = float(np.dot(self.origin - p0, self.normal)) / den
        q = p0 + t * d - self.origin
        return float(np.dot(q, self.u)), float(np.dot(q, self.v))

    def outline_loop(self) -> np.ndarray:
        """Closed polyline (k + 1, 3) of the zone's outline: its polygon, or its rectangle."""
        if self.outline is None:
            return self.rectangle(0, 0, *self.size)
        return np.array([self.to_world(u, v) for u, v in [*self.outline, self.outline[0]]])

    def rectangle(self, u0: float, v0: float, u1: float, v1: float) -> np.ndarray:
        """Closed polyline (5, 3) of a rectangle in zone coordinates."""
        return np.array(
            [self.to_world(a, b) for a, b in ((u0, v0), (u1, v0), (u1, v1), (u0, v1), (u0, v0))]
        )
