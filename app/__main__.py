"""``lightinv`` / ``python -m app``: start the desktop application.

lightinv                      the built-in demo project (office)
lightinv PROJECT.json         a project file
lightinv --scene patio        a new project on a built-in scene
lightinv PROJECT.json --run   open and start its optimisation

Work left by a session that did not close normally (a crash, a kill) is offered for
recovery at start-up (see app/window/recovery.py).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

PROJECTS = Path(__file__).resolve().parent.parent / "resources" / "projects"
# What `lightinv` opens without a project: the flagship office (README, docs/design.md).
DEMO = PROJECTS / "office-flagship.json"
INTEGRATED = PROJECTS / "office-integrated.json"  # the paper-style climate demo


def parse_args(argv: list[str]) -> argparse.Namespace:
    ap = argparse.ArgumentParser(prog="lightinv", description="LightInv inverse lighting design")
    ap.add_argument(
        "project", nargs="?", help="project file to open (default: the flagship office)"
    )
    ap.add_argument("--scene", help="start a new project on this built-in scene")
    ap.add_argument("--resolution", type=float, help="patch size (m) for --scene")
    ap.add_argument(
        "--self-test",
        action="store_true",
        help="check the installation (scene, operator, off-screen render) and exit",
    )
    ap.add_argument(
        "--run",
        action="store_true",
        help="start the project's optimisation as soon as its operator is ready",
    )
    ap.add_argument(
        "--autosave-interval",
        type=float,
        metavar="SECONDS",
        help="seconds between autosaves (default 30, or $LIGHTINV_AUTOSAVE_SECONDS)",
    )
    ap.add_argument(
        "--no-recovery",
        action="store_true",
        help="do not offer to recover autosaves of sessions that did not close normally",
    )
    ap.add_argument(
        "--screenshot",
        metavar="PNG",
        help="open, wait for the operator, save a window screenshot and quit",
    )
    return ap.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    if args.self_test:
        from app.self_test import run

        return run()
    from PySide6 import QtCore, QtWidgets

    from app.window.main_window import MainWindow

    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication(sys.argv[:1])
    app.setApplicationName("LightInv")
    window = MainWindow(autosave_seconds=args.autosave_interval)
    window.show()
    recovered = not args.no_recovery and window.offer_recovery()
    if not recovered:
        if args.scene:
            ok = window.new_project(args.scene, args.resolution)
        else:
            ok = window.open_path(args.project or DEMO)
        if not ok:
            return 2
    if args.run:
        window.run_after_precompute = True
        if window.worker is None and window.doc.operator is not None:
            window.runs.start()
    if args.screenshot:

        def shoot() -> None:
            if window.worker is not None or window.runs.running or window.run_after_precompute:
                QtCore.QTimer.singleShot(200, shoot)
                return
            window.grab().save(args.screenshot)
            window.ask_before_discard = False  # a scripted picture: nothing to ask
            window.close()

        QtCore.QTimer.singleShot(500, shoot)
    return app.exec()


if __name__ == "__main__":
    sys.exit(main())
