"""The Properties panel's View group: what the patches are coloured by (the design's
light, or a daylight map: ``view.daylight_maps``), the colour map and its range, and
whether the zone axes are shown. It holds only the choices; the window's colouring
(app/window/view_colouring.py) reads them."""

from __future__ import annotations

from PySide6 import QtWidgets

from app.view.daylight_maps import maps

COLORMAPS = ("inferno", "viridis", "plasma", "coolwarm", "gray")


class ViewOptions(QtWidgets.QGroupBox):
    """Colour by, colour map, range, zone axes."""

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__("View", parent)
        form = QtWidgets.QFormLayout(self)
        self.colour_by = QtWidgets.QComboBox()
        self.colour_by.addItem("illuminance (lux)", "lux")
        self.colour_by.addItem("radiosity B (lm/m²)", "B")
        for key, (text, _units, _fmt) in maps().items():
            self.colour_by.addItem(text, key)
        self.colour_by.setToolTip(
            "The design's light (illuminance: the design scenario), or a daylight map of the "
            "layout shown (weather, occupancy and the hour of the year: the Climate tab). "
            "DA and UDI are drawn 0-100%; the daylight factor on its own range."
        )
        # Its longest entry would make the Properties dock wider than a laptop leaves it:
        # the box shrinks, the list shows the entries whole.
        self.colour_by.setSizeAdjustPolicy(
            QtWidgets.QComboBox.AdjustToMinimumContentsLengthWithIcon
        )
        self.colour_by.setMinimumContentsLength(18)
        form.addRow("Colour by", self.colour_by)
        self.cmap = QtWidgets.QComboBox()
        self.cmap.addItems(COLORMAPS)
        form.addRow("Colour map", self.cmap)
        self.auto_range = QtWidgets.QCheckBox("automatic")
        self.auto_range.setChecked(True)
        self.range_max = QtWidgets.QDoubleSpinBox(decimals=0, suffix="", maximum=1e7)
        self.range_max.setValue(1000.0)
        self.range_max.setEnabled(False)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.auto_range)
        row.addWidget(self.range_max)
        form.addRow("Range 0 to", row)
        self.zone_axes = QtWidgets.QCheckBox("zone origin and u, v axes")
        self.zone_axes.setChecked(True)
        self.zone_axes.setToolTip(
            "Where the corners u0 v0 u1 v1 in Properties are measured from, and along"
        )
        form.addRow("Show", self.zone_axes)
        # A storey of a building: what is above the cut is neither drawn nor picked, and
        # zones are drawn on the ceiling under it (a roof hid the ground floor's ceiling).
        self.cut_on = QtWidgets.QCheckBox("cut above")
        self.cut_on.setToolTip(
            "Hide the model above this height, to see and draw on a lower storey "
            "(set it just above the storey's ceiling)"
        )
        self.cut_height = QtWidgets.QDoubleSpinBox(decimals=2, singleStep=0.1, suffix=" m")
        self.cut_height.setRange(-1e4, 1e4)
        self.cut_height.setKeyboardTracking(False)
        self.cut_height.setEnabled(False)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.cut_on)
        row.addWidget(self.cut_height, 1)
        form.addRow("Model", row)
        self.auto_range.toggled.connect(lambda on: self.range_max.setEnabled(not on))
        self.cut_on.toggled.connect(self.cut_height.setEnabled)

    def cut(self) -> float | None:
        """The height (m) above which the model is hidden (None: all of it shown)."""
        return self.cut_height.value() if self.cut_on.isChecked() else None

    def model_heights(self, low: float, high: float) -> None:
        """A new model from ``low`` to ``high`` m: the cut offered within it (untouched
        while it is on)."""
        if not self.cut_on.isChecked():
            self.cut_height.setRange(low, high)
            self.cut_height.setValue(high)

    def clim(self) -> tuple[float, float] | None:
        """The colour range set (None: automatic)."""
        return None if self.auto_range.isChecked() else (0.0, self.range_max.value())
