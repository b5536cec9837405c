"""The "Achieved" tab: every lighting intention of the design on screen, live.

For each bound of each intention: what is required, what the design as shown (hand
edits, a dragged source, a loaded result) achieves on every patch of the intention,
and whether it holds (to the tolerance the optimiser judges with). It refreshes with
the light, so dragging a source shows the desks' average and U0 change as it moves.
Intentions on a work plane read its grid points (EN 12464-1: Em the plain mean).
"""

from __future__ import annotations

import numpy as np
from PySide6 import QtGui, QtWidgets

from app.document import Document
from app.results_panel import distinct
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Bound
from lightinv_core.light.intentions import bound_checks, intention_stats

COLUMNS = ("intention", "bound", "required", "achieved", "units", "")
OK, NOT_OK = "met", "not met"
LABELS = {
    Bound.MIN: "min ≥",
    Bound.MAX: "max ≤",
    Bound.AVERAGE: "average ≥",
    Bound.UNIFORMITY: "U0 ≥",
}


class AchievedPanel(QtWidgets.QWidget):
    """Required against achieved for every intention bound of the design on screen."""

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        lay = QtWidgets.QVBoxLayout(self)
        self.summary = QtWidgets.QLabel()
        self.summary.setWordWrap(True)
        lay.addWidget(self.summary)
        self.table = QtWidgets.QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(COLUMNS)
        self.table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
        self.table.verticalHeader().hide()
        lay.addWidget(self.table)
        # Every design edit relights once an operator exists (lightingChanged follows
        # designChanged); before it, only the scene's arrival matters.
        doc.lightingChanged.connect(self.refresh)
        doc.sceneChanged.connect(self.refresh)
        self.refresh()

    def rows(self) -> list[tuple[str, str, str, str, str, bool]]:
        """(intention, bound, required, achieved, units, met) of the design's light."""
        d = self.doc
        field = d.design_field() if d.project is not None else None
        if field is None:
            return []
        out = []
        grids, lux = d.shown_grids()
        for it in d.design.intentions:
            if it.grid is not None:
                if grids is None or lux is None or it.grid not in grids.spans:
                    continue
                q = lux[grids.spans[it.grid]][:, None]
                checks = bound_checks(it, intention_stats(q, np.ones(len(q))))
            else:
                try:
                    checks = field.intention(it).checks
                except LightInvError:
                    continue  # its patches are not in this scene (the tree says why)
            for chk in checks:
                achieved, required = distinct(float(chk.value[0]), float(chk.limit))
                units = "" if chk.bound == Bound.UNIFORMITY else chk.units
                out.append(
                    (it.name, LABELS[chk.bound], required, achieved, units, bool(chk.met[0]))
                )
        return out

    def refresh(self) -> None:
        rows = self.rows()
        d = self.doc
        if d.project is None or d.design_field() is None:
            self.summary.setText("Lighting appears once the radiosity operator is ready.")
        elif not d.design.intentions:
            self.summary.setText(
                "No lighting intentions yet: double-click a group in the tree to add one."
            )
        else:
            bad = sum(not r[5] for r in rows)
            self.summary.setText(
                "The design on screen meets every lighting intention."
                if not bad
                else f"The design on screen misses {bad} of {len(rows)} bounds (red)."
            )
        self.table.setRowCount(len(rows))
        red, green = QtGui.QColor("#fbd5d5"), QtGui.QColor("#d9f2d9")
        for r, (*cells, met) in enumerate(rows):
            for c, text in enumerate((*cells, OK if met else NOT_OK)):
                item = QtWidgets.QTableWidgetItem(text)
                item.setBackground(green if met else red)
                self.table.setItem(r, c, item)
        self.table.resizeColumnsToContents()
