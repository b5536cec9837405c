"""The Climate tab's chart of the monthly lighting energy (kWh), pyqtgraph bars."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6 import QtCore, QtWidgets

from lightinv_core.editing.climate import MONTHS


class EnergyChart(pg.PlotWidget):
    """Lighting energy per month (kWh) as bars."""

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.setMinimumHeight(150)
        self.setMouseEnabled(x=False, y=False)
        self.hideButtons()
        self.setMenuEnabled(False)
        self.showGrid(y=True, alpha=0.3)
        self.setLabel("left", "kWh")
        self.getAxis("bottom").setTicks([[(i + 1, m) for i, m in enumerate(MONTHS)]])
        self.bars = pg.BarGraphItem(
            x=np.arange(1, 13), height=np.zeros(12), width=0.7, brush="#3b7dd8"
        )
        self.addItem(self.bars)
        self.setXRange(0.4, 12.6, padding=0)
        self.monthly = np.zeros(12)

    def sizeHint(self) -> QtCore.QSize:
        return QtCore.QSize(380, 200)  # not a plot widget's 640 x 480: the tab is short

    def set_months(self, kwh) -> None:
        """Draw 12 monthly values (kWh); None empties the chart."""
        self.monthly = np.zeros(12) if kwh is None else np.asarray(kwh, float)
        self.bars.setOpts(height=self.monthly)
        self.setYRange(0.0, max(float(self.monthly.max()) * 1.1, 1e-3), padding=0)
