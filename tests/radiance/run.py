"""Running Radiance on LightInv's patches: point illuminance (``rtrace``) under one sky,
and the annual illuminance of Radiance's two-phase daylight-coefficient method
(``rfluxmtx``, ``gendaymtx``, the product of the two matrices as ``dctimestep`` does).

The binaries come from the ``pyradiance`` wheel (a dev extra, never needed at run time).
Everything is written to a temporary directory removed afterwards.
"""

from __future__ import annotations

import gzip
import math
import os
import shutil
import subprocess
import tempfile
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from lightinv_core.export.radiance_scene import write_patches as write_scene
from lightinv_core.export.radiance_sky import RGB_TO_LUX
from lightinv_core.scene.patches import Patches

POINT_PARAMS = "-aa 0 -ad 16384 -as 0 -lw 1e-5 -lr -12 -dj 0 -ds 0 -dt 0 -dc 1 -dr 3 -st 0 -ss 0"
"""rtrace settings beside ``-ab``: a pure Monte-Carlo estimate (no ambient cache, -aa 0)
with 16384 hemisphere samples at the first bounce (fewer deeper, by ray weight, down to
-lw 1e-5), every light source tested for every shadow ray (-dt 0 -dc 1), the sun as a
point (-dj 0) and every specular ray traced (-st 0)."""

ANNUAL_PARAMS = "-ad 32768 -lw 2e-6 -lr -12"
"""rfluxmtx (rcontrib) settings beside ``-ab``: 32768 samples over each sensor's
hemisphere, rays followed down to a weight of 2e-6 (below 1 / ad, or the deeper bounces
would be cut). The daylight matrix's noise is the same for every hour, a bias per point
over the year: 8192 samples left +-2.3% at the office's points, 32768 +-0.6%."""

SKY_SENDER = """#@rfluxmtx h=u
void glow ground_glow
0
0
4 1 1 1 0

ground_glow source ground
0
0
4 0 0 -1 180

#@rfluxmtx h=r{mf} u=+Y
void glow sky_glow
0
0
4 1 1 1 0

sky_glow source sky
0
0
4 0 0 1 180
"""
"""rfluxmtx's senders: the ground (one bin) and the Reinhart sky of subdivision mf with
+Y north, the rows gendaymtx writes (ground first, then 145 mf^2 sky patches)."""


def radiance_env() -> dict:
    """The environment for Radiance's tools: pyradiance's ``bin`` first on PATH and its
    ``lib`` (skybright.cal, perezlum.cal, ...) on RAYPATH."""
    import pyradiance

    root = Path(pyradiance.__file__).parent
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(root / "bin"), env.get("PATH", "")])
    env["RAYPATH"] = os.pathsep.join([".", str(root / "lib"), env.get("RAYPATH", "")])
    return env


def _run(args: Sequence[str], cwd: Path, stdin: bytes | None = None, out: Path | None = None):
    """Run one Radiance command in ``cwd``; its stdout (bytes), or written to ``out``."""
    sink = open(out, "wb") if out is not None else subprocess.PIPE  # noqa: SIM115
    try:
        res = subprocess.run(
            list(args), cwd=cwd, input=stdin, stdout=sink, stderr=subprocess.PIPE,
            env=radiance_env(), check=False,
        )  # fmt: skip
    finally:
        if out is not None:
            sink.close()
    if res.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} failed: {res.stderr.decode(errors='replace')}")
    return res.stdout


def _rays(points: np.ndarray, normals: np.ndarray) -> bytes:
    p = np.asarray(points, float).reshape(-1, 3)
    n = np.asarray(normals, float).reshape(-1, 3)
    if p.shape != n.shape:
        raise ValueError("points and normals must both be (q, 3)")
    n = n / np.linalg.norm(n, axis=1, keepdims=True)
    return "".join(f"{a[0]:.9g} {a[1]:.9g} {a[2]:.9g} {b[0]:.9g} {b[1]:.9g} {b[2]:.9g}\n"
                   for a, b in zip(p, n, strict=True)).encode()  # fmt: skip


def _octree(
    tmp: Path,
    patches: Patches | None,
    glazing: dict[str, float],
    diffusing,
    extra: str,
    *,
    openings=frozenset(),
    black: bool = False,
    turn_scene_deg: float = 0.0,
) -> Path:
    """scene.oct in ``tmp`` from the patches (optional) and the ``extra`` text."""
    (tmp / "extra.rad").write_text(extra)
    files = ["extra.rad"]
    if patches is not None:
        write_scene(
            patches, glazing, tmp / "scene.rad", diffusing=diffusing, openings=openings,
            black=black,
        )  # fmt: skip
        if turn_scene_deg:
            (tmp / "turned.rad").write_text(f"!xform -rz {turn_scene_deg:.9g} scene.rad\n")
            files.append("turned.rad")
        else:
            files.append("scene.rad")
    _run(["oconv", *files], tmp, out=tmp / "scene.oct")
    return tmp / "scene.oct"


def point_lux(
    patches: Patches | None,
    glazing: dict[str, float],
    sky_text: str,
    points: np.ndarray,
    normals: np.ndarray,
    *,
    north_deg: float = 0.0,
    diffusing: set[str] | frozenset[str] = frozenset(),
    openings: set[str] | frozenset[str] = frozenset(),
    ab: int = 7,
    params: str = POINT_PARAMS,
    procs: int = 1,
) -> np.ndarray:
    """Illuminance (lux, (q,)) at ``points`` (q, 3) on planes facing ``normals`` (q, 3),
    by ``rtrace -I -ab ab`` under ``sky_text`` (one of ``tests.radiance.scene``'s skies,
    in Radiance's frame, turned into the scene's axes by ``north_deg``).

    ``patches=None`` traces the sky alone; ``diffusing`` and ``openings`` as
    ``write_scene``. Points should sit a little off any surface.
    """
    with tempfile.TemporaryDirectory(prefix="lightinv-rad-") as d:
        tmp = Path(d)
        (tmp / "sky.rad").write_text(sky_text)
        sky = f"!xform -rz {north_deg:.9g} sky.rad\n"
        oct_ = _octree(tmp, patches, glazing, diffusing, sky, openings=openings)
        args = ["rtrace", "-h", "-I+", "-ov", "-ab", str(ab), *params.split()]
        if procs > 1:
            args += ["-n", str(procs)]
        raw = _run([*args, oct_.name], tmp, stdin=_rays(points, normals))
    rgb = np.array(raw.split(), dtype=float).reshape(-1, 3)
    return rgb @ RGB_TO_LUX


def read_matrix(path: Path) -> np.ndarray:
    """A Radiance matrix file (header then float or ascii data) as (rows, cols, comps)."""
    data = path.read_bytes()
    end = data.index(b"\n\n") + 2
    head = dict(line.split("=", 1) for line in data[:end].decode().splitlines() if "=" in line)
    rows, cols = int(head["NROWS"]), int(head["NCOLS"])
    comps = int(head.get("NCOMP", "3"))
    fmt = head.get("FORMAT", "ascii").strip()
    if fmt == "float":
        values = np.frombuffer(data[end:], dtype="<f4" if head.get("BigEndian", "0") == "0"
                               else ">f4")  # fmt: skip
    elif fmt == "ascii":
        values = np.array(data[end:].split(), dtype=float)
    else:
        raise ValueError(f"{path.name}: unsupported matrix format {fmt!r}")
    return values.reshape(rows, cols, comps).astype(np.float64)


def _epw(weather_path: Path, tmp: Path) -> Path:
    """The weather file as a plain .epw in ``tmp`` (gunzipped if needed)."""
    target = tmp / "weather.epw"
    opener = gzip.open if weather_path.suffix == ".gz" else open
    with opener(weather_path, "rb") as src, open(target, "wb") as dst:
        shutil.copyfileobj(src, dst)
    return target


def _turned(v, north_deg: float) -> np.ndarray:
    """(q, 3) vectors turned about z by -``north_deg`` into Radiance's frame (+Y north)."""
    turn = np.radians(-north_deg)
    rot = np.array(
        [[math.cos(turn), -math.sin(turn), 0], [math.sin(turn), math.cos(turn), 0], [0, 0, 1]]
    )
    return np.asarray(v, float).reshape(-1, 3) @ rot.T


def annual_lux(
    patches: Patches,
    glazing: dict[str, float],
    points: np.ndarray,
    normals: np.ndarray,
    weather_path: str | Path,
    *,
    north_deg: float = 0.0,
    diffusing: set[str] | frozenset[str] = frozenset(),
    openings: set[str] | frozenset[str] = frozenset(),
    mf: int = 4,
    ab: int = 6,
    params: str = ANNUAL_PARAMS,
    ground_reflectance: float = 0.2,
    direct_sun_only: bool = False,
    procs: int = 1,
) -> np.ndarray:
    """Illuminance (lux, (q, hours)) at ``points`` facing ``normals`` for every hour of
    the EPW weather file (.epw or .epw.gz), by Radiance's two-phase method.

    The daylight matrix is ``rfluxmtx -I+`` from the points to the ground and the
    Reinhart sky of subdivision ``mf`` (145 mf^2 patches); the sky matrix is
    ``gendaymtx -m mf -O0`` (visible Perez skies with the sun spread over the patches
    around it) from ``epw2wea``; their product per hour is what ``dctimestep`` computes.
    The scene is turned into Radiance's frame (``xform -rz -north_deg``, the points and
    normals alike), so the sky keeps +Y north. ``diffusing`` and ``openings`` as
    ``write_scene``.

    ``direct_sun_only`` gives the sun's direct light alone for ASE: the sun-only sky
    matrix (``gendaymtx -d``) through a black scene with one bounce (-ab 1: the sensors'
    hemisphere rays reach the sky patches straight or through the glass, nothing is
    reflected).
    """
    p, n = _turned(points, north_deg), _turned(normals, north_deg)
    with tempfile.TemporaryDirectory(prefix="lightinv-rad-") as d:
        tmp = Path(d)
        epw = _epw(Path(weather_path), tmp)
        _run(["epw2wea", epw.name, "weather.wea"], tmp)
        rg = f"{ground_reflectance:g}"
        sky_args = ["gendaymtx", "-m", str(mf), "-O0", "-of", "-g", rg, rg, rg]
        if direct_sun_only:
            sky_args.append("-d")
        _run([*sky_args, "weather.wea"], tmp, out=tmp / "sky.smx")
        (tmp / "senders.rad").write_text(SKY_SENDER.format(mf=mf))
        oct_ = _octree(
            tmp, patches, glazing, diffusing, "", openings=openings, black=direct_sun_only,
            turn_scene_deg=-north_deg,
        )  # fmt: skip
        bounces = 1 if direct_sun_only else ab
        args = ["rfluxmtx", "-I+", "-y", str(len(p)), "-faf", "-ab", str(bounces)]
        args += params.split()
        if procs > 1:
            args += ["-n", str(procs)]
        args += ["-", "senders.rad", "-i", oct_.name]
        _run(args, tmp, stdin=_rays(p, n), out=tmp / "dc.mtx")
        dc = read_matrix(tmp / "dc.mtx")
        sky = read_matrix(tmp / "sky.smx")
    if dc.shape[1] != sky.shape[0]:
        raise RuntimeError(f"daylight matrix {dc.shape} and sky matrix {sky.shape} disagree")
    rgb = np.einsum("qpc,ptc->qtc", dc, sky)
    return rgb @ RGB_TO_LUX


SUN_DISC_DEG = 0.533
"""The sun's apparent diameter, degrees (the five-phase method's solar discs)."""


def annual_sun_discs(
    patches: Patches,
    glazing: dict[str, float],
    points: np.ndarray,
    normals: np.ndarray,
    weather_path: str | Path,
    *,
    north_deg: float = 0.0,
    mf: int = 6,
    openings: set[str] | frozenset[str] = frozenset(),
) -> np.ndarray:
    """The sun's direct light (lux, (q, hours)) for ASE by the five-phase method's sun
    step: solar discs of ``SUN_DISC_DEG`` at the Reinhart MF:``mf`` patch centres
    (``reinsrc.cal``), their coefficients at the points through the black scene by
    ``rcontrib -ab 0`` (shadow rays only, through the glass), and the sun matrix
    ``gendaymtx -5 0.533 -d`` (each hour's sun radiance for a disc, in its nearest
    patch). Unlike ``annual_lux(direct_sun_only=True)``, whose sun is spread over a
    patch of about 3 degrees, the beam's edge stays sharp. Only the discs some hour uses
    are traced."""
    p, n = _turned(points, north_deg), _turned(normals, north_deg)
    with tempfile.TemporaryDirectory(prefix="lightinv-rad-") as d:
        tmp = Path(d)
        epw = _epw(Path(weather_path), tmp)
        _run(["epw2wea", epw.name, "weather.wea"], tmp)
        sky = ["gendaymtx", "-5", f"{SUN_DISC_DEG:g}", "-d", "-m", str(mf), "-O0", "-of"]
        _run([*sky, "weather.wea"], tmp, out=tmp / "sun.smx")
        sun = read_matrix(tmp / "sun.smx")  # (1 + patches, hours, 3), row 0 the ground
        bins = np.flatnonzero(sun[1:].any(axis=(1, 2))) + 1
        where = _run(
            ["rcalc", "-e", f"MF:{mf}", "-f", "reinsrc.cal", "-e", "Rbin=$1",
             "-o", "${Dx} ${Dy} ${Dz}"],
            tmp, stdin="".join(f"{b}\n" for b in bins).encode(),
        )  # fmt: skip
        dirs = np.array(where.split(), dtype=float).reshape(-1, 3)
        discs = "".join(
            f"void light solar{b}\n0\n0\n3 1 1 1\n\nsolar{b} source sun{b}\n0\n0\n"
            f"4 {x:.9g} {y:.9g} {z:.9g} {SUN_DISC_DEG:g}\n\n"
            for b, (x, y, z) in zip(bins, dirs, strict=True)
        )
        (tmp / "mods.txt").write_text("".join(f"solar{b}\n" for b in bins))
        oct_ = _octree(
            tmp, patches, glazing, frozenset(), discs, openings=openings, black=True,
            turn_scene_deg=-north_deg,
        )  # fmt: skip
        args = ["rcontrib", "-I+", "-y", str(len(p)), "-faf", "-ab", "0", "-dc", "1"]
        args += ["-dt", "0", "-dj", "0", "-ds", "0", "-lw", "1e-6", "-M", "mods.txt"]
        _run([*args, oct_.name], tmp, stdin=_rays(p, n), out=tmp / "dc.mtx")
        dc = read_matrix(tmp / "dc.mtx")  # (q, discs, 3)
    rgb = np.einsum("qpc,ptc->qtc", dc, sun[bins])
    return rgb @ RGB_TO_LUX
