"""What a user can do in the window, for tests that do only that: find a widget by the
text it shows, click it at its centre with the mouse, type into it with the keyboard,
answer a modal dialog by clicking its buttons, choose a file in the file dialog by
typing its path, and drag or click in the 3D view at the pixel where a world point is
drawn. Nothing here calls the window's document or a private method.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from PySide6 import QtCore, QtGui, QtWidgets
from PySide6.QtTest import QTest

LEFT = QtCore.Qt.LeftButton


def wait_for(condition: Callable[[], bool], timeout_ms: int) -> bool:
    """Process events until ``condition()`` holds or ``timeout_ms`` pass; whether it
    held (PySide6's QTest has no qWaitFor)."""
    timer = QtCore.QElapsedTimer()
    timer.start()
    while not condition():
        if timer.elapsed() > timeout_ms:
            return False
        QTest.qWait(20)
    return True


def plain(text: str) -> str:
    """``text`` as shown: the mnemonic "&" dropped, "…" and "..." alike."""
    return text.replace("&", "").replace("…", "...").strip()


def shown(widget: QtWidgets.QWidget) -> bool:
    """Whether ``widget`` is on screen (visible, not clipped away entirely)."""
    return widget.isVisible() and not widget.visibleRegion().isEmpty()


def click(widget: QtWidgets.QWidget, pos: QtCore.QPoint | None = None, button=LEFT) -> None:
    """A mouse click on ``widget`` at ``pos`` (its centre by default)."""
    assert widget.isEnabled(), f"{widget!r} is disabled"
    QTest.mouseClick(widget, button, QtCore.Qt.NoModifier, pos or widget.rect().center())


def double_click(widget: QtWidgets.QWidget, pos: QtCore.QPoint) -> None:
    """A double-click as the mouse makes it: a click, then the double-click."""
    QTest.mouseClick(widget, LEFT, QtCore.Qt.NoModifier, pos)
    QTest.mouseDClick(widget, LEFT, QtCore.Qt.NoModifier, pos)


def type_text(widget: QtWidgets.QWidget, text: str) -> None:
    """Click into ``widget``, select what it holds (Ctrl+A) and type ``text``."""
    target = widget.lineEdit() if hasattr(widget, "lineEdit") and widget.lineEdit() else widget
    click(target)
    QTest.keyClick(target, QtCore.Qt.Key_A, QtCore.Qt.ControlModifier)
    QTest.keyClicks(target, text)


def type_number(box: QtWidgets.QAbstractSpinBox, text: str) -> None:
    """Click into the number field ``box``, select what it holds, type ``text`` and
    leave it with Tab (the field reports one edit when typing is done)."""
    click(box)
    QTest.keyClick(box, QtCore.Qt.Key_A, QtCore.Qt.ControlModifier)
    type_text(box, text)
    QTest.keyClick(box, QtCore.Qt.Key_Tab)


def form_row(widget: QtWidgets.QWidget, text: str) -> list[QtWidgets.QWidget]:
    """The widgets of the form row labelled ``text`` in ``widget`` (a row of several)."""
    for form in widget.findChildren(QtWidgets.QFormLayout):
        for row in range(form.rowCount()):
            lab = form.itemAt(row, QtWidgets.QFormLayout.LabelRole)
            if lab is not None and plain(lab.widget().text()) == text:
                cell = form.itemAt(row, QtWidgets.QFormLayout.FieldRole).layout()
                return [cell.itemAt(i).widget() for i in range(cell.count())]
    raise AssertionError(f"no row {text!r}")


def press(widget: QtWidgets.QWidget, key, modifiers=QtCore.Qt.NoModifier) -> None:
    """A key pressed while ``widget`` has the focus."""
    QTest.keyClick(widget, key, modifiers)


def button(parent: QtWidgets.QWidget, text: str) -> QtWidgets.QAbstractButton:
    """The one button inside ``parent`` showing ``text``, scrolled into sight if its
    panel scrolls."""
    found = [
        b
        for b in parent.findChildren(QtWidgets.QAbstractButton)
        if plain(b.text()) == plain(text) and b.isVisible()
    ]
    assert len(found) == 1, f"{len(found)} buttons {text!r} in {parent!r}"
    return reveal(found[0])


def reveal(widget: QtWidgets.QWidget) -> QtWidgets.QWidget:
    """Turn the mouse wheel over the scroll area ``widget`` is in until all of it is in
    sight (as a user scrolls a panel taller than the screen); ``widget`` returned."""
    area = widget.parentWidget()
    while area is not None and not isinstance(area, QtWidgets.QScrollArea):
        area = area.parentWidget()
    for _ in range(60):
        if area is None or whole(widget):
            break
        # Down while the widget is below the area's middle, else up.
        centre = widget.mapTo(area.viewport(), widget.rect().center())
        step = -120 if centre.y() > area.viewport().height() // 2 else 120
        at = QtCore.QPointF(area.viewport().rect().center())
        wheel = QtGui.QWheelEvent(
            at,
            area.viewport().mapToGlobal(at),
            QtCore.QPoint(0, 0),
            QtCore.QPoint(0, step),
            QtCore.Qt.NoButton,
            QtCore.Qt.NoModifier,
            QtCore.Qt.NoScrollPhase,
            False,
        )
        QtWidgets.QApplication.sendEvent(area.viewport(), wheel)
        QtWidgets.QApplication.processEvents()
    assert whole(widget), f"{widget!r} cannot be scrolled into sight"
    return widget


def whole(widget: QtWidgets.QWidget) -> bool:
    """Whether all of ``widget`` is drawn (not cut by a scroll area or the window)."""
    return widget.isVisible() and widget.visibleRegion().boundingRect().size() == widget.size()


def label(parent: QtWidgets.QWidget, starts: str) -> QtWidgets.QLabel:
    """The first label on screen inside ``parent`` whose text starts with ``starts``."""
    for lab in parent.findChildren(QtWidgets.QLabel):
        if shown(lab) and plain(lab.text()).startswith(starts):
            return lab
    raise AssertionError(f"no label {starts!r} on screen")


def field(dialog: QtWidgets.QWidget, text: str) -> QtWidgets.QWidget:
    """The input of the form row labelled ``text`` on screen in ``dialog``."""
    for form in dialog.findChildren(QtWidgets.QFormLayout):
        for row in range(form.rowCount()):
            item = form.itemAt(row, QtWidgets.QFormLayout.LabelRole)
            lab = item.widget() if item is not None else None
            if not isinstance(lab, QtWidgets.QLabel) or plain(lab.text()) != plain(text):
                continue
            if not shown(lab):  # a row of a page or tab not on screen
                continue
            cell = form.itemAt(row, QtWidgets.QFormLayout.FieldRole)
            return cell.widget() or cell.layout().itemAt(0).widget()
    raise AssertionError(f"no field {text!r} in {dialog.windowTitle()!r}")


def beside(parent: QtWidgets.QWidget, text: str) -> QtWidgets.QWidget:
    """The input right of the label showing ``text`` in a grid of label/input pairs."""
    for grid in parent.findChildren(QtWidgets.QGridLayout):
        for i in range(grid.count()):
            lab = grid.itemAt(i).widget()
            if not isinstance(lab, QtWidgets.QLabel) or plain(lab.text()) != plain(text):
                continue
            if not shown(lab):
                continue
            row, col, _, _ = grid.getItemPosition(i)
            cell = grid.itemAtPosition(row, col + 1)
            if cell is not None and cell.widget() is not None:
                return cell.widget()
    raise AssertionError(f"no input beside {text!r}")


def choose(combo: QtWidgets.QComboBox, text: str) -> None:
    """Open ``combo``'s list with a click and click the entry starting with ``text``."""
    view = combo.view()
    for _ in range(3):
        click(combo)
        # A click just after the list closed can be taken as that close's echo: the list
        # does not open, and the user clicks the box again.
        if QTest.qWaitForWindowExposed(view.window(), 2000) and view.isVisible():
            break
        QTest.qWait(QtWidgets.QApplication.doubleClickInterval() + 100)
    assert view.isVisible(), f"the list of {text!r} did not open after three clicks"
    # The list ignores a release this soon after it opened (a press-drag-release choice).
    QTest.qWait(QtWidgets.QApplication.doubleClickInterval() + 100)
    model = view.model()
    rows = [r for r in range(model.rowCount()) if plain(combo.itemText(r)).startswith(text)]
    assert rows, f"no entry {text!r} in {[combo.itemText(r) for r in range(combo.count())]}"
    index = model.index(rows[0], combo.modelColumn())
    view.scrollTo(index)
    picked: list[int] = []
    slot = picked.append
    combo.activated.connect(slot)
    try:
        for _ in range(3):
            click(view.viewport(), view.visualRect(index).center())
            # On a loaded machine the list can still take the release for the end of the
            # opening click and stay open: the user clicks the entry again.
            for _ in range(40):
                QTest.qWait(50)
                if not view.isVisible():
                    # Chosen, not dismissed (a preset box may show its header again).
                    assert picked == [rows[0]], f"{text!r} not chosen (activated {picked})"
                    return
    finally:
        combo.activated.disconnect(slot)
    raise AssertionError(f"the list of {text!r} stayed open after three clicks")


def tab(window: QtWidgets.QWidget, text: str) -> None:
    """Click the tab showing ``text`` (a dock's tab or a tab widget's)."""
    for bar in window.findChildren(QtWidgets.QTabBar):
        if not shown(bar):
            continue
        for i in range(bar.count()):
            if plain(bar.tabText(i)) == plain(text):
                click(bar, bar.tabRect(i).center())
                QTest.qWait(100)
                return
    raise AssertionError(f"no tab {text!r} on screen")


def menu(window: QtWidgets.QMainWindow, *path: str) -> None:
    """Open the menu bar's menus along ``path`` with the mouse and click the last entry
    ("File", "Import model..."); an entry that opens a modal dialog returns once it is
    answered (see ``answer``)."""
    bar = window.menuBar()
    actions = bar.actions()
    act = _entry(actions, path[0])
    click(bar, bar.actionGeometry(act).center())
    current = act.menu()
    for name in path[1:]:
        QTest.qWaitForWindowExposed(current)
        act = _entry(current.actions(), name)
        assert act.isEnabled(), f"{' > '.join(path)} is disabled"
        click(current, current.actionGeometry(act).center())
        current = act.menu()


def _entry(actions, name: str) -> QtGui.QAction:
    found = [a for a in actions if plain(a.text()) == plain(name) and a.isVisible()]
    assert found, f"no menu entry {name!r} in {[plain(a.text()) for a in actions]}"
    return found[0]


def toolbar_button(window: QtWidgets.QMainWindow, text: str) -> QtWidgets.QToolButton:
    """The toolbar button showing ``text``."""
    for bar in window.findChildren(QtWidgets.QToolBar):
        for b in bar.findChildren(QtWidgets.QToolButton):
            if shown(b) and plain(b.text()) == plain(text):
                return b
    raise AssertionError(f"no toolbar button {text!r}")


def table_cell(table: QtWidgets.QTableWidget, text: str) -> QtWidgets.QTableWidgetItem:
    """The first cell of ``table`` showing ``text`` (starts with it)."""
    for r in range(table.rowCount()):
        for c in range(table.columnCount()):
            item = table.item(r, c)
            if item is not None and item.text().startswith(text):
                return item
    raise AssertionError(f"no cell {text!r} in the table")


def click_cell(table: QtWidgets.QTableWidget, text: str) -> None:
    """Click the cell of ``table`` showing ``text``."""
    item = table_cell(table, text)
    table.scrollToItem(item)
    click(table.viewport(), table.visualItemRect(item).center())


def tree_item(tree: QtWidgets.QTreeWidget, text: str) -> QtWidgets.QTreeWidgetItem:
    """The item of ``tree`` whose first column is ``text``."""
    found = tree.findItems(text, QtCore.Qt.MatchExactly | QtCore.Qt.MatchRecursive)
    assert found, f"no item {text!r} in the tree"
    return found[0]


def click_tree(tree: QtWidgets.QTreeWidget, text: str) -> None:
    """Click the tree's item ``text`` (its branch expanded first, as a user would)."""
    item = tree_item(tree, text)
    parent = item.parent()
    while parent is not None:
        parent.setExpanded(True)
        parent = parent.parent()
    tree.scrollToItem(item)
    click(tree.viewport(), tree.visualItemRect(item).center())
    QTest.qWait(100)


def tree_texts(tree: QtWidgets.QTreeWidget, branch: str) -> dict[str, str]:
    """{name: details} of the items under the tree's top-level item ``branch``."""
    top = tree_item(tree, branch)
    return {top.child(i).text(0): top.child(i).text(1) for i in range(top.childCount())}


# -- modal dialogs ------------------------------------------------------------------------
def answer(open_it: Callable[[], object], *responses: Callable) -> list[str]:
    """Do ``open_it`` (it shows modal dialogs and waits), and answer the dialogs shown,
    in turn, with ``responses`` (each takes the dialog, with the mouse and keyboard).

    A failing test cannot hang: a dialog still open after its answer, or one whose
    answer failed, is rejected, and so is every dialog shown after a failure; the
    failure is raised once ``open_it`` returns. Returns the titles of the dialogs
    answered, as the user saw them."""
    seen: list = []
    titles: list[str] = []
    todo = list(responses)
    done: list[bool] = []
    failed: list[BaseException] = []

    def poll() -> None:
        if done:
            return
        dialog = QtWidgets.QApplication.activeModalWidget()
        if dialog is not None and failed:
            dialog.reject()  # after a failure: close whatever else opens
        elif dialog is not None and not todo and not (seen and dialog is seen[-1]):
            # A dialog nobody expected (an error message): the test fails, not hangs.
            titles.append(dialog.windowTitle())
            text = getattr(dialog, "text", lambda: "")()
            failed.append(AssertionError(f"unexpected dialog {titles[-1]!r}: {text}"))
            dialog.reject()
        elif dialog is not None and not (seen and dialog is seen[-1]) and todo:
            seen.append(dialog)
            titles.append(dialog.windowTitle())
            respond = todo.pop(0)
            try:
                QTest.qWaitForWindowExposed(dialog)
                respond(dialog)
                QTest.qWait(50)
                if dialog.isVisible() and QtWidgets.QApplication.activeModalWidget() is dialog:
                    titles.append("left open")
                    dialog.reject()
            except BaseException as exc:  # re-raised below, outside the Qt event loop
                failed.append(exc)
                if dialog.isVisible():
                    dialog.reject()
        QtCore.QTimer.singleShot(40, poll)

    QtCore.QTimer.singleShot(0, poll)
    try:
        open_it()
    finally:
        done.append(True)
    if failed:
        raise AssertionError(f"answering {titles[-1]!r} failed: {failed[0]!r}") from failed[0]
    assert "left open" not in titles, f"a dialog was left open: {titles}"
    assert not todo, f"{len(todo)} dialog(s) never shown; seen {titles}"
    return titles


def ok(dialog: QtWidgets.QWidget) -> None:
    """Click the dialog's OK button."""
    click(button(dialog, "OK"))


def click_text(text: str) -> Callable[[QtWidgets.QWidget], None]:
    """An answer: click the dialog's button showing ``text``."""
    return lambda dialog: click(button(dialog, text))


def file_name(path: Path) -> Callable[[QtWidgets.QWidget], None]:
    """An answer to a file dialog: type ``path`` into its file name box, click Open
    (or Save)."""

    def respond(dialog: QtWidgets.QWidget) -> None:
        assert isinstance(dialog, QtWidgets.QFileDialog), f"not a file dialog: {dialog!r}"
        box = next(
            lab.buddy()
            for lab in dialog.findChildren(QtWidgets.QLabel)
            if plain(lab.text()).startswith("File name") and lab.buddy() is not None
        )
        buttons = dialog.findChild(QtWidgets.QDialogButtonBox)
        accept = [
            b
            for b in buttons.buttons()
            if buttons.buttonRole(b) == QtWidgets.QDialogButtonBox.AcceptRole and shown(b)
        ]
        typed = []
        # The dialog lists the folder while the name is typed, and now and then puts
        # the name of the file it selects back into the box: type it again, as one does.
        for _ in range(3):
            type_text(box, str(path))
            typed.append(box.text())
            # The button is enabled once the dialog has taken the name in (later on a
            # busy machine), as a user waits to see it enabled.
            # A busy machine lists the folder late; the dialog may judge the name before
            # then and leave the button off until the name changes: type it again.
            if not wait_for(accept[0].isEnabled, 10_000):
                typed[-1] += " (button disabled)"
                continue
            # Its Open / Save button, not Enter: Enter may go to the completer's list.
            click(accept[0])
            if wait_for(lambda: not dialog.isVisible(), 1000):
                return
        raise AssertionError(f"the file dialog took none of {typed}")

    return respond


# -- the 3D view --------------------------------------------------------------------------
def view_pixel(viewport, world) -> QtCore.QPointF:
    """Where the 3D view draws the world point ``world`` (widget pixels)."""
    ren = viewport.plotter.renderer
    ren.SetWorldPoint(*world, 1.0)
    ren.WorldToDisplay()
    x, y, _ = ren.GetDisplayPoint()
    h = viewport.plotter.interactor.height()
    return QtCore.QPointF(x, h - 1 - y)


def _mouse(widget, kind, pos: QtCore.QPointF, button=LEFT, buttons=None) -> None:
    if buttons is None:
        buttons = QtCore.Qt.NoButton if kind == QtCore.QEvent.Type.MouseButtonRelease else button
    event = QtGui.QMouseEvent(
        kind, pos, widget.mapToGlobal(pos), button, buttons, QtCore.Qt.NoModifier
    )
    QtWidgets.QApplication.sendEvent(widget, event)


def view_drag(viewport, a, b, steps: int = 4) -> None:
    """Press the left button where world point ``a`` is drawn, move in ``steps`` to
    where ``b`` is drawn, release (the mouse events VTK's Qt widget gets)."""
    iw = viewport.plotter.interactor
    start, end = view_pixel(viewport, a), view_pixel(viewport, b)
    _mouse(iw, QtCore.QEvent.Type.MouseButtonPress, start)
    for k in range(1, steps + 1):
        t = k / steps
        at = QtCore.QPointF(
            start.x() + t * (end.x() - start.x()), start.y() + t * (end.y() - start.y())
        )
        _mouse(iw, QtCore.QEvent.Type.MouseMove, at, QtCore.Qt.NoButton, LEFT)
        QTest.qWait(20)
    _mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, end)


def view_click(viewport, world, double: bool = False) -> None:
    """A left click (or double-click) where world point ``world`` is drawn."""
    iw = viewport.plotter.interactor
    at = view_pixel(viewport, world)
    _mouse(iw, QtCore.QEvent.Type.MouseButtonPress, at)
    _mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, at)
    if double:
        _mouse(iw, QtCore.QEvent.Type.MouseButtonDblClick, at)
        _mouse(iw, QtCore.QEvent.Type.MouseButtonRelease, at)


def drawn_centre(viewport, layer: str) -> tuple[float, float, float]:
    """The centre (m) of what the 3D view draws as ``layer`` ("current": the current
    source's green outline)."""
    actor = viewport.plotter.actors[layer]
    x0, x1, y0, y1, z0, z1 = actor.GetBounds()
    return ((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2)


def view_key(viewport, key) -> None:
    """A key pressed with the 3D view focused."""
    QTest.keyClick(viewport.plotter.interactor, key)


def screenshot(window: QtWidgets.QWidget, folder: Path, name: str) -> Path:
    """The whole window as the screen shows it (the 3D view included), as a PNG."""
    folder.mkdir(parents=True, exist_ok=True)
    QtWidgets.QApplication.processEvents()
    path = folder / f"{name}.png"
    screen = window.screen()
    pixmap = screen.grabWindow(0, *window.frameGeometry().getRect())
    pixmap.save(str(path))
    return path
