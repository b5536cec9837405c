"""The live convergence of a run (pyqtgraph): the best objective and the penalty against
evaluations, one curve per run. It draws only what the run panel feeds it (throttled
snapshots).

Sub-runs that optimise goals of other units (an epsilon sweep's range run on the
glazing area, m², before its runs on annual energy, kWh; the two-step's light power, lm,
and electric power, W) are drawn in a plot of their own, each titled and labelled with
its goal and units. A run's points before its first lit candidate (no finite value yet)
are not drawn."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6 import QtWidgets

PENALTY_FLOOR = 1e-6
"""Penalties are drawn on a log axis; P = 0 (feasible) is drawn at this floor."""


def _pen(run: int, current: bool):
    colour = pg.intColor(run, hues=9, values=1, maxValue=200)
    return pg.mkPen(colour, width=2 if current else 1)


def _plot(title: str) -> pg.PlotWidget:
    plot = pg.PlotWidget()
    plot.showGrid(x=True, y=True, alpha=0.3)
    plot.setLabel("bottom", "evaluations")
    plot.setMinimumHeight(150)
    plot.setTitle(title, size="9pt")
    return plot


class ConvergencePlot(QtWidgets.QWidget):
    """Best objective and penalty P(x) against evaluations, one curve per run; one
    objective plot per goal the runs optimise (``goal_plots``, by its label)."""

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self._lay = QtWidgets.QHBoxLayout(self)
        self._lay.setContentsMargins(0, 0, 0, 0)
        self.goal_plot = _plot("best objective")
        self.penalty_plot = _plot("penalty P (feasible drawn at 1e-6)")
        self.penalty_plot.setLogMode(y=True)
        self._lay.addWidget(self.goal_plot)
        self._lay.addWidget(self.penalty_plot)
        self.goal_plots: dict[str, pg.PlotWidget] = {}
        self._run_label = None
        self._data: dict[int, list[list[float]]] = {}
        self._curves: dict[int, tuple[pg.PlotDataItem, pg.PlotDataItem]] = {}
        self.point_count = 0
        self.redraws = 0
        self.reset("objective")

    def reset(self, goal_label: str, run_label=None) -> None:
        """Empty the plots; ``goal_label`` names the objective axis (with units);
        ``run_label(run)`` the goal of sub-run ``run`` when it differs (None: all
        ``goal_label``): runs of another goal get a plot of their own."""
        for plot in self.goal_plots.values():
            if plot is not self.goal_plot:
                self._lay.removeWidget(plot)
                plot.deleteLater()
        self.goal_plot.clear()
        self.penalty_plot.clear()
        self._data.clear()
        self._curves.clear()
        self.point_count = 0
        self.goal_plot.setTitle(f"best {goal_label}", size="9pt")
        self.goal_plot.setLabel("left", goal_label)
        self.goal_plots = {goal_label: self.goal_plot}
        self._goal_label, self._run_label = goal_label, run_label

    def plot_of(self, run: int) -> pg.PlotWidget:
        """The objective plot run ``run`` is drawn in (made on its first point)."""
        label = self._goal_label if self._run_label is None else self._run_label(run)
        if label not in self.goal_plots:
            plot = _plot(f"best {label}")
            plot.setLabel("left", label)
            self._lay.insertWidget(self._lay.indexOf(self.penalty_plot), plot)
            self.goal_plots[label] = plot
        return self.goal_plots[label]

    def add_points(self, rows, latest: tuple[int, int] | None = None) -> None:
        """Append (run, evaluations, goal, penalty) rows and redraw; ``latest`` (run,
        evaluations) extends that run's curve flat to where the search is now."""
        for run, evals, goal, pen in rows:
            if not (np.isfinite(goal) and np.isfinite(pen)):
                continue  # nothing lit yet: no best to draw
            self._data.setdefault(int(run), []).append([evals, goal, pen])
            self.point_count += 1
        if latest is not None and latest[0] in self._data:
            d = self._data[latest[0]]
            if latest[1] > d[-1][0]:
                if len(d) >= 2 and d[-1][1:] == d[-2][1:]:
                    d[-1][0] = latest[1]  # move the flat tail, don't grow it
                else:
                    d.append([latest[1], *d[-1][1:]])
        self._redraw(latest[0] if latest is not None else None)

    def _redraw(self, current: int | None) -> None:
        for run, rows in self._data.items():
            a = np.asarray(rows, dtype=float)
            if run not in self._curves:
                self._curves[run] = (self.plot_of(run).plot(), self.penalty_plot.plot())
            g, p = self._curves[run]
            pen = _pen(run, run == current)
            # pyqtgraph's "right": each value holds from its x to the next point's x.
            g.setData(a[:, 0], a[:, 1], pen=pen, stepMode="right")
            p.setData(a[:, 0], np.maximum(a[:, 2], PENALTY_FLOOR), pen=pen, stepMode="right")
        self.redraws += 1

    def curve(self, run: int = 0) -> np.ndarray:
        """The (evaluations, goal, penalty) rows drawn for ``run`` (tests, export)."""
        return np.asarray(self._data.get(run, []), dtype=float)
