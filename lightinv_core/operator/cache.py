"""On-disk cache of built radiosity operators: one file per (geometry, settings) key.

File layout: a fixed magic line, an 8-byte header length, a JSON header (key,
array table, build info, SHA-256 and size of the payload), then the raw array
bytes. Loading checks the magic, the version, the key and the checksum; any
mismatch means the file is stale or corrupt, and it is rebuilt, never used.
Writes go to a temporary file renamed into place, so a crash never leaves a
half-written cache behind.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from lightinv_core.atomic import atomic_writer, remove_stale_temporaries
from lightinv_core.errors import LightInvError
from lightinv_core.operator.build import OPERATOR_VERSION, build_operator
from lightinv_core.operator.lowrank import LowRank
from lightinv_core.operator.radiosity import RadiosityOperator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.patches import Patches
from lightinv_core.transport.formfactors import escape_warning

MAGIC = b"LIGHTINV-OPERATOR 1\n"
SUFFIX = ".lrr"


class CacheError(LightInvError):
    """A cache file is missing, stale or corrupt (the caller rebuilds)."""


def cache_dir() -> Path:
    """``$LIGHTINV_CACHE_DIR`` or the user's cache folder (platformdirs) / operators."""
    env = os.environ.get("LIGHTINV_CACHE_DIR")
    if env:
        return Path(env)
    from platformdirs import user_cache_dir

    return Path(user_cache_dir("lightinv")) / "operators"


def operator_key(patches: Patches, settings: OperatorSettings) -> str:
    """Hash of everything the operator depends on: geometry, materials, zones, settings."""
    h = hashlib.sha256(patches.digest().encode())
    h.update(np.ascontiguousarray(patches.zone_id).tobytes())
    s = settings
    keyed = {
        "version": OPERATOR_VERSION,
        "rank": s.rank,
        "tol": None if s.rank else s.tol,
        "rays": s.rays,
        "seed": s.seed,
    }
    h.update(json.dumps(keyed, sort_keys=True).encode())
    return h.hexdigest()


def _arrays(op: RadiosityOperator) -> dict[str, np.ndarray]:
    lr = op.lowrank
    return {
        "Y": lr.Y,
        "labels": lr.labels,
        "area": lr.area,
        "rho": lr.rho,
        "cluster_area": lr.cluster_area,
        "zone_patches": op.zone_patches,
        "G": op.G,
        "power": op.power,
        "F_data": op.F.data,
        "F_indices": op.F.indices,
        "F_indptr": op.F.indptr,
    }


def _raw(a: np.ndarray) -> memoryview:
    """The array's bytes in its own memory order (C or Fortran), without copying."""
    if a.size == 0:  # e.g. the zone basis of a scene without emitter zones
        return memoryview(b"")
    return memoryview(a.T if a.flags.f_contiguous and not a.flags.c_contiguous else a).cast("B")


def save_operator(op: RadiosityOperator, path: str | Path, key: str) -> None:
    """Write ``op`` atomically to ``path`` under ``key``."""
    arrays = _arrays(op)
    table, offset, sha = [], 0, hashlib.sha256()
    for name, a in arrays.items():
        raw = _raw(a)
        sha.update(raw)
        order = "F" if a.flags.f_contiguous and not a.flags.c_contiguous else "C"
        table.append(
            {
                "name": name,
                "dtype": a.dtype.str,
                "shape": list(a.shape),
                "order": order,
                "offset": offset,
                "nbytes": raw.nbytes,
            }
        )
        offset += raw.nbytes
    header = json.dumps(
        {
            "key": key,
            "version": OPERATOR_VERSION,
            "digest": op.digest,
            "arrays": table,
            "info": op.info,
            "payload_bytes": offset,
            "payload_sha256": sha.hexdigest(),
        }
    ).encode()
    with atomic_writer(path, "wb") as fh:
        fh.write(MAGIC)
        fh.write(len(header).to_bytes(8, "little"))
        fh.write(header)
        for a in arrays.values():
            fh.write(_raw(a))


def load_operator(path: str | Path, key: str) -> RadiosityOperator:
    """Read and verify an operator; CacheError if missing, stale or corrupt.

    Nothing in the header is trusted before it is checked against the file: a header
    claiming a petabyte payload, an array past the payload's end, an object dtype or
    a missing array is a corrupt cache (rebuilt), not a crash on every later run.
    """
    path = Path(path)
    try:
        with open(path, "rb") as fh:
            if fh.read(len(MAGIC)) != MAGIC:
                raise CacheError(f"{path.name}: not an operator cache file (bad magic)")
            size = int.from_bytes(fh.read(8), "little")
            if not 0 < size < 1 << 24:
                raise CacheError(f"{path.name}: header length {size} is corrupt")
            header = json.loads(fh.read(size))
            if not isinstance(header, dict):
                raise CacheError(f"{path.name}: header is not an object (corrupt)")
            if header.get("key") != key or header.get("version") != OPERATOR_VERSION:
                raise CacheError(f"{path.name}: built for other settings or version (stale)")
            nbytes = header["payload_bytes"]
            left = os.fstat(fh.fileno()).st_size - fh.tell()
            if type(nbytes) is not int or nbytes != left:
                raise CacheError(
                    f"{path.name}: truncated or padded payload ({left:,} bytes, the header "
                    f"says {nbytes!r})"
                )
            payload = np.empty(nbytes, np.uint8)
            got = fh.readinto(memoryview(payload))
            if got != payload.nbytes or fh.read(1):
                raise CacheError(f"{path.name}: truncated or padded payload")
    except CacheError:
        raise
    except FileNotFoundError:
        raise CacheError(f"{path.name}: no cache yet") from None
    except (OSError, ValueError, KeyError, TypeError, MemoryError) as exc:
        raise CacheError(f"{path.name}: unreadable ({type(exc).__name__}: {exc})") from None
    if hashlib.sha256(payload).hexdigest() != header.get("payload_sha256"):
        raise CacheError(f"{path.name}: checksum mismatch (corrupt)")
    try:
        arrays = {t["name"]: _array(payload, t) for t in header["arrays"]}
        _check_shapes(arrays)
        lowrank = LowRank(
            arrays["Y"], arrays["labels"], arrays["area"], arrays["rho"], arrays["cluster_area"]
        )
        info = header["info"]
        if not isinstance(info, dict):
            raise TypeError("info is not an object")
        n = lowrank.n
        F = sp.csr_matrix(
            (arrays["F_data"], arrays["F_indices"], arrays["F_indptr"]), shape=(n, n), copy=False
        )
        F.check_format(full_check=True)  # indices in range, indptr ordered
        return RadiosityOperator(
            lowrank,
            arrays["zone_patches"],
            F,
            arrays["G"],
            arrays["power"],
            str(header["digest"]),
            info,
        )
    except (ValueError, KeyError, TypeError, IndexError, AttributeError) as exc:
        raise CacheError(
            f"{path.name}: inconsistent arrays ({type(exc).__name__}: {exc})"
        ) from None


def _check_shapes(a: dict[str, np.ndarray]) -> None:
    """The arrays describe one operator: n patches, k clusters, nz zone patches, a CSR
    form-factor matrix of float32 values."""
    n, k = a["Y"].shape
    nz = len(a["zone_patches"])
    nnz = len(a["F_data"])
    want = {
        "labels": (n,),
        "area": (n,),
        "rho": (n,),
        "cluster_area": (k,),
        "zone_patches": (nz,),
        "G": (k, nz),
        "power": (nz,),
        "F_indices": (nnz,),
        "F_indptr": (n + 1,),
    }
    if a["F_data"].dtype != np.float32 or a["F_indices"].dtype.kind != "i":
        raise ValueError("form factors must be float32 values with integer indices")
    for name, shape in want.items():
        if a[name].shape != shape:
            raise ValueError(f"array {name!r} has shape {a[name].shape}, expected {shape}")
    z, lab = a["zone_patches"], a["labels"]
    if (nz and not (z.min() >= 0 and z.max() < n)) or (
        n and not (lab.min() >= 0 and lab.max() < k)
    ):
        raise ValueError("zone patch or cluster indices out of range")


def _array(payload: np.ndarray, t: dict) -> np.ndarray:
    """One array of the payload as described by its table entry, checked against it."""
    dtype = np.dtype(t["dtype"])
    if dtype.kind not in "fiub":
        raise TypeError(f"array {t['name']!r} has dtype {dtype} (numbers only)")
    shape = tuple(int(d) for d in t["shape"])
    start, size = int(t["offset"]), int(t["nbytes"])
    if min(shape, default=0) < 0 or size != math.prod(shape) * dtype.itemsize:
        raise ValueError(f"array {t['name']!r}: shape {shape} does not match {size} bytes")
    if not 0 <= start <= start + size <= len(payload):
        raise ValueError(f"array {t['name']!r} lies outside the payload")
    if t["order"] not in ("C", "F"):
        raise ValueError(f"array {t['name']!r}: order {t['order']!r}")
    return payload[start : start + size].view(dtype).reshape(shape, order=t["order"])


@dataclass(frozen=True)
class CachedOperator:
    """An operator with where it came from."""

    operator: RadiosityOperator
    from_cache: bool
    path: Path | None
    seconds: float


def open_scene_warning(op: RadiosityOperator) -> str | None:
    """The escaping-light warning of the operator's traced form factors, if any."""
    return escape_warning(float(op.info.get("lost_fraction", 0.0)))


CLI_REMEDY = "fix a higher rank (--rank) or use a coarser resolution"
"""What a command-line user can do about a missed accuracy target."""


def accuracy_warning(op: RadiosityOperator, remedy: str = CLI_REMEDY) -> str | None:
    """A warning when the build stopped at its largest rank above the target error;
    ``remedy`` says what the user can do (the window has no --rank).

    None for a scene without emitter zones: its error is estimated on scattered single
    patches emitting (``accuracy.sample_emissions``), light no source can give (sources
    and arrays lie in zones), and the low-rank part resolves such point-like emitters
    badly (tens of percent on a bare room whose first zone brings it under 1%)."""
    info = op.info
    if info.get("tol_met", True) or info.get("nz", 1) == 0:
        return None
    return (
        f"the radiosity operator's estimated error is {100 * info['estimated_rel_error']:.1f}% "
        f"(target {100 * info['tol']:.1f}%) at its largest rank, k = {op.k}: reflected light "
        f"may be off by about that much; {remedy}"
    )


def operator_warnings(op: RadiosityOperator, remedy: str = CLI_REMEDY) -> list[str]:
    """Everything worth telling the user about an operator: escaping light, accuracy
    (``remedy``: what the user can do about it)."""
    return [w for w in (open_scene_warning(op), accuracy_warning(op, remedy)) if w]


def get_operator(
    patches: Patches,
    settings: OperatorSettings | None = None,
    use_cache: bool = True,
    progress: Callable[[float], None] | None = None,
    cancel: Callable[[], bool] | None = None,
    warn: Callable[[str], None] | None = None,
    scheduler: str | None = None,
    remedy: str = CLI_REMEDY,
) -> CachedOperator:
    """Load the operator built with ``settings`` (default ``OperatorSettings()``) from the
    cache, or build it (and cache it); ``scheduler`` (``tcp://host:port``) builds it on
    that Dask cluster (the same operator, so it is not part of the cache key).

    A stale or corrupt cache file is reported through ``warn`` and rebuilt; the
    operator's warnings go to ``warn`` too (``remedy``: what the user can do about a
    missed accuracy target).
    """
    import time

    settings = settings or OperatorSettings()
    t0 = time.perf_counter()
    key = operator_key(patches, settings)
    path = cache_dir() / f"{key[:32]}{SUFFIX}" if use_cache else None
    if path is not None:
        remove_stale_temporaries(path.parent)  # of builds killed while saving
    if path is not None and path.exists():
        try:
            op = load_operator(path, key)
            if op.digest != patches.digest():
                raise CacheError(f"{path.name}: geometry digest differs (stale)")
            for msg in operator_warnings(op, remedy) if warn is not None else ():
                warn(msg)
            return CachedOperator(op, True, path, time.perf_counter() - t0)
        except CacheError as exc:
            if warn is not None:
                warn(f"operator cache {exc}; rebuilding")
    op = build_operator(patches, settings, progress=progress, cancel=cancel, scheduler=scheduler)
    for msg in operator_warnings(op, remedy) if warn is not None else ():
        warn(msg)
    if path is not None:
        try:
            save_operator(op, path, key)
        except OSError as exc:
            if warn is not None:
                warn(f"could not write the operator cache {path}: {exc}")
    return CachedOperator(op, False, path, time.perf_counter() - t0)
