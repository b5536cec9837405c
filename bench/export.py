"""Benchmark: the design exports of the export tests' office (tests/export/office.py:
the built-in office at 1 m, an array of three real IES downlights, a 3,000 lm Lambertian
panel, a diffusing skylight and a work plane). Prints JSON.

    python bench/export.py [--ab 10] [--ad 2048] [--daylight-only]

For each format: the time to write it and the files' size. Then the Radiance scene
traced with ``rtrace`` beside LightInv's own illuminance: the luminaires' direct light
alone at every work-plane point (``-ab 0`` against LightInv's point-source sum), the
panel's direct light against the closed form (with ``-ds 0``, the point-source setting
the first version of this bench used, and with ``PARAMS``), at night the array and the
panel with interreflections at every work-plane point, and the skylight under the CIE
overcast sky at 6 points (two runs with different random seeds); LightInv both as the
tests' coarse office (1 m, rank 60, 128 rays) and ``fine`` (0.5 m, default tolerance,
512 rays). The mean and largest relative difference per point.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from lightinv_core.export import exporters
from lightinv_core.export.radiance_scene import write_radiance
from lightinv_core.export.radiance_sky import RGB_TO_LUX
from lightinv_core.light.arrays import caster_for
from lightinv_core.transport.luminaires import PlacedLuminaire
from tests.export.office import exported, office_project
from tests.radiance.run import radiance_env

PARAMS = "-aa 0 -as 0 -lw 1e-4 -lr -12 -dj 0 -ds 0.02 -dt 0 -dc 1 -dr 3 -st 0 -ss 0 -u+"
"""rtrace settings beside -ab and -ad: the harness's (tests/radiance/run.py): no
ambient cache or super-samples, Russian roulette below -lw (rtrace's default too), area
sources split into parts under 2% of their distance (-ds 0.02: the first version's
-ds 0 traced the 1 x 3 m panel as a point at its centre, 21 lux instead of 26.6 at one
point), a new random seed per run (-u+)."""
DAYLIGHT = PARAMS.replace("-lw 1e-4", "-lw 1e-6")
"""For the skylight: its light reaches the room by ambient rays alone (a transmitter is
no light source), so the dark points far from it are noisy: at -ad 8192 and 1e-5 runs
read 13.8 to 17.4 lux at one point (LightInv 18.7); 1e-6 and -ad 16384, 17.9 to 18.5."""


def rtrace(folder: Path, points: np.ndarray, ab: int, ad: int, params: str = PARAMS) -> np.ndarray:
    env = radiance_env()
    with open(folder / "scene.oct", "wb") as fh:
        subprocess.run(["oconv", "scene.rad"], cwd=folder, env=env, stdout=fh, check=True)
    rays = "".join(f"{p[0]:.9g} {p[1]:.9g} {p[2]:.9g} 0 0 1\n" for p in points).encode()
    args = ["rtrace", "-h", "-I+", "-ov", "-ab", str(ab), "-ad", str(ad), *params.split()]
    args += ["-n", "1", "scene.oct"]
    out = subprocess.run(args, input=rays, cwd=folder, env=env, capture_output=True, check=True)
    return np.array(out.stdout.split(), float).reshape(-1, 3) @ RGB_TO_LUX


def errors(got: np.ndarray, want: np.ndarray) -> dict:
    rel = np.abs(got / want - 1)
    return {"points": len(want), "mean_rel": float(rel.mean()), "max_rel": float(rel.max())}


def daylight(ab: int, ad: int, runs: int = 2) -> dict:
    """The skylight alone (diffusing, filter 0.5, transmittance 0.6) under the CIE
    overcast sky of the design's 10,000 lux, at 6 work-plane points, against the
    design scenario LightInv reports (coarse and fine); rtrace's mean of ``runs``."""
    ex = exported(office_project(arrays=False, panel=False))
    fine = exported(office_project(arrays=False, panel=False, fine=True)).planes[0]
    plane = ex.planes[0]
    pick = np.linspace(0, len(plane.points) - 1, 6).astype(int)
    assert np.allclose(fine.points[pick], plane.points[pick])
    with tempfile.TemporaryDirectory() as d:
        write_radiance(ex, Path(d) / "scene.rad", sky="overcast")
        each = [rtrace(Path(d), plane.points[pick], ab, ad, DAYLIGHT) for _ in range(runs)]
    got = np.mean(each, axis=0)
    res = {"coarse": errors(got, plane.lux[pick]), "fine": errors(got, fine.lux[pick])}
    res.update(
        ab=ab, ad=ad, runs=[g.round(1).tolist() for g in each],
        lightinv=plane.lux[pick].round(1).tolist(), lightinv_fine=fine.lux[pick].round(1).tolist(),
    )  # fmt: skip
    return res


OLD_PARAMS = "-aa 0 -lw 1e-5 -dj 0 -ds 0 -dt 0 -dc 1 -dr 0 -st 0 -ss 0"
"""The first version's rtrace settings (beside -ab 6 -ad 8192 for the skylight)."""


def diagnose() -> dict:
    """``--diagnose``: the skylight at 6 points with the first version's settings (two
    runs), and the panel alone with interreflections against coarse and fine LightInv."""
    out: dict = {}
    ex = exported(office_project(arrays=False, panel=False))
    plane = ex.planes[0]
    pick = np.linspace(0, len(plane.points) - 1, 6).astype(int)
    with tempfile.TemporaryDirectory() as d:
        write_radiance(ex, Path(d) / "scene.rad", sky="overcast")
        runs = [rtrace(Path(d), plane.points[pick], 6, 8192, OLD_PARAMS) for _ in range(2)]
    out["daylight_first_settings"] = {"runs": [r.round(1).tolist() for r in runs]}
    pan = exported(office_project(arrays=False, skylight=False))
    fine = exported(office_project(arrays=False, skylight=False, fine=True)).planes[0]
    plane = pan.planes[0]
    with tempfile.TemporaryDirectory() as d:
        write_radiance(pan, Path(d) / "scene.rad", sky="none")
        got = rtrace(Path(d), plane.points[pick], 10, 16384, DAYLIGHT)
    out["panel_interreflected"] = {
        "rtrace": got.round(1).tolist(), "lightinv": plane.lux[pick].round(1).tolist(),
        "lightinv_fine": fine.lux[pick].round(1).tolist(),
        "coarse": errors(got, plane.lux[pick]), "fine": errors(got, fine.lux[pick]),
    }  # fmt: skip
    return out


def panel_direct() -> dict:
    """The 3,000 lm panel's direct light (-ab 0) at 6 work-plane points against the
    closed form, with -ds 0 (the source as a point at its centre) and with PARAMS."""
    ex = exported(office_project(arrays=False, skylight=False))
    plane = ex.planes[0]
    pick = np.linspace(0, len(plane.points) - 1, 6).astype(int)
    pan = next(p for p in ex.panels if p.electric)
    want = rectangle_lux(pan.corners, pan.lumens / np.prod(pan.size), plane.points[pick])
    out: dict = {"closed_form": want.round(1).tolist()}
    with tempfile.TemporaryDirectory() as d:
        write_radiance(ex, Path(d) / "scene.rad", sky="none")
        for key, params in (("ds0", PARAMS.replace("-ds 0.02", "-ds 0")), ("params", PARAMS)):
            got = rtrace(Path(d), plane.points[pick], 0, 1, params)
            out[key] = {**errors(got, want), "rtrace": got.round(1).tolist()}
    return out


def rectangle_lux(corners: np.ndarray, exitance: float, points: np.ndarray, n: int = 80):
    """Illuminance (lux) on upward-facing ``points`` from a Lambertian rectangle of
    ``exitance`` (lm/m²) facing down: M/pi * sum cos cos / r² dA (n x n midpoints)."""
    a, b = corners[1] - corners[0], corners[3] - corners[0]
    t = (np.arange(n) + 0.5) / n
    cells = corners[0] + t[:, None, None] * a + t[None, :, None] * b
    area = np.linalg.norm(a) * np.linalg.norm(b) / n**2
    out = []
    for p in points:
        v = cells - p
        r2 = (v**2).sum(-1)
        out.append(float((exitance / np.pi * (v[..., 2] ** 2 / r2) / r2 * area).sum()))
    return np.array(out)


def daylight_direct(ad: int) -> dict:
    """The skylight's direct light alone: every surface black (-ab 2: a sample of the
    transmitter, and the transmitter's of the sky), against the closed form of a
    Lambertian rectangle of filter x transmittance x 10,000 lux."""
    ex = exported(office_project(arrays=False, panel=False))
    plane = ex.planes[0]
    pick = np.linspace(0, len(plane.points) - 1, 6).astype(int)
    sky = next(p for p in ex.panels if not p.electric)
    exitance = sky.transmittance * ex.project.design.daylight.exterior_lux
    black = re.compile(r"void plastic (\S+)\n0\n0\n5 [^\n]*")
    with tempfile.TemporaryDirectory() as d:
        folder = Path(d)
        write_radiance(ex, folder / "scene.rad", sky="overcast")
        for f in (folder / "scene.rad", folder / "scene_geometry.rad"):
            f.write_text(black.sub(r"void plastic \1\n0\n0\n5 0 0 0 0 0", f.read_text()))
        got = rtrace(folder, plane.points[pick], 2, ad, DAYLIGHT)
    want = rectangle_lux(sky.corners, exitance, plane.points[pick])
    res = errors(got, want)
    res.update(ab=2, ad=ad, rtrace=got.round(1).tolist(), closed_form=want.round(1).tolist())
    return res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ab", type=int, default=10)
    ap.add_argument("--ad", type=int, default=2048)
    ap.add_argument("--daylight-only", action="store_true", help="only the skylight part")
    ap.add_argument("--diagnose", action="store_true", help="only the diagnosis runs")
    a = ap.parse_args()
    if a.diagnose:
        print(json.dumps(diagnose(), indent=2))
        return
    out: dict = {"params": PARAMS, "daylight_overcast": daylight(a.ab, 16384)}
    out["daylight_direct_black_room"] = daylight_direct(16384)
    out["panel_direct"] = panel_direct()
    if a.daylight_only:
        print(json.dumps(out, indent=2))
        return
    out["formats"] = {}
    ex = exported()
    with tempfile.TemporaryDirectory() as d:
        for e in exporters():
            t = time.perf_counter()
            written = e.write(ex, Path(d) / f"design{e.suffixes[0]}")
            out["formats"][e.name] = {
                "seconds": time.perf_counter() - t,
                "bytes": sum(f.stat().st_size for f in written.files),
                "counts": written.counts,
            }
    night = exported(office_project(skylight=False))
    plane = night.planes[0]
    with tempfile.TemporaryDirectory() as d:
        folder = Path(d)
        t = time.perf_counter()
        caster = caster_for(night.patches)
        up = np.tile([0.0, 0.0, 1.0], (len(plane.points), 1))
        own = sum(
            f.maintenance
            * PlacedLuminaire(f.name, f.position, f.photometry, f.aim, f.c0, f.dimming).illuminance(
                plane.points, up, caster
            )
            for f in night.fixtures
        )
        panel = [p for p in night.panels if p.electric]
        lit = own > 1.0  # the array's light (the panel's direct light is not in ``own``)
        write_radiance(
            exported(office_project(skylight=False, panel=False)), folder / "scene.rad", sky="none"
        )
        direct = rtrace(folder, plane.points, 0, 1)
        out["direct_array"] = errors(direct[lit], own[lit])
        write_radiance(night, folder / "scene.rad", sky="none")
        total = rtrace(folder, plane.points, a.ab, a.ad)
        fine = exported(office_project(skylight=False, fine=True)).planes[0]
        assert np.allclose(fine.points, plane.points)
        out["night_interreflected"] = {
            "coarse": errors(total, plane.lux), "fine": errors(total, fine.lux),
            "ab": a.ab, "ad": a.ad, "panels": len(panel),
        }  # fmt: skip
        out["rtrace_seconds"] = time.perf_counter() - t
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
