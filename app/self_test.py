"""``lightinv --self-test``: check an installation (or the desktop bundle) end to end.

Loads a built-in scene, builds a small radiosity operator, evaluates a source's
light, renders it off-screen with VTK, prints a JSON summary and exits 0; any
failure prints the error and exits 1. Needs no display (VTK falls back to EGL).
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import time


def _optimizers(light, lamp) -> dict:
    """A short CMA-ES and NSGA-II run each (the bundle must carry cma and pymoo)."""
    from dataclasses import replace

    from lightinv_core.design.model import CORNERS, Design, Goal
    from lightinv_core.optimize.method import RunContext
    from lightinv_core.optimize.problem import DesignProblem
    from lightinv_core.optimize.registry import get_method
    from lightinv_core.optimize.settings import OptimizerSettings
    from lightinv_core.optimize.termination import StopRule

    free = replace(lamp, free=CORNERS)
    design = Design((free,), (Goal("min_electric_power"), Goal("max_light_power")))
    out = {}
    for name in ("cmaes", "nsga2"):
        context = RunContext(OptimizerSettings(population=8), StopRule(200), seed=0)
        res = get_method(name).run(DesignProblem(design, light), context)
        if res.status != "feasible":
            raise RuntimeError(f"{name}: a short run ended {res.status}")
        out[name] = res.evaluations
    return out


def run() -> int:
    """Run the checks; returns the process exit status."""
    t0 = time.perf_counter()
    report: dict = {"python": sys.version.split()[0], "frozen": bool(getattr(sys, "frozen", False))}
    try:
        if not os.environ.get("DISPLAY"):
            os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
        import numpy as np

        from lightinv_core.design.model import Daylight, Source
        from lightinv_core.kinds import SourceKind
        from lightinv_core.light import LightModel
        from lightinv_core.operator.build import build_operator
        from lightinv_core.operator.settings import OperatorSettings
        from lightinv_core.scene.builtin import builtin_scene
        from lightinv_core.scene.patches import mesh_patches

        scene = builtin_scene("cornell", 0.3)
        patches = mesh_patches(scene)
        op = build_operator(patches, OperatorSettings(rank=80, rays=128))
        lamp = Source("L", "light", SourceKind.LUMINAIRE, (0.1, 0.1, 0.4, 0.4), flux=1000.0)
        lux = LightModel(scene, patches, op).field((lamp,), Daylight()).illuminance
        report.update(
            patches=patches.n,
            k=op.k,
            max_lux=float(lux.max()),
            operator_error=op.info["estimated_rel_error"],
        )
        if not np.all(np.isfinite(lux)) or lux.max() <= 0:
            raise RuntimeError("the evaluated lighting is empty or not finite")
        report["optimizers"] = _optimizers(LightModel(scene, patches, op), lamp)
        import pyvista as pv

        vertices, faces, tri_patch = patches.triangle_mesh()
        cells = np.hstack([np.full((len(faces), 1), 3), faces]).ravel()
        mesh = pv.PolyData(vertices.astype(float), cells)
        mesh.cell_data["lux"] = lux[tri_patch]
        plotter = pv.Plotter(off_screen=True, window_size=(320, 240))
        plotter.add_mesh(mesh, scalars="lux", culling="back", lighting=False)
        plotter.camera_position = "iso"
        with tempfile.TemporaryDirectory() as tmp:
            image = plotter.screenshot(os.path.join(tmp, "self-test.png"), return_img=True)
        plotter.close()
        report["render_std"] = float(image.std())
        if image.std() < 5:
            raise RuntimeError("the off-screen render is blank")
    except Exception as exc:  # report every failure, it is what a self-test is for
        report.update(ok=False, error=f"{type(exc).__name__}: {exc}")
        print(json.dumps(report, indent=2))
        return 1
    report.update(ok=True, seconds=time.perf_counter() - t0)
    print(json.dumps(report, indent=2))
    return 0
