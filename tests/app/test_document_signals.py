"""The Qt adapter's signals carry the editing model's payloads, and the window's slots
that take no argument keep working (PySide6 calls a Python slot with the arguments it
can take)."""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets

from app.document import Document
from lightinv_core.editing import (
    EVENT_TYPES,
    DesignChanged,
    PathChanged,
    SceneChanged,
    SelectionChanged,
    blank_project,
)
from lightinv_core.editing.changes import CURRENT_SOURCE


class Panel(QtWidgets.QWidget):
    """Slots of every shape the window connects: no parameter, a Qt ``Slot()``, one
    parameter (the payload)."""

    def __init__(self):
        super().__init__()
        self.calls: list[tuple[str, object]] = []

    def refresh(self) -> None:
        self.calls.append(("refresh", None))

    @QtCore.Slot()
    def refresh_slot(self) -> None:
        self.calls.append(("slot", None))

    def show_change(self, change) -> None:
        self.calls.append(("payload", change))


def test_signals_carry_payloads_and_slots_without_parameters_still_run(qtbot):
    doc, panel = Document(), Panel()
    qtbot.addWidget(panel)
    plain: list[str] = []
    doc.designChanged.connect(panel.refresh)
    doc.designChanged.connect(panel.refresh_slot)
    doc.designChanged.connect(panel.show_change)
    doc.designChanged.connect(lambda: plain.append("lambda"))
    doc.designChanged.connect(plain_function(plain))
    carried = []
    for signal in (doc.sceneChanged, doc.designChanged, doc.pathChanged):
        signal.connect(carried.append)
    doc.set_project(blank_project("office", 0.7))
    assert [type(p) for p in carried] == [SceneChanged, DesignChanged, PathChanged]
    assert carried[0].patches is doc.patches and carried[2].dirty is False
    assert [name for name, _ in panel.calls] == ["refresh", "slot", "payload"]
    assert panel.calls[2][1].design is doc.design and plain == ["lambda", "function"]
    panel.calls.clear()
    src = doc.add_source("lum_west")
    (change,) = [c for name, c in panel.calls if name == "payload"]
    assert change.changed == {"sources", CURRENT_SOURCE} and change.current_source == src.name
    assert change.label == f"add source {src.name}"


def plain_function(log: list[str]):
    def refreshed() -> None:
        log.append("function")

    return refreshed


def test_every_event_has_its_signal_and_the_selection_arrives(qtbot):
    doc = Document()
    for name in EVENT_TYPES:
        assert isinstance(getattr(Document, f"{name}Changed"), QtCore.Signal)
    doc.set_project(blank_project("office", 0.7))
    with qtbot.waitSignal(doc.selectionChanged) as blocker:
        doc.set_selection([4, 1, 4])
    (picked,) = blocker.args
    assert isinstance(picked, SelectionChanged) and picked.patches.tolist() == [1, 4]


def test_a_slot_with_a_default_parameter_receives_the_payload(qtbot):
    """Why app/document.py says to wrap such a slot in a lambda."""
    doc, got = Document(), []

    def refresh(keep: bool = False) -> None:
        got.append(keep)

    doc.pathChanged.connect(refresh)
    doc.pathChanged.connect(lambda: refresh())
    doc.set_project(blank_project("office", 0.7))
    assert isinstance(got[0], PathChanged) and got[1] is False
