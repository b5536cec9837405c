"""The Achieved tab's glare box: the simplified DGP at each observer over the year.

Shown when an intention bounds ``dgp`` at the observers (``light.dgp_observers``): per
eye, the share of the occupied hours whose DGPs exceeds the design's limit, EN 17037's
glare protection level (each limit 0.45 / 0.40 / 0.35 exceeded in no more than 5% of
the hours), the year's largest DGPs and eye illuminance. A row is red when the share
is above 5% (EN 17037's time share), green otherwise.
"""

from __future__ import annotations

from PySide6 import QtGui, QtWidgets

from lightinv_core.climate.sun_metrics import GLARE_TIME_SHARE

COLUMNS = ("observer", "hours above the limit", "EN 17037 glare protection", "max DGPs", "max Ev")


def figure_cells(name: str, got: dict) -> tuple[str, ...]:
    """The row of one observer's figures (``light.dgp_observers.observer_dgp``)."""
    return (
        name,
        f"{100 * got['exceedance']:.1f}% of {got['hours']:,} h (DGPs > {got['limit']:.2f})",
        got["en17037_glare"],
        f"{got['dgp_max']:.2f}",
        f"{got['ev_max_lux']:,.0f} lux",
    )


class ObserverDgpBox(QtWidgets.QGroupBox):
    """A table of each observer's simplified DGP figures; hidden without any."""

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__("Glare at the observers: simplified DGP over the occupied hours", parent)
        lay = QtWidgets.QVBoxLayout(self)
        self.table = QtWidgets.QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(COLUMNS)
        self.table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
        self.table.verticalHeader().hide()
        lay.addWidget(self.table)
        self.setSizePolicy(QtWidgets.QSizePolicy.Preferred, QtWidgets.QSizePolicy.Maximum)
        self.hide()

    def show_figures(self, figures: dict | None) -> None:
        """Fill the table with {observer: figures}, or hide it (None or empty)."""
        self.setVisible(bool(figures))
        figures = figures or {}
        self.table.setRowCount(len(figures))
        for r, (name, got) in enumerate(figures.items()):
            ok = got["exceedance"] <= GLARE_TIME_SHARE + 1e-12
            colour = QtGui.QColor("#d9f2d9" if ok else "#fbd5d5")
            for c, text in enumerate(figure_cells(name, got)):
                item = QtWidgets.QTableWidgetItem(text)
                item.setBackground(colour)
                self.table.setItem(r, c, item)
        self.table.resizeColumnsToContents()
        rows = max(len(figures), 1)
        height = self.table.horizontalHeader().height() + rows * self.table.rowHeight(0) + 4
        self.table.setFixedHeight(height if figures else 0)
