"""Benchmark: Radiance's annual daylight metrics on the two bench rooms. Prints JSON.

    python bench/radiance_annual.py [--spacing 0.5] [--mf 4] [--ad 32768] [--procs 1]

The rooms (tests/radiance/rooms.py): a 4 x 6 x 3 m office with a 3 x 1.5 m clear
window (tau 0.7) in its south wall, and the same room with a 1.5 x 1.5 m clear
rooflight (tau 0.7) in the middle of its ceiling; walls 0.5, ceiling 0.7, floor 0.2,
north up (north_deg 0), the Chicago TMY3 year (tests/data/weather/chicago.epw.gz).
The work plane is a grid of ``spacing`` m cells at 0.75 m.

Each room's year comes from Radiance's two-phase daylight-coefficient method
(``annual_lux``: rfluxmtx to a Reinhart sky of subdivision ``mf``, gendaymtx, the
matrix product) and, for ASE, the sun alone through the black room
(``direct_sun_only``). The metrics, per point with plain numpy over the occupied hours
(8:00 to 18:00 local standard time every day, the hours whose EPW interval starts at
8 to 17, 3,650 hours):

- DA300: the fraction of occupied hours with at least 300 lux (mean over the points),
  sDA300/50%: the fraction of points whose DA300 is at least 50% (blinds always open);
- UDI: the fractions of occupied hours below 100 lux (udi_n), from 100 to 3,000
  (udi_100_3000), above 3,000 (udi_x), means over the points;
- ASE1000,250: the fraction of points with more than 250 occupied hours of direct sun
  of at least 1,000 lux, and the mean such hours.

CPU time: this process's (``time.process_time``) plus its children's (the Radiance
tools, ``os.times``), and the wall time.
"""

from __future__ import annotations

import argparse
import gzip
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # run as a script from anywhere: tests/ is not installed

from tests.radiance import annual_lux, rooflight_room, window_office, work_plane  # noqa: E402

EPW = ROOT / "tests" / "data" / "weather" / "chicago.epw.gz"
TAU = 0.7
OCCUPIED = (8, 18)
"""Occupied hours: EPW intervals starting from 8:00 up to 17:00 (ending by 18:00)."""


def occupied_hours(n: int = 8760) -> np.ndarray:
    """Boolean (n,) of the occupied hours (interval start hour in [8, 18))."""
    start = np.arange(n) % 24
    return (start >= OCCUPIED[0]) & (start < OCCUPIED[1])


def metrics(year: np.ndarray, sun: np.ndarray, occupied: np.ndarray) -> dict:
    """The daylight metrics of a (q, hours) year and its direct-sun-only year (lux)."""
    e, s = year[:, occupied], sun[:, occupied]
    da = (e >= 300).mean(axis=1)
    ase_hours = (s >= 1000).sum(axis=1)
    return {
        "da300_mean": round(float(da.mean()), 4),
        "sda300_50": round(float((da >= 0.5).mean()), 4),
        "udi_n": round(float((e < 100).mean()), 4),
        "udi_100_3000": round(float(((e >= 100) & (e <= 3000)).mean()), 4),
        "udi_x": round(float((e > 3000).mean()), 4),
        "ase1000_250": round(float((ase_hours > 250).mean()), 4),
        "ase_hours_mean": round(float(ase_hours.mean()), 1),
        "mean_lux": round(float(e.mean()), 1),
    }


def cpu_seconds() -> float:
    """This process's CPU time plus its finished children's (user + system)."""
    t = os.times()
    return time.process_time() + t.children_user + t.children_system


def run(spacing: float, mf: int, ad: int, procs: int) -> dict:
    rooms = {
        "window_office": (window_office(), "window"),
        "rooflight": (rooflight_room(), "rooflight"),
    }
    points, normals = work_plane((4.0, 6.0), spacing=spacing)
    occ = occupied_hours()
    lw = min(2e-6, 0.05 / ad)  # below 1 / ad: the deeper bounces are not cut
    params = f"-ad {ad} -lw {lw:g} -lr -12"
    out: dict = {
        "weather": EPW.name,
        "points": len(points),
        "occupied_hours": int(occ.sum()),
        "settings": {"mf": mf, "ab": 6, "ad": ad, "lw": lw, "tau": TAU},
        "cores": os.cpu_count(),
        "rooms": {},
    }
    with tempfile.TemporaryDirectory(prefix="lightinv-bench-") as d:
        epw = Path(d) / "chicago.epw"
        with gzip.open(EPW, "rb") as src:
            epw.write_bytes(src.read())
        for name, (patches, group) in rooms.items():
            cpu0, wall0 = cpu_seconds(), time.perf_counter()
            year = annual_lux(patches, {group: TAU}, points, normals, epw, mf=mf, params=params,
                              procs=procs)  # fmt: skip
            sun = annual_lux(patches, {group: TAU}, points, normals, epw, mf=mf, params=params,
                             procs=procs, direct_sun_only=True)  # fmt: skip
            room = metrics(year, sun, occ)
            room["cpu_s"] = round(cpu_seconds() - cpu0, 2)
            room["wall_s"] = round(time.perf_counter() - wall0, 2)
            out["rooms"][name] = room
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, default=0.5, help="work-plane grid, m")
    ap.add_argument("--mf", type=int, default=4, help="Reinhart sky subdivision")
    ap.add_argument("--ad", type=int, default=32768, help="rfluxmtx ambient divisions")
    ap.add_argument("--procs", type=int, default=1, help="rfluxmtx processes")
    a = ap.parse_args()
    print(json.dumps(run(a.spacing, a.mf, a.ad, a.procs), indent=2))


if __name__ == "__main__":
    main()
