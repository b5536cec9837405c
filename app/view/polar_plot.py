"""A luminaire product's intensity as a polar diagram (pyqtgraph), for the catalogue."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6 import QtCore, QtWidgets

from lightinv_core.light.arrays import Product


class PolarPlot(pg.PlotWidget):
    """A product's intensity (cd/klm) in its C0-C180 and C90-C270 planes, as a polar
    diagram: down is nadir (gamma 0), circles every ``ring`` cd/klm.

    The diagram always fills the widget: its range is the curves' and rings' box, set
    again on every resize (it was auto-ranged over the ring labels too, whose size is in
    pixels, and shrank to a dot in a dock made wider or shorter). No panning or zooming:
    a diagram to read, not a plot to explore."""

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.setAspectLocked(True)
        self.hideAxis("bottom")
        self.hideAxis("left")
        self.setMinimumHeight(170)
        self.setMouseEnabled(x=False, y=False)
        self.hideButtons()
        self.setMenuEnabled(False)
        self.curves: dict[str, np.ndarray] = {}
        self.box: QtCore.QRectF | None = None  # the diagram's extent (cd/klm)

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self._fit()

    def _fit(self) -> None:
        if getattr(self, "box", None) is not None:  # None until the first product
            self.getPlotItem().getViewBox().setRange(rect=self.box, padding=0.04)

    def show_product(self, product: Product | None) -> None:
        """Draw ``product``'s curves (nothing for None)."""
        self.clear()
        self.curves = {}
        self.box = None
        if product is None:
            self.setTitle("")
            return
        gam = np.radians(np.linspace(0.0, 180.0, 181))
        per_klm = 1000.0 / max(product.lumens, 1e-9)
        peak = 1.0
        for c, colour, style in ((0.0, "#1f77b4", QtCore.Qt.SolidLine), (90.0, "#ff7f0e", None)):
            deg = np.degrees(gam)
            right = product.photometry.intensity(np.full_like(deg, c), deg) * per_klm
            left = product.photometry.intensity(np.full_like(deg, c + 180.0), deg) * per_klm
            r = np.concatenate([right, left[::-1]])
            t = np.concatenate([gam, -gam[::-1]])
            x, y = r * np.sin(t), -r * np.cos(t)
            pen = pg.mkPen(colour, width=2, style=style or QtCore.Qt.DashLine)
            self.plot(x, y, pen=pen, name=f"C{c:.0f}")
            self.curves[f"C{c:.0f}"] = np.column_stack([x, y])
            peak = max(peak, float(r.max()))
        # At most four rings at a round step, labelled along the 45-degree line.
        step = 10 ** np.floor(np.log10(peak / 4))
        ring = next(m * step for m in (1, 2, 2.5, 5, 10) if peak / (m * step) <= 4)
        for k in range(1, int(peak // ring) + 1):
            r = k * ring
            circle = QtWidgets.QGraphicsEllipseItem(-r, -r, 2 * r, 2 * r)
            circle.setPen(pg.mkPen("#bbbbbb", width=1))
            self.addItem(circle)
            label = pg.TextItem(f"{r:g}", color="#777777", anchor=(0, 0))
            label.setPos(r * np.sqrt(0.5), -r * np.sqrt(0.5))
            self.addItem(label)
        for angle in (0.0, 45.0, 90.0):  # nadir, 45 and 90 degrees either side
            t = np.radians(angle)
            for sign in (1, -1):
                self.plot(
                    [0, sign * peak * np.sin(t)],
                    [0, -peak * np.cos(t)],
                    pen=pg.mkPen("#dddddd", width=1),
                )
        self.setTitle(f"{product.name}: cd/klm (C0 solid, C90 dashed)", size="8pt")
        # The whole diagram: the curves, the rings and the guide lines (radius ``peak``).
        xy = np.vstack(list(self.curves.values()))
        reach = max(peak, int(peak // ring) * ring, float(np.abs(xy).max()))
        self.box = QtCore.QRectF(-reach, -reach, 2 * reach, 2 * reach)
        self._fit()
