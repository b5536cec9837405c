"""Benchmark: annual daylight through clear glazing, LightInv beside Radiance. Prints JSON.

    python bench/peers.py [--weather tests/data/weather/chicago.epw.gz] [--resolution 0.5]

On the two daylight rooms (the built-in ``sidelit``: a 4.8 x 1.6 m clear south window
in a 6 x 8 x 3 m room; ``toplit``: a 2 x 2 m clear rooflight in an 8 x 8 x 4 m room)
and the office (``office``: 12 x 8 x 3 m with eight desks and a 4 x 2 m rooflight), glass
of visible transmittance 0.7, the same work-plane points (0.8 m, the EN 12464-1
grid with a 0.5 m border) and the same weather year are computed by

- **LightInv**: ``lightinv-cli simulate``'s year through clear glazing
  (``study.clear_year``: Tregenza daylight coefficients with the Perez all-weather sky,
  the sun traced hour by hour, its reflections by sun-position bins);
- **Radiance**: the two-phase daylight-coefficient method (``rfluxmtx`` with a Reinhart
  MF:4 sky, ``gendaymtx``, ``dctimestep``) for the total; for ASE the five-phase
  method's sun step (solar discs of 0.533 degrees at the Reinhart MF:6 patch centres
  through the black room, ``rcontrib -ab 0``, ``gendaymtx -5 0.533 -d``), and, for
  comparison, the two-phase sun alone (spread over its MF:4 patch of about 3 degrees)
  (the harness in ``tests/radiance``).

Also one moment, point by point (``tests.radiance.compare``): the work planes of the
two daylight rooms under the sun alone, the CIE clear sky alone and both with the
ground, against ``rtrace -ab 10`` with 16,384 hemisphere samples: the mean and largest
relative error per point.

Both hourly results go through the same metric code (``climate.metrics``,
``climate.sun_metrics``) over the same occupied hours (weekdays 8-18), blinds open:
DA300, UDI bands, sDA300/50% and ASE1000,250. Printed: both metric sets, their
differences in percentage points, the mean point error of the annual illuminance, and
each side's CPU seconds (process plus children) with their ratio.
"""

from __future__ import annotations

import argparse
import gzip
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from lightinv_core.climate.metrics import daylight_metrics  # noqa: E402
from lightinv_core.climate.sun_metrics import ase  # noqa: E402
from lightinv_core.design.model import Daylight  # noqa: E402
from lightinv_core.scene.builtin import builtin_scene  # noqa: E402
from lightinv_core.study import SimulationSpec, simulate  # noqa: E402
from lightinv_core.transport.workplane import WorkPlane  # noqa: E402

ROOMS = {"sidelit": "window", "toplit": "rooflight", "office": "roof"}
TAU = 0.7


def cpu() -> float:
    """CPU seconds of this process and its finished children."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def metrics(lux: np.ndarray, sun: np.ndarray, occupied: np.ndarray) -> dict:
    """The compared metrics of hourly lux and direct-sun lux (q, 8760)."""
    m = daylight_metrics(lux[:, occupied])
    s = m.summary()
    a = ase(sun[:, occupied])
    return {
        "da300_mean": s["da300_mean"],
        "sda300_50": s["sda300_50"],
        "udi_n": s["udi_n"],
        "udi_100_3000": s["udi_100_3000"],
        "udi_x": s["udi_x"],
        "ase1000_250": float(a.share),
    }


def lightinv(room: str, group: str, weather: Path, resolution: float):
    """LightInv's year: (points, normals, hourly lux, direct sun lux, occupied, cpu s)."""
    t0 = cpu()
    spec = SimulationSpec(
        builtin_scene(room, resolution),
        glazing={group: TAU},
        glazing_kinds={group: "clear"},
        workplane=WorkPlane(0.8, 0.5),
        annual=Daylight(weather=str(weather)),
        rays=1024,
    )
    res = simulate(spec)
    year = res.clear_year
    lux = year.total()
    sun = year.direct_sun.sum(axis=0)
    return res.grid, res.patches, lux, sun, year.occupied, cpu() - t0


def radiance(patches, group: str, grid, weather: Path):
    """Radiance's year at the same points: (hourly lux, direct sun lux by solar discs,
    direct sun lux by the two-phase patches, cpu s of the first two)."""
    from tests.radiance.run import annual_lux, annual_sun_discs

    t0 = cpu()
    lux = annual_lux(patches, {group: TAU}, grid.points, grid.normals, weather)
    discs = annual_sun_discs(patches, {group: TAU}, grid.points, grid.normals, weather)
    spent = cpu() - t0
    spread = annual_lux(
        patches, {group: TAU}, grid.points, grid.normals, weather, direct_sun_only=True
    )
    return lux, discs, spread, spent


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--weather", default=str(ROOT / "tests/data/weather/chicago.epw.gz"))
    ap.add_argument("--resolution", type=float, default=0.5)
    args = ap.parse_args()
    out = {"weather": Path(args.weather).name, "transmittance": TAU, "rooms": {}, "moment": {}}
    from tests.radiance.compare import CASES, compare

    for room in ("sidelit", "toplit"):
        for case in CASES:
            got = compare(room, case)
            out["moment"][f"{room}/{case}"] = {
                "points": len(got["error"]),
                "mean_rel_error": float(got["error"].mean()),
                "max_rel_error": float(got["error"].max()),
                "sunlit_points_agree": bool((got["sunlit_ours"] == got["sunlit_theirs"]).all()),
            }
    with tempfile.TemporaryDirectory() as tmp:
        weather = Path(args.weather)
        if weather.suffix == ".gz":
            plain = Path(tmp) / weather.stem
            with gzip.open(weather, "rb") as src, open(plain, "wb") as dst:
                shutil.copyfileobj(src, dst)
            weather = plain
        for room, group in ROOMS.items():
            t = time.perf_counter()
            grid, patches, lux, sun, occ, cpu_li = lightinv(room, group, weather, args.resolution)
            r_lux, r_sun, r_spread, cpu_rad = radiance(patches, group, grid, weather)
            ours, theirs = metrics(lux, sun, occ), metrics(r_lux, r_sun, occ)
            spread_ase = float(ase(r_spread[:, occ]).share)
            lit = occ & (r_sun.max(axis=0) > 0)
            day = occ & (r_lux.mean(axis=0) > 50)
            rel = np.abs(lux[:, day].sum(axis=1) / np.maximum(r_lux[:, day].sum(axis=1), 1e-9) - 1)
            out["rooms"][room] = {
                "points": len(grid.points),
                "patches": patches.n,
                "lightinv": ours,
                "radiance": theirs,
                "difference_points": {k: 100 * (ours[k] - theirs[k]) for k in ours},
                "annual_lux_mean_rel_error": float(rel.mean()),
                "radiance_ase_two_phase_sun": spread_ase,
                "direct_sun_sum_ratio": float(sun[:, lit].sum() / r_sun[:, lit].sum()),
                "lightinv_cpu_s": cpu_li,
                "radiance_cpu_s": cpu_rad,
                "cpu_ratio_radiance_over_lightinv": cpu_rad / cpu_li,
                "wall_s": time.perf_counter() - t,
            }
    out["cores"] = os.cpu_count()
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
