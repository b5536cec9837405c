"""Cycles are collected by the window's event loop while a window is open, and by
Python again once the last window has closed (app/window/collector.py)."""

from __future__ import annotations

import gc
import weakref

from PySide6.QtTest import QTest

from app.window.collector import INTERVAL_MS


class Node:
    """An object in a reference cycle (only the cyclic collector frees it)."""

    def __init__(self):
        self.me = self


def test_cycles_are_collected_between_events_while_a_window_is_open(window):
    assert not gc.isenabled()
    gone = []
    for _ in range(3000):  # past generation 0's threshold (700)
        n = Node()
        weakref.finalize(n, gone.append, 1)
    del n
    # A few timer ticks (INTERVAL_MS); more on a busy machine, where they come late.
    QTest.qWait(3 * INTERVAL_MS)
    for _ in range(40):
        if len(gone) > 2000:
            break
        QTest.qWait(INTERVAL_MS)
    assert len(gone) > 2000


def test_python_collects_again_once_the_window_closes(window):
    assert not gc.isenabled()
    window.close()
    assert gc.isenabled()
