"""Calculation objects against closed forms, and what their points cost.

- cylindrical Ez and semi-cylindrical Esc of an isotropic 1,000 cd point source at
  ``--positions`` random places 0.3-3 m (in plan) from its foot, against Ez = I sin(t) /
  (pi d²) and Esc = Ez (1 + cos a): the largest relative error of Ez, and of Esc
  relative to Ez (the error is the ring's, the same for both) and relative to Esc with
  the source in front (cos a >= 0);
- the ring's worst error for 16 to 64 directions, over every azimuth of the source;
- a wall rectangle facing the window of the black side-lit room (0.5 m mesh): its points'
  illuminance through the design path (zone basis, window source) against M times
  Howell C-11's point-to-parallel-rectangle factor; and the seconds the zone basis of the
  points took (a cylinder costs 32 samples per point).

    python bench/calc_objects.py --positions 500
"""

from __future__ import annotations

import argparse
import json
import math
import time
from dataclasses import replace

import numpy as np

from lightinv_core.design.model import CalcObject, Daylight, Source
from lightinv_core.light.grids import design_grids, grid_light
from lightinv_core.light.model import LightModel
from lightinv_core.luminaires.photometry import Photometry
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.builtin import builtin_scene
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.transport.luminaires import PlacedLuminaire


def corner(x: float, y: float) -> float:
    """Howell C-11 (differential): unit distance to a parallel x-by-y corner rectangle."""
    return (
        x / math.sqrt(1 + x * x) * math.atan(y / math.sqrt(1 + x * x))
        + y / math.sqrt(1 + y * y) * math.atan(x / math.sqrt(1 + y * y))
    ) / (2 * math.pi)


def rect(px, pz, x0, x1, z0, z1, c) -> float:
    def f(a, b):
        return math.copysign(1, a) * math.copysign(1, b) * corner(abs(a) / c, abs(b) / c)

    return f(x1 - px, z1 - pz) - f(x0 - px, z1 - pz) - f(x1 - px, z0 - pz) + f(x0 - px, z0 - pz)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--positions", type=int, default=500)
    args = ap.parse_args()
    scene = builtin_scene("sidelit", 0.5)
    black = Scene(
        scene.name,
        tuple(replace(s, reflectance=0.0) for s in scene.surfaces),
        scene.zones,
        scene.resolution,
    )
    patches = mesh_patches(black)
    out: dict = {"positions": args.positions}
    g = np.linspace(0.0, 180.0, 37)
    iso = Photometry("C", np.array([0.0]), g, np.full((1, len(g)), 1000.0))
    src = np.array([3.0, 4.0, 2.6])
    lum = PlacedLuminaire("iso", src, iso)
    rng = np.random.default_rng(0)
    r = rng.uniform(0.3, 3.0, args.positions)
    az = rng.uniform(0, 2 * math.pi, args.positions)
    xy = src[:2] + np.column_stack([r * np.cos(az), r * np.sin(az)])
    for kind in ("cylindrical", "semi_cylindrical"):
        o = CalcObject("c", kind, height=1.2, positions=tuple(map(tuple, xy)))
        ps = o.spec.readings(o, patches, None)
        got = ps.values(lum.illuminance(ps.points, ps.normals, None))
        d = np.linalg.norm(ps.at - src, axis=1)
        ez = 1000.0 * r / d / (math.pi * d**2)
        if kind == "cylindrical":
            out["ez_max_rel_error"] = float(np.abs(got / ez - 1).max())
        else:
            a = np.arctan2(*(src - ps.at)[:, 1::-1].T)
            esc = ez * (1 + np.cos(a))
            front = np.cos(a) >= 0
            out["esc_max_error_of_ez"] = float((np.abs(got - esc) / ez).max())
            out["esc_front_max_rel_error"] = float(np.abs(got[front] / esc[front] - 1).max())
    ring = {}
    for n in (16, 24, 32, 48, 64):
        phi0 = np.linspace(0, 2 * math.pi / n, 401)
        k = np.arange(n) * 2 * math.pi / n
        mean = np.maximum(0, np.cos(k[None] - phi0[:, None])).mean(axis=1) * math.pi
        ring[n] = float(np.abs(mean - 1).max())
    out["ring_worst_error"] = ring
    light = LightModel(black, patches, build_operator(patches, OperatorSettings(rays=64)))
    wall = CalcObject("north", "surface", origin=(1.0, 8.0, 0.5), u=(4.0, 0, 0), v=(0, 0, 2.0))
    cyl = CalcObject("cyl", "cylindrical", positions=tuple(map(tuple, xy[:20])), height=1.2)
    t0 = time.process_time()
    grids = design_grids(light, (), (wall, cyl))
    out["zone_basis_cpu_seconds"] = time.process_time() - t0
    out["samples"] = len(grids.samples.points)
    window = Source("w", "window", "window", (0, 0, *light.zone_size("window")), filter=1.0)
    day = Daylight()
    lux = grid_light(light, grids, (window,), (), day)
    m = day.transmittance * day.exterior_lux
    span = grids.calc_spans["north"]
    expect = np.array([m * rect(x, z, 0.6, 5.4, 0.9, 2.5, y) for x, y, z in grids.points[span]])
    out["wall_points"] = len(expect)
    out["wall_max_rel_error"] = float(np.abs(lux[span] / expect - 1).max())
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
