"""Python's cyclic garbage collector, run by the window's event loop instead of at
arbitrary allocations.

With automatic collection, a collection can start in the middle of a VTK render (inside
pyvistaqt's make-current or frame callbacks) or in a worker thread: it then frees VTK
props or Qt objects whose destructors touch the OpenGL context or another thread's
objects, and the process crashes (seen as a segmentation fault under "Garbage-collecting"
in ``_cb_frame`` and ``_cb_make_current`` while an operator was built in a worker). Here
automatic collection is off and the main thread collects from a timer, between events,
where nothing is rendering: the same generations and thresholds Python would use, only
at a safe moment. Reference counting still frees everything that is not in a cycle at
once, so memory does not wait on the timer.
"""

from __future__ import annotations

import gc

from PySide6 import QtCore

INTERVAL_MS = 500
"""How often the window looks at the collector's counts (ms)."""


class GarbageCollector(QtCore.QObject):
    """Collects cycles from the main thread's event loop while windows are open (one per
    application): automatic collection comes back when the last window closes."""

    _instance: GarbageCollector | None = None

    def __init__(self, parent: QtCore.QObject | None = None):
        super().__init__(parent)
        self.thresholds = gc.get_threshold()
        self.users: set[int] = set()
        self.timer = QtCore.QTimer(self)
        self.timer.timeout.connect(self.check)

    def check(self) -> int:
        """Collect the oldest generation whose count passed its threshold (the rule of
        automatic collection); objects found unreachable are returned."""
        counts = gc.get_count()
        for generation in (2, 1, 0):
            if counts[generation] > self.thresholds[generation]:
                return gc.collect(generation)
        return 0

    @classmethod
    def install(cls, window: QtCore.QObject) -> GarbageCollector:
        """Collect from the event loop while ``window`` is open (``release`` it when it
        closes)."""
        if cls._instance is None:
            cls._instance = cls(QtCore.QCoreApplication.instance())
        self = cls._instance
        if not self.users:
            gc.disable()
            self.timer.start(INTERVAL_MS)
        self.users.add(id(window))
        return self

    @classmethod
    def release(cls, window: QtCore.QObject) -> None:
        """``window`` closed: with no window left, automatic collection is back on."""
        self = cls._instance
        if self is None or id(window) not in self.users:
            return
        self.users.discard(id(window))
        if not self.users:
            self.timer.stop()
            gc.enable()
