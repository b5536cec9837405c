"""Benchmark: clear glazing whose shape the optimiser moves (issue #30). Prints JSON.

    python bench/clear_shapes.py [--batch 32] [--repeats 10] [--rounds 5] [--evals 150]
    python bench/clear_shapes.py --flagship     # one flagship window free: build, memory

On a room 8 x 8 x 3 m (0.5 m patches) with a 3 x 3 m clear rooflight zone (36 cells)
whose rooflight is centred and free in size, a luminaire strip, glass 0.7, Greensboro
TMY3, weekdays 8-18, goal least annual energy (dimming to 300 lux), intentions
sDA300/50% >= 50% and ASE1000,250 <= 10% (LEED v4):

- ``build``: CPU seconds of the per-cell trace (``light.clear_cells``) against a fixed
  build of the whole zone, the cells' memory (their columns and sparse direct sun) and
  the hourly blocks the batches keep;
- ``cost``: CPU per candidate of the annual evaluation (batches of ``--batch`` random
  sizes, rounds measured in turn) against a single-scenario evaluation of the same
  design (its intentions replaced by one on the work plane's overcast lux), and
  against the same annual design with the rooflight fixed clear;
- ``validation``: per rectangle, the cells' sum against a fresh fixed build traced at
  that rectangle (``layout_daylight`` of a fixed design): the per-point annual mean
  (mean and largest relative difference) and DA300, sDA300/50%, ASE1000,250 both ways;
- ``hour_reduction``: the experiment of replacing the occupied hours by K representative
  hours for the search (k-means on the log of every cell's hourly light at the points,
  each cluster's hour nearest its centre weighted by its size), over ``--rectangles``
  random rectangles: the largest error of DA, UDI, sDA, ASE (points) and of the dimming
  sum (%) against every hour (docs/daylight.md: not adopted);
- ``optimisation``: CMA-ES (``--evals``) from the whole rooflight: the chosen size, its
  figures as the optimiser judged them, and the forward study (``study.simulate``) of a
  room whose rooflight is the chosen one.

The CPU figures are measured with BLAS on one thread (``threadpool_limits``): on the
shared 2-core machine a second BLAS thread spins and doubles the CPU counted.

``--flagship`` instead frees one clear window of the flagship office
(resources/projects/office-flagship.json, its own resolution) and reports the build's
CPU, the cells and their memory (its patch rows: those its intentions read), and the CPU
of one batch against the same batch with every window fixed (the first batch of each
also computes the luminaire arrays' responses, not counted here).
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

from lightinv_core.design.model import Daylight, Design, Goal, Intention, Rule, Source, Workplane
from lightinv_core.light.clear_build import clear_light
from lightinv_core.light.daylight import layout_daylight
from lightinv_core.light.model import LightModel
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.method import RunContext
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.registry import get_method
from lightinv_core.optimize.termination import StopRule
from lightinv_core.quantities import quantity_spec
from lightinv_core.scene.builders import Insert, room_faces, split_rect
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import mesh_patches

TAU = 0.7
ZONE = (2.5, 2.5, 5.5, 5.5)
ROOT = Path(__file__).resolve().parent.parent


def roof_room(rooflight=ZONE, resolution: float = 0.5) -> Scene:
    """8 x 8 x 3 m, a rooflight zone (ceiling u, v) and a luminaire strip."""
    faces = room_faces(0, 0, 0, 8, 8, 3)
    ceiling = [
        Insert("roof", *rooflight, group="roof", zone_kind="skylight"),
        Insert("lum", 0.5, 0.5, 7.5, 1.5, group="lum", zone_kind="luminaire"),
    ]
    parts = {"floor": ("floor", 0.3, []), "ceiling": ("ceiling", 0.8, ceiling)}
    parts |= {k: ("walls", 0.6, []) for k in ("south", "north", "west", "east")}
    surfaces, zones = [], []
    for key, (group, rho, inserts) in parts.items():
        s, z = split_rect(key, group, rho, faces[key], inserts)
        surfaces += s
        zones += z
    return Scene("roomlit", tuple(surfaces), tuple(zones), resolution, "bench room")


def model(scene: Scene) -> LightModel:
    patches = mesh_patches(scene)
    return LightModel(scene, patches, build_operator(patches, OperatorSettings(rays=512, seed=0)))


def design(light: LightModel, free=("u0", "v0")) -> Design:
    w, h = light.zone_size("roof")
    s1 = Source("S1", "roof", "skylight", (0.0, 0.0, w, h), glazing="clear", free=free)
    lum = Source("L1", "lum", "luminaire", (0, 0, *light.zone_size("lum")), flux=6000.0)
    return Design(
        sources=(s1, lum),
        rules=(Rule("centred", ("S1",)),) if free == ("u0", "v0") else (),
        goals=(Goal("min_annual_energy"),),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        daylight=Daylight(transmittance=TAU, target_lux=300.0),
        intentions=(
            Intention("sDA", grid="wp", quantity="sda", average=0.5),
            Intention("ASE", grid="wp", quantity="ase", max_average=0.1),
        ),
    )


def per_candidate(problem: DesignProblem, batches, repeats: int) -> float:
    """CPU seconds per candidate over the batches."""
    t0 = time.process_time()
    for _ in range(repeats):
        for X in batches:
            problem.evaluate(X)
    return (time.process_time() - t0) / (repeats * sum(len(X) for X in batches))


def grid_figures(parts, idx) -> dict:
    out = {
        q: round(100 * float(parts.band(quantity_spec(q).hours, idx)[:, 0].mean()), 2)
        for q in ("da", "sda", "ase")
    }
    return out


def cost(light, args) -> dict:
    with threadpool_limits(limits=1, user_api="blas"):
        return _cost(light, args)


def _cost(light, args) -> dict:
    d = design(light)
    clear = DesignProblem(d, light)
    over = replace(
        d,
        goals=(Goal("min_glazing_area"),),
        intentions=(Intention("o", grid="wp", quantity="lux", average=100.0, scenario="overcast"),),
    )
    overcast = DesignProblem(over, light)
    fixed = DesignProblem(design(light, free=()), light)
    rng = np.random.default_rng(0)
    hi = clear.vars.hi
    batches = [rng.uniform(0, hi, (args.batch, len(hi))) for _ in range(4)]
    for p in (clear, overcast):
        p.evaluate(batches[0])  # the first batch makes the hourly blocks
    fixed.evaluate(np.zeros((args.batch, 0)))
    rounds = []
    for _ in range(args.rounds):
        a = per_candidate(clear, batches, args.repeats)
        b = per_candidate(overcast, batches, args.repeats)
        c = per_candidate(fixed, [np.zeros((args.batch, 0))] * 4, args.repeats)
        rounds.append((a, b, c))
    r = np.array(rounds)
    return {
        "batch": args.batch,
        "ms_per_candidate_annual_moving": round(1e3 * float(np.median(r[:, 0])), 3),
        "ms_per_candidate_overcast_moving": round(1e3 * float(np.median(r[:, 1])), 4),
        "ms_per_candidate_annual_fixed_clear": round(1e3 * float(np.median(r[:, 2])), 4),
        "ratio_annual_over_overcast": round(float(np.median(r[:, 0] / r[:, 1])), 1),
        "ratio_annual_moving_over_fixed": round(float(np.median(r[:, 0] / r[:, 2])), 1),
        "kept_hourly_blocks_mb": round(
            sum(
                (b.data.nbytes + b.indices.nbytes + b.indptr.nbytes)
                if hasattr(b, "indptr")
                else b.nbytes
                for b in clear.clear_cells.kept.values()
            )
            / 1e6,
            1,
        ),
    }


def build(light) -> dict:
    d = design(light)
    t0 = time.process_time()
    p = DesignProblem(d, light)
    cells = p.clear_cells
    t1 = time.process_time()
    clear_light(light, design(light, free=()))
    t2 = time.process_time()
    return {
        "patches": light.n,
        "cells": cells.count,
        "points": cells.points,
        "columns_per_cell": int(cells.coef.shape[2]),
        "cells_cpu_s": round(cells.seconds, 2),
        "problem_cpu_s": round(t1 - t0, 2),
        "fixed_whole_zone_cpu_s": round(t2 - t1, 2),
        "cells_mb": round(cells.nbytes / 1e6, 1),
        "direct_nonzero_share": round(
            float(sum(x.nnz for x in cells.direct) / (cells.count * cells.points * 8760)), 4
        ),
    }


def validation(light) -> list:
    w, h = light.zone_size("roof")
    p = DesignProblem(design(light, free=("u0", "v0", "u1", "v1")), light)
    level = p.level(1)
    idx = slice(len(level.rows), None)
    rows = []
    for rect in [
        (0, 0, w, h),
        (0, 0, w, h / 2),
        (0.5, 0.5, 2.5, 2.5),
        (0.3, 0.7, 2.2, 2.6),
        (1.0, 0.25, 2.0, 2.75),
    ]:
        lit = p.lighting.of(*p.vars.decode(np.atleast_2d(rect)), level, None)
        fx = layout_daylight(
            light,
            replace(
                design(light, free=()),
                sources=(
                    replace(design(light).sources[0], rect=tuple(rect), free=()),
                    design(light).sources[1],
                ),
            ),
        )
        span = fx.grids.span("wp")
        a = lit.parts.clear_hours(idx)[:, 0].mean(axis=1)
        b = fx.points.clear_hours(span).mean(axis=1)
        rel = np.abs(a / b - 1)
        rows.append(
            {
                "rect": [round(float(x), 3) for x in rect],
                "mean_lux_cells_fixed": [round(float(a.mean()), 1), round(float(b.mean()), 1)],
                "per_point_rel_mean_pct": round(100 * float(rel.mean()), 2),
                "per_point_rel_max_pct": round(100 * float(rel.max()), 2),
                "cells": grid_figures(lit.parts, idx),
                "fixed": grid_figures(fx.points, span),
            }
        )
    return rows


def optimisation(light, args) -> dict:
    from lightinv_core.study import SimulationSpec, simulate
    from lightinv_core.study.clear_metrics import work_plane_metrics
    from lightinv_core.transport.workplane import WorkPlane

    d = design(light)
    p = DesignProblem(d, light)
    ctx = RunContext(stop=StopRule(max_evals=args.evals, stall=None), seed=1, x0=np.zeros(2))
    t0 = time.process_time()
    best = get_method("cmaes").run(p, ctx).best
    cpu = time.process_time() - t0
    x = np.asarray(best.x)
    ev = p.evaluate(x[None])
    level = p.level(1)
    lit = p.lighting.of(*p.vars.decode(x[None]), level, None)
    idx = slice(len(level.rows), None)
    got = grid_figures(lit.parts, idx)
    u0, v0, u1, v1 = p.sources_at(x)[0].rect
    scene = roof_room((ZONE[0] + u0, ZONE[1] + v0, ZONE[0] + u1, ZONE[1] + v1))
    spec = SimulationSpec(
        scene=scene,
        glazing={"roof": TAU},
        glazing_kinds={"roof": "clear"},
        workplane=WorkPlane(0.8, 0.5),
        rays=512,
        annual=Daylight(transmittance=TAU),
    )
    t1 = time.process_time()
    want, _ = work_plane_metrics(simulate(spec).clear_year)
    return {
        "evaluations": args.evals,
        "cpu_s": round(cpu, 1),
        "feasible": bool(ev.feasible[0]),
        "rect": [round(float(c), 3) for c in (u0, v0, u1, v1)],
        "area_m2": round(float((u1 - u0) * (v1 - v0)), 3),
        "energy_kwh": round(float(ev.goals["min_annual_energy"][0]), 2),
        "optimiser": got,
        "study": {
            "sda": round(100 * want["sda300_50"], 2),
            "ase": round(100 * want["ase1000_250"], 2),
            "da": round(100 * want["da300_mean"], 2),
        },
        "study_cpu_s": round(time.process_time() - t1, 1),
        "whole_rooflight": grid_figures(*_whole(p)),
    }


def _kmeans(X: np.ndarray, k: int, seed: int = 1, iters: int = 25):
    """(representative rows, cluster sizes): k-means++ then Lloyd; each cluster's
    representative is its member nearest the centre (a real hour)."""
    rng = np.random.default_rng(seed)
    pick = [int(rng.integers(len(X)))]
    d2 = ((X - X[pick[0]]) ** 2).sum(1)
    for _ in range(k - 1):
        pick.append(int(rng.choice(len(X), p=d2 / d2.sum())))
        d2 = np.minimum(d2, ((X - X[pick[-1]]) ** 2).sum(1))
    centre = X[pick].copy()
    for _ in range(iters + 1):
        lab = (-2 * X @ centre.T + (centre**2).sum(1)).argmin(1)
        for j in range(k):
            if (lab == j).any():
                centre[j] = X[lab == j].mean(0)
    reps, size = [], []
    for j in range(k):
        on = np.flatnonzero(lab == j)
        if len(on):
            reps.append(on[((X[on] - centre[j]) ** 2).sum(1).argmin()])
            size.append(len(on))
    return np.array(reps), np.array(size, float)


def _year_figures(L, S, w, full) -> dict:
    """DA, UDI, sDA, ASE (grid means, m,) and the dimming sum of m candidates' light
    ``L`` (with blinds) and direct sun ``S`` (m, R, T) over hours weighted ``w``."""
    from lightinv_core.climate.metrics import dimming_level

    da = ((L >= 300) * w).sum(-1) / w.sum()
    return {
        "da": da.mean(1),
        "udi": (((L >= 100) & (L <= 3000)) * w).sum(-1).mean(1) / w.sum(),
        "sda": (da >= 0.5).mean(1),
        "ase": (((S > 1000) * w).sum(-1) > 250).mean(1),
        "dimming": (dimming_level(L.mean(1).astype(float), full[:, None], 300.0, 0.0) * w).sum(-1),
    }


def hour_reduction(light, args) -> dict:
    """K representative hours for the search against every occupied hour (see the
    module): each candidate's own blinds and sun at the representative hours."""
    from lightinv_core.light.clear_batch import cell_hours

    p = DesignProblem(design(light, free=("u0", "v0", "u1", "v1")), light)
    level = p.level(1)
    X = np.random.default_rng(2).uniform(0, p.vars.hi, (args.rectangles, 4))
    parts = p.lighting.of(*p.vars.decode(X), level, None).parts
    cb, idx = parts.clear, slice(len(level.rows), None)
    occ = cb.occupied
    L, S = cb._light(idx, occ, True), cb._light(idx, occ, False, True)
    full = parts.electric[idx].mean(axis=0)
    T = L.shape[2]
    exact = _year_figures(L, S, np.ones(T), full)
    blocks = cell_hours(p.clear_cells, cb.year_pos[idx], occ, False)  # (C, R, T)
    F = np.log1p(blocks.reshape(-1, T).T.astype(float))
    U, sv, _ = np.linalg.svd(F - F.mean(0), full_matrices=False)
    out = {"rectangles": args.rectangles, "hours": T, "by_k": []}
    for k in (100, 200, 400, 800):
        t0 = time.process_time()
        reps, size = _kmeans(U[:, :48] * sv[:48], k)
        cpu = time.process_time() - t0
        got = _year_figures(L[:, :, reps], S[:, :, reps], size, full)
        row = {"k": k, "clustering_cpu_s": round(cpu, 2), "hours_share": round(k / T, 3)}
        for q in ("da", "udi", "sda", "ase"):
            row[f"{q}_max_error_points"] = round(100 * float(np.abs(got[q] - exact[q]).max()), 2)
        rel = np.abs(got["dimming"] / np.maximum(exact["dimming"], 1e-9) - 1)
        row["dimming_max_error_pct"] = round(100 * float(rel.max()), 2)
        row["dimming_mean_error_pct"] = round(100 * float(rel.mean()), 2)
        out["by_k"].append(row)
    return out


def _whole(p):
    level = p.level(1)
    lit = p.lighting.of(*p.vars.decode(np.zeros((1, 2))), level, None)
    return lit.parts, slice(len(level.rows), None)


def flagship(args) -> dict:
    from lightinv_core.project import load_project
    from lightinv_core.study import prepare

    project = load_project(ROOT / "resources" / "projects" / "office-flagship.json")
    t0 = time.process_time()
    prep = prepare(project)
    t1 = time.process_time()
    d = project.design
    w1 = next(j for j, s in enumerate(d.sources) if getattr(s, "glazing", None) == "clear")
    first = d.sources[w1]
    sources = tuple(
        replace(s, free=("u0", "v0", "u1", "v1")) if s is first else s for s in d.sources
    )
    d = replace(d, sources=sources)
    p = DesignProblem(d, prep.light)
    t2 = time.process_time()
    cells = p.clear_cells
    rng = np.random.default_rng(0)
    X = np.clip(
        p.vars.initial() + rng.normal(0, 0.05, (args.batch, p.vars.n)), p.vars.lo, p.vars.hi
    )
    p.evaluate(X)
    t3 = time.process_time()
    p.evaluate(X)
    t4 = time.process_time()
    q = DesignProblem(project.design, prep.light)  # every window fixed, as shipped
    keep = [k for k, v in enumerate(p.vars.vars) if v.owner != "source" or v.source != w1]
    q.evaluate(X[:, keep])
    t5 = time.process_time()
    q.evaluate(X[:, keep])
    t6 = time.process_time()
    return {
        "patches": prep.light.n,
        "clear_sources": cells.sources,
        "cells": cells.count,
        "points": cells.points,
        "operator_cpu_s": round(t1 - t0, 1),
        "problem_cpu_s": round(t2 - t1, 1),
        "cells_cpu_s": round(cells.seconds, 1),
        "cells_mb": round(cells.nbytes / 1e6, 1),
        "first_batch_cpu_s": round(t3 - t2, 2),
        "batch_cpu_s": round(t4 - t3, 3),
        "fixed_batch_cpu_s": round(t6 - t5, 3),
        "cell_rows": len(cells.rows),
        "cell_year_rows": len(cells.year_rows),
        "batch": args.batch,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--evals", type=int, default=150)
    ap.add_argument("--rectangles", type=int, default=200)
    ap.add_argument("--flagship", action="store_true")
    args = ap.parse_args()
    if args.flagship:
        with threadpool_limits(limits=1, user_api="blas"):
            print(json.dumps({"flagship": flagship(args)}, indent=1))
        return
    light = model(roof_room())
    out = {"build": build(light)}
    out["cost"] = cost(light, args)
    out["hour_reduction"] = hour_reduction(light, args)
    out["validation"] = validation(light)
    out["optimisation"] = optimisation(light, args)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
