"""Fast Qt plots (pyqtgraph): the live convergence of a run and the result scatter.

Both only draw what they are given; the run panel feeds them throttled snapshots and
the solutions panel the project's results.
"""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6 import QtCore, QtWidgets

from app.goals import axis_label
from lightinv_core.kinds import GoalKind, SourceKind

PENALTY_FLOOR = 1e-6
"""Penalties are drawn on a log axis; P = 0 (feasible) is drawn at this floor."""

pg.setConfigOptions(antialias=False, background="w", foreground="k")


def _pen(run: int, current: bool):
    colour = pg.intColor(run, hues=9, values=1, maxValue=200)
    return pg.mkPen(colour, width=2 if current else 1)


class ConvergencePlot(QtWidgets.QWidget):
    """Best objective and penalty P(x) against evaluations, one curve per VNS run."""

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        lay = QtWidgets.QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        self.goal_plot = pg.PlotWidget()
        self.penalty_plot = pg.PlotWidget()
        self.penalty_plot.setLogMode(y=True)
        for plot in (self.goal_plot, self.penalty_plot):
            plot.showGrid(x=True, y=True, alpha=0.3)
            plot.setLabel("bottom", "evaluations")
            plot.setMinimumHeight(150)
            lay.addWidget(plot)
        self.penalty_plot.setTitle("penalty P (feasible drawn at 1e-6)", size="9pt")
        self._data: dict[int, list[list[float]]] = {}
        self._curves: dict[int, tuple[pg.PlotDataItem, pg.PlotDataItem]] = {}
        self.point_count = 0
        self.redraws = 0
        self.reset("objective")

    def reset(self, goal_label: str) -> None:
        """Empty both plots; ``goal_label`` names the objective axis (with units)."""
        self.goal_plot.clear()
        self.penalty_plot.clear()
        self._data.clear()
        self._curves.clear()
        self.point_count = 0
        self.goal_plot.setTitle(f"best {goal_label}", size="9pt")

    def add_points(self, rows, latest: tuple[int, int] | None = None) -> None:
        """Append (run, evaluations, goal, penalty) rows and redraw; ``latest`` (run,
        evaluations) extends that run's curve flat to where the search is now."""
        for run, evals, goal, pen in rows:
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
                self._curves[run] = (self.goal_plot.plot(), self.penalty_plot.plot())
            g, p = self._curves[run]
            pen = _pen(run, run == current)
            # pyqtgraph's "right": each value holds from its x to the next point's x.
            g.setData(a[:, 0], a[:, 1], pen=pen, stepMode="right")
            p.setData(a[:, 0], np.maximum(a[:, 2], PENALTY_FLOOR), pen=pen, stepMode="right")
        self.redraws += 1

    def curve(self, run: int = 0) -> np.ndarray:
        """The (evaluations, goal, penalty) rows drawn for ``run`` (tests, export)."""
        return np.asarray(self._data.get(run, []), dtype=float)


def _goal(kind: GoalKind):
    return lambda s: s.objectives.get(kind)


GOAL_AXES = {
    GoalKind.MIN_ELECTRIC_POWER: "power",
    GoalKind.MAX_LIGHT_POWER: "light",
    GoalKind.MATCH: "match",
    GoalKind.MIN_INSTALLED_POWER: "installed",
    GoalKind.MIN_LUMINAIRE_COUNT: "count",
    GoalKind.MIN_ANNUAL_ENERGY: "energy",
    GoalKind.MAX_SDA: "sda",
    GoalKind.MIN_GLAZING_AREA: "glazing",
}
"""The scatter axis of each goal's value."""

AXES = {
    "power": (axis_label(GoalKind.MIN_ELECTRIC_POWER), _goal(GoalKind.MIN_ELECTRIC_POWER)),
    "light": (axis_label(GoalKind.MAX_LIGHT_POWER), _goal(GoalKind.MAX_LIGHT_POWER)),
    "energy": (axis_label(GoalKind.MIN_ANNUAL_ENERGY), _goal(GoalKind.MIN_ANNUAL_ENERGY)),
    "glazing": (axis_label(GoalKind.MIN_GLAZING_AREA), _goal(GoalKind.MIN_GLAZING_AREA)),
    "sda": (axis_label(GoalKind.MAX_SDA), _goal(GoalKind.MAX_SDA)),
    "installed": (axis_label(GoalKind.MIN_INSTALLED_POWER), _goal(GoalKind.MIN_INSTALLED_POWER)),
    "count": (axis_label(GoalKind.MIN_LUMINAIRE_COUNT), _goal(GoalKind.MIN_LUMINAIRE_COUNT)),
    "sky_area": (
        "skylight area (m²)",
        lambda s: sum(x.area for x in s.sources if x.kind == SourceKind.SKYLIGHT),
    ),
    "sky_filter": (
        "mean skylight filter",
        lambda s: _mean([x.filter for x in s.sources if x.kind == SourceKind.SKYLIGHT]),
    ),
    "lum_area": (
        "luminaire area (m²)",
        lambda s: sum(x.area for x in s.sources if x.kind == SourceKind.LUMINAIRE),
    ),
    "lum_flux": (
        "luminaire flux (lm)",
        lambda s: sum(x.flux or 0.0 for x in s.sources if x.kind == SourceKind.LUMINAIRE),
    ),
    "penalty": ("penalty P", lambda s: s.penalty),
    "match": (axis_label(GoalKind.MATCH), _goal(GoalKind.MATCH)),
}
"""Scatter axes: key -> (label with units, value of a solution or None)."""


def front_axes(objectives) -> tuple[str, str]:
    """The (x, y) scatter axes of a front of two goal kinds: the first objective across,
    the second up, except that a glazing area goes across (energy against glazing)."""
    a, b = (GOAL_AXES[GoalKind(k)] for k in tuple(objectives)[:2])
    return (b, a) if b == "glazing" else (a, b)


def _mean(values) -> float | None:
    return float(np.mean(values)) if values else None


def axis_value(solution, axis: str) -> float:
    """A solution's value on a scatter axis (NaN when it has none)."""
    v = AXES[axis][1](solution)
    return float("nan") if v is None else float(v)


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
        """Draw ``solutions`` on ``axes`` (x, y keys of ``AXES``); ``on_front`` and
        ``pinned`` are flags per solution; ``groups`` (e.g. the run of each) gives each
        group's front its own line (default: one group)."""
        ax, ay = axes
        self.setLabel("bottom", AXES[ax][0])
        self.setLabel("left", AXES[ay][0])
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

    def set_chosen(self, index: int | None) -> None:
        """Ring the result ``index`` (None: none)."""
        if index is None or index >= len(self.xy) or not np.isfinite(self.xy[index]).all():
            self.chosen.setData([])
        else:
            self.chosen.setData([self.xy[index, 0]], [self.xy[index, 1]])

    def _clicked(self, _item, points, *_rest) -> None:
        if len(points):
            self.clicked.emit(int(points[0].data()))
