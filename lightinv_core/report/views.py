"""False-colour views of a scene coloured by a per-patch value (illuminance in lux).

Rendered with matplotlib alone (no OpenGL): the patches are projected with an
orthographic camera, patches facing away from it are dropped (back-face culling, so
the ceiling disappears from above and the near walls from the front, giving a cut-away
view of an interior whose normals face inwards), the rest are sorted far to near
(painter's algorithm) and drawn as one ``PolyCollection``. Source and zone outlines are
drawn on top. 25,000 patches take about a second.

Figures are plain ``matplotlib.figure.Figure`` objects with an Agg canvas: pyplot and
the global backend are never touched, so this is safe next to a GUI.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import PolyCollection
from matplotlib.colors import Normalize
from matplotlib.figure import Figure, FigureBase

from lightinv_core.design.model import LuminaireArray, Source
from lightinv_core.errors import LightInvError
from lightinv_core.light.arrays import resolve_product
from lightinv_core.light.arrays import zone_frame as light_zone_frame
from lightinv_core.report.tables import Table
from lightinv_core.scene.patches import Patches
from lightinv_core.scene.zone_grid import zone_grid

A4_LANDSCAPE = (11.69, 8.27)
OUTLINE_COLOUR = "#00e5ff"


@dataclass(frozen=True)
class Camera:
    """An orthographic camera looking along ``direction`` with ``up`` towards the top of
    the picture. ``axes`` names the picture's horizontal and vertical world axes when
    they are world axes (plans and elevations get metre ticks), else None."""

    name: str
    direction: tuple[float, float, float]
    up: tuple[float, float, float]
    title: str
    axes: tuple[str, str] | None = None

    def basis(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(right, up, forward) unit vectors of the picture."""
        d = np.asarray(self.direction, float)
        d = d / np.linalg.norm(d)
        right = np.cross(d, np.asarray(self.up, float))
        if np.linalg.norm(right) < 1e-9:
            raise LightInvError(f"camera {self.name!r}: up is parallel to the direction")
        right /= np.linalg.norm(right)
        return right, np.cross(right, d), d


CAMERAS = {
    "top": Camera(
        "top", (0, 0, -1), (0, 1, 0), "top view (looking down, ceiling removed)", ("x (m)", "y (m)")
    ),
    "front": Camera(
        "front", (0, 1, 0), (0, 0, 1), "front view (looking north, +y)", ("x (m)", "z (m)")
    ),
    "iso": Camera("iso", (1, 1, -1), (0, 0, 1), "isometric view (from the south-west, above)"),
}


@dataclass(frozen=True)
class Outline:
    """A closed 3-D polygon drawn over a view: a source (``kind`` "source"), one
    luminaire of an array ("luminaire", labelled with the array's name) or an emitter
    zone ("zone"), with its label."""

    label: str
    points: np.ndarray
    kind: str = "source"


def camera_of(camera: str | Camera) -> Camera:
    """A preset name ("top", "front", "iso") or a ``Camera``."""
    if isinstance(camera, Camera):
        return camera
    if camera not in CAMERAS:
        raise LightInvError(f"unknown view {camera!r} (views: {', '.join(CAMERAS)})")
    return CAMERAS[camera]


def visible_patches(patches: Patches, camera: str | Camera) -> np.ndarray:
    """Ids of the patches facing the camera, far to near (the order to paint them)."""
    _, _, d = camera_of(camera).basis()
    facing = np.flatnonzero(patches.normal @ d < -1e-6)
    depth = patches.centroid[facing] @ d
    return facing[np.argsort(-depth, kind="stable")]


def patch_polygons(patches: Patches, idx: np.ndarray) -> np.ndarray:
    """(len(idx), 4, 3) corners of the patches; a triangle repeats its last corner."""
    o, e1, e2 = patches.origin[idx], patches.edge1[idx], patches.edge2[idx]
    third = np.where(patches.is_triangle[idx][:, None], o + e2, o + e1 + e2)
    return np.stack([o, o + e1, third, o + e2], axis=1)


def zone_frame(
    patches: Patches, zone: str
) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[float, float]]:
    """(origin, unit u, unit v, (width, height) m) of an emitter zone's own axes."""
    g = zone_grid(patches, zone)
    p = g.patch[0, 0]
    u = patches.edge1[p] / np.linalg.norm(patches.edge1[p])
    v = patches.edge2[p] / np.linalg.norm(patches.edge2[p])
    return patches.origin[p].copy(), u, v, g.size


def source_outlines(
    patches: Patches, sources: Sequence[Source], zones: bool = True
) -> list[Outline]:
    """Outlines of the sources' rectangles (and of the zones they are in) in 3-D."""
    out = []
    frames = {}
    for s in sources:
        if s.zone not in frames:
            frames[s.zone] = zone_frame(patches, s.zone)
            o, u, v, (w, h) = frames[s.zone]
            if zones:
                polygon = patches.zone_outline(s.zone)
                if polygon is None:
                    polygon = np.array([(0, 0), (w, 0), (w, h), (0, h)], dtype=float)
                pts = o + polygon[:, :1] * u + polygon[:, 1:] * v
                out.append(Outline(s.zone, pts, "zone"))
    for s in sources:
        o, u, v, _ = frames[s.zone]
        (a, b), (c, d) = s.u_range, s.v_range
        pts = np.array([o + a * u + c * v, o + b * u + c * v, o + b * u + d * v, o + a * u + d * v])
        out.append(Outline(s.name, pts, "source"))
    return out


def luminaire_outlines(patches: Patches, arrays: Sequence[LuminaireArray]) -> list[Outline]:
    """Outlines of every luminaire opening of the arrays (as written) in 3-D, each
    labelled with its array's name."""
    out = []
    for a in arrays:
        prod = resolve_product(a.product, a.watts)
        frame = light_zone_frame(patches, a.zone)
        w, length = (max(x, 0.05) for x in prod.opening)
        # The opening's length runs along C0: u at rotation 0, v at 90.
        hu, hv = (length / 2, w / 2) if a.rotation == 0 else (w / 2, length / 2)
        for cu, cv in a.positions():
            corners = [
                (cu - hu, cv - hv),
                (cu + hu, cv - hv),
                (cu + hu, cv + hv),
                (cu - hu, cv + hv),
            ]
            pts = np.array([frame.point(u, v) for u, v in corners])
            out.append(Outline(a.name, pts, "luminaire"))
    return out


def render_view(
    patches: Patches,
    values: np.ndarray,
    camera: str | Camera = "top",
    *,
    outlines: Sequence[Outline] = (),
    vmin: float | None = None,
    vmax: float | None = None,
    cmap: str = "inferno",
    label: str = "Illuminance (lux)",
    title: str | None = None,
    figsize: tuple[float, float] = A4_LANDSCAPE,
    fig: FigureBase | None = None,
    numbered: bool = False,
) -> FigureBase:
    """A figure of the patches facing ``camera`` coloured by ``values`` (one per patch),
    with a colour bar labelled ``label`` and the ``outlines`` drawn on top.

    ``vmin``/``vmax`` fix the colour range (default: 0 to the 99th percentile of the
    visible values, so a few hot spots do not wash out the rest; the bar then shows an
    arrow for the values above). ``fig``: draw into this (sub)figure instead of a new
    one. ``numbered``: mark each source and array with its number from
    ``marker_numbers`` (listed by ``marker_legend``) instead of its name, so that many
    luminaires stay readable.
    """
    cam = camera_of(camera)
    values = np.asarray(values, dtype=float)
    if values.shape != (patches.n,):
        raise LightInvError(f"expected {patches.n} values (one per patch), got {values.shape}")
    right, up, _ = cam.basis()
    idx = visible_patches(patches, cam)
    poly3 = patch_polygons(patches, idx)
    verts = np.stack([poly3 @ right, poly3 @ up], axis=-1)
    vals = values[idx]
    if vmin is None:
        vmin = min(0.0, float(np.nanmin(vals))) if len(vals) else 0.0
    if vmax is None:
        vmax = float(np.nanpercentile(vals, 99.0)) if len(vals) else 1.0
    if not vmax > vmin:  # also catches NaN
        vmax = vmin + 1.0

    if fig is None:
        fig = Figure(figsize=figsize, layout="constrained")
        FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    coll = PolyCollection(
        verts,
        array=vals,
        cmap=cmap,
        norm=Normalize(vmin, vmax),
        edgecolors="face",
        linewidths=0.3,
        antialiaseds=False,
    )
    coll.set_rasterized(True)  # a PDF keeps one image, not 25,000 paths
    ax.add_collection(coll)
    numbers = marker_numbers(outlines) if numbered else {}
    centres: dict[str, list[np.ndarray]] = {}
    for o in outlines:
        p = np.asarray(o.points, float)
        xy = np.stack([p @ right, p @ up], axis=-1)
        closed = np.vstack([xy, xy[:1]])
        if o.kind == "zone":
            ax.plot(closed[:, 0], closed[:, 1], color="0.75", lw=0.9, ls="--", zorder=3)
            continue
        ax.plot(closed[:, 0], closed[:, 1], color=OUTLINE_COLOUR, lw=1.4, zorder=4)
        centres.setdefault(o.label, []).append(xy.mean(axis=0))
    span = float(np.ptp(verts.reshape(-1, 2), axis=0).max()) if len(verts) else 1.0
    placed = _spread(
        {name: _anchor(np.asarray(cs)) for name, cs in centres.items()},
        MARKER_SPACING * span if numbered else 0.0,
    )
    for name, c in placed.items():
        text = str(numbers[name]) if name in numbers else name
        ax.annotate(
            text,
            c,
            color="black" if numbered else OUTLINE_COLOUR,
            fontsize=8 if numbered else 9,
            ha="center",
            va="center",
            zorder=5,
            fontweight="bold",
            bbox=dict(boxstyle="circle,pad=0.25", fc="white", ec="#007c91", lw=0.8)
            if numbered
            else None,
        )
    if len(verts):
        lo, hi = verts.reshape(-1, 2).min(axis=0), verts.reshape(-1, 2).max(axis=0)
        pad = 0.03 * max(hi - lo)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_facecolor("0.85")  # gaps (column footprints, open sides) read as "no surface"
    if cam.axes is None:
        ax.set_axis_off()
    else:
        ax.set_xlabel(cam.axes[0])
        ax.set_ylabel(cam.axes[1])
    extend = "max" if len(vals) and np.nanmax(vals) > vmax else "neither"
    fig.colorbar(coll, ax=ax, label=label, extend=extend, shrink=0.85)
    ax.set_title(title if title is not None else f"{label.split(' (')[0]}, {cam.title}")
    return fig


MARKER_SPACING = 0.035
"""Least distance between two numbered markers, as a share of the view's width: closer
markers are pushed apart (an array above a skylight, a source seen edge-on)."""


def _anchor(centres: np.ndarray) -> np.ndarray:
    """Where an outline group's marker goes: on the luminaire nearest the group's
    middle (a mark between luminaires would point at nothing)."""
    return centres[np.argmin(np.linalg.norm(centres - centres.mean(axis=0), axis=1))]


def _spread(points: dict[str, np.ndarray], gap: float) -> dict[str, np.ndarray]:
    """The points moved apart until no two are closer than ``gap`` (a few passes of
    pushing each close pair apart along the line joining them, sideways if they
    coincide)."""
    names = list(points)
    p = np.array([points[n] for n in names], dtype=float).reshape(-1, 2)
    for _ in range(30):
        moved = False
        for i in range(len(p)):
            for j in range(i + 1, len(p)):
                d = p[j] - p[i]
                dist = float(np.hypot(*d))
                if dist >= gap:
                    continue
                way = d / dist if dist > 1e-12 else np.array([1.0, 0.0])
                push = 0.5 * (gap - dist) + 1e-9
                p[i] -= way * push
                p[j] += way * push
                moved = True
        if not moved:
            break
    return {n: p[k] for k, n in enumerate(names)}


def marker_numbers(outlines: Sequence[Outline]) -> dict[str, int]:
    """1, 2, ... for each source and array drawn, in the order of the outlines."""
    labels = [o.label for o in outlines if o.kind != "zone"]
    return {label: k for k, label in enumerate(dict.fromkeys(labels), 1)}


def marker_legend(outlines: Sequence[Outline], describe: dict[str, str] | None = None) -> Table:
    """The numbered markers' legend (``tables.Table``): number, name, what it is (from
    ``describe``: name -> text) and how many luminaires it outlines."""
    numbers = marker_numbers(outlines)
    counts: dict[str, int] = {}
    kinds: dict[str, str] = {}
    for o in outlines:
        if o.kind != "zone":
            counts[o.label] = counts.get(o.label, 0) + 1
            kinds[o.label] = o.kind
    rows = []
    for label, n in numbers.items():
        what = (describe or {}).get(
            label, "luminaire array" if kinds[label] == "luminaire" else "source"
        )
        rows.append(
            (str(n), label, what, str(counts[label]) if kinds[label] == "luminaire" else "1")
        )
    return Table("Legend of the views", ("no.", "name", "what", "luminaires"), tuple(rows))


def view_extent(patches: Patches, camera: str | Camera) -> tuple[float, float]:
    """Width and height (m) of what ``camera`` sees of the patches."""
    cam = camera_of(camera)
    right, up, _ = cam.basis()
    idx = visible_patches(patches, cam)
    if not len(idx):
        return 1.0, 1.0
    pts = patch_polygons(patches, idx).reshape(-1, 3)
    w = float(np.ptp(pts @ right))
    h = float(np.ptp(pts @ up))
    return max(w, 1e-3), max(h, 1e-3)
