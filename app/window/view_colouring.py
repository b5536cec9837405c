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

from app.view import calc_overlay, luminaire_overlay, observer_overlay, sensor_overlay
from app.view.daylight_maps import design_caption, map_values, maps
from lightinv_core.editing.next_step import document_next_step
from lightinv_core.editing.results import result_label
from lightinv_core.errors import LightInvError
from lightinv_core.light.arrays import array_escape_warnings

NO_LIGHT = (
    "No light yet: the design has no luminaire or skylight. "
    "Surfaces are shown in the grey of their reflectance."
)
"""The caption of a design that emits no light (the view shows its materials)."""


class ViewColouring(QtCore.QObject):
    """The colouring of a main window's (``window``) viewport."""

    def __init__(self, window):
        super().__init__(window)
        self.win, self.doc, self.viewport = window, window.doc, window.viewport
        self.options = window.view_options
        self.last_render_ms = float("nan")
        self._luminaire_key = None
        self.sensors: tuple = ()  # the control groups' sensor outlines drawn
        self.doc.designChanged.connect(self.draw_sensors)
        o = self.options
        o.colour_by.currentIndexChanged.connect(self.recolour)
        o.colour_by.currentIndexChanged.connect(self._colour_by_changed)
        o.cmap.currentTextChanged.connect(self.viewport.set_colormap)
        o.auto_range.toggled.connect(self.recolour)
        o.range_max.valueChanged.connect(self.recolour)
        o.zone_axes.toggled.connect(self._zone_axes_toggled)
        o.cut_on.toggled.connect(self._cut_changed)
        o.cut_height.valueChanged.connect(self._cut_changed)
        # The next-step hint follows every change that can complete a step.
        for signal in (self.doc.sceneChanged, self.doc.designChanged, self.doc.resultsChanged):
            signal.connect(self.update_hint)
        # Connected before the window's own slot, which builds the new mesh: a zone drawn
        # on a room with no light yet keeps the camera too (the window keeps the picture,
        # and with it the camera, only when there was light to keep).
        self.doc.sceneChanged.connect(self._scene_changed)
        # The grid points that break a work-plane intention, beside the floor under them
        # that the Violations tab highlights.
        window.violations_panel.highlightChanged.connect(self.mark_broken_points)

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
            picked = self.win.edits.current_observer
            observer_overlay.draw(self.viewport.plotter, d.patches, d.design.observers, picked)
            calc_overlay.draw(self.viewport.plotter, d.patches, d.design.calc_objects)
            self.draw_sensors()
            self._luminaire_warnings(d.patches, d.design.arrays)
        self.update_hint()
        if field is None or not np.any(field.illuminance > 0):
            # No light model, or a design that emits none: its materials, not a black
            # room under a colour bar of zeros.
            luminaire_overlay.draw_planes(self.viewport.plotter, None, None)
            self.colour_observers(None)
            self.viewport.set_caption(None if field is None else NO_LIGHT)
            self.viewport.set_values(None)
            return
        self.paint(field)
        self.last_render_ms = 1e3 * (time.perf_counter() - t0)
        self.win.status_eval.setText(
            f"lighting {self.doc.last_eval_ms:.1f} ms, view {self.last_render_ms:.1f} ms"
        )

    def draw_sensors(self) -> None:
        """Outline each control group's sensor on its work plane (``sensor_overlay``); on
        every design change too, so an edit or an undo shows before any light does."""
        d, vp = self.doc, self.viewport
        if d.project is None or vp.mesh is None:
            return
        grids, _ = d.shown_grids()
        self.sensors = sensor_overlay.draw(vp.plotter, d.design, d.patches, grids)
        vp.request_render()

    def paint(self, field) -> None:
        """Colour the patches as View > Colour by says: the light shown, a pinned
        result's difference, or a daylight map (``daylight_maps.map_values``)."""
        other = self.win.solutions_panel.compared()
        cmap = "coolwarm" if other is not None else self.options.cmap.currentText()
        if cmap != self.viewport.cmap:
            self.viewport.set_colormap(cmap)
        key, fmt, caption = self.options.colour_by.currentData(), "%.0f", None
        grids, grid_values = self.doc.shown_grids()
        label, plane_clim, plane_cmap = "{:.0f}", None, "inferno"
        observers = None  # the observers' colours: a map at the observers only
        if other is not None:
            # Difference view: the loaded layout minus a pinned one, centred on zero, on
            # the patches and the work planes alike (signed labels).
            values = field.illuminance - self.doc.lighting_of(other.sources, other.arrays)
            m = float(np.abs(values).max()) or 1.0
            if grids is not None and grid_values is not None:
                pinned = self.doc.grid_lux_of(other.sources, other.arrays)
                grid_values = grid_values - pinned
                m = max(m, float(np.abs(grid_values).max()))
                label, plane_clim, plane_cmap = "{:+.0f}", (-m, m), "coolwarm"
            self.viewport.clim = (-m, m)
            units, fmt = "Δ lux", "%+.0f"  # a short title: a long one was cut off
            caption = (
                f"Difference: the loaded layout minus the pinned one ({result_label(other)}), "
                "lux; red brighter, blue darker"
            )
        elif key == "B":
            values, units = field.radiosity, "lm/m²"
            caption = design_caption(self.doc, "Radiosity B")
        elif key in maps():
            shown = map_values(self.doc, key, self.win.climate_panel.current_hour())
            values, units, fmt, caption = shown.values, shown.units, shown.fmt, shown.caption
            grids, grid_values = shown.grids, shown.grid_values
            label, plane_clim, observers = shown.label_format, shown.clim, shown.observers
            if shown.clim is not None:
                self.viewport.clim = shown.clim
            elif key == "df":
                self.viewport.clim = None  # a few percent: the lux range means nothing
        else:
            values, units = field.illuminance, "lux"
            caption = design_caption(self.doc, "Illuminance")
        if self.viewport.mesh is not None:
            # The work planes show the same quantity as the patches, iso-lines labelled.
            luminaire_overlay.draw_planes(
                self.viewport.plotter, grids, grid_values, label, plane_clim, plane_cmap
            )
        self.viewport.set_caption(caption)
        self.viewport.set_values(values, units, fmt)
        self.colour_observers(observers)

    def colour_observers(self, colours) -> None:
        """Colour the observers' glyphs by a map at the observers (None: plain,
        ``observer_overlay.set_colours``), redrawn when that changes."""
        d, vp = self.doc, self.viewport
        if observer_overlay.set_colours(vp.plotter, colours) and d.project is not None:
            picked = self.win.edits.current_observer
            observer_overlay.draw(vp.plotter, d.patches, d.design.observers, picked)
            vp.request_render()

    def _scene_changed(self, change) -> None:
        self.viewport.keep_camera = bool(change.rebuilt)

    def mark_broken_points(self) -> None:
        """Red dots on the work-plane points that break the violation selected in the
        Violations tab (or every one), while its highlight box is ticked."""
        panel, d = self.win.violations_panel, self.doc
        grids, _ = d.shown_grids() if d.project is not None else (None, None)
        points = []
        if grids is not None and panel.highlight.isChecked() and d.shown is not None:
            rows = {i.row() for i in panel.table.selectionModel().selectedRows()}
            chosen = {(d.shown.violations[r].name, d.shown.violations[r].constraint) for r in rows}
            points = [
                p
                for name, bound, _, p in d.offending_points()
                if not chosen or (name, bound) in chosen
            ]
        marked = np.concatenate(points) if points else np.zeros(0, np.int64)
        self.viewport.set_point_marks(grids.points[np.unique(marked)] if len(marked) else None)

    def update_hint(self) -> None:
        """The next step of the open design's workflow over the view (draw zones, add
        light, a work plane, its EN 12464-1 intention, Run:
        ``lightinv_core.editing.next_step``), gone once a run has left results."""
        step = document_next_step(self.doc)
        self.viewport.set_hint(None if step is None else step.hint())

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

    def _cut_changed(self, _=None) -> None:
        self.viewport.set_cut(self.options.cut())

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
