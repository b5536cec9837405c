"""``precompute``: build (or load from the cache) the radiosity operator of a scene."""

from __future__ import annotations

from lightinv_core.cli.output import out, peak_rss_mb, progress_printer, warn
from lightinv_core.cli.scenes import scene_of
from lightinv_core.operator.cache import CachedOperator, get_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.patches import Patches, mesh_patches


def operator_of(args, patches: Patches) -> CachedOperator:
    """The operator of ``patches`` at the arguments' tolerance, rank, rays and seed."""
    settings = OperatorSettings(tol=args.tol, rank=args.rank, rays=args.rays, seed=args.seed)
    return get_operator(
        patches,
        settings,
        use_cache=not args.no_cache,
        progress=progress_printer("precompute"),
        warn=warn,
        scheduler=args.scheduler,
    )


def cmd_precompute(args) -> int:
    """Build (or load from the cache) the radiosity operator of a scene."""
    scene = scene_of(args)
    p = mesh_patches(scene)
    got = operator_of(args, p)
    info = got.operator.info
    result = {
        "scene": scene.name,
        "n": p.n,
        "k": got.operator.k,
        "nz": info["nz"],
        "seconds": got.seconds,
        "from_cache": got.from_cache,
        "cache_path": str(got.path) if got.path else None,
        "estimated_rel_error": info["estimated_rel_error"],
        "estimated_max_rel_error": info["estimated_max_rel_error"],
        "tol_met": info["tol_met"],
        "build_seconds": info["build_seconds"],
        "operator_mb": got.operator.nbytes() / 2**20,
        "peak_rss_mb": peak_rss_mb(),
    }
    lines = [
        f"{scene.name}: n = {p.n:,} patches, k = {got.operator.k}, {info['nz']:,} zone patches",
        f"{'loaded from cache' if got.from_cache else 'built'} in {got.seconds:.2f} s"
        f" ({result['operator_mb']:.0f} MB)",
        f"estimated relative error of C: {100 * info['estimated_rel_error']:.2f}% "
        f"(max {100 * info['estimated_max_rel_error']:.2f}%)",
        f"cache: {result['cache_path'] or 'disabled'}",
    ]
    out(args, result, "\n".join(lines))
    return 0
