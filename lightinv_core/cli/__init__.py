"""``lightinv-cli``: the headless command line.

Every subcommand prints human-readable text, or one JSON object with ``--json``.
User errors (bad names, bad files, bad numbers) exit with status 2 and a one-line
message on stderr, never a traceback.

One module per subcommand (``scenes``: scenes and scene-info, ``simulate``,
``precompute``, ``solve``, ``report``), the argument types in ``args``, the shared
output helpers in ``output``, the parser in ``parser``; ``main`` is here.
"""

from __future__ import annotations

import sys
import warnings
from collections.abc import Sequence

from lightinv_core.cli.output import peak_rss_mb, warn
from lightinv_core.cli.parser import build_parser
from lightinv_core.cli.solve import daylight_summary
from lightinv_core.errors import CancelledError, LightInvError

__all__ = ["build_parser", "daylight_summary", "main", "peak_rss_mb"]


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """Any Python warning (numpy's RuntimeWarning on a bad number) as one line on
    stderr, never the source line of a library: a number the engine did not catch."""
    warn(f"warning: {category.__name__}: {message} (please report it with the input used)")


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the process exit status."""
    try:
        args = build_parser().parse_args(argv)
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            return args.func(args)
    except (LightInvError, OSError) as exc:
        print(f"lightinv-cli: error: {exc}", file=sys.stderr)
        return 2
    except (KeyboardInterrupt, CancelledError):
        print("lightinv-cli: cancelled", file=sys.stderr)
        return 130
