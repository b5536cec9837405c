"""Colouring the viewport: the patches as View > Colour by says (the light shown, a
pinned result's difference, or a daylight map), the luminaire glyphs and the work
planes' iso-lines, on every change of the light or the view options.

``ViewColouring`` reads the document, the View options, the Solutions tab's comparison
and the Climate tab's hour, and only draws: it changes no state of the design.
"""

from __future__ import annotations

import time

import numpy as np
from PySide6 import QtCore

from app.view import luminaire_overlay
from app.view.daylight_maps import map_values, maps
from lightinv_core.errors import LightInvError
from lightinv_core.light.arrays import array_escape_warnings


class ViewColouring(QtCore.QObject):
    """The colouring of a main window's (``window``) viewport."""

    def __init__(self, window):
        super().__init__(window)
        self.win, self.doc, self.viewport = window, window.doc, window.viewport
        self.options = window.view_options
        self.last_render_ms = float("nan")
        self._luminaire_key = None
        o = self.options
        o.colour_by.currentIndexChanged.connect(self.recolour)
        o.colour_by.currentIndexChanged.connect(self._colour_by_changed)
        o.cmap.currentTextChanged.connect(self.viewport.set_colormap)
        o.auto_range.toggled.connect(self.recolour)
        o.range_max.valueChanged.connect(self.recolour)
        o.zone_axes.toggled.connect(self._zone_axes_toggled)

    def shown_sources(self) -> tuple:
        """The sources the view outlines: a running optimisation's best so far, else the
        design's (rules applied)."""
        preview = self.doc.preview_sources()
        return preview if preview is not None else self.doc.effective_sources()

    def recolour(self) -> None:
        """Redraw the light, the outlines and the luminaires (the light or a choice
        changed)."""
        field = self.doc.field
        if field is not None:
            self.viewport.set_sources(self.shown_sources(), self.doc.current_source)
        t0 = time.perf_counter()
        self.viewport.clim = self.options.clim()
        d = self.doc
        if d.project is not None and self.viewport.mesh is not None:
            luminaire_overlay.draw(self.viewport.plotter, d.patches, d.design.arrays)
            self._luminaire_warnings(d.patches, d.design.arrays)
        if field is None:
            self.viewport.set_caption(None)
            self.viewport.set_values(None)
            return
        self.paint(field)
        self.last_render_ms = 1e3 * (time.perf_counter() - t0)
        self.win.status_eval.setText(
            f"lighting {self.doc.last_eval_ms:.1f} ms, view {self.last_render_ms:.1f} ms"
        )

    def paint(self, field) -> None:
        """Colour the patches as View > Colour by says: the light shown, a pinned
        result's difference, or a daylight map (``daylight_maps.map_values``)."""
        other = self.win.solutions_panel.compared()
        cmap = "coolwarm" if other is not None else self.options.cmap.currentText()
        if cmap != self.viewport.cmap:
            self.viewport.set_colormap(cmap)
        key, fmt, caption = self.options.colour_by.currentData(), "%.0f", None
        grids, grid_values = self.doc.shown_grids()
        label, plane_clim = "{:.0f}", None
        if other is not None:
            # Difference view: the loaded layout minus a pinned one, centred on zero.
            values = field.illuminance - self.doc.lighting_of(other.sources)
            m = float(np.abs(values).max()) or 1.0
            self.viewport.clim = (-m, m)
            units = "lux, loaded − pinned"
        elif key == "B":
            values, units = field.radiosity, "lm/m²"
        elif key in maps():
            shown = map_values(self.doc, key, self.win.climate_panel.current_hour())
            values, units, fmt, caption = shown.values, shown.units, shown.fmt, shown.caption
            grids, grid_values = shown.grids, shown.grid_values
            label, plane_clim = shown.label_format, shown.clim
            if shown.clim is not None:
                self.viewport.clim = shown.clim
            elif key == "df":
                self.viewport.clim = None  # a few percent: the lux range means nothing
        else:
            values, units = field.illuminance, "lux"
        if self.viewport.mesh is not None:
            # The work planes show the same quantity as the patches, iso-lines labelled.
            luminaire_overlay.draw_planes(
                self.viewport.plotter, grids, grid_values, label, plane_clim
            )
        self.viewport.set_caption(caption)
        self.viewport.set_values(values, units, fmt)

    def hour_moved(self, _hour: int) -> None:
        """The hour slider moved: relight the view if it shows that hour (a sum over the
        layout's light built once per design change: no new light is computed)."""
        if self.options.colour_by.currentData() == "hour" and self.doc.field is not None:
            self.viewport.clim = self.options.clim()
            self.paint(self.doc.field)

    def show_hour(self, on: bool) -> None:
        """The Climate tab's "light the view at this hour" ticked or not."""
        box = self.options.colour_by
        if (box.currentData() == "hour") != on:
            box.setCurrentIndex(box.findData("hour" if on else "lux"))

    def _colour_by_changed(self) -> None:
        box = self.win.climate_panel.show_hour
        box.blockSignals(True)
        box.setChecked(self.options.colour_by.currentData() == "hour")
        box.blockSignals(False)

    def _zone_axes_toggled(self, on: bool) -> None:
        self.viewport.show_zone_axes = on
        self.viewport.show_axes(*self.viewport.axes_focus)

    def _luminaire_warnings(self, patches, arrays) -> None:
        """Name the design's luminaires whose light mostly leaves the model (the status
        bar's warnings), traced again only when the patches or the arrays change."""
        key = (id(patches), tuple(arrays))
        if self._luminaire_key == key:
            return
        self._luminaire_key = key
        try:
            lost = array_escape_warnings(patches, arrays)
        except LightInvError:
            lost = []  # a product that cannot be read is reported where it is set
        self.win.set_warnings("luminaire placement", lost)
