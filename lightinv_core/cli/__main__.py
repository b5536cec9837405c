"""``python -m lightinv_core.cli``: the command line."""

import sys

from lightinv_core.cli import main

if __name__ == "__main__":
    sys.exit(main())
