"""``scenes`` and ``scene-info``: the built-in scenes, and what a scene holds."""

from __future__ import annotations

import argparse

from lightinv_core.cli import args as types
from lightinv_core.cli.output import out
from lightinv_core.scene.builtin import BUILTIN_SCENES, builtin_scene
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import count_patches, mesh_patches


def add_scene_args(p: argparse.ArgumentParser) -> None:
    """The scene and how to read it: shared by every subcommand that takes a scene."""
    p.add_argument(
        "scene",
        help="built-in scene name or path to a model file (.obj, .gltf, .glb, .ply, .ifc)",
    )
    p.add_argument("--resolution", type=types.positive, help="target patch size in metres")
    p.add_argument("--materials", help="model files only: materials JSON (reflectance per group)")
    p.add_argument(
        "--scale",
        type=types.positive,
        default=1.0,
        help="model files only: metres per model unit (0.001 for millimetres)",
    )
    p.add_argument(
        "--up",
        choices=("z", "y"),
        default=None,
        help="model files only: up axis (default: y for glTF, z for the others)",
    )
    p.add_argument(
        "--skip-degenerate",
        action="store_true",
        help="model files only: drop zero-area faces (with a warning) instead of failing",
    )
    p.add_argument(
        "--group-by",
        choices=("node", "material"),
        default="node",
        help="glTF only: lighting groups named after nodes (default) or materials",
    )


def scene_of(args) -> Scene:
    """The scene the arguments name (``add_scene_args``)."""
    return load_scene(
        args.scene,
        args.resolution,
        args.materials,
        args.scale,
        args.up,
        args.skip_degenerate,
        group_by=args.group_by,
    )


def cmd_scenes(args) -> int:
    """List the built-in scenes with their default patch counts."""
    scenes = []
    for name in BUILTIN_SCENES:
        s = builtin_scene(name)
        scenes.append(
            {
                "name": name,
                "patches": count_patches(s),
                "resolution": s.resolution,
                "description": s.description,
            }
        )
    lines = [f"{s['name']:<10} {s['patches']:>7,} patches  {s['description']}" for s in scenes]
    out(args, {"scenes": scenes}, "\n".join(lines))
    return 0


def cmd_scene_info(args) -> int:
    """Patch count, area, groups and emitter zones of a scene, and for a model file its
    import report (what each element or group became, what was dropped and why)."""
    from lightinv_core.scene.importers.report import report_of

    scene = scene_of(args)
    p = mesh_patches(scene)
    groups = [
        {
            "name": g,
            "patches": int((p.group_id == k).sum()),
            "area_m2": float(p.area[p.group_id == k].sum()),
        }
        for k, g in enumerate(p.group_names)
    ]
    zones = []
    for z in scene.zones:
        r = scene.zone_rect(z.name)
        zones.append(
            {
                "name": z.name,
                "kind": z.kind,
                "size_m": list(r.size),
                "grid": list(p.grid_shape[z.surface]),
                "origin": r.origin.tolist(),
                "u_axis": (r.u / r.size[0]).tolist(),
                "v_axis": (r.v / r.size[1]).tolist(),
                "normal": r.normal.tolist(),
                "outline": None if z.outline is None else z.outline.tolist(),
            }
        )
    info = {
        "name": scene.name,
        "patches": p.n,
        "area_m2": float(p.area.sum()),
        "resolution": scene.resolution,
        "groups": groups,
        "zones": zones,
        "warnings": list(scene.info.get("warnings", [])),
    }
    report = report_of(scene)
    if report is not None:
        info["import_report"] = report.to_dict()
    lines = [
        f"{scene.name}: {p.n:,} patches, {info['area_m2']:.1f} m² "
        f"(resolution {scene.resolution} m)",
        "groups:",
    ]
    lines += [
        f"  {g['name']:<14} {g['patches']:>7,} patches {g['area_m2']:9.2f} m²" for g in groups
    ]
    lines.append("emitter zones:" if zones else "emitter zones: none")
    lines += [
        f"  {z['name']:<10} {z['kind']:<9} {z['size_m'][0]:.2f} x {z['size_m'][1]:.2f} m, "
        f"grid {z['grid'][0]} x {z['grid'][1]}"
        + (f", polygon of {len(z['outline'])} corners" if z["outline"] else "")
        for z in zones
    ]
    if report is not None:
        lines += ["import report:", *(f"  {line}" for line in report.lines())]
    lines += [f"warning: {w}" for w in info["warnings"]]
    out(args, info, "\n".join(lines))
    return 0
