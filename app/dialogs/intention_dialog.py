"""The lighting intention dialog: name, quantity, scenario and bounds of an intention on
a group, the selection or a work plane. The quantities are the registry's
(``lightinv_core.quantities``): a new quantity shows in the list with its bounds."""

from __future__ import annotations

from PySide6 import QtWidgets

from app.dialogs.fields import ok_cancel, optional_number
from lightinv_core.design.model import DesignError, Intention
from lightinv_core.kinds import Bound, Scenario
from lightinv_core.quantities import quantity_spec, quantity_specs
from lightinv_core.scenarios import scenario_specs

BOUND_FIELDS = {
    Bound.MIN: ("Minimum", 300.0),
    Bound.MAX: ("Maximum", 1000.0),
    Bound.AVERAGE: ("Average at least", 500.0),
    Bound.UNIFORMITY: ("Uniformity U0 at least", 0.6),
    Bound.MAX_AVERAGE: ("Average at most", 0.1),
}
"""Each bound of an intention: its label and the value the dialog offers."""


"""The scenarios an intention is judged in (annual: the daylight metrics only)."""


class IntentionDialog(QtWidgets.QDialog):
    """Name, quantity, scenario and bounds of a lighting intention on a group, the
    selection or a work plane."""

    def __init__(
        self,
        target: str,
        parent: QtWidgets.QWidget | None = None,
        at_observers: bool = False,
        on_grid: bool = False,
    ):
        super().__init__(parent)
        self.setWindowTitle(f"Lighting intention on {target}")
        form = QtWidgets.QFormLayout(self)
        self.name = QtWidgets.QLineEdit(target)
        form.addRow("Name", self.name)
        self.quantity = QtWidgets.QComboBox()
        for q in quantity_specs():
            self.quantity.addItem(q.label, str(q.name))
        # UGR is judged at observers, the other quantities at patches or grid points,
        # a work plane's own figure (EN 17037) on a work plane: the list offers what the
        # target takes.
        for row, q in enumerate(quantity_specs()):
            takes = q.at_observers == at_observers and (on_grid or not q.plane)
            self.quantity.model().item(row).setEnabled(takes)
        if at_observers:
            first = next(r for r, q in enumerate(quantity_specs()) if q.at_observers)
            self.quantity.setCurrentIndex(first)
        form.addRow("Quantity", self.quantity)
        self.scenario = QtWidgets.QComboBox()
        for sc in scenario_specs():
            self.scenario.addItem(sc.label, str(sc.name))
        self.scenario.setToolTip(
            "The light the intention is judged in. A daylight metric has its own: the "
            "daylight factor the overcast sky, DA, UDI and sDA the weather year (Climate tab)."
        )
        form.addRow("Scenario", self.scenario)
        self.fields = {}
        self._rows = []  # the bounds' form rows (hidden for a quantity with levels)
        for bound, (label, default) in BOUND_FIELDS.items():
            key, u0 = str(bound), bound == Bound.UNIFORMITY
            self._rows.append(form.rowCount())
            self.fields[key] = optional_number(
                form, label, default, 1.0 if u0 else 1e6, decimals=2 if u0 else 1
            )
        # A quantity with named levels (EN 17037) is bounded by choosing one: its min.
        self.level = QtWidgets.QComboBox()
        self.level.setToolTip("The level the work plane must reach at least")
        self._rows.append(form.rowCount())
        form.addRow("Level at least", self.level)
        self._form = form
        self.fields[str(Bound.AVERAGE)][0].setChecked(True)
        self.fields[str(Bound.UNIFORMITY)][0].setChecked(True)
        form.addRow(ok_cancel(self))
        self.quantity.currentIndexChanged.connect(self._quantity_changed)
        self._quantity_changed()

    def _quantity_changed(self) -> None:
        """A daylight metric fixes the scenario and takes bounds in its own units."""
        q = quantity_spec(self.quantity.currentData())
        forced = q.scenario
        for row, sc in enumerate(scenario_specs()):
            # A scenario without an illuminance (the weather year) measures metrics only.
            self.scenario.model().item(row).setEnabled(sc.lux is not None or sc.name == forced)
        if forced is not None:
            self.scenario.setCurrentIndex(self.scenario.findData(str(forced)))
        elif self._last_metric():  # leave the scenario the metric had fixed
            self.scenario.setCurrentIndex(self.scenario.findData(str(Scenario.DESIGN)))
        # UGR rates the luminaires alone, whatever the scenario (light/glare.py).
        self.scenario.setEnabled(forced is None and not q.at_observers)
        self._metric = forced is not None
        decimals, top, defaults = q.decimals, q.high, q.defaults
        values = (*defaults[:3], defaults[2])
        for key, value in zip(("min", "max", "average", "max_average"), values, strict=True):
            box = self.fields[key][1]
            box.setDecimals(decimals)
            box.setMaximum(top)
            box.setValue(value)
        self.fields["uniformity"][1].setValue(defaults[3])
        self.set_values(max_average=None)
        if q.average_only:  # sDA is the average of a 0/1 mark: only that bound tells
            self.set_values(min=None, max=None, uniformity=None, average=None)
            self.set_values(**{str(q.average_bound): defaults[2]})  # ASE: at most
        if q.at_observers:  # UGR is bounded from above only
            self.set_values(min=None, average=None, uniformity=None, max=defaults[1])
        self.level.clear()
        for name, value in q.levels:
            self.level.addItem(name, value)
        for row in self._rows[:-1]:
            self._form.setRowVisible(row, not q.levels)
        self._form.setRowVisible(self._rows[-1], bool(q.levels))

    def _last_metric(self) -> bool:
        return getattr(self, "_metric", False)

    def load(self, intention: Intention) -> None:
        """Show an existing intention's name, quantity, scenario and bounds (to edit
        it)."""
        self.setWindowTitle(f"Edit lighting intention {intention.name}")
        self.name.setText(intention.name)
        self.quantity.setCurrentIndex(max(0, self.quantity.findData(str(intention.quantity))))
        self.scenario.setCurrentIndex(max(0, self.scenario.findData(str(intention.scenario))))
        self.set_values(**{str(b): getattr(intention, str(b)) for b in Bound})
        if self.level.count() and intention.min is not None:
            self.level.setCurrentIndex(max(0, self.level.findData(float(intention.min))))

    def set_quantity(self, quantity: str, scenario: str | None = None) -> None:
        """Choose the quantity (and the scenario of lux or C) (tests, scripted use)."""
        self.quantity.setCurrentIndex(self.quantity.findData(str(quantity)))
        if scenario is not None and self.scenario.isEnabled():
            self.scenario.setCurrentIndex(self.scenario.findData(str(scenario)))

    def set_values(self, **values) -> None:
        """Pre-fill bounds (tests, scripted use): key=None unticks a bound."""
        for key, value in values.items():
            check, box = self.fields[key]
            check.setChecked(value is not None)
            if value is not None:
                box.setValue(value)

    def intention(
        self, group: str | None = None, patches=None, grid=None, observers=None
    ) -> Intention:
        """The intention described (DesignError if inconsistent, e.g. min above max);
        ``observers``: names of the design's observers (UGR)."""
        bounds = {k: box.value() for k, (check, box) in self.fields.items() if check.isChecked()}
        if self.level.count():  # a quantity with levels: the level chosen is its min
            bounds = {str(Bound.MIN): float(self.level.currentData())}
        if not bounds:
            raise DesignError("tick at least one bound")
        return Intention(
            self.name.text().strip() or "intention",
            group=group,
            patches=None if patches is None else tuple(int(i) for i in patches),
            quantity=self.quantity.currentData(),
            grid=grid,
            observers=None if observers is None else tuple(observers),
            scenario=self.scenario.currentData(),
            **bounds,
        )


def intention_target(it: Intention) -> str:
    """What an intention bounds, in words: a group, picked patches, a work plane, its
    observers."""
    if it.grid is not None:
        return f"work plane {it.grid}"
    if it.observers is not None:
        return "observers " + ", ".join(it.observers)
    return it.group if it.group is not None else f"{len(it.patches)} picked patches"
