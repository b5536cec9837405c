"""Benchmark: what the window computes for View > Colour by's glare maps at the observers
and for a sensor region dragged in the view (docs/daylight.md "DGP in the view; dragging
sensors"), on the window's own thread. Prints JSON.

    python bench/dgp_view.py [--resolution 1.0] [--out bench/results-dgp-view.json]

On the flagship office (its four observers, five clear windows, Greensboro TMY3; meshed
at ``--resolution``, operator rank 120, as the GUI tests open it) and on the side-lit
room with its clear window and two observers (1 m patches):

- ``dgp_first``: the editing model's ``observer_dgp`` once the clear glazing's light is
  built (the map chosen): wall and CPU seconds; ``dgp_again``: the same design (a
  recolour, memoised); ``dgp_after_move``: after an observer moved 0.1 m (what each
  mouse move of an observer's drag costs while the map is shown);
- ``sensor_drop`` (flagship): the window row's sensor set by ``update_control_group``
  (a drag's release) and the design's light in every scenario made again
  (``layout_daylight``, which the energy box and the Achieved tab read), wall and CPU.
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import replace
from pathlib import Path

from lightinv_core.design.model import Daylight, Design, Goal, Observer, Source, Workplane
from lightinv_core.editing import DocumentModel, blank_project
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.project import load_project

ROOT = Path(__file__).resolve().parent.parent
FLAGSHIP = ROOT / "resources" / "projects" / "office-flagship.json"


def timed(fn) -> tuple[object, dict]:
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return out, {
        "wall_s": round(time.perf_counter() - t0, 3),
        "cpu_s": round(time.process_time() - c0, 3),
    }


def flagship(resolution: float) -> DocumentModel:
    p = load_project(FLAGSHIP)
    p = replace(
        p,
        scene=replace(p.scene, resolution=resolution),
        operator=OperatorSettings(rank=120, rays=128),
    )
    doc = DocumentModel()
    doc.set_project(p)
    doc.set_operator(build_operator(doc.patches, p.operator))
    return doc


def sidelit() -> DocumentModel:
    doc = DocumentModel()
    doc.set_project(blank_project("sidelit", 1.0))
    size = doc.zone_size("window")
    design = Design(
        sources=(Source("W1", "window", "window", (0.0, 0.0, *size), glazing="clear"),),
        goals=(Goal("min_electric_power"),),
        workplanes=(Workplane("wp", 0.8, 0.5),),
        daylight=Daylight(transmittance=0.7),
        observers=(
            Observer("near", (3.0, 1.5), azimuth=-90.0),
            Observer("back", (3.0, 7.0), azimuth=-90.0),
        ),
    )
    doc.project = replace(doc.project, design=design)
    doc.set_operator(build_operator(doc.patches, OperatorSettings(rank=60, rays=128, seed=0)))
    return doc


def dgp_costs(doc: DocumentModel) -> dict:
    out = {"observers": len(doc.design.observers), "patches": int(doc.patches.n)}
    doc.layout_daylight()  # the clear glazing's light built first, as the window's worker does
    (figures, _), out["dgp_first"] = timed(doc.observer_dgp)
    _, out["dgp_again"] = timed(doc.observer_dgp)
    doc.move_observer(doc.design.observers[0].name, 0.1, 0.0)
    _, out["dgp_after_move"] = timed(doc.observer_dgp)
    out["figures"] = {
        n: {k: g[k] for k in ("exceedance", "en17037_glare", "dgp_max", "ev_max_lux")}
        for n, g in figures.items()
    }
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--resolution", type=float, default=1.0)
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    result = {"sidelit": dgp_costs(sidelit())}
    doc = flagship(args.resolution)
    result["flagship"] = dgp_costs(doc)
    kwh = {g.name: g.energy_kwh for g in doc.layout_daylight().energy().groups}
    result["flagship"]["window_row_kwh_before_drop"] = round(kwh["window row"], 1)
    doc.update_control_group("window row", sensor=(3.0, 1.0, 15.0, 3.0))
    ld, result["flagship"]["sensor_drop"] = timed(doc.layout_daylight)
    row = next(g for g in ld.energy().groups if g.name == "window row")
    result["flagship"]["window_row_kwh_after_drop"] = round(row.energy_kwh, 1)
    text = json.dumps(result, indent=1)
    print(text)
    if args.out is not None:
        args.out.write_text(text + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
