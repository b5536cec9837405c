"""Every editing dialog of the window, opened from its button or menu as a user does, has
visible OK and Cancel buttons: OK (or Enter) adds what it describes, Escape or Cancel
adds nothing, and a value that cannot be built keeps the dialog open (issue #29,
blocker 1)."""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtWidgets
from PySide6.QtTest import QTest

from app.dialogs import ask

SHOTS = Path("/tmp/lightinv-dialogs")


def button(parent: QtWidgets.QWidget, text: str) -> QtWidgets.QAbstractButton:
    """The visible button of ``parent`` showing ``text`` (mnemonic "&" ignored)."""
    found = [
        b
        for b in parent.findChildren(QtWidgets.QAbstractButton)
        if b.text().replace("&", "") == text and b.isVisible()
    ]
    assert len(found) == 1, f"{text!r}: {[b.text() for b in found]}"
    return found[0]


def field(dialog: QtWidgets.QDialog, label: str) -> QtWidgets.QWidget:
    """The (first) field of ``dialog``'s form row labelled ``label``, clicked."""
    form = dialog.layout()
    for row in range(form.rowCount()):
        item = form.itemAt(row, QtWidgets.QFormLayout.LabelRole)
        if item is not None and item.widget() is not None and item.widget().text() == label:
            cell = form.itemAt(row, QtWidgets.QFormLayout.FieldRole)
            widget = cell.widget() or cell.layout().itemAt(0).widget()
            QTest.mouseClick(widget, QtCore.Qt.LeftButton)
            return widget
    raise AssertionError(f"no field {label!r} in {dialog.windowTitle()!r}")


def menu_action(win, path: str):
    """The menu bar's action at ``path`` ("Design/Add a geometric rule...")."""
    *menus, last = path.split("/")
    actions = win.menuBar().actions()
    for name in menus:
        menu = next(a for a in actions if a.text().replace("&", "") == name).menu()
        actions = menu.actions()
    return next(a for a in actions if a.text().replace("&", "") == last)


def answer(open_it, respond) -> dict:
    """Call ``open_it`` (it shows a modal dialog and waits), and ``respond(dialog)`` once
    the dialog is up; the dialog's OK / Cancel buttons and a screenshot are kept. A
    dialog left open after ``respond`` is rejected so a failing test cannot hang."""
    seen: dict = {}

    def poll() -> None:
        dialog = QtWidgets.QApplication.activeModalWidget()
        if "result" in seen:  # nothing was shown: stop looking
            return
        if dialog is None:
            QtCore.QTimer.singleShot(30, poll)
            return
        seen["dialog"] = type(dialog).__name__
        seen["title"] = dialog.windowTitle()
        texts = {b.text().replace("&", "") for b in dialog.findChildren(QtWidgets.QPushButton)}
        seen["buttons"] = {t for t in texts if t in ("OK", "Cancel")}
        for text in seen["buttons"]:  # shown inside the dialog, not cut off
            b = button(dialog, text)
            corner = b.mapTo(dialog, b.rect().bottomRight())
            seen[f"{text} inside"] = dialog.rect().contains(corner)
        SHOTS.mkdir(exist_ok=True)
        dialog.grab().save(str(SHOTS / f"{seen['dialog']}.png"))
        try:
            respond(dialog)
        finally:
            if dialog.isVisible() and QtWidgets.QApplication.activeModalWidget() is dialog:
                seen["left open"] = True
                dialog.reject()

    QtCore.QTimer.singleShot(0, poll)
    seen["result"] = open_it()
    return seen


def click(text: str):
    return lambda dialog: QTest.mouseClick(button(dialog, text), QtCore.Qt.LeftButton)


def key(k):
    """Press ``k`` in the dialog's first field (as typed after it opens)."""

    def press(dialog):
        dialog.activateWindow()
        QTest.keyClick(dialog.focusWidget() or dialog, k)

    return press


def ok_and_cancel(seen: dict) -> None:
    assert seen["buttons"] == {"OK", "Cancel"}, seen
    assert seen["OK inside"] and seen["Cancel inside"], seen
    assert "left open" not in seen, seen


def test_the_luminaire_dialogs_have_ok_and_cancel(qtbot, window, monkeypatch):
    assert window.new_project("office", 0.5)
    panel, d = window.luminaires_panel, window.doc
    window.findChild(QtWidgets.QDockWidget, "luminaires").raise_()
    add_plane = button(panel, "Add work plane…")

    # Add work plane…: Escape adds nothing, OK adds one, Enter in the name field another.
    seen = answer(
        lambda: QTest.mouseClick(add_plane, QtCore.Qt.LeftButton), key(QtCore.Qt.Key_Escape)
    )
    ok_and_cancel(seen)
    assert seen["dialog"] == "WorkplaneDialog" and d.design.workplanes == ()
    ok_and_cancel(answer(lambda: QTest.mouseClick(add_plane, QtCore.Qt.LeftButton), click("OK")))
    assert [w.name for w in d.design.workplanes] == ["wp"]

    def rename_and_enter(dialog):
        name = field(dialog, "Name")
        QTest.keyClick(name, QtCore.Qt.Key_A, QtCore.Qt.ControlModifier)
        QTest.keyClicks(name, "desk")
        QTest.keyClick(name, QtCore.Qt.Key_Return)

    ok_and_cancel(
        answer(lambda: QTest.mouseClick(add_plane, QtCore.Qt.LeftButton), rename_and_enter)
    )
    assert [w.name for w in d.design.workplanes] == ["wp", "desk"]

    # A name that cannot be: Enter says why and the dialog stays open for a fix.
    warned = []
    monkeypatch.setattr(ask, "warn", lambda parent, message: warned.append(message))

    def empty_then_fix(dialog):
        name = field(dialog, "Name")
        QTest.keyClick(name, QtCore.Qt.Key_A, QtCore.Qt.ControlModifier)
        QTest.keyClick(name, QtCore.Qt.Key_Delete)
        QTest.keyClick(name, QtCore.Qt.Key_Return)
        assert dialog.isVisible() and warned and "name" in warned[0]
        QTest.keyClicks(name, "aisle")
        QTest.mouseClick(button(dialog, "OK"), QtCore.Qt.LeftButton)

    ok_and_cancel(answer(lambda: QTest.mouseClick(add_plane, QtCore.Qt.LeftButton), empty_then_fix))
    assert [w.name for w in d.design.workplanes] == ["wp", "desk", "aisle"]

    # Add array…: Cancel adds nothing; Enter adds the array the dialog shows.
    add_array = button(panel, "Add array…")
    seen = answer(lambda: QTest.mouseClick(add_array, QtCore.Qt.LeftButton), click("Cancel"))
    ok_and_cancel(seen)
    assert seen["dialog"] == "ArrayDialog" and d.design.arrays == ()
    ok_and_cancel(
        answer(lambda: QTest.mouseClick(add_array, QtCore.Qt.LeftButton), key(QtCore.Qt.Key_Return))
    )
    assert [a.name for a in d.design.arrays] == ["A1"]

    # Edit… the array: OK takes the new row count, Escape keeps it.
    panel.arrays.selectRow(0)

    def three_rows(dialog):
        rows = field(dialog, "Layout")  # "[2] rows (along v) x [2] columns"
        QTest.keyClick(rows.lineEdit(), QtCore.Qt.Key_A, QtCore.Qt.ControlModifier)
        QTest.keyClicks(rows.lineEdit(), "3")
        QTest.mouseClick(button(dialog, "OK"), QtCore.Qt.LeftButton)

    edit = button(panel, "Edit…")
    seen = answer(lambda: QTest.mouseClick(edit, QtCore.Qt.LeftButton), three_rows)
    ok_and_cancel(seen)
    assert seen["title"] == "Edit array A1" and d.design.arrays[0].rows == 3
    ok_and_cancel(
        answer(lambda: QTest.mouseClick(edit, QtCore.Qt.LeftButton), key(QtCore.Qt.Key_Escape))
    )
    assert d.design.arrays[0].rows == 3


def test_the_design_and_import_dialogs_have_ok_and_cancel(qtbot, window, monkeypatch, tmp_path):
    assert window.new_project("office", 0.5)
    d = window.doc
    window.findChild(QtWidgets.QDockWidget, "luminaires").raise_()
    # Design > Add a geometric rule...: an array first, for the rule to bind.
    add_array = button(window.luminaires_panel, "Add array…")
    ok_and_cancel(answer(lambda: QTest.mouseClick(add_array, QtCore.Qt.LeftButton), click("OK")))
    rule = menu_action(window, "Design/Add a geometric rule...")
    before = len(d.design.rules)
    seen = answer(rule.trigger, click("Cancel"))
    ok_and_cancel(seen)
    assert seen["dialog"] == "RuleDialog" and len(d.design.rules) == before
    ok_and_cancel(answer(rule.trigger, click("OK")))
    assert len(d.design.rules) == before + 1

    # A double-click on a lighting group in the tree: the intention dialog.
    tree = window.tree
    floor = tree.findItems("floor", QtCore.Qt.MatchExactly | QtCore.Qt.MatchRecursive)[0]
    floor.parent().setExpanded(True)  # the "Surfaces" branch's arrow
    tree.scrollToItem(floor)
    at = tree.visualItemRect(floor).center()
    before = len(d.design.intentions)

    def double_click():  # a press first, as a real double-click has
        QTest.mouseClick(tree.viewport(), QtCore.Qt.LeftButton, QtCore.Qt.NoModifier, at)
        QTest.mouseDClick(tree.viewport(), QtCore.Qt.LeftButton, QtCore.Qt.NoModifier, at)

    seen = answer(double_click, key(QtCore.Qt.Key_Escape))
    ok_and_cancel(seen)
    assert seen["dialog"] == "IntentionDialog" and len(d.design.intentions) == before

    # File > Import model...: the file chooser answers with a small OBJ room.
    obj = tmp_path / "box.obj"
    obj.write_text(
        "v 0 0 0\nv 4 0 0\nv 4 3 0\nv 0 3 0\nv 0 0 2.5\nv 4 0 2.5\nv 4 3 2.5\nv 0 3 2.5\n"
        "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n"
    )
    monkeypatch.setattr(ask, "open_file", lambda *a, **k: str(obj))
    seen = answer(menu_action(window, "File/Import model...").trigger, click("Cancel"))
    ok_and_cancel(seen)
    assert seen["dialog"] == "ImportDialog" and d.scene.name == "office"
