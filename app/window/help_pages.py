"""Help: the documentation pages, opened in the desktop's viewer, and About."""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from PySide6 import QtCore, QtGui

from app.dialogs import ask

DOCS = Path(__file__).resolve().parent.parent.parent / "docs"
"""The documentation pages (docs/ in the source tree and in the bundle)."""


def doc_url(name: str) -> QtCore.QUrl:
    """The URL of a documentation page (``""``: the folder), in the source tree or the
    bundle."""
    return QtCore.QUrl.fromLocalFile(str(DOCS / name) if name else str(DOCS))


def open_doc(parent, name: str) -> bool:
    """Open a documentation page in the desktop's viewer; a message if none opens."""
    url = doc_url(name)
    if not (DOCS / name).exists() or not QtGui.QDesktopServices.openUrl(url):
        ask.inform(parent, f"The documentation is in {url.toLocalFile()}")
        return False
    return True


def about(parent) -> None:
    """Version, licence and where the documentation is."""
    try:
        v = version("lightinv")
    except PackageNotFoundError:
        v = "(source tree)"
    ask.inform(
        parent,
        f"LightInv {v}\nInverse lighting design for building interiors.\n"
        f"MIT licence. Documentation: {DOCS}",
    )
