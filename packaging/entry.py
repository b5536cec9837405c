"""Entry script of the desktop bundle (PyInstaller): the ``lightinv`` command."""

import multiprocessing
import sys

if __name__ == "__main__":
    multiprocessing.freeze_support()
    from app.__main__ import main

    sys.exit(main())
