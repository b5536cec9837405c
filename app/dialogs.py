"""The window's small dialogs: file choosers, messages, confirmations, the recovery prompt.

Each is one function returning the user's answer, so the window's logic reads as
"ask, then act" and a test can replace the question (the editing dialogs with fields,
``IntentionDialog`` and ``ZoneDialog``, are in panels.py).
"""

from __future__ import annotations

from PySide6 import QtWidgets

from app.autosave import Recoverable

PROJECT_FILTER = "LightInv project (*.json)"
TITLE = "LightInv"


def accepted(dialog: QtWidgets.QDialog) -> bool:
    """Whether ``dialog`` was accepted: already (a test or script set its result) or once
    shown."""
    ok = QtWidgets.QDialog.Accepted
    return dialog.result() == ok or dialog.exec() == ok


def open_file(parent, caption: str, file_filter: str = PROJECT_FILTER) -> str:
    """A file to open ("" if cancelled)."""
    path, _ = QtWidgets.QFileDialog.getOpenFileName(parent, caption, "", file_filter)
    return path


def save_file(parent, caption: str, file_filter: str = PROJECT_FILTER) -> str:
    """A file to write ("" if cancelled)."""
    path, _ = QtWidgets.QFileDialog.getSaveFileName(parent, caption, "", file_filter)
    return path


def inform(parent, message: str) -> None:
    """A message the user acknowledges."""
    QtWidgets.QMessageBox.information(parent, TITLE, message)


def warn(parent, message: str) -> None:
    """An edit was refused: why."""
    QtWidgets.QMessageBox.warning(parent, TITLE, message)


def error(parent, what: str, message: str) -> None:
    """Something failed (``what``: "cannot open", "precompute failed", ...)."""
    QtWidgets.QMessageBox.critical(parent, f"{TITLE}: {what}", message)


def confirm_discard(parent) -> bool:
    """Whether unsaved changes may be discarded."""
    answer = QtWidgets.QMessageBox.question(
        parent,
        TITLE,
        "The project has unsaved changes. Discard them?",
        QtWidgets.QMessageBox.Discard | QtWidgets.QMessageBox.Cancel,
    )
    return answer == QtWidgets.QMessageBox.Discard


def ask_recovery(parent, rec: Recoverable) -> str:
    """What to do with an orphaned autosave: "recover", "discard" or "keep"."""
    box = QtWidgets.QMessageBox(parent)
    box.setWindowTitle(f"{TITLE}: recover unsaved work")
    if rec.project is None:
        box.setText(f"An autosave could not be read:\n{rec.path}\n{rec.error}")
        delete = box.addButton("Delete it", QtWidgets.QMessageBox.DestructiveRole)
        box.addButton("Keep it", QtWidgets.QMessageBox.RejectRole)
        box.exec()
        return "discard" if box.clickedButton() is delete else "keep"
    where = str(rec.original) if rec.original else "a project never saved"
    box.setText(
        f"LightInv did not close normally. Recover the work autosaved at {rec.saved_at} "
        f"({rec.note}) for {where}?"
    )
    recover = box.addButton("Recover", QtWidgets.QMessageBox.AcceptRole)
    discard = box.addButton("Discard", QtWidgets.QMessageBox.DestructiveRole)
    box.addButton("Not now", QtWidgets.QMessageBox.RejectRole)
    box.exec()
    clicked = box.clickedButton()
    return "recover" if clicked is recover else ("discard" if clicked is discard else "keep")
