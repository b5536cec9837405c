"""The "Climate" tab: the project's weather and site, occupancy and daylight-linked
dimming, an hour-of-year slider that relights the view, and the monthly lighting energy.

Every field is the design's ``Daylight`` (written through ``DocumentModel.set_daylight``,
so Edit > Undo takes it back and a saved project keeps it). The light of the design in
every scenario is built once per design change (``DocumentModel.layout_daylight``); the
slider only sums it for one hour (``LayoutDaylight.hour_lux``: a few microseconds).
What cannot be shown (an unreadable weather file, no skylights, no work plane to dim
on) is said in the panel, never raised. The daylight maps of the view (DF, DA300, UDI,
one hour) are in app/view/daylight_maps.py.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from PySide6 import QtCore, QtWidgets

from app.dialogs import ask
from app.dialogs.fields import compact_form, typed_number
from app.document import Document
from app.widgets.control_groups_box import ControlGroupsBox
from app.widgets.energy_box import EnergyBox
from lightinv_core.climate.weather import BUILTIN
from lightinv_core.editing.climate import (
    HOURS_PER_YEAR,
    MONTHS,
    hour_date,
    hour_index,
    hour_state,
    month_days,
    site_text,
    weather_notes,
    weather_of,
)
from lightinv_core.errors import LightInvError

NO_ALTITUDE = -6.0  # the altitude box's "not set" (the project allows -5 degrees and up)

WEATHER_FILTER = (
    "Weather files (*.epw *.csv *.tm2);;EnergyPlus weather (*.epw);;TMY3 (*.csv);;TMY2 (*.tm2)"
)
DEFAULT_HOUR = hour_index(6, 21, 12)  # midsummer noon


class ClimatePanel(QtWidgets.QWidget):
    """Weather, site and controls of the design's daylight; the hour of the year; the
    monthly energy. ``hourChanged(hour)`` when the hour moves, ``showHourToggled(on)``
    when the view should (not) be lit at that hour."""

    hourChanged = QtCore.Signal(int)
    showHourToggled = QtCore.Signal(bool)

    def __init__(self, doc: Document, parent: QtWidgets.QWidget | None = None):
        super().__init__(parent)
        self.doc = doc
        self._stale = True  # the weather-dependent parts wait until the tab is seen
        outer = QtWidgets.QVBoxLayout(self)
        outer.setContentsMargins(4, 4, 4, 4)
        self.message = QtWidgets.QLabel("")
        self.message.setWordWrap(True)
        self.message.setStyleSheet("color: #a01010;")
        self.message.hide()
        outer.addWidget(self.message)
        # Two by two, not four in a row: the Optimisation dock shares a 1366 px laptop
        # screen's width with the Properties and Luminaires column.
        grid = QtWidgets.QGridLayout()
        outer.addLayout(grid, 1)
        grid.addWidget(self._site_group(), 0, 0)
        # Beside the site's long form, not in it: a row there would push the rows below
        # out of sight of a 768 px screen's Climate tab.
        right = QtWidgets.QVBoxLayout()
        right.addWidget(self._control_group())
        right.addWidget(self._sky_group())
        right.addStretch(1)
        grid.addLayout(right, 0, 1)
        grid.addWidget(self._hour_group(), 1, 0)
        self.energy = EnergyBox()
        grid.addWidget(self.energy, 1, 1)
        self.groups = ControlGroupsBox(doc)
        grid.addWidget(self.groups, 2, 0, 1, 2)  # below: the dock has no width to spare
        grid.setColumnStretch(1, 1)
        self._fields = (
            self.north,
            self.ground,
            self.overcast,
            self.exterior_lux,
            self.transmittance,
            self.sun_day,
            self.sun_altitude,
            self.basis,
            self.dgp_limit,
            self.sky,
            self.start,
            self.end,
            self.weekdays,
            self.target,
            self.min_level,
            self.standby,
            self.plane,
        )
        doc.designChanged.connect(self.refresh_fields)
        doc.sceneChanged.connect(self.refresh_fields)
        doc.lightingChanged.connect(self.refresh_light)
        doc.sceneChanged.connect(self.refresh_light)
        self.set_hour(DEFAULT_HOUR)
        self.refresh_fields()

    # -- layout ---------------------------------------------------------------------------
    def _site_group(self) -> QtWidgets.QGroupBox:
        group = QtWidgets.QGroupBox("Weather and site")
        form = compact_form(group)
        self.weather_path = QtWidgets.QLineEdit()
        self.weather_path.setReadOnly(True)
        self.weather_path.setMinimumWidth(200)
        self.browse_button = QtWidgets.QPushButton("Browse...")
        self.browse_button.setToolTip(
            "An EnergyPlus (.epw), TMY3 (.csv) or TMY2 (.tm2) weather file"
        )
        self.builtin_button = QtWidgets.QPushButton("Built-in")
        self.builtin_button.setToolTip("The shipped Greensboro, NC TMY3 year")
        form.addRow("Weather", self.weather_path)
        wrow = QtWidgets.QHBoxLayout()
        wrow.addWidget(self.browse_button)
        wrow.addWidget(self.builtin_button)
        wrow.addStretch(1)
        form.addRow("", wrow)
        self.site = QtWidgets.QLabel("-")
        form.addRow("Site", self.site)
        self.north = typed_number(-360.0, 360.0, 5.0, 1, "°")
        self.north.setToolTip("Compass bearing of the scene's +y axis (0: +y points north)")
        form.addRow("North", self.north)
        self.ground = typed_number(0.0, 0.99, 0.05, 2)
        form.addRow("Ground reflectance", self.ground)
        self.overcast = typed_number(0.0, 2e5, 1000.0, 0, " lux")
        self.overcast.setToolTip("Horizontal exterior illuminance of the design overcast sky")
        form.addRow("Overcast sky", self.overcast)
        self.exterior_lux = typed_number(0.0, 2e5, 1000.0, 0, " lux")
        self.exterior_lux.setToolTip(
            "The design scenario's exterior lux on every skylight (the paper's model)"
        )
        form.addRow("Design sky", self.exterior_lux)
        self.transmittance = typed_number(0.0, 1.0, 0.05, 2)
        self.transmittance.setToolTip("Of the glazing, in every scenario")
        form.addRow("Transmittance", self.transmittance)
        # EN 17037 sunlight exposure: the day it is counted on (1 February to 21 March)
        # and the sun's least altitude for the site, which has no default: the standard
        # sets it by country and latitude, and a sunlight intention waits for it.
        self.sun_day = QtWidgets.QComboBox()  # the 49 days the standard allows, by name
        day = QtCore.QDate(2001, 2, 1)
        while day <= QtCore.QDate(2001, 3, 21):
            self.sun_day.addItem(day.toString("d MMMM"), day.toString("MM-dd"))
            day = day.addDays(1)
        self.sun_day.setToolTip("EN 17037 sunlight exposure: the day the sun's hours are counted")
        form.addRow("Sunlight day", self.sun_day)
        self.sun_altitude = typed_number(NO_ALTITUDE, 89.0, 1.0, 1, "°")
        self.sun_altitude.setSpecialValueText("not set")
        self.sun_altitude.setToolTip(
            "EN 17037 sunlight exposure: the sun counts above this altitude (the standard's "
            "value for the site)"
        )
        form.addRow("Sun counts above", self.sun_altitude)
        # EN 17037 daylight provision's two readings of "a plane fraction for half the
        # daylight hours" (docs/daylight.md, "EN 17037's hours basis in a project").
        self.basis = QtWidgets.QComboBox()
        self.basis.addItem("points: each point", "points")
        self.basis.addItem("hours: each hour", "hours")
        self.basis.setToolTip(
            "EN 17037 daylight provision: 'points' counts the points reaching the "
            "illuminance in half the daylight hours (Honeybee); 'hours' the hours in which "
            "the plane fraction reaches it (ClimateStudio)"
        )
        form.addRow("Provision basis", self.basis)
        self.dgp_limit = typed_number(0.19, 1.0, 0.05, 2)
        self.dgp_limit.setToolTip(
            "Simplified DGP at observers: the limit whose exceedance a glare intention "
            "counts (0.40: EN 17037 medium; 0.45 minimum, 0.35 high)"
        )
        form.addRow("DGP limit", self.dgp_limit)
        self.browse_button.clicked.connect(lambda: self.browse())
        self.builtin_button.clicked.connect(lambda: self.set_weather("builtin"))
        self.north.valueChanged.connect(lambda v: self._set(north_deg=v))
        self.ground.valueChanged.connect(lambda v: self._set(ground_reflectance=v))
        self.overcast.valueChanged.connect(lambda v: self._set(overcast_lux=v))
        self.exterior_lux.valueChanged.connect(lambda v: self._set(exterior_lux=v))
        self.transmittance.valueChanged.connect(lambda v: self._set(transmittance=v))
        self.sun_day.activated.connect(
            lambda _i: self._set(sunlight_date=self.sun_day.currentData())
        )
        self.sun_altitude.valueChanged.connect(
            lambda v: self._set(sunlight_min_altitude=None if v <= NO_ALTITUDE else v)
        )
        self.basis.activated.connect(lambda _i: self._set(en17037_basis=self.basis.currentData()))
        self.dgp_limit.valueChanged.connect(lambda v: self._set(dgp_limit=v))
        return group

    def _control_group(self) -> QtWidgets.QGroupBox:
        group = QtWidgets.QGroupBox("Occupancy and dimming")
        form = compact_form(group)
        self.start = typed_number(0.0, 24.0, 0.5, 1, " h")
        self.end = typed_number(0.0, 24.0, 0.5, 1, " h")
        orow = QtWidgets.QHBoxLayout()
        orow.addWidget(self.start)
        orow.addWidget(QtWidgets.QLabel("to"))
        orow.addWidget(self.end)
        form.addRow("Occupied", orow)
        self.weekdays = QtWidgets.QCheckBox("weekdays only")
        self.weekdays.setToolTip("Monday to Friday; unticked: every day of the week")
        form.addRow("", self.weekdays)
        self.target = typed_number(0.0, 1e5, 50.0, 0, " lux")
        self.target.setToolTip("Daylight-linked dimming keeps the work plane's mean at this")
        form.addRow("Dimming target", self.target)
        self.min_level = typed_number(0.0, 1.0, 0.05, 2)
        self.min_level.setToolTip("The lowest output the luminaires dim to while occupied (0-1)")
        form.addRow("Minimum level", self.min_level)
        self.standby = typed_number(0.0, 1e6, 1.0, 1, " W")
        self.standby.setToolTip("Drawn by the controls all year, on or off")
        form.addRow("Standby", self.standby)
        self.plane = QtWidgets.QComboBox()
        self.plane.setToolTip("The work plane the dimming, the annual energy and sDA read")
        # Sized to its entries as they change ("none: add a work plane (Luminaires)" was
        # cut to the width of the entries it had when first shown).
        self.plane.setSizeAdjustPolicy(QtWidgets.QComboBox.AdjustToContents)
        form.addRow("Control work plane", self.plane)
        self.start.valueChanged.connect(self._occupancy_edited)
        self.end.valueChanged.connect(self._occupancy_edited)
        self.weekdays.toggled.connect(lambda on: self._set(weekdays=on))
        self.target.valueChanged.connect(lambda v: self._set(target_lux=v))
        self.min_level.valueChanged.connect(lambda v: self._set(min_level=v))
        self.standby.valueChanged.connect(lambda v: self._set(standby_w=v))
        self.plane.activated.connect(lambda _i: self._set(workplane=self.plane.currentData()))
        return group

    def _sky_group(self) -> QtWidgets.QGroupBox:
        # Clear glazing's sky in finer patches (docs/daylight.md, "Finer skies in
        # projects"): the sun is traced by direction either way.
        group = QtWidgets.QGroupBox("Clear glazing")
        form = compact_form(group)
        self.sky = QtWidgets.QComboBox()
        for mf, text in ((1, "145 (Tregenza)"), (2, "577 (Reinhart MF:2)"), (4, "2,305 (MF:4)")):
            self.sky.addItem(text, mf)
        self.sky.setToolTip(
            "Clear glazing: the sky's patches. Finer patches follow the sky's luminance "
            "more closely and cost more time and memory to trace; the sun is traced by "
            "direction either way, so ASE does not change"
        )
        form.addRow("Sky patches", self.sky)
        self.sky.activated.connect(lambda _i: self._set(sky_subdivision=self.sky.currentData()))
        return group

    def _hour_group(self) -> QtWidgets.QGroupBox:
        group = QtWidgets.QGroupBox("Hour of the year")
        lay = QtWidgets.QVBoxLayout(group)
        self.slider = QtWidgets.QSlider(QtCore.Qt.Horizontal)
        self.slider.setRange(0, HOURS_PER_YEAR - 1)
        self.slider.setPageStep(24)  # Page Up / Down: a day
        self.slider.setMinimumWidth(240)
        lay.addWidget(self.slider)
        drow = QtWidgets.QHBoxLayout()
        self.month = QtWidgets.QComboBox()
        self.month.addItems(MONTHS)
        self.day = QtWidgets.QSpinBox(minimum=1, maximum=31)
        self.hour = QtWidgets.QSpinBox(minimum=0, maximum=23, suffix=":00")
        self.hour.setWrapping(True)
        for label, w in (("Month", self.month), ("Day", self.day), ("Hour", self.hour)):
            drow.addWidget(QtWidgets.QLabel(label))
            drow.addWidget(w)
        drow.addStretch(1)
        lay.addLayout(drow)
        self.when = QtWidgets.QLabel("-")
        self.exterior = QtWidgets.QLabel("-")
        self.level = QtWidgets.QLabel("-")
        self.glazing = QtWidgets.QLabel("")
        for w in (self.when, self.exterior, self.glazing, self.level):
            lay.addWidget(w)
        self.show_hour = QtWidgets.QCheckBox("light the view at this hour")
        self.show_hour.setToolTip(
            "Daylight of the hour plus the luminaires as the dimming sets them "
            "(off outside the occupied hours); also View > Colour by"
        )
        lay.addWidget(self.show_hour)
        lay.addStretch(1)
        self.slider.valueChanged.connect(self._slider_moved)
        # Moving the hour by hand lights the view at it.
        self.slider.actionTriggered.connect(lambda _a: self.show_hour.setChecked(True))
        self.month.currentIndexChanged.connect(self._date_edited)
        self.day.valueChanged.connect(self._date_edited)
        self.hour.valueChanged.connect(self._date_edited)
        self.show_hour.toggled.connect(self.showHourToggled)
        return group

    # -- document -> widgets ----------------------------------------------------------------
    def refresh_fields(self) -> None:
        """Show the design's daylight fields (signals blocked: showing is not editing)."""
        d = self.doc
        has = d.project is not None
        for w in (*self._fields, self.browse_button, self.builtin_button):
            w.setEnabled(has)
        if not has:
            return
        day = d.design.daylight
        for w in self._fields:
            w.blockSignals(True)
        try:
            self.weather_path.setText(
                "built-in: Greensboro, NC (TMY3)" if day.weather == "builtin" else day.weather
            )
            self.weather_path.setToolTip(str(BUILTIN) if day.weather == "builtin" else day.weather)
            self.north.setValue(day.north_deg)
            self.ground.setValue(day.ground_reflectance)
            self.overcast.setValue(day.overcast_lux)
            self.exterior_lux.setValue(day.exterior_lux)
            self.transmittance.setValue(day.transmittance)
            self.sun_day.setCurrentIndex(max(self.sun_day.findData(day.sunlight_date), 0))
            alt = day.sunlight_min_altitude
            self.sun_altitude.setValue(NO_ALTITUDE if alt is None else alt)
            self.basis.setCurrentIndex(max(self.basis.findData(day.en17037_basis), 0))
            self.dgp_limit.setValue(day.dgp_limit)
            self.sky.setCurrentIndex(max(self.sky.findData(day.sky_subdivision), 0))
            self.start.setValue(day.occupancy[0])
            self.end.setValue(day.occupancy[1])
            self.weekdays.setChecked(day.weekdays)
            self.target.setValue(day.target_lux)
            self.min_level.setValue(day.min_level)
            self.standby.setValue(day.standby_w)
            self.plane.clear()
            planes = [w.name for w in d.design.workplanes]
            if planes:
                self.plane.addItem(f"the first ({planes[0]})", None)
                for name in planes:
                    self.plane.addItem(name, name)
                self.plane.setCurrentIndex(max(self.plane.findData(day.workplane), 0))
            else:
                self.plane.addItem("none: add a work plane (Luminaires)", None)
            self.plane.setEnabled(bool(planes))
        finally:
            for w in self._fields:
                w.blockSignals(False)

    def refresh_light(self) -> None:
        """The site, the hour and the energy of the design (now if the tab is seen, else
        when it is: the first look reads the weather file, about a second)."""
        if not self.isVisible():
            self._stale = True
            return
        self._stale = False
        problems = []
        d = self.doc
        if d.project is None:
            return
        try:
            weather = d.weather()
            self.site.setText(site_text(weather))
            self.site.setToolTip(f"{weather.hours:,} hours; illuminance {weather.illuminance}")
            problems += weather_notes(weather)
        except LightInvError as exc:
            self.site.setText("cannot be read")
            problems.append(str(exc))
        ld = None
        try:
            ld = d.layout_daylight(shown=True)
        except LightInvError as exc:
            problems.append(str(exc))
        if ld is None and d.light is None:
            self.when.setText("The hours and the energy appear")
            self.exterior.setText("once the light model is ready.")
            self.glazing.setText("")
            self.level.setText("")
            self.energy.clear()
            self._say(problems)
            return
        if ld is not None and not ld.patches.daylit:
            problems.append(
                "The design has no skylights: no daylight reaches the room (DF, DA and UDI "
                "are 0; the luminaires dim only to the target)."
            )
        self._show_hour(ld, problems)
        self.energy.show_energy(ld, problems)
        self._say(problems)

    def _say(self, problems: list[str]) -> None:
        unique = list(dict.fromkeys(problems))
        self.message.setText("\n".join(unique))
        self.message.setVisible(bool(unique))

    def _show_hour(self, ld, problems: list[str]) -> None:
        if ld is None:
            return
        try:
            weather = self.doc.weather()
        except LightInvError:
            weather = None
        try:
            s = hour_state(ld, weather, self.slider.value())
        except LightInvError as exc:
            problems.append(str(exc))
            for w in (self.when, self.exterior, self.glazing, self.level):
                w.setText("-")
            return
        self.when.setText(f"{s.when} ({'occupied' if s.occupied else 'unoccupied'})")
        glazing = ", ".join(f"{x:,.0f}" for x in s.glazing_lux)
        self.exterior.setText(f"Exterior {s.horizontal_lux:,.0f} lux (horizontal)")
        self.glazing.setText(f"On the glazing {glazing} lux" if glazing else "No glazing")
        self.level.setText(
            f"Luminaires dimmed to {100 * s.level:.0f}%" if s.occupied else "Luminaires off"
        )

    def showEvent(self, event) -> None:
        super().showEvent(event)
        if self._stale:
            QtCore.QTimer.singleShot(0, self.refresh_light)

    # -- the hour ---------------------------------------------------------------------------
    def set_hour(self, hour: int) -> None:
        """Move to hour ``hour`` of the year (0-8759)."""
        if self.slider.value() == int(hour):
            self._slider_moved(self.slider.value())  # shown anew (the first call)
        else:
            self.slider.setValue(int(hour))

    def current_hour(self) -> int:
        """The hour of the year shown (0-8759)."""
        return self.slider.value()

    def _slider_moved(self, hour: int) -> None:
        month, day, h = hour_date(hour)
        for w in (self.month, self.day, self.hour):
            w.blockSignals(True)
        self.month.setCurrentIndex(month - 1)
        self.day.setMaximum(month_days(month))
        self.day.setValue(day)
        self.hour.setValue(h)
        for w in (self.month, self.day, self.hour):
            w.blockSignals(False)
        if self.isVisible():
            try:
                ld = self.doc.layout_daylight(shown=True)
            except LightInvError:
                ld = None
            problems: list[str] = []
            self._show_hour(ld, problems)
        self.hourChanged.emit(hour)

    def _date_edited(self) -> None:
        self.show_hour.setChecked(True)
        month = self.month.currentIndex() + 1
        self.day.setMaximum(month_days(month))
        self.slider.setValue(hour_index(month, self.day.value(), self.hour.value()))

    # -- widgets -> document ----------------------------------------------------------------
    def _set(self, **fields) -> bool:
        self._say([])
        try:
            self.doc.set_daylight(**fields)
        except LightInvError as exc:
            self._say([str(exc)])
            self.refresh_fields()
            return False
        return True

    def _occupancy_edited(self) -> None:
        self._set(occupancy=(self.start.value(), self.end.value()))

    def set_weather(self, path: str) -> bool:
        """Use the weather file ``path`` ("builtin": the shipped one): it is read first,
        and an unreadable file is refused with a message (the design keeps its weather)."""
        value = "builtin" if path == "builtin" else str(Path(path).resolve())
        try:
            weather_of(replace(self.doc.design.daylight, weather=value))
        except LightInvError as exc:
            self._say([f"Weather file not changed: {exc}"])
            return False
        ok = self._set(weather=value)
        if ok:
            self.refresh_light()
        return ok

    def browse(self) -> bool:
        """Choose a weather file (EPW or TMY3)."""
        path = ask.open_file(self, "Weather file", WEATHER_FILTER)
        return bool(path) and self.set_weather(path)
