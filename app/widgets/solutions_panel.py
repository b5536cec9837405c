"""Browsing results: the run history and the solutions (Pareto front, seeds, pinned).

Which run's results to browse (one run, the saved results or all of them; each run's
method, settings and outcome in one line; a run can be deleted, and Edit > Undo brings it
back), a scatter on two chosen axes (every registered goal, each source type's area and
strength: ``view.scatter_axes``) and a table of those results; clicking a point or a row
loads that result into the design (viewport and source list); results can be pinned
(offered for comparison, kept when their run is deleted, saved with the project) and the
view can show the difference between the loaded result and a pinned one.
"""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets

from app.document import Document
from app.view.scatter_axes import axes, axis_label, axis_value, front_axes
from app.view.solution_scatter import SolutionScatter
from app.widgets.numbers import fmt
from lightinv_core.editing.results import ALL, SAVED, browse, method_label, run_label
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import GoalKind

COLUMNS = ("result", "feasible", "x", "y", "penalty", "pinned")
"""The table's columns; the two values are those of the scatter's x and y axes."""


class SolutionsPanel(QtWidgets.QWidget):
    """Scatter + table of the project's results, pin, compare."""

    compareChanged = QtCore.Signal()
    runDeleted = QtCore.Signal(int)

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        self.entries: list = []  # results.Entry (label, solution, run) as listed
        self._front_objectives: tuple | None = None  # the front whose axes are chosen
        self.pinned_list: list = []  # the pinned results the compare list offers
        outer = QtWidgets.QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        runs = QtWidgets.QHBoxLayout()
        self.run_choice = QtWidgets.QComboBox()
        self.run_choice.setSizeAdjustPolicy(QtWidgets.QComboBox.AdjustToContents)
        self.delete_run_button = QtWidgets.QPushButton("Delete run")
        self.delete_run_button.setToolTip("Delete this run and its results (Edit > Undo)")
        runs.addWidget(QtWidgets.QLabel("Results of"))
        runs.addWidget(self.run_choice)
        runs.addWidget(self.delete_run_button)
        self.run_info = QtWidgets.QLabel("")
        self.run_info.setWordWrap(True)
        runs.addWidget(self.run_info, 1)
        outer.addLayout(runs)
        lay = QtWidgets.QHBoxLayout()
        outer.addLayout(lay, 1)
        left = QtWidgets.QVBoxLayout()
        row_axes = QtWidgets.QHBoxLayout()
        self.x_axis, self.y_axis = QtWidgets.QComboBox(), QtWidgets.QComboBox()
        defaults = (GoalKind.MIN_ELECTRIC_POWER, GoalKind.MAX_LIGHT_POWER)
        for box, default in zip((self.x_axis, self.y_axis), defaults, strict=True):
            for key, (label, _) in axes().items():
                box.addItem(label, key)
            box.setCurrentIndex(box.findData(str(default)))
            box.currentIndexChanged.connect(self.refresh)
        row_axes.addWidget(QtWidgets.QLabel("x"))
        row_axes.addWidget(self.x_axis)
        row_axes.addWidget(QtWidgets.QLabel("y"))
        row_axes.addWidget(self.y_axis)
        left.addLayout(row_axes)
        self.scatter = SolutionScatter()
        left.addWidget(self.scatter, 1)
        lay.addLayout(left, 1)
        right = QtWidgets.QVBoxLayout()
        self.table = QtWidgets.QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(COLUMNS)
        self.table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectRows)
        self.table.setSelectionMode(QtWidgets.QAbstractItemView.SingleSelection)
        self.table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
        self.table.verticalHeader().setVisible(False)
        self.table.horizontalHeader().setStretchLastSection(True)
        right.addWidget(self.table, 1)
        row = QtWidgets.QHBoxLayout()
        self.pin_button = QtWidgets.QPushButton("Pin / unpin")
        self.compare = QtWidgets.QComboBox()
        self.difference = QtWidgets.QCheckBox("show loaded minus")
        row.addWidget(self.pin_button)
        row.addWidget(self.difference)
        row.addWidget(self.compare, 1)
        right.addLayout(row)
        self.summary = QtWidgets.QLabel("No results yet: press Run.")
        right.addWidget(self.summary)
        lay.addLayout(right, 1)

        self.run_choice.activated.connect(self._run_chosen)
        self.delete_run_button.clicked.connect(self.delete_run)
        self.scatter.clicked.connect(self.load)
        self.table.cellClicked.connect(lambda r, _c: self.load(r))
        self.pin_button.clicked.connect(self.toggle_pin)
        self.difference.toggled.connect(self.compareChanged)
        self.compare.currentIndexChanged.connect(self._compare_edited)
        doc.resultsChanged.connect(self.refresh)
        doc.sceneChanged.connect(self._new_project)

    # -- document -> widgets ----------------------------------------------------------------
    def refresh(self) -> None:
        """Rebuild the run list, table, scatter and compare list from the project's
        results."""
        if self.doc.project is None:
            return
        self._fill_runs()
        self._front_axes()
        self.entries = self.doc.results()
        sols = [e.solution for e in self.entries]
        on_front = [self.doc.on_front(s) for s in sols]
        pinned = [s.info.pinned for s in sols]
        chosen = self.index_of(self.doc.shown)
        self.table.blockSignals(True)
        self.table.setRowCount(len(sols))
        ax, ay = self.x_axis.currentData(), self.y_axis.currentData()
        self.table.setHorizontalHeaderLabels(
            (*COLUMNS[:2], axis_label(ax), axis_label(ay), *COLUMNS[4:])
        )
        rows = zip(self.entries, on_front, pinned, strict=True)
        for r, (entry, front, pin) in enumerate(rows):
            s = entry.solution
            cells = (
                entry.label + (" (front)" if front else ""),
                "yes" if s.feasible else "no",
                fmt(axis_value(s, ax)),
                fmt(axis_value(s, ay)),
                f"{s.penalty:.3g}",
                "pinned" if pin else "",
            )
            for c, text in enumerate(cells):
                item = QtWidgets.QTableWidgetItem(text)
                if c >= 2:
                    item.setTextAlignment(QtCore.Qt.AlignRight | QtCore.Qt.AlignVCenter)
                self.table.setItem(r, c, item)
        if chosen is not None:
            self.table.selectRow(chosen)
        self.table.blockSignals(False)
        self.table.resizeColumnsToContents()
        axes = (self.x_axis.currentData(), self.y_axis.currentData())
        groups = [e.run for e in self.entries]
        self.scatter.set_results(sols, on_front, pinned, axes, chosen, groups)
        self._fill_compare()
        n_front = sum(on_front)
        # A result listed twice (in its run and among the saved results) is one pin.
        n_pinned = len({e.solution.x for e, p in zip(self.entries, pinned, strict=True) if p})
        front = self.doc.front()
        method = method_label(front.method) if front is not None else ""  # NSGA-II, not nsga2
        q = self.doc.front_quality() if n_front else None
        quality = ""
        if q is not None:
            spread = "–" if q.spacing is None else f"{q.spacing:.4f}"
            quality = f"\nfront hypervolume {q.hypervolume:.4f}, spacing {spread} (normalised)"
        fronts = len({e.run for e, f in zip(self.entries, on_front, strict=True) if f})
        where = f"the {method} front" if fronts <= 1 else f"{fronts} fronts"
        self.summary.setText(
            f"{len(sols)} results"
            + (f", {n_front} on {where}" if n_front else "")
            + (f", {n_pinned} pinned" if n_pinned else "")
            + quality
            if sols
            else "No results yet: press Run."
        )

    def _new_project(self) -> None:
        """Another project (or scene): its front chooses the axes again, and the plot's
        ranges are its own, not the previous project's."""
        self._front_objectives = None
        self.scatter.reset_view()

    def _front_axes(self) -> None:
        """Put the browsed front's two objectives on the axes when the front's
        objectives change (power against light, or annual energy against glazing area);
        the axes picked by hand stay while they do not."""
        front = self.doc.front()
        objectives = tuple(front.objectives) if front is not None else None
        if objectives is None or objectives == self._front_objectives:
            return
        self._front_objectives = objectives
        try:
            x, y = front_axes(objectives)
        except (KeyError, ValueError):  # a goal kind this window does not know
            return
        for box, key in ((self.x_axis, x), (self.y_axis, y)):
            box.blockSignals(True)
            box.setCurrentIndex(max(box.findData(key), 0))
            box.blockSignals(False)

    def _fill_runs(self) -> None:
        """The run picker: every run, the saved results (when there are some), or all."""
        d = self.doc
        self.run_choice.blockSignals(True)
        self.run_choice.clear()
        self.run_choice.addItem(f"all runs ({len(d.runs)})", ALL)
        if d.project.solutions or d.project.pareto is not None:
            self.run_choice.addItem("saved results", SAVED)
        for run in reversed(d.runs):  # newest first
            self.run_choice.addItem(f"{run_label(run)} ({run.status or 'ended'})", run.number)
        self.run_choice.setCurrentIndex(max(self.run_choice.findData(d.browsed_run), 0))
        self.run_choice.blockSignals(False)
        number = d.browsed_run
        one = number is not ALL and number != SAVED
        self.delete_run_button.setEnabled(one)
        if one:
            self.run_info.setText(d.run_summary(number))
        elif number == SAVED:
            self.run_info.setText(
                "results kept outside the run history (an older file, "
                "lightinv-cli solve, pinned results of a deleted run)"
            )
        else:
            self.run_info.setText(
                f"{len(d.runs)} runs kept; pick one to see its settings" if d.runs else ""
            )

    def _run_chosen(self, index: int) -> None:
        self.doc.browse_run(self.run_choice.itemData(index))

    def choose_run(self, number: int | None) -> bool:
        """Browse run ``number`` (``ALL`` (None): every run; ``SAVED`` (0): the saved
        results); False if the list does not offer it."""
        i = self.run_choice.findData(number)
        if i < 0:
            return False
        self.run_choice.setCurrentIndex(i)
        self._run_chosen(i)
        return True

    def delete_run(self) -> None:
        """Delete the run browsed and its results (pinned ones are kept); Edit > Undo
        brings it back."""
        number = self.doc.browsed_run
        if number is ALL or number == SAVED:
            return
        self.doc.delete_run(number)
        self.runDeleted.emit(number)

    def _fill_compare(self) -> None:
        current = self.compare.currentData()
        self.compare.blockSignals(True)
        self.compare.clear()
        self.pinned_list = self.doc.pinned()
        ax = self.x_axis.currentData()
        for i, s in enumerate(self.pinned_list):
            value = f"{axis_label(ax)} {fmt(axis_value(s, ax))}"
            self.compare.addItem(f"pinned: {_pinned_label(self.doc, s)}, {value}", i)
        if current is not None and self.compare.findData(current) >= 0:
            self.compare.setCurrentIndex(self.compare.findData(current))
        self.compare.blockSignals(False)
        has = self.compare.count() > 0
        self.difference.setEnabled(has)
        if not has and self.difference.isChecked():
            self.difference.setChecked(False)

    def index_of(self, solution) -> int | None:
        """Row of ``solution`` among the listed results (None if not listed)."""
        if solution is None:
            return None
        return next((i for i, e in enumerate(self.entries) if e.solution.x == solution.x), None)

    # -- actions ------------------------------------------------------------------------------
    def load(self, index: int) -> bool:
        """Load result ``index`` into the design (viewport and source list)."""
        if not 0 <= index < len(self.entries):
            return False
        try:
            self.doc.apply_solution(self.entries[index].solution)
        except LightInvError as exc:
            QtWidgets.QMessageBox.warning(self, "LightInv", str(exc))
            return False
        return True

    def toggle_pin(self) -> None:
        """Pin the selected result (or unpin it)."""
        rows = self.table.selectionModel().selectedRows()
        if not rows:
            QtWidgets.QMessageBox.information(self, "LightInv", "Select a result to pin first.")
            return
        s = self.entries[rows[0].row()].solution
        self.doc.pin(s, not s.info.pinned)

    def _compare_edited(self) -> None:
        if self.difference.isChecked():
            self.compareChanged.emit()

    def compared(self):
        """The pinned result the view subtracts, or None when not comparing."""
        if not self.difference.isChecked() or self.compare.currentData() is None:
            return None
        i = self.compare.currentData()
        return self.pinned_list[i] if i < len(self.pinned_list) else None


def _pinned_label(doc: Document, solution) -> str:
    """A pinned result's name: its run and label ("run 2: seed 3")."""
    entry = next((e for e in browse(doc.project, ALL) if e.solution.x == solution.x), None)
    return entry.label if entry is not None else "result"
