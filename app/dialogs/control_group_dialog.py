"""The dialog of one daylight-linked control group: its name, the work plane its sensor
reads, the plan rectangle of that plane's points it reads (or the whole plane), how its
luminaires follow the sensor (a control mode of ``climate.control_modes``: dimming or
switching), the illuminance it keeps (its own target, or the daylight's), for a mode
that takes one (switching) its dead band, and the lowest level its luminaires dim to (or
the daylight's)."""

from __future__ import annotations

from PySide6 import QtWidgets

from app.dialogs import ask
from app.dialogs.fields import number_box, ok_cancel, optional_number
from lightinv_core.climate.control_modes import control_mode, control_mode_names
from lightinv_core.design.model import ControlGroup
from lightinv_core.errors import LightInvError

WHOLE_PLANE = "the whole work plane"


class ControlGroupDialog(QtWidgets.QDialog):
    """Fields of one ``ControlGroup``; ``group()`` builds it (DesignError if bad).
    ``planes``: the design's work planes (the first entry stands for the control plane);
    ``bounds``: (x0, y0, x1, y1) m proposed for a new sensor rectangle."""

    def __init__(
        self,
        planes: list[str],
        base: ControlGroup,
        bounds: tuple[float, float, float, float] = (0.0, 0.0, 1.0, 1.0),
        min_level: float = 0.1,
        parent: QtWidgets.QWidget | None = None,
        target_lux: float = 500.0,
    ):
        super().__init__(parent)
        self.setWindowTitle("Control group")
        form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(base.name)
        form.addRow("Name", self.name)
        self.plane = QtWidgets.QComboBox()
        self.plane.addItem("the control work plane", None)
        for p in planes:
            self.plane.addItem(p, p)
        self.plane.setCurrentIndex(max(0, self.plane.findData(base.workplane)))
        form.addRow("Sensor on", self.plane)
        self.whole = QtWidgets.QCheckBox(WHOLE_PLANE)
        self.whole.setChecked(base.sensor is None)
        form.addRow("Sensor reads", self.whole)
        rect = base.sensor or bounds
        self.corners = [number_box(-1e4, 1e4, x, 2, 0.5) for x in rect]
        row = QtWidgets.QHBoxLayout()
        for box in self.corners:
            row.addWidget(box)
            box.setEnabled(base.sensor is not None)
            self.whole.toggled.connect(lambda on, b=box: b.setEnabled(not on))
        form.addRow("Region x0 y0 x1 y1 (m)", row)
        self.mode = QtWidgets.QComboBox()
        for name in control_mode_names():
            self.mode.addItem(control_mode(name).label, name)
        self.mode.setCurrentIndex(max(0, self.mode.findData(base.mode)))
        self.mode.setToolTip(
            "dimming: continuously, to top the daylight up to the target; switching: off "
            "while the daylight alone meets the target, else full output"
        )
        form.addRow("Control", self.mode)
        own = target_lux if base.target_lux is None else base.target_lux
        self.own_target, self.target = optional_number(form, "Own target (lux)", own, 1e5, 0)
        self.own_target.setChecked(base.target_lux is not None)
        self.target.setSingleStep(50)
        self.band = number_box(0.0, 200.0, 100.0 * base.dead_band, 0, 5.0)
        self.band.setSuffix(" %")
        self.band.setToolTip(
            "switching: off once the daylight reaches the target plus this share, back on "
            "when it falls below the target, so the luminaires do not cycle (0: off at the "
            "target; a product's photocell has 15)"
        )
        form.addRow("Dead band", self.band)
        self.mode.currentIndexChanged.connect(lambda _i: self._band_enabled())
        self._band_enabled()
        self.own_floor, self.floor = optional_number(
            form, "Own lowest level", min_level if base.min_level is None else base.min_level, 1.0
        )
        self.own_floor.setChecked(base.min_level is not None)
        self.floor.setSingleStep(0.05)
        form.addRow(ok_cancel(self))

    def _band_enabled(self) -> None:
        """The dead band only for a mode that takes one (switching)."""
        self.band.setEnabled(control_mode(self.mode.currentData()).banded is not None)

    def accept(self) -> None:
        """Close only on a group that can be built; else say why and stay."""
        try:
            self.group()
        except LightInvError as exc:
            ask.warn(self, str(exc))
            return
        super().accept()

    def group(self) -> ControlGroup:
        """The group as entered (DesignError naming the bad field)."""
        sensor = None if self.whole.isChecked() else tuple(b.value() for b in self.corners)
        return ControlGroup(
            self.name.text().strip(),
            sensor=sensor,
            workplane=self.plane.currentData(),
            min_level=self.floor.value() if self.own_floor.isChecked() else None,
            mode=self.mode.currentData(),
            target_lux=self.target.value() if self.own_target.isChecked() else None,
            dead_band=self.band.value() / 100.0 if self.band.isEnabled() else 0.0,
        )
