"""How much memory this process may still use: the machine's and its container's share.

Builds and imports refuse work that would not fit rather than be killed by the
kernel with no message. In a container (docker, CI runners, systemd slices) the
limit that kills is the cgroup's, not the machine's ``MemAvailable``, so both are
read and the smaller wins.
"""

from __future__ import annotations

from pathlib import Path

UNLIMITED = 1 << 60
"""Bytes; what an unknown or absent limit counts as (cgroup v1 writes 2**63 - 4096)."""


def _read_int(path: Path) -> int | None:
    try:
        text = path.read_text().strip()
    except (OSError, ValueError):
        return None
    if text == "max":
        return UNLIMITED
    try:
        return int(text)
    except ValueError:
        return None


def _stat_value(path: Path, key: str) -> int:
    """One counter of a cgroup's memory.stat (0 if absent)."""
    try:
        for line in path.read_text().splitlines():
            name, _, value = line.partition(" ")
            if name == key:
                return int(value)
    except (OSError, ValueError):
        pass
    return 0


def machine_available_bytes(proc: Path = Path("/proc")) -> int:
    """MemAvailable from /proc/meminfo (bytes), or ``UNLIMITED`` where unknown."""
    try:
        with open(proc / "meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return UNLIMITED


def _cgroup_dirs(proc: Path, root: Path) -> list[tuple[Path, str]]:
    """Candidate (folder, version) pairs of this process's memory cgroup, innermost first."""
    try:
        lines = (proc / "self" / "cgroup").read_text().splitlines()
    except OSError:
        lines = []
    out = []
    for line in lines:
        hid, _, rest = line.partition(":")
        controllers, _, rel = rest.partition(":")
        rel = rel.lstrip("/")
        if hid == "0" and controllers == "":
            out += [(root / rel, "v2"), (root, "v2")]
        elif "memory" in controllers.split(","):
            out += [(root / "memory" / rel, "v1"), (root / "memory", "v1")]
    return out


def cgroup_available_bytes(proc: Path = Path("/proc"), root: Path = Path("/sys/fs/cgroup")) -> int:
    """Limit minus usage of this process's memory cgroup (bytes), ``UNLIMITED`` if none.

    Page cache the kernel would drop first (inactive files) does not count as used,
    as in docker's own accounting.
    """
    best = UNLIMITED
    for folder, version in _cgroup_dirs(proc, root):
        if version == "v2":
            limit, used = _read_int(folder / "memory.max"), _read_int(folder / "memory.current")
            cache = _stat_value(folder / "memory.stat", "inactive_file")
        else:
            limit = _read_int(folder / "memory.limit_in_bytes")
            used = _read_int(folder / "memory.usage_in_bytes")
            cache = _stat_value(folder / "memory.stat", "total_inactive_file")
        if limit is None or used is None or limit >= UNLIMITED:
            continue
        best = min(best, max(0, limit - max(0, used - cache)))
    return best


def available_memory_bytes() -> int:
    """Bytes this process may still allocate: the smaller of the machine's MemAvailable
    and its cgroup's remaining limit."""
    return min(machine_available_bytes(), cgroup_available_bytes())


def format_bytes(nbytes: float) -> str:
    """Bytes as GiB, MiB below 1 GiB, KiB below 1 MiB, bytes below 1 KiB (never "0.0 GiB")."""
    if nbytes >= 2**30:
        return f"{nbytes / 2**30:.1f} GiB"
    if nbytes >= 2**20:
        return f"{nbytes / 2**20:.0f} MiB"
    if nbytes >= 2**10:
        return f"{nbytes / 2**10:.0f} KiB"
    return f"{int(nbytes)} bytes"
