"""The Qt binding keeps Python's reference counts right.

PySide6-Essentials 6.12.0 on Python 3.11 drops a reference to None on every call of a
void method (QPainter.setPen, drawLine, ...): the window aborts with "none_dealloc"
after some ten thousand calls — seconds of live plotting. pyproject.toml excludes it;
this test catches a binding with the same fault before a user does.
"""

from __future__ import annotations

import sys

from PySide6 import QtCore, QtGui


def test_void_qt_calls_do_not_eat_references_to_none(qapp):
    image = QtGui.QImage(64, 64, QtGui.QImage.Format_ARGB32)
    painter = QtGui.QPainter(image)
    pen = QtGui.QPen(QtGui.QColor("red"))
    a, b = QtCore.QPointF(0, 0), QtCore.QPointF(10, 10)
    try:
        before = sys.getrefcount(None)
        for _ in range(500):  # few enough not to exhaust None even on a faulty binding
            painter.setPen(pen)
            painter.drawLine(a, b)
            painter.save()
            painter.restore()
        lost = before - sys.getrefcount(None)
    finally:
        painter.end()
    assert lost < 50, f"the Qt binding lost {lost} references to None in 2,000 void calls"
