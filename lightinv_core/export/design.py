"""What every export format writes, gathered once from a solved project: the scene's
patches, the luminaires at their solved positions, the designed glazing, the work
planes with their EN 12464-1 results and the illuminance on every patch.

Formats (``ifc_export``, ``radiance_scene``, ``gltf_export``) read an ``ExportDesign``
and never the optimiser's variables: a luminaire of an array is where
``light.arrays.array_luminaires`` places it (the report's and the light's own layout),
a rectangular source is its rectangle in its zone's frame.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from lightinv_core.atomic import atomic_writer
from lightinv_core.design.en12464 import LEGACY_EDITION
from lightinv_core.design.solution import Solution
from lightinv_core.kinds import Bound
from lightinv_core.light.arrays import array_luminaires, zone_frame
from lightinv_core.luminaires.photometry import Photometry
from lightinv_core.project import Project
from lightinv_core.report.chosen import choose_solution
from lightinv_core.scene.patches import Patches
from lightinv_core.sources.types import source_type
from lightinv_core.study import SolutionLight, solution_light


@dataclass(frozen=True)
class Fixture:
    """One photometric luminaire as placed: ``position`` (3,) m (its photometric
    centre), ``aim`` (3,) the direction of gamma 0, ``c0`` (3,) of the C0 plane;
    ``lumens`` and ``watts`` as designed (dimming applied), ``rated_lumens`` and
    ``rated_watts`` the product's; ``photometry_file`` the IES/LDT it came from ("" for
    a table made in memory); ``maintenance`` its array's maintenance factor (what the
    maintained values LightInv reports are scaled by)."""

    name: str
    group: str
    product: str
    position: np.ndarray
    aim: np.ndarray
    c0: np.ndarray
    photometry: Photometry
    dimming: float
    rated_lumens: float
    rated_watts: float
    photometry_file: str = ""
    maintenance: float = 1.0

    @property
    def lumens(self) -> float:
        """Flux emitted as designed, lm."""
        return self.rated_lumens * self.dimming

    @property
    def watts(self) -> float:
        """Power drawn as designed, W."""
        return self.rated_watts * self.dimming

    @property
    def c90(self) -> np.ndarray:
        """Direction of the C90 plane, ``-aim x c0`` (transport.luminaires' convention)."""
        return np.cross(-self.aim, self.c0)


@dataclass(frozen=True)
class Panel:
    """A rectangular source as placed: ``corners`` (4, 3) m counter-clockwise seen from
    the room (so their right-hand normal is ``normal``, into the room); ``kind`` its
    source kind; ``electric``: a luminaire (``lumens``, ``watts``), else glazing
    letting daylight in with ``transmittance`` (the filter times the design's glazing
    transmittance)."""

    name: str
    zone: str
    kind: str
    corners: np.ndarray
    normal: np.ndarray
    electric: bool
    lumens: float = 0.0
    watts: float = 0.0
    transmittance: float = 0.0

    @property
    def size(self) -> tuple[float, float]:
        """Its side lengths (m), along its first and second edges."""
        c = self.corners
        return float(np.linalg.norm(c[1] - c[0])), float(np.linalg.norm(c[3] - c[0]))

    @property
    def centre(self) -> np.ndarray:
        """Its centre, m."""
        return self.corners.mean(axis=0)


@dataclass(frozen=True)
class PlaneResult:
    """A work plane's grid and EN 12464-1 values (lux; ``u0`` a ratio) as designed."""

    name: str
    height: float
    points: np.ndarray
    lux: np.ndarray
    em: float
    emin: float
    emax: float
    u0: float
    standard: str = str(LEGACY_EDITION)
    requirements: tuple[str, ...] = field(default=())


@dataclass
class ExportDesign:
    """A solved project ready to export (see the module); build it with
    ``export_design``."""

    project: Project
    prepared: object  # study.Prepared: its patches, scene and light model
    solution: Solution
    label: str
    light: SolutionLight

    @property
    def patches(self) -> Patches:
        """The scene's patches (m)."""
        return self.prepared.patches

    @property
    def name(self) -> str:
        """The project's name."""
        return self.project.name

    @cached_property
    def illuminance(self) -> np.ndarray:
        """Illuminance (lux, (n,)) on every patch in the design scenario."""
        return np.asarray(self.light.field.illuminance, float)

    @cached_property
    def fixtures(self) -> tuple[Fixture, ...]:
        """Every luminaire of the solution's arrays, where the light model puts it."""
        out = []
        for a, prod, placed in array_luminaires(self.patches, self.solution.arrays):
            src = Path(prod.photometry.source) if prod.photometry.source else None
            file = str(src) if src is not None and src.is_file() else ""
            for p in placed:
                out.append(
                    Fixture(
                        p.name, a.name, prod.name, np.asarray(p.position, float), p.aim, p.c0,
                        prod.photometry, p.dimming, prod.lumens, prod.watts, file,
                        a.maintenance_factor,
                    )
                )  # fmt: skip
        return tuple(out)

    @cached_property
    def panels(self) -> tuple[Panel, ...]:
        """Every rectangular source of the solution (luminaires and glazing)."""
        daylight = self.project.design.daylight
        out = []
        for s in self.solution.sources:
            t = source_type(s.kind)
            frame = zone_frame(self.patches, s.zone)
            (u0, u1), (v0, v1) = s.u_range, s.v_range
            uv = [(u0, v0), (u1, v0), (u1, v1), (u0, v1)]
            corners = np.array([frame.point(u, v) for u, v in uv])
            normal = frame.normal
            if np.dot(np.cross(frame.u, frame.v), normal) < 0:
                corners = corners[::-1]
            rect = np.array([[u0, v0, u1, v1]])
            flux = t.flux(s, daylight)
            watts = float(t.electric_power(s, rect, np.array([flux]))[0]) if t.electric else 0.0
            tau = 0.0 if t.electric else s.filter * daylight.transmittance
            out.append(
                Panel(
                    s.name, s.zone, str(s.kind), corners, np.asarray(normal, float), t.electric,
                    flux if t.electric else 0.0, watts, tau,
                )
            )  # fmt: skip
        return tuple(out)

    @cached_property
    def planes(self) -> tuple[PlaneResult, ...]:
        """The design's work planes with their grids and values as designed."""
        grids, lux = self.light.grids, self.light.grid_lux
        if grids is None:
            return ()
        design = self.project.design
        editions = {wp.name: str(wp.edition) for wp in design.workplanes}
        out = []
        for name, span in grids.spans.items():
            st = self.light.grid_stats[name]
            reqs = tuple(
                f"{it.quantity} {b} {getattr(it, b):g}"
                for it in design.intentions
                if it.grid == name
                for b in Bound
                if getattr(it, b) is not None
            )
            out.append(
                PlaneResult(
                    name, grids.plane_height(name), grids.points[span], lux[span],
                    st["Em"], st["Emin"], st["Emax"], st["U0"], editions[name], reqs,
                )
            )  # fmt: skip
        return tuple(out)

    @property
    def model_file(self) -> Path | None:
        """The model file the scene was imported from (None for a built-in scene)."""
        obj = self.project.scene.obj
        return Path(obj) if obj else None


@dataclass(frozen=True)
class ExportedFile:
    """What an exporter wrote: ``path`` the main file, ``files`` every file written
    (the main one first), ``counts`` what it holds ({"luminaires": 12, ...}),
    ``notes`` what was left out or approximated, for the user."""

    path: Path
    files: tuple[Path, ...]
    counts: dict[str, int]
    notes: tuple[str, ...] = ()


def export_design(project: Project, prepared, solution: Solution | None = None) -> ExportDesign:
    """The solved ``project`` (``prepared``: its ``study.Prepared``) ready to export:
    ``solution`` or, by default, the one a report would show (``choose_solution``;
    ``LightInvError`` when the project holds none)."""
    chosen = choose_solution(project, solution)
    light = solution_light(prepared, project.design, chosen.solution)
    return ExportDesign(project, prepared, chosen.solution, chosen.label, light)


def write_text(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` all or nothing (``atomic.atomic_writer``)."""
    with atomic_writer(path, "w", encoding="utf-8") as fh:
        fh.write(text)


def patch_triangles(patches: Patches, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The patches ``idx`` as triangles: vertices (v, 3) m, faces (f, 3) whose
    right-hand normal is the patch's, and the patch of each face (f,)."""
    o, e1, e2 = patches.origin[idx], patches.edge1[idx], patches.edge2[idx]
    tri = patches.is_triangle[idx]
    flip = np.einsum("ij,ij->i", np.cross(e1, e2), patches.normal[idx]) < 0
    corners = np.stack([o, o + e1, o + e1 + e2, o + e2], axis=1)  # (m, 4, 3)
    corners[tri, 2] = o[tri] + e2[tri]  # a triangle's third corner
    vertices = corners.reshape(-1, 3)
    base = 4 * np.arange(len(idx))
    faces, owner = [], []
    for k in range(len(idx)):
        b = base[k]
        fs = [(b, b + 1, b + 2)] if tri[k] else [(b, b + 1, b + 2), (b, b + 2, b + 3)]
        if flip[k]:
            fs = [(a, c, bb) for a, bb, c in fs]
        faces += fs
        owner += [k] * len(fs)
    return vertices, np.array(faces, np.int64), np.array(owner, np.int64)
