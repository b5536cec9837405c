"""The ``lightinv-cli`` entry point: a Ctrl-C at any moment ends the program with one
line and status 130, never a traceback.

The command line's own module imports numpy, scipy and the engine (about half a
second); an interrupt during those imports used to print a ``KeyboardInterrupt``
traceback. This module imports nothing heavy itself and catches the interrupt around
that import and around the whole run.
"""

from __future__ import annotations

import sys

INTERRUPTED = 130


def main() -> int:
    """Import and run the command line; a Ctrl-C prints one line and returns 130."""
    try:
        from lightinv_core.cli import main as run

        return run()
    except KeyboardInterrupt:
        print("lightinv-cli: cancelled", file=sys.stderr)
        return INTERRUPTED


if __name__ == "__main__":
    sys.exit(main())
