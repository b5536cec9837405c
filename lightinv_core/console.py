"""The ``lightinv-cli`` entry point: a Ctrl-C at any moment ends the program with one
line and status 130, never a traceback.

The command line's own module imports numpy, scipy and the engine (about half a
second); an interrupt during those imports used to print a ``KeyboardInterrupt``
traceback, and one landing inside a C extension's own import (numpy importing
``datetime`` from C) surfaces as an ``ImportError`` instead. So during the imports the
interrupt is only recorded, and acted on once they are done; the run itself is wrapped
to catch it. This module imports nothing heavy itself.
"""

from __future__ import annotations

import signal
import sys

INTERRUPTED = 130


def _cancelled() -> int:
    print("lightinv-cli: cancelled", file=sys.stderr)
    return INTERRUPTED


def main() -> int:
    """Import and run the command line; a Ctrl-C prints one line and returns 130."""
    pressed: list[int] = []
    installed = True
    try:
        previous = signal.signal(signal.SIGINT, lambda signum, frame: pressed.append(signum))
    except ValueError:  # not the main thread: no handler can be set, import as is
        installed = False
    try:
        from lightinv_core.cli import main as run
    except KeyboardInterrupt:
        return _cancelled()
    finally:
        if installed:
            # A handler not set from Python reads as None: restore Python's default.
            signal.signal(signal.SIGINT, previous or signal.default_int_handler)
    if pressed:
        return _cancelled()
    try:
        return run()
    except KeyboardInterrupt:
        return _cancelled()


if __name__ == "__main__":
    sys.exit(main())
