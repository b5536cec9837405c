"""Radiance scene export: a solved design as a scene a designer can render or trace
with Radiance, so any LightInv result can be checked there (docs/export.md).

``write_patches`` writes LightInv's patches as Radiance polygons (grey ``plastic`` of
each patch's reflectance; glazing groups as ``glass`` or diffusing ``trans``); the
project's own cross-checks with Radiance use it (``tests/radiance``).
``write_radiance`` writes a whole design: the scene, each designed skylight or window
cut into its zone as diffusing glazing (``trans``: Lambertian, transmittance = its
filter x the design's glazing transmittance), each rectangular luminaire as a
Lambertian ``light`` polygon, each luminaire of an array as ``light`` spheres whose
radiance follows its photometry (``brightdata`` over the table sampled as LightInv
interpolates it, in the aim and C0 frame of ``transport.luminaires``), and a sky.
Run it from its folder: ``oconv design.rad > design.oct`` (its data files are found
through Radiance's RAYPATH, which starts with ".").
"""

from __future__ import annotations

import itertools
import math
import re
from pathlib import Path

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.export.design import ExportDesign, ExportedFile, Fixture, write_text
from lightinv_core.export.radiance_sky import (
    EFFICACY,
    cie_overcast_args,
    glass_transmissivity,
    inline_sky,
    perez_args,
)
from lightinv_core.luminaires.opening import opening_points
from lightinv_core.luminaires.photometry import Photometry
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.luminaires import SEGMENT

SUFFIXES = (".rad",)
SKIES = ("auto", "overcast", "none")
"""``write_radiance``'s skies: the CIE overcast sky at the design's exterior lux, no sky,
or ``auto`` (overcast when the design lets daylight in)."""
SPHERE_RADIUS = 0.005
"""m: each point source of a luminaire is a light sphere this small (well inside the
2 cm it hangs below its zone), whose projected area is the same from every side."""
C_STEP, GAMMA_STEP = 2.5, 1.0
"""Degrees: the regular grid the photometry is sampled on for ``brightdata``."""
PANEL_LIFT = 1e-3
"""m: a luminaire panel's light polygon lies this far into the room off its zone."""

CAL = """{ LightInv luminaires (radiance_scene.py). Arguments: A1-A3 the aim (gamma 0),
  A4-A6 the C0 direction, A7-A9 C90 (= -aim x C0), A10 the radiance per candela.
  A ray travels towards the source, so the light leaves along -D. }
lum_mult(v) = arg(10) * v;
lum_gamma = Acos(-(Dx*arg(1) + Dy*arg(2) + Dz*arg(3))) / DEGREE;
lum_c = mod(Atan2(-(Dx*arg(7) + Dy*arg(8) + Dz*arg(9)),
                  -(Dx*arg(4) + Dy*arg(5) + Dz*arg(6))) / DEGREE, 360);
"""


def _polygon(mat: str, name: str, points: np.ndarray) -> str:
    coords = "\n".join(f"  {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}" for p in points)
    return f"{mat} polygon {name}\n0\n0\n{3 * len(points)}\n{coords}\n"


def _patch_corners(patches: Patches, i: int) -> np.ndarray:
    """Patch ``i``'s corners in the order whose right-hand normal is its own."""
    o, e1, e2 = patches.origin[i], patches.edge1[i], patches.edge2[i]
    if patches.is_triangle[i]:
        pts = np.array([o, o + e1, o + e2])
    else:
        pts = np.array([o, o + e1, o + e1 + e2, o + e2])
    return pts[::-1] if np.dot(np.cross(e1, e2), patches.normal[i]) < 0 else pts


def _plastic(r: float, mat: str) -> str:
    return f"void plastic {mat}\n0\n0\n5 {r:.6g} {r:.6g} {r:.6g} 0 0\n"


def _trans(mat: str, rho: float, tau: float) -> str:
    """A Lambertian transmitter (``trans``, no specular part) of total transmittance
    ``tau`` and reflectance ``rho``."""
    colour = rho + tau
    if colour > 1.0 + 1e-9:
        raise ValueError(f"{mat}: reflectance + transmittance > 1")
    frac = tau / colour if colour > 0 else 0.0
    c = f"{colour:.6g}"
    return f"void trans {mat}\n0\n0\n7 {c} {c} {c} 0 0 {frac:.8g} 0\n"


def write_patches(
    patches: Patches,
    glazing: dict[str, float],
    path: str | Path,
    *,
    diffusing: set[str] | frozenset[str] = frozenset(),
    openings: set[str] | frozenset[str] = frozenset(),
    black: bool = False,
    skip: np.ndarray | None = None,
) -> Path:
    """Write ``patches`` as a Radiance scene file (.rad) and return its path.

    Every patch is a polygon whose vertex order gives its LightInv normal. Opaque
    patches are grey ``plastic`` of their reflectance (no specularity, no roughness;
    ``black=True`` makes them all 0). Each group named in ``glazing`` (name -> normal
    transmittance) is clear ``glass`` with the transmissivity of
    ``glass_transmissivity``; a group also in ``diffusing`` is instead a Lambertian
    transmitter (``trans`` with no specular part) whose total transmittance is the value
    and whose reflectance is its patches' ``rho``. Groups in ``openings`` are left out
    (empty holes: light passes unchanged), and so are the patches where ``skip`` (n,)
    is True.
    """
    path = Path(path)
    unknown = (set(glazing) | set(diffusing) | set(openings)) - set(patches.group_names)
    if unknown:
        raise ValueError(f"no groups {sorted(unknown)} in the patches")
    if not set(diffusing) <= set(glazing):
        raise ValueError("every diffusing group needs its transmittance in glazing")
    lines: list[str] = []
    material_of_group: dict[int, str] = {}
    for name, tau in glazing.items():
        g = patches.group_names.index(name)
        mat = f"glazing_{g}"
        material_of_group[g] = mat
        if name in diffusing:
            rhos = patches.rho[patches.group_id == g]
            rho = 0.0 if black else float(rhos.mean()) if len(rhos) else 0.0
            lines.append(_trans(mat, rho, tau))
        else:
            tn = glass_transmissivity(tau)
            lines.append(f"void glass {mat}\n0\n0\n3 {tn:.8g} {tn:.8g} {tn:.8g}\n")
    rhos = np.zeros(patches.n) if black else np.round(np.asarray(patches.rho, float), 6)
    plastics = {r: f"grey_{k}" for k, r in enumerate(np.unique(rhos))}
    lines += [_plastic(r, mat) for r, mat in plastics.items()]
    holes = [patches.group_names.index(g) for g in openings]
    keep = ~np.isin(patches.group_id, holes)
    if skip is not None:
        keep &= ~np.asarray(skip, bool)
    for i in np.flatnonzero(keep):
        mat = material_of_group.get(int(patches.group_id[i])) or plastics[rhos[i]]
        lines.append(_polygon(mat, f"p{i}", _patch_corners(patches, i)))
    write_text(path, "\n".join(lines))
    return path


def _safe(name: str) -> str:
    """A Radiance identifier (no blanks, at most 40 characters) made of a name."""
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name)[:40] or "x"


def _data_file(ph: Photometry) -> str:
    """The intensity table (cd) as a Radiance data file over (C, gamma) on a regular
    grid (gamma only for a rotationally symmetric table), sampled with LightInv's own
    interpolation so Radiance's linear interpolation reads the same light."""
    gammas = np.linspace(0.0, 180.0, round(180 / GAMMA_STEP) + 1)
    if ph.c_angles.size == 1:
        cd = ph.intensity(np.zeros_like(gammas), gammas)
        head = f"1\n0 180 {len(gammas)}\n"
    else:
        cs = np.linspace(0.0, 360.0, round(360 / C_STEP) + 1)
        cd = ph.intensity(cs[:, None], gammas[None, :])
        head = f"2\n0 360 {len(cs)}\n0 180 {len(gammas)}\n"
    values = np.asarray(cd, float).reshape(-1)
    rows = [" ".join(f"{v:.6g}" for v in values[k : k + 10]) for k in range(0, len(values), 10)]
    return head + "\n".join(rows) + "\n"


def _fixture_text(f: Fixture, data: str, cal: str, k: int) -> str:
    """One luminaire: its ``brightdata`` in its own frame, its ``light`` and a sphere per
    point source of its opening (each 1/k of the intensity, as LightInv splits it)."""
    offsets = opening_points(f.photometry.opening, SEGMENT)
    centres = f.position + offsets[:, :1] * f.c0 + offsets[:, 1:] * f.c90
    # A sphere of radius r shows pi r² to every direction: radiance = I / (pi r²).
    # Maintained light, as LightInv reports it (its array's maintenance factor).
    per_cd = f.dimming * f.maintenance / (len(centres) * math.pi * SPHERE_RADIUS**2 * EFFICACY)
    coords = "lum_c lum_gamma" if f.photometry.c_angles.size > 1 else "lum_gamma"
    n_str = 3 + len(coords.split())
    args = [*f.aim, *f.c0, *f.c90, per_cd]
    name = f"lum{k}_{_safe(f.name)}"
    out = [
        f"# {f.name}: {f.product[:60]}, {f.lumens:.1f} lm, maintenance factor "
        f"{f.maintenance:g}, {f.watts:.2f} W",
        f"void brightdata {name}_dist\n{n_str} lum_mult {data} {cal} {coords}\n0\n"
        f"10 {' '.join(f'{a:.9g}' for a in args)}\n",
        f"{name}_dist light {name}_light\n0\n0\n3 1 1 1\n",
    ]
    for j, c in enumerate(centres):
        out.append(
            f"{name}_light sphere {name}.{j}\n0\n0\n4 {c[0]:.9g} {c[1]:.9g} {c[2]:.9g} "
            f"{SPHERE_RADIUS:g}\n"
        )
    return "\n".join(out)


def _zone_pieces(corners: np.ndarray, holes: list[tuple[float, float, float, float]]):
    """The zone rectangle ``corners`` (4, 3) cut along every hole's edges (holes in the
    zone's (s, t) fractions 0-1 of its first and second edges): (cell corners (4, 3),
    index of the hole it lies in or None) for every cell."""
    ss = sorted({0.0, 1.0, *(h[0] for h in holes), *(h[2] for h in holes)})
    ts = sorted({0.0, 1.0, *(h[1] for h in holes), *(h[3] for h in holes)})
    o, a, b = corners[0], corners[1] - corners[0], corners[3] - corners[0]
    for s0, s1 in itertools.pairwise(ss):
        for t0, t1 in itertools.pairwise(ts):
            if s1 - s0 < 1e-9 or t1 - t0 < 1e-9:
                continue
            sm, tm = (s0 + s1) / 2, (t0 + t1) / 2
            inside = next(
                (k for k, h in enumerate(holes) if h[0] < sm < h[2] and h[1] < tm < h[3]), None
            )
            cell = [o + s * a + t * b for s, t in ((s0, t0), (s1, t0), (s1, t1), (s0, t1))]
            yield np.array(cell), inside


def _zone_corners(patches: Patches, zone: str) -> np.ndarray:
    """The corners of emitter zone ``zone`` counter-clockwise seen from the room."""
    from lightinv_core.light.arrays import zone_frame

    f = zone_frame(patches, zone)
    w, h = f.size
    c = np.array([f.point(0.0, 0.0), f.point(w, 0.0), f.point(w, h), f.point(0.0, h)])
    return c if np.dot(np.cross(f.u, f.v), f.normal) > 0 else c[::-1]


def _glazing_text(ex: ExportDesign) -> tuple[str, np.ndarray]:
    """Every zone holding designed glazing, cut into glazing (``trans``) and the rest
    of the zone (``plastic`` of its reflectance), and the mask of the zones' patches
    this replaces."""
    patches = ex.patches
    skip = np.zeros(patches.n, bool)
    out: list[str] = []
    by_zone: dict[str, list] = {}
    for p in ex.panels:
        if not p.electric:
            by_zone.setdefault(p.zone, []).append(p)
    for zone, panels in by_zone.items():
        zi = patches.zone_names.index(zone)
        mask = patches.zone_id == zi
        skip |= mask
        rho = float(patches.rho[mask].mean())
        corners = _zone_corners(patches, zone)
        a, b = corners[1] - corners[0], corners[3] - corners[0]
        holes = []
        for p in panels:
            rel = np.array([[(c - corners[0]) @ a / (a @ a), (c - corners[0]) @ b / (b @ b)]
                            for c in p.corners])  # fmt: skip
            lo, hi = np.clip(rel.min(axis=0), 0, 1), np.clip(rel.max(axis=0), 0, 1)
            holes.append((lo[0], lo[1], hi[0], hi[1]))
        zmat = f"zone_{_safe(zone)}"
        out.append(_plastic(rho, zmat))
        for p in panels:
            out.append(
                _trans(f"glazing_{_safe(p.name)}", rho * (1 - p.transmittance), p.transmittance)
            )
        for k, (cell, hole) in enumerate(_zone_pieces(corners, holes)):
            mat = zmat if hole is None else f"glazing_{_safe(panels[hole].name)}"
            out.append(_polygon(mat, f"{zmat}.{k}", cell))
    return "\n".join(out), skip


def _panel_text(ex: ExportDesign) -> str:
    """Every rectangular luminaire as a Lambertian light polygon facing the room."""
    out = []
    for p in ex.panels:
        if not p.electric:
            continue
        w, h = p.size
        radiance = p.lumens / max(w * h, 1e-12) / math.pi / EFFICACY
        name = _safe(p.name)
        out.append(
            f"void light panel_{name}\n0\n0\n3 {radiance:.8g} {radiance:.8g} {radiance:.8g}\n"
        )
        out.append(_polygon(f"panel_{name}", f"{name}.panel", p.corners + PANEL_LIFT * p.normal))
    return "\n".join(out)


def write_radiance(
    ex: ExportDesign,
    path: str | Path,
    *,
    sky: str = "auto",
    sun: tuple[float, float, float, float] | None = None,
) -> ExportedFile:
    """Write the design ``ex`` as a Radiance scene ``path`` (.rad), with its geometry
    in ``<stem>_geometry.rad``, one data file per luminaire product and the function
    file ``<stem>_lum.cal`` beside it (see the module).

    ``sky``: "overcast" (the CIE overcast sky, ``gensky -c``, of the design's exterior
    lux), "none", or "auto" (overcast when the design lets daylight in); ``sun`` =
    (altitude, compass azimuth deg, DNI, DHI W/m²) writes the Perez sky of that hour
    (``gendaylit``) instead. Skies are turned by the design's ``north_deg``.
    """
    if sky not in SKIES:
        raise LightInvError(f"Radiance sky {sky!r}: use one of {', '.join(SKIES)}")
    path = Path(path)
    stem, folder = path.stem, path.parent
    daylight = ex.project.design.daylight
    glazing, skip = _glazing_text(ex)
    geometry = folder / f"{stem}_geometry.rad"
    write_patches(ex.patches, {}, geometry, skip=skip)
    files = [path, geometry]
    cal = folder / f"{stem}_lum.cal"
    data_of: dict[int, str] = {}
    fixtures = []
    for k, f in enumerate(ex.fixtures):
        key = id(f.photometry)
        if key not in data_of:
            data_of[key] = f"{stem}_product{len(data_of) + 1}.dat"
            write_text(folder / data_of[key], _data_file(f.photometry))
            files.append(folder / data_of[key])
        fixtures.append(_fixture_text(f, data_of[key], cal.name, k + 1))
    if fixtures:
        write_text(cal, CAL)
        files.append(cal)
    parts = [f"# LightInv design {ex.name!r} ({ex.label}); run oconv from this folder"]
    parts.append(f"!xform {geometry.name}")
    notes = []
    has_glazing = any(not p.electric for p in ex.panels)
    if sun is not None:
        alt, az, dni, dhi = sun
        args = perez_args(alt, az, dni, dhi, daylight.ground_reflectance)
        parts.append(inline_sky(args, daylight.north_deg))
    elif sky == "overcast" or (sky == "auto" and has_glazing):
        args = cie_overcast_args(daylight.exterior_lux, daylight.ground_reflectance)
        parts.append(inline_sky(args, daylight.north_deg))
    else:
        notes.append("no sky: the luminaires' light alone")
    parts += [glazing, _panel_text(ex), *fixtures]
    write_text(path, "\n".join(p for p in parts if p) + "\n")
    counts = {
        "patches": int((~skip).sum()),
        "luminaires": len(ex.fixtures) + sum(p.electric for p in ex.panels),
        "glazing": sum(not p.electric for p in ex.panels),
        "products": len(data_of),
    }
    return ExportedFile(path, tuple(files), counts, tuple(notes))
