"""Undo and redo: every edit of the editing model as a ``QUndoCommand``.

The model reports each edit with the project before and after it
(``DocumentModel.on_edit``); a command puts one or the other back with
``DocumentModel.restore``, which applies only that step's change to the results (a
deleted run comes back; runs made since stay). Consecutive moves of the same source (a
drag sends one per mouse move) merge into one step. Opening or starting a project clears
the history.
"""

from __future__ import annotations

from PySide6 import QtGui

MOVE_ID = 1


class EditCommand(QtGui.QUndoCommand):
    """One edit: ``label`` (shown as "Undo move L1"), the projects before and after."""

    def __init__(self, doc, label: str, before, after):
        super().__init__(label)
        self.doc, self.before, self.after = doc, before, after
        self._done = True  # the edit has happened already: the first redo() is a no-op

    def id(self) -> int:
        return MOVE_ID if self.text().startswith("move ") else -1

    def mergeWith(self, other: QtGui.QUndoCommand) -> bool:
        if other.id() != MOVE_ID or other.text() != self.text():
            return False
        self.after = other.after  # one step from before the drag to after it
        return True

    def redo(self) -> None:
        if self._done:
            self._done = False
            return
        self.doc.restore(self.after, self.before)

    def undo(self) -> None:
        self.doc.restore(self.before, self.after)


def undo_stack(window) -> QtGui.QUndoStack:
    """The window's undo stack, fed by the document's edits."""
    stack = QtGui.QUndoStack(window)
    window.doc.model.on_edit = lambda label, before, after: stack.push(
        EditCommand(window.doc, label, before, after)
    )
    return stack
