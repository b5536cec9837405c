"""Browsing results: the solutions (Pareto front, seeds, pinned) and the violations of
the loaded one.

``SolutionsPanel``: a scatter on two chosen axes and a table of every result; clicking
a point or a row loads that result into the design (viewport and source list); results
can be pinned (kept across runs, saved with the project) and the view can show the
difference between the loaded result and a pinned one.

``ViolationsPanel``: the loaded result's violated rules and intentions with their
amounts; the patches that break an intention are highlighted in the viewport.
"""

from __future__ import annotations

import math

import numpy as np
from PySide6 import QtCore, QtWidgets

from app.document import Document
from app.plots import AXES, SolutionScatter, axis_value
from lightinv_core.errors import LightInvError

COLUMNS = ("result", "feasible", "power (W)", "light (lm)", "penalty", "pinned")


def _fmt(v: float) -> str:
    return "-" if v is None or not math.isfinite(v) else f"{v:,.1f}"


def distinct(value: float, bound: float) -> tuple[str, str]:
    """A value and its bound with as many decimals as it takes to tell them apart (a U0
    of 0.593 against 0.6 read "0.6 vs 0.6, off by 1.3%"), at most 6."""
    if value is None or bound is None or not (math.isfinite(value) and math.isfinite(bound)):
        return _fmt(value), _fmt(bound)
    size = max(abs(value), abs(bound))
    d = 1 if size >= 10 else (2 if size >= 1 else 3)
    while d < 6 and value != bound and f"{value:,.{d}f}" == f"{bound:,.{d}f}":
        d += 1
    return f"{value:,.{d}f}", f"{bound:,.{d}f}"


class SolutionsPanel(QtWidgets.QWidget):
    """Scatter + table of the project's results, pin, compare."""

    compareChanged = QtCore.Signal()

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        self.entries: list = []  # (label, Solution) as listed
        lay = QtWidgets.QHBoxLayout(self)
        left = QtWidgets.QVBoxLayout()
        axes = QtWidgets.QHBoxLayout()
        self.x_axis, self.y_axis = QtWidgets.QComboBox(), QtWidgets.QComboBox()
        for box, default in ((self.x_axis, "power"), (self.y_axis, "light")):
            for key, (label, _) in AXES.items():
                box.addItem(label, key)
            box.setCurrentIndex(box.findData(default))
            box.currentIndexChanged.connect(self.refresh)
        axes.addWidget(QtWidgets.QLabel("x"))
        axes.addWidget(self.x_axis)
        axes.addWidget(QtWidgets.QLabel("y"))
        axes.addWidget(self.y_axis)
        left.addLayout(axes)
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

        self.scatter.clicked.connect(self.load)
        self.table.cellClicked.connect(lambda r, _c: self.load(r))
        self.pin_button.clicked.connect(self.toggle_pin)
        self.difference.toggled.connect(self.compareChanged)
        self.compare.currentIndexChanged.connect(self._compare_edited)
        doc.resultsChanged.connect(self.refresh)

    # -- document -> widgets ----------------------------------------------------------------
    def refresh(self) -> None:
        """Rebuild the table, scatter and compare list from the project's results."""
        if self.doc.project is None:
            return
        self.entries = self.doc.results()
        sols = [s for _, s in self.entries]
        on_front = [self.doc.on_front(s) for s in sols]
        pinned = [s.info.pinned for s in sols]
        chosen = self.index_of(self.doc.shown)
        self.table.blockSignals(True)
        self.table.setRowCount(len(sols))
        rows = zip(self.entries, on_front, pinned, strict=True)
        for r, ((label, s), front, pin) in enumerate(rows):
            cells = (
                label + (" (front)" if front else ""),
                "yes" if s.feasible else "no",
                _fmt(axis_value(s, "power")),
                _fmt(axis_value(s, "light")),
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
        self.scatter.set_results(sols, on_front, pinned, axes, chosen)
        self._fill_compare()
        n_front = sum(on_front)
        method = self.doc.project.pareto.method if self.doc.project.pareto else ""
        q = self.doc.front_quality() if n_front else None
        quality = ""
        if q is not None:
            spread = "–" if q.spacing is None else f"{q.spacing:.4f}"
            quality = f"\nfront hypervolume {q.hypervolume:.4f}, spacing {spread} (normalised)"
        self.summary.setText(
            f"{len(sols)} results"
            + (f", {n_front} on the {method} front" if n_front else "")
            + (f", {sum(pinned)} pinned" if any(pinned) else "")
            + quality
            if sols
            else "No results yet: press Run."
        )

    def _fill_compare(self) -> None:
        current = self.compare.currentData()
        self.compare.blockSignals(True)
        self.compare.clear()
        for i, (label, s) in enumerate(self.entries):
            if s.info.pinned:
                self.compare.addItem(f"pinned: {label}, {_fmt(axis_value(s, 'power'))} W", i)
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
        return next((i for i, (_, s) in enumerate(self.entries) if s.x == solution.x), None)

    # -- actions ------------------------------------------------------------------------------
    def load(self, index: int) -> bool:
        """Load result ``index`` into the design (viewport and source list)."""
        if not 0 <= index < len(self.entries):
            return False
        try:
            self.doc.apply_solution(self.entries[index][1])
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
        s = self.entries[rows[0].row()][1]
        self.doc.pin(s, not s.info.pinned)

    def _compare_edited(self) -> None:
        if self.difference.isChecked():
            self.compareChanged.emit()

    def compared(self):
        """The pinned result the view subtracts, or None when not comparing."""
        if not self.difference.isChecked() or self.compare.currentData() is None:
            return None
        i = self.compare.currentData()
        return self.entries[i][1] if i < len(self.entries) else None


class ViolationsPanel(QtWidgets.QWidget):
    """The loaded result's violated rules and intentions; highlights offending patches."""

    highlightChanged = QtCore.Signal()

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        self.offending: list = []  # (intention, bound, patch ids)
        lay = QtWidgets.QVBoxLayout(self)
        self.summary = QtWidgets.QLabel("Load a result to see whether it meets the design.")
        self.summary.setWordWrap(True)
        lay.addWidget(self.summary)
        self.table = QtWidgets.QTableWidget(0, 6)
        self.table.setHorizontalHeaderLabels(
            ("rule or intention", "bound", "value", "limit", "units", "off by")
        )
        self.table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
        self.table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectRows)
        self.table.verticalHeader().setVisible(False)
        self.table.horizontalHeader().setStretchLastSection(True)
        lay.addWidget(self.table, 1)
        self.highlight = QtWidgets.QCheckBox(
            "highlight the patches that break the selected (or every) intention"
        )
        self.highlight.setChecked(True)
        lay.addWidget(self.highlight)
        self.highlight.toggled.connect(self.highlightChanged)
        self.table.itemSelectionChanged.connect(self.highlightChanged)
        doc.resultsChanged.connect(self.refresh)
        doc.designChanged.connect(self.refresh)

    def refresh(self) -> None:
        """List the shown result's violations and find their patches."""
        sol = self.doc.shown
        self.offending = []
        self.table.blockSignals(True)
        self.table.setRowCount(0)
        if sol is None:
            self.summary.setText("Load a result to see whether it meets the design.")
        elif sol.feasible:
            self.summary.setText("Feasible: every rule and lighting intention is met.")
        else:
            self.offending = self.doc.offending_patches()
            n = sum(len(ids) for _, _, ids in self.offending)
            self.summary.setText(
                f"Not feasible: {len(sol.violations)} violated"
                + (f"; {n:,} patches out of bounds (red in the view)" if n else "")
            )
            self.table.setRowCount(len(sol.violations))
            for r, v in enumerate(sol.violations):
                value, bound = distinct(v.value, v.bound)
                cells = (v.name, v.constraint, value, bound, v.units, f"{100 * v.amount:.1f}%")
                for c, text in enumerate(cells):
                    self.table.setItem(r, c, QtWidgets.QTableWidgetItem(text))
            self.table.resizeColumnsToContents()
        self.table.blockSignals(False)
        self.highlightChanged.emit()

    def highlighted(self) -> np.ndarray:
        """Patch ids to highlight: the selected violation's, else every one's."""
        if not self.highlight.isChecked() or not self.offending:
            return np.zeros(0, np.int64)
        rows = {i.row() for i in self.table.selectionModel().selectedRows()}
        sol = self.doc.shown
        names = {(sol.violations[r].name, sol.violations[r].constraint) for r in rows}
        picked = [ids for name, bound, ids in self.offending if not names or (name, bound) in names]
        return np.unique(np.concatenate(picked)) if picked else np.zeros(0, np.int64)
