"""Form pieces the editing dialogs and panels share: OK / Cancel buttons, a bound that
counts when ticked, number fields, the choice of a source kind."""

from __future__ import annotations

from PySide6 import QtWidgets

from lightinv_core.sources.types import source_types


def optional_number(
    form: QtWidgets.QFormLayout,
    label: str,
    value: float,
    hi: float,
    decimals: int = 2,
    step: float = 1.0,
) -> tuple[QtWidgets.QCheckBox, QtWidgets.QDoubleSpinBox]:
    """A form row "label [x] [value]": a bound that counts when ticked (unticked, its
    number is greyed out)."""
    check = QtWidgets.QCheckBox()
    box = QtWidgets.QDoubleSpinBox(decimals=decimals, singleStep=step)
    box.setRange(0.0, hi)
    box.setValue(value)
    box.setEnabled(False)
    check.toggled.connect(box.setEnabled)
    row = QtWidgets.QHBoxLayout()
    row.addWidget(check)
    row.addWidget(box)
    form.addRow(label, row)
    return check, box


def ok_cancel(dialog: QtWidgets.QDialog) -> QtWidgets.QDialogButtonBox:
    """OK and Cancel buttons that accept and reject ``dialog`` (to add to its layout)."""
    buttons = QtWidgets.QDialogButtonBox(
        QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Cancel
    )
    buttons.accepted.connect(dialog.accept)
    buttons.rejected.connect(dialog.reject)
    return buttons


def number_box(
    lo: float, hi: float, value: float, decimals: int = 2, step: float = 0.1
) -> QtWidgets.QDoubleSpinBox:
    """A number field from ``lo`` to ``hi`` showing ``value``."""
    box = QtWidgets.QDoubleSpinBox(decimals=decimals, singleStep=step)
    box.setRange(lo, hi)
    box.setValue(value)
    return box


def integer_box(lo: int, hi: int, value: int) -> QtWidgets.QSpinBox:
    """A whole-number field from ``lo`` to ``hi`` showing ``value``."""
    box = QtWidgets.QSpinBox()
    box.setRange(lo, hi)
    box.setValue(value)
    return box


def source_kind_box() -> QtWidgets.QComboBox:
    """A choice of every registered source kind: its label shown, its kind as the data."""
    box = QtWidgets.QComboBox()
    for t in source_types():
        box.addItem(t.label, str(t.kind))
    return box


def compact_form(group: QtWidgets.QGroupBox) -> QtWidgets.QFormLayout:
    """A form whose fields keep their natural width (the tab is wide and short)."""
    form = QtWidgets.QFormLayout(group)
    form.setFieldGrowthPolicy(QtWidgets.QFormLayout.FieldsStayAtSizeHint)
    return form


def typed_number(
    lo: float, hi: float, step: float, decimals: int, suffix: str = ""
) -> QtWidgets.QDoubleSpinBox:
    """A number field from ``lo`` to ``hi`` that reports one edit when typing is done."""
    box = QtWidgets.QDoubleSpinBox(decimals=decimals, singleStep=step, suffix=suffix)
    box.setRange(lo, hi)
    box.setKeyboardTracking(False)  # one edit when typing is done, not one per digit
    return box
