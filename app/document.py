"""The open project as the window sees it: a thin Qt adapter over the editing model.

``lightinv_core.editing.DocumentModel`` holds the state and every editing rule, Qt-free;
this ``QObject`` owns one, turns its named events into Qt signals (same names as the
model's events, ``sceneChanged`` for "scene" and so on, each carrying the event's
payload), and forwards attribute reads and the model's methods, so widgets call
``doc.add_source(...)`` and connect ``doc.designChanged``. Widgets keep no state of
their own: they read the document and call its setters; the model emits, and every
view refreshes (napari's model/view split).
"""

from __future__ import annotations

from PySide6 import QtCore

from lightinv_core.editing import DocumentModel, blank_project

__all__ = ["Document", "blank_project"]

_STATE = frozenset({"project", "current_source", "dirty", "path", "shown", "selection"})
"""Model attributes a caller may assign through the adapter (scripts, tests)."""


class Document(QtCore.QObject):
    """Qt signals for a ``DocumentModel``; every other attribute is the model's."""

    # Each signal carries its event's frozen payload (``lightinv_core.editing.changes``:
    # ``SceneChanged``, ``DesignChanged``, ...). A slot may take it or not: PySide6 calls
    # a Python slot with no parameters without it. A slot whose parameters all have
    # defaults would receive it in the first one: wrap such a slot in a lambda.
    sceneChanged = QtCore.Signal(object)
    operatorChanged = QtCore.Signal(object)
    designChanged = QtCore.Signal(object)
    selectionChanged = QtCore.Signal(object)
    lightingChanged = QtCore.Signal(object)
    pathChanged = QtCore.Signal(object)
    resultsChanged = QtCore.Signal(object)

    def __init__(self, parent: QtCore.QObject | None = None, model: DocumentModel | None = None):
        super().__init__(parent)
        self.model = model if model is not None else DocumentModel()
        for name in self.model.events.names:
            self.model.events.connect(name, getattr(self, f"{name}Changed").emit)

    def __getattr__(self, name: str):
        # Only called when normal lookup fails: the model's state and methods.
        if name == "model":  # not set yet (during __init__)
            raise AttributeError(name)
        return getattr(self.model, name)

    def __setattr__(self, name: str, value) -> None:
        if name in _STATE:
            setattr(self.model, name, value)
        else:
            super().__setattr__(name, value)
