"""The Violations tab: the loaded result's violated rules and intentions with their
amounts; the patches that break an intention are highlighted in the viewport."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore, QtWidgets

from app.document import Document
from app.widgets.numbers import distinct


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
            # The solution's own penalty (optimize/judge.py ``penalty``), the number the
            # results table and the report show: the sum of weight x off-by^power below.
            # A broken geometric rule has no light to judge: no finite penalty.
            pen = f", penalty P = {sol.penalty:.3g}" if np.isfinite(sol.penalty) else ""
            self.summary.setText(
                f"Not feasible: {len(sol.violations)} violated{pen}"
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
