"""What every subcommand shares on the way out: printing text or JSON, warnings and
progress on stderr, and writing files without losing computed results."""

from __future__ import annotations

import json
import resource
import sys
from collections.abc import Callable
from pathlib import Path

from lightinv_core.atomic import rescue_paths
from lightinv_core.errors import LightInvError


def peak_rss_mb() -> float:
    """Peak resident memory of this process so far, in MB."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def out(args, payload: dict, text: str) -> None:
    """Print ``payload`` as one JSON object with ``--json``, else ``text``."""
    print(json.dumps(payload, indent=2) if args.json else text)


def warn(msg: str) -> None:
    """One line on stderr."""
    print(f"lightinv-cli: {msg}", file=sys.stderr)


def failed(message: str) -> int:
    """Exit status 2 with the message when an output could not be written where asked."""
    if not message:
        return 0
    print(f"lightinv-cli: error: {message}", file=sys.stderr)
    return 2


def write_or_rescue(label: str, path: str, write: Callable[[Path], object]) -> tuple[Path, str]:
    """Write an output with ``write(path)``; if that fails (disk full, folder gone), write
    it to the first of ``rescue_paths`` that works. Returns (where it went, the failure
    message or ""), so computed results are never thrown away."""
    try:
        write(Path(path))
        return Path(path), ""
    except (OSError, LightInvError) as exc:
        first = str(exc)
    for other in rescue_paths(path):
        try:
            write(other)
        except (OSError, LightInvError):
            continue
        return other, f"could not write {label} {path}: {first}; it was written to {other} instead"
    return Path(path), f"could not write {label} {path}: {first}, nor anywhere else"


def progress_printer(label: str) -> Callable[[float], None] | None:
    """A progress callback that redraws a percentage on stderr when it is a terminal."""
    if not sys.stderr.isatty():
        return None
    last = [-1]

    def report(frac: float) -> None:
        pct = int(100 * frac)
        if pct != last[0]:
            last[0] = pct
            print(f"\r{label}: {pct:3d}%", end="" if pct < 100 else "\n", file=sys.stderr)

    return report
