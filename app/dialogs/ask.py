"""The window's questions: file choosers, messages, confirmations, the recovery prompt.

Each is one function returning the user's answer, so the window's logic reads as
"ask, then act" and a test can replace the question (``monkeypatch`` on this module);
the dialogs with fields are one module each beside this one.
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


def save_file(parent, caption: str, file_filter: str = PROJECT_FILTER, suffix: str = "") -> str:
    """A file to write ("" if cancelled); ``suffix`` (".pdf") is added when the name
    typed has none (the file dialogs of some desktops do not add it)."""
    path, _ = QtWidgets.QFileDialog.getSaveFileName(parent, caption, "", file_filter)
    return with_suffix(path, suffix)


def with_suffix(path: str, suffix: str) -> str:
    """``path`` ending in ``suffix`` (any case); "" stays ""."""
    if path and suffix and not path.lower().endswith(suffix.lower()):
        return path + suffix
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


def unsaved_box(parent) -> tuple[QtWidgets.QMessageBox, dict]:
    """The unsaved-changes question: Save (the default, so Enter keeps the work),
    Discard, Cancel; with its buttons by answer."""
    box = QtWidgets.QMessageBox(parent)
    box.setWindowTitle(TITLE)
    box.setIcon(QtWidgets.QMessageBox.Warning)
    box.setText("The project has unsaved changes.")
    box.setInformativeText("Save them before going on?")
    buttons = {
        "save": box.addButton(QtWidgets.QMessageBox.Save),
        "discard": box.addButton(QtWidgets.QMessageBox.Discard),
        "cancel": box.addButton(QtWidgets.QMessageBox.Cancel),
    }
    box.setDefaultButton(buttons["save"])
    box.setEscapeButton(buttons["cancel"])
    return box, buttons


def ask_unsaved(parent) -> str:
    """What to do with unsaved changes: "save", "discard" or "cancel"."""
    box, buttons = unsaved_box(parent)
    box.exec()
    clicked = box.clickedButton()
    return next((k for k, b in buttons.items() if b is clicked), "cancel")


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
