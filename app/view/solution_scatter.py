"""The result scatter (pyqtgraph): the project's results on two chosen axes
(``scatter_axes``), the Pareto front joined by a line."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6 import QtCore, QtWidgets

from app.view.scatter_axes import axis_label, axis_value


class SolutionScatter(pg.PlotWidget):
    """Results as points on two chosen axes: the Pareto front joined by a line,
    other candidates grey, pinned ones as stars, the chosen one ringed in red.
    ``clicked(index)`` gives the index of the clicked result."""

    clicked = QtCore.Signal(int)

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.showGrid(x=True, y=True, alpha=0.3)
        self.setMinimumHeight(180)
        self.front_pen = pg.mkPen("#1f5fbf", width=1)
        self.front_lines: list = []  # one line per front (the runs browsed)
        self.points = pg.ScatterPlotItem()
        self.points.sigClicked.connect(self._clicked)
        self.addItem(self.points)
        self.chosen = pg.ScatterPlotItem(
            size=18, pen=pg.mkPen("r", width=2), brush=pg.mkBrush(None)
        )
        self.addItem(self.chosen)
        self.xy = np.zeros((0, 2))

    def set_results(
        self, solutions, on_front, pinned, axes, chosen: int | None, groups=None
    ) -> None:
        """Draw ``solutions`` on ``axes`` (x, y keys of ``scatter_axes``); ``on_front`` and
        ``pinned`` are flags per solution; ``groups`` (e.g. the run of each) gives each
        group's front its own line (default: one group)."""
        ax, ay = axes
        self.setLabel("bottom", axis_label(ax))
        self.setLabel("left", axis_label(ay))
        xy = np.array([[axis_value(s, ax), axis_value(s, ay)] for s in solutions], float)
        self.xy = xy.reshape(-1, 2)
        spots = []
        for i, (x, y) in enumerate(self.xy):
            if not (np.isfinite(x) and np.isfinite(y)):
                continue
            feasible = solutions[i].feasible
            colour = "#1f5fbf" if on_front[i] else ("#909090" if feasible else "#e08030")
            spots.append(
                {
                    "pos": (x, y),
                    "data": i,
                    "size": 14 if pinned[i] else 10,
                    "symbol": "star" if pinned[i] else ("o" if feasible else "x"),
                    "brush": pg.mkBrush(colour),
                    "pen": pg.mkPen(colour),
                }
            )
        self.points.setData(spots)
        if not spots:
            self.reset_view()  # nothing to show: no range left from earlier results
        for line in self.front_lines:
            self.removeItem(line)
        self.front_lines = []
        groups = np.zeros(len(self.xy)) if groups is None else np.asarray(groups, float)
        flags = np.asarray(on_front, bool)
        for g in np.unique(groups[flags]) if len(self.xy) else ():
            front = self.xy[flags & (groups == g)]
            front = front[np.argsort(front[:, 0])]
            self.front_lines.append(self.plot(front[:, 0], front[:, 1], pen=self.front_pen))
        self.set_chosen(chosen)

    def reset_view(self) -> None:
        """Forget the ranges panned or zoomed to: fit the next results (or 0 to 1 on
        both axes while there are none)."""
        if not np.isfinite(self.xy).all(axis=1).any():
            self.setRange(xRange=(0.0, 1.0), yRange=(0.0, 1.0), padding=0.0)
        self.enableAutoRange()

    def set_chosen(self, index: int | None) -> None:
        """Ring the result ``index`` (None: none)."""
        if index is None or index >= len(self.xy) or not np.isfinite(self.xy[index]).all():
            self.chosen.setData([])
        else:
            self.chosen.setData([self.xy[index, 0]], [self.xy[index, 1]])

    def _clicked(self, _item, points, *_rest) -> None:
        if len(points):
            self.clicked.emit(int(points[0].data()))
