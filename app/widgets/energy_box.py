"""The Climate tab's annual lighting energy: the monthly chart and the year's figures
(LENI, the saving against full output, the mean dimming level) of the layout shown."""

from __future__ import annotations

from PySide6 import QtWidgets

from app.view.energy_chart import EnergyChart
from lightinv_core.climate.control_modes import control_text
from lightinv_core.errors import LightInvError


class EnergyBox(QtWidgets.QGroupBox):
    """Monthly kWh and the year's figures under daylight-linked dimming."""

    def __init__(self, parent: QtWidgets.QWidget | None = None):
        super().__init__("Annual lighting energy (daylight-linked dimming)", parent)
        lay = QtWidgets.QVBoxLayout(self)
        self.chart = EnergyChart()
        lay.addWidget(self.chart, 1)
        self.text = QtWidgets.QLabel("-")
        self.text.setWordWrap(True)  # a line per control group: no wider than the dock
        lay.addWidget(self.text)

    def clear(self) -> None:
        """Nothing to show (no light model yet)."""
        self.chart.set_months(None)
        self.text.setText("-")

    def show_energy(self, ld, problems: list[str]) -> None:
        """The annual energy of the layout's light ``ld`` (a ``LayoutDaylight``; None:
        nothing to show); what cannot be measured is added to ``problems``."""
        if ld is None:
            return
        try:
            e = ld.energy()
        except LightInvError as exc:
            problems.append(f"Annual energy: {exc}")
            self.chart.set_months(None)
            self.text.setText(f"Not measured:\n{exc}")
            return
        self.chart.set_months(e.monthly_kwh)
        if ld.installed_w <= 0:
            self.text.setText("No luminaires: no electric lighting energy.")
            return
        saved = 1.0 - e.energy_kwh / e.full_kwh if e.full_kwh > 0 else 0.0
        self.text.setText(
            f"Annual {e.energy_kwh:,.1f} kWh, LENI {e.leni:.2f} kWh/m²·a ({e.floor_m2:,.0f} m²)\n"
            f"{100 * saved:.0f}% less than at full output ({e.full_kwh:,.1f} kWh); "
            f"mean level {100 * e.mean_level:.0f}%\n"
            f"{ld.installed_w:,.0f} W installed, dimmed on work plane {ld.control}"
            + "".join(
                f"\ngroup {g.name} ({control_text(g.mode, g.target_lux, g.dead_band)}): "
                f"{g.watts:,.0f} W, "
                f"{g.energy_kwh:,.1f} kWh, "
                f"LENI {g.leni:.2f}, level {100 * g.mean_level:.0f}%"
                for g in e.groups
            )
        )
